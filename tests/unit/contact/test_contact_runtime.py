"""ContactRuntime set-up: kinds, sides, release depth, resultants, errors."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact import ContactRuntime, build_surface
from hollowbody.errors import UserInputError
from hollowbody.mesh import block_mesh, plate_mesh
from hollowbody.model.model import ContactDef, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model, part_contact


def _rigid_cube_on_block(depth=0.3):
    """Small rigid cube (pid 2) pressed into the top of a large deformable block (pid 1)."""
    xb, cb = block_mesh((4, 4, 2), (40.0, 40.0, 10.0), (-20.0, -20.0, -10.0))
    xc, cc = block_mesh((1, 1, 1), (5.0, 5.0, 5.0), (2.5, 2.5, -depth))  # between nodes
    model = assemble_model([PartSpec(1, xb, cb, "solid", "elastic", {"E": 0.01, "PR": 0.3}),
                            PartSpec(2, xc, cc, "solid", "rigid", {"E": 210.0, "PR": 0.3})])
    n = model.n_nodes
    rigid = np.zeros(n, bool)
    rigid[xb.shape[0]:] = True
    return model, np.full(n, 1e-3), rigid, xb.shape[0]


def _call(model, rt, dt=1e-3):
    f = np.zeros((model.n_nodes, 3))
    rt.add_forces(model.node_x0, np.zeros((model.n_nodes, 3)), dt, 0, f)
    return f


def test_surface_to_surface_second_pass_catches_master_nodes():
    # the cube's corners sit inside one block face: only the symmetric pass
    # (master nodes vs slave segments) sees them
    model, mass, rigid, nb = _rigid_cube_on_block()
    one = ContactRuntime(part_contact(1, "nodes_to_surface", [1], [2]), model, mass, rigid)
    assert np.all(_call(model, one) == 0.0)
    two = ContactRuntime(part_contact(1, "surface_to_surface", [1], [2]), model, mass, rigid)
    f = _call(model, two)
    assert two.n_active == 4 and len(two.passes) == 2
    assert np.all(f[nb:][model.node_x0[nb:, 2] < 0, 2] > 0.0)  # cube pushed up
    np.testing.assert_allclose(two.master_force, f[nb:].sum(axis=0), atol=1e-15)
    np.testing.assert_allclose(two.slave_force, f[:nb].sum(axis=0), atol=1e-15)
    assert two.slave_force[2] < 0.0
    np.testing.assert_allclose(two.slave_force, -two.master_force)


def test_set_penmax_changes_release_depth():
    model, mass, rigid, nb = _rigid_cube_on_block(depth=3.0)  # 3 mm into 5 mm elements
    rt = ContactRuntime(part_contact(1, "surface_to_surface", [1], [2]), model, mass, rigid)
    assert rt.penmax == 0.4
    assert np.all(_call(model, rt) == 0.0)  # 3 mm > 0.4 * 5 mm: released
    rt.set_penmax(0.8)
    _call(model, rt)
    assert rt.n_active == 4


def test_segment_set_master_and_node_set_slave():
    xp, cp = plate_mesh((2, 2), (20.0, 20.0), (-10.0, -10.0, 0.0))
    pts = np.array([[0.0, 0.0, 0.2], [3.0, 1.0, -0.2]])
    model = assemble_model([PartSpec(1, pts, np.zeros((0, 8), np.int32)),
                            PartSpec(2, xp, cp, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                     1e-6, 1.0)])
    cd = ContactDef(cid=4, kind="nodes_to_surface",
                    slave=SurfaceRef(kind="nodes", nodes=np.array([0, 1])),
                    master=SurfaceRef(kind="segments", segments=cp + 2))
    n = model.n_nodes
    rt = ContactRuntime(cd, model, np.full(n, 1e-3), np.zeros(n, bool))
    f = _call(model, rt)
    assert rt.n_active == 2
    assert f[0, 2] > 0.0 and f[1, 2] < 0.0  # two-sided shell: each to its own side
    np.testing.assert_allclose(f[0, 2], -f[1, 2])
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-15)


def test_soft1_first_call_with_zero_dt_uses_soft0():
    model, mass, rigid, nb = _rigid_cube_on_block()
    a = ContactRuntime(part_contact(1, "surface_to_surface", [1], [2], soft=1), model, mass,
                       rigid)
    b = ContactRuntime(part_contact(1, "surface_to_surface", [1], [2], soft=0), model, mass,
                       rigid)
    np.testing.assert_allclose(_call(model, a, 0.0), _call(model, b, 0.0))
    assert np.abs(_call(model, a, 1e-4)).max() > np.abs(_call(model, b, 1e-4)).max()


def test_overlapping_separate_surfaces_are_reported():
    x1, c1 = plate_mesh((2, 2), (4.0, 4.0))
    x2, c2 = plate_mesh((2, 2), (4.0, 4.0), (0.0, 0.0, 0.5))
    model = assemble_model([PartSpec(1, np.concatenate([x1, x2]),
                                     np.concatenate([c1, c2 + x1.shape[0]]), "shell",
                                     "elastic", {"E": 0.1, "PR": 0.3}, 1e-6, 1.0)])
    cd = ContactDef(cid=1, kind="single_surface", slave=SurfaceRef(kind="all"), master=None)
    n = model.n_nodes
    rt = ContactRuntime(cd, model, np.full(n, 1e-3), np.zeros(n, bool))
    assert rt.n_initial_penetrations > 0


def test_errors():
    model, mass, rigid, nb = _rigid_cube_on_block()
    with pytest.raises(UserInputError):
        ContactRuntime(part_contact(1, "surface_to_surface", [1], None), model, mass, rigid)
    with pytest.raises(UserInputError):
        ContactRuntime(part_contact(1, "tied", [1], [2]), model, mass, rigid)
    cd = ContactDef(cid=1, kind="nodes_to_surface", slave=SurfaceRef(kind="parts", pids=[1]),
                    master=SurfaceRef(kind="nodes", nodes=np.array([0])))
    with pytest.raises(UserInputError):
        ContactRuntime(cd, model, mass, rigid)
    with pytest.raises(UserInputError):
        build_surface(SurfaceRef(kind="box"), model)


def test_deleted_elements_leave_the_contact():
    """Segments of eroded elements push no node (LS-DYNA removes them too): two
    nodes touching a 2 x 2 shell plate feel it until the elements under them
    are deactivated; the other elements' segments stay."""
    xp, cp = plate_mesh((2, 2), (20.0, 20.0), (-10.0, -10.0, 0.0))
    pts = np.array([[-5.0, -5.0, 0.2], [5.0, 5.0, 0.2]])  # above elements 1 and 4
    model = assemble_model([PartSpec(1, pts, np.zeros((0, 8), np.int32)),
                            PartSpec(2, xp, cp, "shell", "elastic", {"E": 0.1, "PR": 0.3},
                                     1e-6, 1.0)])
    cd = ContactDef(cid=4, kind="nodes_to_surface",
                    slave=SurfaceRef(kind="nodes", nodes=np.array([0, 1])),
                    master=SurfaceRef(kind="parts", pids=[2]))
    n = model.n_nodes
    rt = ContactRuntime(cd, model, np.full(n, 1e-3), np.zeros(n, bool))
    f = _call(model, rt)
    assert rt.n_active == 2 and f[0, 2] > 0.0 and f[1, 2] > 0.0
    under_first = int(model.shell_groups[0].elem_ids[0])
    assert rt.deactivate_elements(2, np.array([under_first])) == 1
    assert rt.deactivate_elements(2, np.array([under_first])) == 0  # already out
    f = _call(model, rt)
    assert rt.n_active == 1 and f[0, 2] == 0.0 and f[1, 2] > 0.0


def test_drop_dead_rebuilds_the_candidate_lists():
    from hollowbody.contact.runtime import _drop_dead

    ptr = np.array([0, 3, 3, 5, 5])
    cand = np.array([1, 2, 3, 2, 4], dtype=np.int32)
    alive = np.array([True, True, False, True, False])
    p, c = _drop_dead(ptr, cand, alive)
    assert p.tolist() == [0, 2, 2, 2, 2] and c.tolist() == [1, 3]
