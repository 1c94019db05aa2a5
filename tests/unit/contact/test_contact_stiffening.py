"""Deep-penetration stiffening, shell release depth and pass-through detection."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact import ContactRuntime
from hollowbody.contact.law import STIFFEN_FRACTION, deep_stiffness, penalty_force, release_depth
from hollowbody.mesh import plate_mesh
from hollowbody.model.model import ContactDef, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model, explicit_run

# --- the force law (penalty.penalty_force, penalty.deep_stiffness) ------------------

K, G1, RAMP = 0.01, 2.0, 0.5  # kN/mm, mm (start of the stiffened zone), mm
MASS = 1.0e-4  # kg, slave node mass


def _total(kx: float, e: float) -> float:
    """The stiffening force of a monotonic loading to e at constant extra stiffness kx."""
    return kx * e * e / (2 * RAMP) if e <= RAMP else kx * (e - 0.5 * RAMP)


def test_force_is_linear_up_to_the_stiffening_depth():
    for g in (0.0, 0.5, 1.9, 2.0):
        fn, fd = penalty_force(g, g, 0.0, K, 5.0, G1, RAMP)
        assert fn == pytest.approx(K * g, rel=1e-15) and fd == 0.0


def test_stiffened_zone_ramps_in_and_grows_incrementally():
    kd = 5.0
    kx = kd - K
    # monotonic loading in small steps follows the total form (no kink at g1)
    fd, g_prev = 0.0, G1
    for g in np.linspace(G1, G1 + 1.0, 201)[1:]:
        fn, fd = penalty_force(g, g_prev, fd, K, kd, G1, RAMP)
        g_prev = g
        assert fd == pytest.approx(_total(kx, g - G1), rel=1e-9, abs=1e-12)
    assert fn == pytest.approx(K * (G1 + 1.0) + _total(kx, 1.0), rel=1e-9)
    # the step falls 10x (kd 100x) at a fixed gap: no jump ...
    g = G1 + 1.0
    fn2, fd2 = penalty_force(g, g, fd, K, 100 * kd, G1, RAMP)
    assert fd2 == pytest.approx(fd, rel=1e-12)
    # ... the next increments are stiffer (full stiffness beyond the ramp)
    fn3, fd3 = penalty_force(g + 0.01, g, fd2, K, 100 * kd, G1, RAMP)
    assert fd3 - fd2 == pytest.approx((100 * kd - K) * 0.01, rel=1e-9)
    # the step grows back: capped at the total form with the smaller kx (dissipative drop)
    fn4, fd4 = penalty_force(g + 0.01, g + 0.01, fd3, K, kd, G1, RAMP)
    assert fd4 == pytest.approx(_total(kx, 1.01), rel=1e-12) and fd4 < fd3
    # unloading below g1: gone; never negative
    assert penalty_force(G1 - 0.01, g, fd4, K, kd, G1, RAMP)[1] == 0.0
    assert penalty_force(G1 + 0.6, G1 + 1.0, 0.0, K, kd, G1, RAMP)[1] == 0.0
    # no stiffening when kd <= k
    assert penalty_force(G1 + 1.0, G1, 0.0, K, 0.5 * K, G1, RAMP) == (K * (G1 + 1.0), 0.0)


def test_deep_stiffness_is_the_nodal_stability_bound():
    dt, limit = 1e-3, 0.5
    mloc = np.array([1e-4, 2e-4, 2e-4, 4e-4, 4e-4, np.inf])
    wprev = np.array([1.0, 0.5, 3.0, 4.0, 1.0, 9.0])
    # node 0 against segment (1, 2, 3, 4): m_j / max(W_j, 1) smallest for node 2 (2e-4 / 3)
    kd = deep_stiffness(0, 1, 2, 3, 4, 0.25, 0.25, 0.25, 0.25, mloc, wprev, limit, dt)
    assert kd == pytest.approx(0.5 * limit * (2e-4 / 3.0) / dt**2, rel=1e-12)
    # corners with zero weight do not count; a rigid segment leaves the node alone
    kd = deep_stiffness(0, 1, 2, 3, 4, 0.5, 0.0, 0.0, 0.5, mloc, wprev, limit, dt)
    assert kd == pytest.approx(0.5 * limit * 1e-4 / dt**2, rel=1e-12)
    kd = deep_stiffness(0, 5, 5, 5, 5, 0.25, 0.25, 0.25, 0.25, mloc, wprev, limit, dt)
    assert kd == pytest.approx(0.5 * limit * 1e-4 / dt**2, rel=1e-12)
    # all rigid: no stiffening
    assert deep_stiffness(5, 5, 5, 5, 5, 1.0, 0.0, 0.0, 0.0, mloc, wprev, limit, dt) == 0.0
    # the contact spring alone on a free node: omega dt = sqrt(limit / 2)
    kd = deep_stiffness(0, 5, 5, 5, 5, 0.25, 0.25, 0.25, 0.25, mloc, np.zeros(6), limit, dt)
    assert np.sqrt(kd / mloc[0]) * dt == pytest.approx(np.sqrt(limit / 2), rel=1e-12)


def test_release_depth_of_shells_is_at_least_the_reach():
    assert release_depth(1.6, 2.0, True) == 2.0  # 4 mm shell, 4 mm segments
    assert release_depth(4.0, 0.5, True) == 4.0  # 1 mm shell, 10 mm segments
    assert release_depth(1.6, 2.0, False) == 1.6  # solid faces: penmax * V / A


# --- a node against a thick rigid shell ---------------------------------------------


def _thick_rigid_plate(z_nodes: np.ndarray, e_plate: float = 210.0, soft: int = 0):
    """4 mm rigid shell plate (4 x 4 mm segments, mid-surface z = 0) and free slave nodes.

    Returns (model, runtime, node mass (n,), rigid (n,) bool, number of slave nodes).
    """
    xp, cp = plate_mesh((10, 10), (40.0, 40.0), (-20.0, -20.0, 0.0))
    ns = len(z_nodes)
    xs = np.column_stack([np.linspace(-8.7, 8.3, ns), np.linspace(-5.9, 6.1, ns), z_nodes])
    model = assemble_model([
        PartSpec(1, xs, np.zeros((0, 8), np.int32)),
        PartSpec(2, xp, cp, "shell", "rigid", {"E": e_plate, "PR": 0.3}, 7.8e-6, 4.0)])
    cd = ContactDef(cid=3, kind="nodes_to_surface",
                    slave=SurfaceRef(kind="nodes", nodes=np.arange(ns)),
                    master=SurfaceRef(kind="parts", pids=[2]), soft=soft)
    mass = np.full(model.n_nodes, MASS)
    rigid = np.arange(model.n_nodes) >= ns
    return model, ContactRuntime(cd, model, mass, rigid), mass, rigid, ns


def test_node_past_the_mid_surface_of_a_thick_shell_is_still_pushed_back():
    # reach 2 mm; penmax * sqrt(A) = 1.6 mm would release a node 1.8 mm past the
    # mid-surface inside the shell, where the far side would catch it and push it on
    model, rt, mass, rigid, ns = _thick_rigid_plate(np.array([1.5]))
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    fz = []
    for cycle, z in enumerate([1.5, -1.0, -1.8]):
        x[0, 2] = z
        f = np.zeros_like(x)
        rt.add_forces(x, v, 1e-3, cycle, f)
        fz.append(f[0, 2])
    assert min(fz) > 0.0  # pushed up (the side it came from) all the way
    assert rt.n_pass_through == 0 and rt.pop_events() == []
    # beyond the far contact surface (2 mm past the mid-surface): released, reported
    x[0, 2] = -2.05
    f = np.zeros_like(x)
    rt.add_forces(x, v, 1e-3, 3, f)
    assert np.all(f == 0.0)
    assert rt.n_pass_through == 1 and rt.pass_through_nodes == {1}
    (ev,) = rt.pop_events()
    assert ev["contact"] == 3 and ev["node"] == 1 and ev["segment_part"] == 2
    assert ev["segment_element"] >= 2001 and ev["time_ms"] == pytest.approx(4e-3)
    assert "node 1" in ev["message"] and "contact 3" in ev["message"]
    assert rt.pop_events() == []  # reported once


@pytest.mark.parametrize("stiffen", [True, False, None])
def test_light_nodes_pressed_hard_onto_a_soft_thick_plate(stiffen):
    # A row of light nodes (0.1 g) pushed with 1 N each onto a 4 mm rigid shell whose
    # penalty spring is very soft (E = 0.1 MPa): k (reach + release depth) = 1e-4 kN
    # is 10x less than the push. Without the stiffened zone they pass through
    # (and are reported); with it they stop within the shell's contact thickness.
    # None: the contact as built (shells only, the zone on by default, docs/contact.md)
    z0 = np.full(5, 2.05)
    model, rt, mass, rigid, ns = _thick_rigid_plate(z0, e_plate=1e-4)
    if stiffen is None:
        stiffen = True
    else:
        rt.set_stiffening(STIFFEN_FRACTION if stiffen else 1.0)
    f_ext = np.zeros((model.n_nodes, 3))
    f_ext[:ns, 2] = -1e-3
    zmin = []
    explicit_run([rt], model.node_x0, np.zeros((model.n_nodes, 3)), mass, 1e-3, 4000,
                 fixed=rigid, f_ext=f_ext,
                 callback=lambda step, x, v: zmin.append(x[:ns, 2].min()))
    if stiffen:
        # stopped in the stiffened zone, past g1 = 0.5 (reach + release) = 2 mm,
        # within ~0.1 mm (kd = 0.25 m / dt^2, one spring per node, ramped in over 1 mm)
        assert min(zmin) > -0.5
        assert rt.n_pass_through == 0
    else:
        assert min(zmin) < -10.0
        assert rt.n_pass_through == ns and len(rt.pop_events()) == ns
