"""Single-surface (self) contact of shells: thickness offsets, neighbour exclusion."""

from __future__ import annotations

import numpy as np

from hollowbody.contact import ContactRuntime
from hollowbody.mesh import plate_mesh
from hollowbody.model.model import ContactDef, ShellGroup, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model, explicit_run


def _self_contact(model, **kw):
    cd = ContactDef(cid=3, kind="single_surface", slave=SurfaceRef(kind="parts", pids=[1]),
                    master=None, **kw)
    n = model.n_nodes
    return ContactRuntime(cd, model, np.full(n, 1e-4), np.zeros(n, bool))


def _two_plates(gap, thickness=1.5):
    x1, c1 = plate_mesh((4, 4), (8.0, 8.0), (0.0, 0.0, 0.0))
    x2, c2 = plate_mesh((3, 3), (6.0, 6.0), (1.0, 1.0, gap))
    x = np.concatenate([x1, x2])
    conn = np.concatenate([c1, c2 + x1.shape[0]])
    return assemble_model([PartSpec(1, x, conn, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                    1e-6, thickness)]), x1.shape[0]


def test_overlapping_shells_of_one_part_are_pushed_apart():
    model, n1 = _two_plates(1.0)  # 1.0 apart, contact distance (1.5 + 1.5) / 2
    rt = _self_contact(model)
    f = np.zeros((model.n_nodes, 3))
    rt.add_forces(model.node_x0, np.zeros_like(model.node_x0), 1e-3, 0, f)
    assert rt.n_active > 0
    assert np.all(f[:n1, 2] <= 0.0) and np.all(f[n1:, 2] >= 0.0)
    assert f[n1:, 2].sum() > 0.0
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-15)
    np.testing.assert_allclose(f[:, :2], 0.0, atol=1e-15)  # flat: purely normal


def test_no_contact_between_plates_further_than_thickness():
    model, _ = _two_plates(1.6)
    rt = _self_contact(model)
    f = np.zeros((model.n_nodes, 3))
    rt.add_forces(model.node_x0, np.zeros_like(model.node_x0), 1e-3, 0, f)
    assert rt.n_active == 0 and np.all(f == 0.0)


def test_t_junction_of_thick_walls_has_no_spurious_contact():
    # wall A in y = 0, wall B in x = 2 sharing the junction line; 0.5 mm
    # elements, 1.5 mm walls: neighbours are within contact distance at t = 0
    xa, ca = plate_mesh((8, 4), (4.0, 2.0), (0.0, 0.0, 0.0))
    xa = xa[:, [0, 2, 1]]  # plane y = 0 (x, z)
    xb, cb = plate_mesh((4, 4), (2.0, 2.0), (0.0, 0.0, 0.0))
    xb = np.column_stack([np.full(xb.shape[0], 2.0), xb[:, 0] - 1.0, xb[:, 1]])
    x = np.concatenate([xa, xb])
    conn = np.concatenate([ca, cb + xa.shape[0]])
    # merge coincident nodes (the junction line)
    xr = np.round(x, 9)
    _, first, inv = np.unique(xr, axis=0, return_index=True, return_inverse=True)
    x = x[np.sort(first)]
    remap = np.argsort(np.argsort(first))[inv.ravel()]
    conn = remap[conn]
    model = assemble_model([PartSpec(1, x, conn, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                     1e-6, 1.5)])
    assert isinstance(model.shell_groups[0], ShellGroup)
    rt = _self_contact(model)
    assert rt.passes[0].ex_seg.size > 0  # neighbours excluded
    f = np.zeros((model.n_nodes, 3))
    rt.add_forces(model.node_x0, np.zeros_like(model.node_x0), 1e-3, 0, f)
    assert rt.n_active == 0 and np.all(f == 0.0)


def test_self_contact_bounce_conserves_momentum_and_returns_energy():
    model, n1 = _two_plates(2.0, thickness=1.0)
    n = model.n_nodes
    mass = np.full(n, 1e-4)
    rt = ContactRuntime(ContactDef(cid=1, kind="single_surface",
                                   slave=SurfaceRef(kind="parts", pids=[1]), master=None),
                        model, mass, np.zeros(n, bool))
    v0 = np.zeros((n, 3))
    v0[n1:, 2] = -0.5
    peak = [0]

    def cb(step, x, v):
        peak[0] = max(peak[0], rt.n_active)

    x, v = explicit_run([rt], model.node_x0, v0, mass, 1e-3, 6000, callback=cb)
    assert peak[0] > 0 and rt.n_active == 0
    np.testing.assert_allclose((mass[:, None] * v).sum(axis=0), (mass[:, None] * v0).sum(axis=0),
                               atol=1e-16)
    e0 = 0.5 * (mass[:, None] * v0**2).sum()
    assert abs(rt.energy) < 1e-4 * e0
    assert abs(0.5 * (mass[:, None] * v**2).sum() / e0 - 1.0) < 1e-3


def test_thick_shell_bent_at_an_element_edge_is_not_in_self_contact():
    # 1 mm elements, 1.5 mm thick: folded by 90 degrees along x = 2, the node
    # 1 mm up the fold is 1 mm from the flat segment next to the fold line
    x, conn = plate_mesh((5, 2), (5.0, 2.0))
    model = assemble_model([PartSpec(1, x, conn, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                     1e-6, 1.5)])
    rt = _self_contact(model)
    folded = model.node_x0.copy()
    up = folded[:, 0] > 2.0
    folded[up, 2] = folded[up, 0] - 2.0
    folded[up, 0] = 2.0
    f = np.zeros_like(folded)
    rt.add_forces(folded, np.zeros_like(folded), 1e-3, 1, f)
    assert rt.n_active == 0 and np.all(f == 0.0)


def test_ring_exclusions_of_a_regular_plate():
    from hollowbody.contact.exclusion import merge_csr, ring_exclusions

    x, conn = plate_mesh((4, 4), (4.0, 4.0))
    nodes = np.arange(x.shape[0], dtype=np.int32)
    ptr, seg = ring_exclusions(nodes, conn, x.shape[0])
    centre = 12  # (2, 2): 4 own segments, 12 around them
    assert ptr[centre + 1] - ptr[centre] == 12
    own = set(np.nonzero(np.any(conn == centre, axis=1))[0].tolist())
    assert not own & set(seg[ptr[centre]:ptr[centre + 1]].tolist())
    p2, s2 = merge_csr(ptr, seg, ptr, seg)
    np.testing.assert_array_equal(p2, ptr)
    np.testing.assert_array_equal(s2, seg)


def _hollow_grid(cell=10.0, ncell=(2, 2, 1), h=1.25):
    """Shell walls on every face of a grid of cubic cells (hollow structure)."""
    n = [int(round(c * cell / h)) for c in ncell]
    quads = []
    ax = [np.arange(k + 1) * h for k in n]
    walls = [np.arange(c + 1) * cell for c in ncell]
    for d in range(3):
        a, b = [e for e in range(3) if e != d]
        for w in walls[d]:
            for i in range(n[a]):
                for j in range(n[b]):
                    q = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[d], p[a], p[b] = w, ax[a][i + di], ax[b][j + dj]
                        q.append(p)
                    quads.append(q)
    pts = np.array(quads).reshape(-1, 3)
    uniq, inv = np.unique(np.round(pts, 6), axis=0, return_inverse=True)
    return uniq, inv.reshape(-1, 4).astype(np.int32)


def test_hollow_grid_junctions_give_no_force_at_start():
    x, conn = _hollow_grid()
    model = assemble_model([PartSpec(1, x, conn, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                     1e-6, 1.5)])
    rt = _self_contact(model)
    assert rt.n_initial_penetrations == 0
    f = np.zeros((model.n_nodes, 3))
    rt.add_forces(model.node_x0, np.zeros_like(model.node_x0), 1e-3, 0, f)
    assert rt.n_active == 0 and np.all(f == 0.0)
    # squeeze the top wall (z = 10) down onto the floor: the walls meet
    xs = model.node_x0.copy()
    xs[:, 2] *= 0.05
    rt.add_forces(xs, np.zeros_like(xs), 1e-3, 1, f)
    assert rt.n_active > 0
