"""When ContactRuntime rebuilds its lists, and that its lists never change a force.

The far lists (bucket sort) are rebuilt when the contact's nodes have moved
half the far margin along an axis relative to one common translation, the near lists
(nearlist.near_filter) when they have moved half the near margin, neither when
elements erode. Every check here compares
with a reference that lists every segment for every node (``AllPairs``): the
forces must be the same to the last bit (the kernels' results do not depend on
which or in what order candidates are listed, as long as no pair that can be
in contact is missing).
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact import ContactRuntime
from hollowbody.contact.penalty import gather
from hollowbody.contact.runtime import _drop_dead
from hollowbody.mesh import block_mesh, plate_mesh
from hollowbody.model.model import ContactDef
from hollowbody.model.model import SurfaceRef as Ref
from hollowbody.testing.models import PartSpec, assemble_model, part_contact


class AllPairs(ContactRuntime):
    """Reference: every segment is a candidate of every node (but the node's own
    segments and its exclusion list, as in the bucket sort), never re-sorted, and
    the kernels treat every node (not only those with candidates or in contact)."""

    def _sort(self, dt, cycle):
        for p in self.passes:
            lists = []
            for i, nd in enumerate(p.nodes):
                out = set(p.ex_seg[p.ex_ptr[i]:p.ex_ptr[i + 1]].tolist())
                out |= set(np.nonzero(np.any(p.seg == nd, axis=1))[0].tolist())
                lists.append([s for s in range(p.seg.shape[0]) if s not in out])
            p.ptr = np.zeros(len(lists) + 1, np.int64)
            p.ptr[1:] = np.cumsum([len(c) for c in lists])
            p.cand = np.array([s for c in lists for s in c], dtype=np.int32)
            if not p.seg_alive.all():
                p.ptr, p.cand = _drop_dead(p.ptr, p.cand, p.seg_alive)
        self._margin = np.inf
        self._last_sort = cycle
        self.n_sorts += 1

    def _filter(self):
        super()._filter()
        for p in self.passes:  # and every row treated, listed or not
            p.act = np.arange(p.nodes.shape[0], dtype=np.int32)


def _block_over_plate(gap: float, sort_interval: int, thickness: float = 2.0):
    xb, cb = block_mesh((3, 3, 2), (12.0, 12.0, 8.0), (-6.0, -6.0, gap))
    xp, cp = plate_mesh((6, 6), (30.0, 30.0), (-15.0, -15.0, 0.0))
    model = assemble_model([PartSpec(1, xb, cb), PartSpec(2, xp, cp, "shell", "elastic",
                                                          {"E": 0.1, "PR": 0.3}, 1e-6,
                                                          thickness)],
                           sort_interval=sort_interval)
    return model, xb.shape[0]


def _pair(model, kind="surface_to_surface", **kw):
    n = model.n_nodes
    mass = np.full(n, 1e-3)
    if kind == "single_surface":
        cd = part_contact(1, kind, [1, 2], None, **kw)
    else:
        cd = part_contact(1, kind, [1], [2], **kw)
    return (ContactRuntime(cd, model, mass, np.zeros(n, bool)),
            AllPairs(cd, model, mass, np.zeros(n, bool)))


def _step_both(a, b, x, v, dt, cycle):
    n = x.shape[0]
    fa = np.zeros((n, 3))
    fb = np.zeros((n, 3))
    a.add_forces(x, v, dt, cycle, fa)
    b.add_forces(x, v, dt, cycle, fb)
    np.testing.assert_array_equal(fa, fb)
    assert a.n_active == b.n_active and a.energy == b.energy
    return fa


def _approach(model, nb: int, vz: float, cycles: int):
    """The block's nodes (the first nb) move at vz mm/ms, dt = 0.01 ms, for
    ``cycles``, checked against all pairs every cycle; returns the runtime and
    the first cycle with a node in contact (None: none)."""
    a, b = _pair(model)
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    v[:nb, 2] = vz
    first = None
    for cycle in range(cycles):
        _step_both(a, b, x, v, 0.01, cycle)
        if a.n_active and first is None:
            first = cycle
        x += 0.01 * v
    return a, first


def test_fast_block_is_caught_before_the_sort_interval():
    """A block 30 mm above a plate closes at 1 mm per cycle: it touches after ~28
    cycles, long before the 100-cycle sort interval. The displacement bounds
    rebuild the lists in time (far lists several times, near lists more often),
    and every cycle's forces equal the all-pairs search."""
    model, nb = _block_over_plate(30.0, sort_interval=100)
    a, first = _approach(model, nb, -100.0, 36)  # mm/ms: 1 mm per cycle at dt = 0.01 ms
    assert first is not None and 25 <= first <= 32
    assert a.n_sorts >= 3 and a.n_filters > a.n_sorts


def test_slow_approach_between_near_list_filters():
    """A block closing slowly (0.05 mm per cycle) on a 6 mm thick plate (its
    capture distance is then the contact distance, 3 mm: no slack): the near
    lists are rebuilt every few cycles only, so the first contacts start
    between two filters, from pairs only the near margin kept listed; forces
    equal the all-pairs search in every cycle."""
    model, nb = _block_over_plate(5.5, sort_interval=100, thickness=6.0)
    a, first = _approach(model, nb, -5.0, 60)
    assert first is not None
    assert a.n_sorts <= 3 and a.n_filters >= 3 * a.n_sorts


def test_displacement_bound_holds_every_pair():
    """gather's bound D (along any axis, relative to one translation) must cover
    every pair of nodes along every axis, |u_ik - u_jk| <= 2 D, for any displacement
    field (so |u_i - u_j| <= 2 sqrt(3) D in space); it is never larger than max |u|
    (the bound with no translation), half of it when the nodes spread along one
    direction from rest (a crushed pile under an impactor), and 1 / sqrt(3) of the
    half diagonal of the displacements' box when they spread alike along the three
    axes (folding walls)."""
    rng = np.random.default_rng(3)
    for case in range(40):
        n = int(rng.integers(1, 60))
        x0 = rng.normal(0.0, 10.0, (n, 3))
        u = rng.normal(0.0, 1.0, (n, 3)) * rng.uniform(0.0, 3.0, 3)
        if case % 2:
            u += rng.normal(0.0, 20.0, 3)  # a common translation on top
        x = x0 + u
        u = x - x0  # as gather sees it (to the last bit)
        xl, vl = np.zeros_like(x), np.zeros_like(x)
        d2, dn2 = gather(x, x, np.arange(n, dtype=np.int32), xl, vl, x0, x0)
        assert d2 == dn2
        axis = np.max(np.abs(u[:, None, :] - u[None, :, :]))
        assert axis <= 2.0 * np.sqrt(d2) * (1.0 + 1e-12)
        pair = np.max(np.linalg.norm(u[:, None, :] - u[None, :, :], axis=2))
        assert pair <= 2.0 * np.sqrt(3.0 * d2) * (1.0 + 1e-12)
        assert d2 <= np.max(np.sum(u * u, axis=1))
    z = np.zeros((11, 3))
    u = z.copy()
    u[:, 2] = -np.linspace(0.0, 4.0, 11)  # base at rest, top moved 4 mm down
    d2, _ = gather(u, u, np.arange(11, dtype=np.int32), z.copy(), z.copy(), z, z)
    assert d2 == pytest.approx(4.0)  # (4 / 2)^2: half of max |u| = 4 mm
    u = np.outer(np.linspace(-1.0, 1.0, 11), [1.0, -1.0, 1.0])  # 2 mm along each axis
    d2, _ = gather(u, u, np.arange(11, dtype=np.int32), z.copy(), z.copy(), z, z)
    assert d2 == pytest.approx(1.0)  # the half diagonal would be sqrt(3) mm


@pytest.mark.parametrize("offset, gap", [(2.0, 2.0), (2.0, 4.0), (4.0, 2.0)])
def test_diagonal_approach_over_a_plate_corner(offset, gap):
    """A block beside a plate's corner and above it moves along the diagonal (-1,
    -1, -1) at 0.05 mm per cycle per axis onto the corner. The lists are rebuilt
    when the motion along an axis reaches the margin, so between two sorts node and
    segment approach by up to sqrt(3) margins in space, and the far lists' distance
    cut must keep the pairs that close: forces equal the all-pairs search in every
    cycle (with the cut at one margin, each of these cases loses a contact)."""
    xb, cb = block_mesh((3, 3, 2), (12.0, 12.0, 8.0), (15.0 + offset, 15.0 + offset, gap))
    xp, cp = plate_mesh((6, 6), (30.0, 30.0), (-15.0, -15.0, 0.0))
    model = assemble_model([PartSpec(1, xb, cb), PartSpec(2, xp, cp, "shell", "elastic",
                                                          {"E": 0.1, "PR": 0.3}, 1e-6, 2.0)],
                           sort_interval=100)
    a, b = _pair(model)
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    v[:xb.shape[0]] = -5.0
    active = 0
    for cycle in range(300):
        _step_both(a, b, x, v, 0.01, cycle)
        active += a.n_active
        x += 0.01 * v
    assert active > 0 and a.n_sorts >= 4


def test_a_common_translation_does_not_re_sort():
    """Block and plate flying together at 1 mm per cycle sideways while the block
    closes on the plate at 0.02 mm per cycle: the lists stay complete (forces equal
    the all-pairs search every cycle) and are rebuilt by the relative motion only:
    the interval sort, not one every few cycles as the 1 mm per cycle would need."""
    model, nb = _block_over_plate(0.6, sort_interval=50)
    a, b = _pair(model, fs=0.2, fd=0.2)
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    v[:, 0] = 100.0
    v[:nb, 2] = -2.0
    active = 0
    for cycle in range(100):
        _step_both(a, b, x, v, 0.01, cycle)
        active += a.n_active
        x += 0.01 * v
    assert active > 0
    assert a.n_sorts <= 3  # the first sort and the interval sorts (cycles 0, 50)


@pytest.mark.parametrize("kind", ["surface_to_surface", "single_surface"])
@pytest.mark.parametrize("parallel", [False, True])
def test_random_motion_with_friction_and_erosion(parallel, kind):
    """Random motion of a block on a plate (two-way or single surface, friction), with
    segments deleted part-way: forces equal the all-pairs search in every cycle,
    with the serial and the threaded kernels (sort, near filter, pass).
    Deleting segments does not re-sort: the sorts happen in the same cycles as
    in a twin without the deletion (they depend on the motion only)."""
    rng = np.random.default_rng(7)
    model, nb = _block_over_plate(0.5, sort_interval=10)
    a, b = _pair(model, "single_surface", fs=0.2, fd=0.1)
    if parallel:
        a.parallel_min_nodes = 0
        a.parallel_min_rows = 0
    twin, _ = _pair(model, "single_surface", fs=0.2, fd=0.1)
    x = model.node_x0.copy()
    v = rng.normal(0.0, 0.3, size=x.shape)
    v[:nb, 2] -= 0.5
    active = 0
    plate = model.shell_groups[0].elem_ids
    for cycle in range(120):
        if cycle == 65:  # between two interval sorts (every 10 cycles)
            dead = plate[::3]
            assert a.deactivate_elements(2, dead) == b.deactivate_elements(2, dead) > 0
        _step_both(a, b, x, v, 0.02, cycle)
        twin.add_forces(x, v, 0.02, cycle, np.zeros_like(x))
        assert a.n_sorts == twin.n_sorts
        active += a.n_active
        x += 0.02 * v
        v += rng.normal(0.0, 0.05, size=x.shape)
    assert active > 0 and a.n_sorts > 1
    for p in a.passes:  # near lists are sublists of the far lists
        for i in range(p.nodes.shape[0]):
            near = set(p.ncand[p.nptr[i]:p.nptr[i + 1]].tolist())
            assert near <= set(p.cand[p.ptr[i]:p.ptr[i + 1]].tolist())


def test_nodes_let_go_of_a_deleted_contact_segment():
    """A block pressed onto a plate; the plate elements under it are deleted: every
    node held by one of them lets go at once (no current segment that is dead, no
    held depth, entry or pass-through state left), keeps its side memory, and the
    next cycles report no pass-through against the deleted segments (before, in
    the eroding hollow block at 100 km/h, all three pass-through reports were
    against deleted wall segments)."""
    model, nb = _block_over_plate(0.5, sort_interval=10)
    a, _ = _pair(model, "single_surface", fs=0.2, fd=0.1)
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    v[:nb, 2] = -1.0
    for cycle in range(60):  # 0.6 mm down: the block's bottom nodes in contact
        a.add_forces(x, v, 0.02, cycle, np.zeros_like(x))
        x += 0.02 * v
    held = {k: p.oseg.copy() for k, p in enumerate(a.passes)}
    assert sum(int((o >= 0).sum()) for o in held.values()) > 0
    plate = model.shell_groups[0].elem_ids
    assert a.deactivate_elements(2, plate) > 0
    released = 0
    for k, p in enumerate(a.passes):
        assert np.all((p.oseg < 0) | p.seg_alive[np.maximum(p.oseg, 0)])
        gone = (held[k] >= 0) & ~p.seg_alive[np.maximum(held[k], 0)]
        released += int(gone.sum())
        assert np.all(p.ogap[gone] == 0.0) and np.all(p.odel[gone] == 0.0)
        assert np.all(p.oentry[gone] == 0) and np.all(p.othru[gone] == -1)
        assert np.any(p.nprev[gone] != 0.0)  # the side memory stays
    assert released > 0
    for cycle in range(60, 80):
        a.add_forces(x, v, 0.02, cycle, np.zeros_like(x))
        x += 0.02 * v
    assert a.n_pass_through == 0


def test_node_over_a_shared_edge_takes_the_lower_segment_in_any_list_order():
    """A node exactly over the edge shared by two coplanar segments is inside
    both (within the projection tolerance) at the same distance; it is given
    the lower-numbered one whatever the order of its candidate list, so the
    result does not depend on the bucket sort."""
    xp, cp = plate_mesh((2, 1), (20.0, 10.0), (-10.0, -5.0, 0.0))
    pts = np.array([[0.0, 0.0, 0.3]])
    model = assemble_model([PartSpec(1, pts, np.zeros((0, 8), np.int32)),
                            PartSpec(2, xp, cp, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                     1e-6, 1.0)])
    cd = ContactDef(cid=1, kind="nodes_to_surface", slave=Ref(kind="nodes", nodes=np.array([0])),
                    master=Ref(kind="parts", pids=[2]))
    n = model.n_nodes
    got = []
    for reverse in (False, True):
        rt = ContactRuntime(cd, model, np.full(n, 1e-3), np.zeros(n, bool))
        f = np.zeros((n, 3))
        rt.add_forces(model.node_x0, np.zeros((n, 3)), 0.01, 0, f)
        p = rt.passes[0]
        assert sorted(p.ncand[:p.nptr[1]].tolist()) == [0, 1]
        if reverse:
            p.ncand[:2] = p.ncand[:2][::-1].copy()
        rt.add_forces(model.node_x0, np.zeros((n, 3)), 0.01, 1, f)
        got.append(int(p.oseg[0]))
    assert got == [0, 0]
