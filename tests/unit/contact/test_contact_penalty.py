"""Penalty force, stiffness options and friction of ContactRuntime (single steps)."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact import ContactRuntime
from hollowbody.mesh import block_mesh, plate_mesh
from hollowbody.model.model import ContactDef, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model, part_contact

E_BLOCK, NU = 0.01, 0.3
K_BLOCK = E_BLOCK / (3 * (1 - 2 * NU))


def _rigid_plate_and_node(z_node: float, tilt: float = 0.0, thickness: float = 0.0,
                          solid_plate: bool = True, **kw):
    """A rigid plate (solid slab or shell) and one slave node (node set) above its centre.

    tilt: rotation (rad) of the whole set-up about the x axis.
    Returns (model, runtime, node index, plate normal).
    """
    if solid_plate:
        xp, cp = block_mesh((4, 4, 1), (40.0, 40.0, 5.0), (-20.0, -20.0, -5.0))
        plate = PartSpec(2, xp, cp, "solid", "rigid", {"E": 210.0, "PR": 0.3}, 7.8e-6)
    else:
        xp, cp = plate_mesh((4, 4), (40.0, 40.0), (-20.0, -20.0, 0.0))
        plate = PartSpec(2, xp, cp, "shell", "rigid", {"E": 210.0, "PR": 0.3}, 7.8e-6,
                         thickness)
    node = PartSpec(1, np.array([[1.0, 2.0, z_node]]), np.zeros((0, 8), np.int32), "solid")
    model = assemble_model([node, plate])
    c, s = np.cos(tilt), np.sin(tilt)
    rot = np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    model.node_x0 = model.node_x0 @ rot.T
    cd = ContactDef(cid=7, kind="nodes_to_surface",
                    slave=SurfaceRef(kind="nodes", nodes=np.array([0])),
                    master=SurfaceRef(kind="parts", pids=[2]), **kw)
    mass = np.full(model.n_nodes, 1.0e-3)
    rigid = np.ones(model.n_nodes, bool)
    rigid[0] = False
    rt = ContactRuntime(cd, model, mass, rigid)
    return model, rt, 0, rot @ np.array([0.0, 0.0, 1.0])


def _one_call(model, rt, dt=1.0e-3, v=None):
    f = np.zeros((model.n_nodes, 3))
    v = np.zeros((model.n_nodes, 3)) if v is None else v
    rt.add_forces(model.node_x0, v, dt, 0, f)
    return f


@pytest.mark.parametrize("tilt", [0.0, 0.4])
def test_node_on_rigid_plane_force_is_k_g_along_normal(tilt):
    g = 0.3
    model, rt, i, n = _rigid_plate_and_node(-g, tilt, sofscl=0.1, soft=0)
    f = _one_call(model, rt)
    # node set without elements: the rigid segment's SOFT=0 stiffness alone
    e, nu = 210.0, 0.3
    k_seg = e / (3 * (1 - 2 * nu)) * 100.0**2 / 500.0  # K A^2 / V, 10x10x5 element
    k = model.controls.slsfac * k_seg
    np.testing.assert_allclose(f[i], k * g * n, rtol=1e-9)
    assert rt.n_active == 1
    np.testing.assert_allclose(rt.slave_force, f[i])
    np.testing.assert_allclose(rt.master_force, -f[i])
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-12)


def test_no_force_when_separated_or_released():
    model, rt, i, _ = _rigid_plate_and_node(0.01)
    assert np.all(_one_call(model, rt) == 0.0) and rt.n_active == 0
    # deeper than penmax * element depth (0.4 * 5 mm): released
    model, rt, i, _ = _rigid_plate_and_node(-2.2)
    assert np.all(_one_call(model, rt) == 0.0)


def test_two_sided_shell_with_thickness_pushes_to_the_near_side():
    t = 2.0
    for z, sign in [(0.4, 1.0), (-0.4, -1.0)]:
        model, rt, i, _ = _rigid_plate_and_node(z, thickness=t, solid_plate=False)
        f = _one_call(model, rt)
        assert np.sign(f[i, 2]) == sign
        k = f[i, 2] / (sign * (t / 2 - abs(z)))
        assert k > 0
    model, rt, i, _ = _rigid_plate_and_node(1.01, thickness=t, solid_plate=False)
    assert np.all(_one_call(model, rt) == 0.0)


def _block_on_rigid_plate(gap=0.2, **kw):
    xb, cb = block_mesh((1, 1, 1), (10.0, 10.0, 10.0), (-5.0, -5.0, -gap))
    xp, cp = block_mesh((4, 4, 1), (40.0, 40.0, 5.0), (-20.0, -20.0, -5.0))
    model = assemble_model([PartSpec(1, xb, cb, "solid", "elastic", {"E": E_BLOCK, "PR": NU}),
                            PartSpec(2, xp, cp, "solid", "rigid", {"E": 210.0, "PR": 0.3})])
    mass = np.full(model.n_nodes, 2.0e-4)
    rigid = np.zeros(model.n_nodes, bool)
    rigid[8:] = True
    rt = ContactRuntime(part_contact(1, "nodes_to_surface", [1], [2], **kw), model, mass, rigid)
    return model, rt, mass


def test_soft0_uses_minimum_of_node_and_segment_stiffness():
    model, rt, mass = _block_on_rigid_plate(0.2)
    f = _one_call(model, rt)
    k_node = K_BLOCK * 100.0**2 / 1000.0  # block face A^2 / V
    expect = 0.1 * k_node * 0.2
    bottom = np.nonzero(model.node_x0[:8, 2] < 0)[0]
    np.testing.assert_allclose(f[bottom, 2], expect, rtol=1e-9)
    assert rt.n_active == 4
    # SFS / SFM scale the two sides before the minimum
    model, rt, mass = _block_on_rigid_plate(0.2, sfs=3.0)
    np.testing.assert_allclose(_one_call(model, rt)[bottom, 2], 3 * expect, rtol=1e-9)


def test_soft1_is_max_of_soft0_and_mass_based():
    dt = 1.0e-3
    model, rt, mass = _block_on_rigid_plate(0.2, soft=1, sofscl=0.1)
    f = _one_call(model, rt, dt)
    bottom = np.nonzero(model.node_x0[:8, 2] < 0)[0]
    k0 = 0.1 * K_BLOCK * 100.0**2 / 1000.0
    k1 = 0.1 * 0.5 * 2.0e-4 / dt**2  # deformable side's mass (master is rigid)
    assert k1 > k0
    np.testing.assert_allclose(f[bottom, 2], k1 * 0.2, rtol=1e-9)
    # a longer time step: the SOFT=0 value wins (0.08 ms: k1 = 1.6e-3 < k0 = 8.3e-3
    # kN/mm, and k0 dt^2 / m = 0.27 is below the stability cap, which it must not meet)
    model, rt, mass = _block_on_rigid_plate(0.2, soft=1, sofscl=0.1)
    np.testing.assert_allclose(_one_call(model, rt, 0.08)[bottom, 2], k0 * 0.2, rtol=1e-9)


def test_friction_stick_then_slip():
    dt = 1.0e-3
    model, rt, mass = _block_on_rigid_plate(0.2, fs=0.5, fd=0.3, dc=0.0)
    bottom = np.nonzero(model.node_x0[:8, 2] < 0)[0]
    v = np.zeros((model.n_nodes, 3))
    k = 0.1 * K_BLOCK * 100.0**2 / 1000.0
    fn = k * 0.2
    v[:8, 0] = 1.0e-3  # tiny slide: stick spring k * v dt, below mu F_n
    f = _one_call(model, rt, dt, v)
    np.testing.assert_allclose(f[bottom, 0], -k * 1.0e-6, rtol=1e-9)
    v[:8, 0] = 500.0  # large slide (k v dt > mu F_n): capped at mu F_n (DC = 0 -> mu = FS)
    f = np.zeros_like(f)
    rt.add_forces(model.node_x0, v, dt, 1, f)
    np.testing.assert_allclose(f[bottom, 0], -0.5 * fn, rtol=1e-9)
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-15)


def test_friction_exponential_decay():
    model, rt, mass = _block_on_rigid_plate(0.2, fs=0.5, fd=0.3, dc=2.0)
    bottom = np.nonzero(model.node_x0[:8, 2] < 0)[0]
    v = np.zeros((model.n_nodes, 3))
    v[:8, 1] = 5.0
    # k v dt = 4.2e-3 >> mu F_n = 6.7e-4 kN: sliding (dt 0.1 ms: k dt^2 / m = 0.4, a
    # stable spring, below the stability cap)
    f = _one_call(model, rt, 0.1, v)
    fn = 0.1 * K_BLOCK * 100.0**2 / 1000.0 * 0.2
    mu = 0.3 + 0.2 * np.exp(-2.0 * 5.0)
    np.testing.assert_allclose(f[bottom, 1], -mu * fn, rtol=1e-9)


def test_viscous_damping_adds_to_approach():
    dt = 1.0e-3
    model, rt, mass = _block_on_rigid_plate(0.2, vdc=20.0)
    bottom = np.nonzero(model.node_x0[:8, 2] < 0)[0]
    v = np.zeros((model.n_nodes, 3))
    v[:8, 2] = -0.1
    f = _one_call(model, rt, dt, v)
    k = 0.1 * K_BLOCK * 100.0**2 / 1000.0
    c = 0.2 * 2.0 * 2.0e-4 * np.sqrt(k / 2.0e-4)
    np.testing.assert_allclose(f[bottom, 2], k * 0.2 + c * 0.1, rtol=1e-9)


def test_strongly_warped_master_segment_is_found():
    # saddle quad: corners at z = +-1 on a 2 x 2 square, surface z = xi * eta
    quad = np.array([[-1.0, -1.0, 1.0], [1.0, -1.0, -1.0], [1.0, 1.0, 1.0], [-1.0, 1.0, -1.0]])
    xi = eta = 0.8
    node = np.array([[xi, eta, xi * eta - 0.05]])
    model = assemble_model([
        PartSpec(1, node, np.zeros((0, 8), np.int32)),
        PartSpec(2, quad, np.array([[0, 1, 2, 3]]), "shell", "elastic", {"E": 0.1, "PR": 0.3},
                 1e-6, 0.2)])
    cd = ContactDef(cid=1, kind="nodes_to_surface",
                    slave=SurfaceRef(kind="nodes", nodes=np.array([0])),
                    master=SurfaceRef(kind="parts", pids=[2]))
    rt = ContactRuntime(cd, model, np.full(5, 1e-3), np.zeros(5, bool))
    f = _one_call(model, rt)
    assert rt.n_active == 1
    # about along the surface normal (-eta, -xi, 1) / |.| there (node below:
    # pushed down; the closest point is a little off (xi, eta))
    n = np.array([-eta, -xi, 1.0]) / np.sqrt(1 + xi**2 + eta**2)
    np.testing.assert_allclose(f[0] / np.linalg.norm(f[0]), -n, atol=0.03)
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-15)


def test_two_sided_shell_remembers_the_side_a_node_came_from():
    # 1 mm rigid shell plate (10 x 10 mm segments): reach 0.5 mm, release
    # 0.4 * sqrt(A) = 4 mm past the mid-surface
    model, rt, i, _ = _rigid_plate_and_node(0.3, thickness=1.0, solid_plate=False)
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    fz = []
    for cycle, z in enumerate([0.3, -0.2, -1.0, -4.5]):
        x[i, 2] = z
        f = np.zeros_like(x)
        rt.add_forces(x, v, 1e-3, cycle, f)
        fz.append(f[i, 2])
    k = fz[0] / 0.2
    np.testing.assert_allclose(fz[1:3], [k * 0.7, k * 1.5], rtol=1e-12)  # still pushed up
    assert fz[3] == 0.0  # released
    # a node arriving from below is pushed down
    model, rt, i, _ = _rigid_plate_and_node(-0.3, thickness=1.0, solid_plate=False)
    assert _one_call(model, rt)[i, 2] < 0.0
