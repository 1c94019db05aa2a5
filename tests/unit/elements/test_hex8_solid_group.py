"""SolidGroupRuntime: start-up call, objectivity, hourglass modes, erosion, time step."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.elements.hex8_kinematics import HG_BASE
from hollowbody.elements.solid_group import SolidGroupRuntime
from hollowbody.mesh import block_mesh
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, SolidGroup

MUSCLE_STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                          0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                       0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])


def elastic(e=0.01, nu=0.3, rho=1e-6):
    return MaterialDef(1, "elastic", rho, {"E": e, "PR": nu})


def rubber(km=1.0, mu=0.0):
    mat = MaterialDef(2, "rubber181", 1e-6, {"KM": km, "MU": mu, "G": 0.0, "SIGF": 0.0,
                                             "SGL": 1.0, "SW": 1.0, "ST": 1.0, "LCID": 7})
    return mat, {7: Curve(7, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}


def runtime(x, conn, mat, curves=None, **hg):
    g = SolidGroup(1, np.arange(1, len(conn) + 1), conn)
    return SolidGroupRuntime(g, mat, HourglassDef(0, **hg), curves or {}, x)


def rot_z(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_start_call_with_zero_dt_and_velocity():
    x, conn = block_mesh((2, 2, 2), (4.0, 4.0, 4.0))
    rt = runtime(x, conn, elastic())
    f = np.zeros_like(x)
    dt, i, neg = rt.add_forces(x.copy(), np.zeros_like(x), 0.0, f)
    c = math.sqrt(0.01 * 0.7 / (1.3 * 0.4) / 1e-6)
    # at rest the step keeps the linear bulk viscosity Q2 c (default Q2 0.06)
    assert dt == pytest.approx(2.0 / (c * (0.06 + math.sqrt(1.0 + 0.06**2))), rel=1e-12)
    assert 0 <= i < 8 and neg == -1
    assert np.all(f == 0.0) and np.all(rt.stress == 0.0)
    assert rt.internal_energy == 0.0 and rt.hourglass_energy == 0.0
    np.testing.assert_allclose(rt.mass, 1e-6 * 8.0)
    np.testing.assert_allclose(rt.wave_speed(), c)


def test_rigid_rotation_rotates_prestress_exactly():
    x0, conn = block_mesh((1, 1, 1), (1.0, 2.0, 1.5))
    rt = runtime(x0, conn, elastic(), qm=0.1)
    sig0 = np.array([0.3, -0.1, 0.2, 0.05, -0.02, 0.04]) * 1e-3
    rt.stress[0] = sig0
    n, dt = 90, 1e-3
    r_step = rot_z(0.5 * math.pi / n)
    x = x0.copy()
    f = np.zeros_like(x)
    for _ in range(n):
        x_new = x @ r_step.T
        v = (x_new - x) / dt
        x = x_new
        f[:] = 0.0
        rt.add_forces(x, v, dt, f)
    r = rot_z(0.5 * math.pi)
    s = sig0
    m = np.array([[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]])
    mr = r @ m @ r.T
    expected = [mr[0, 0], mr[1, 1], mr[2, 2], mr[0, 1], mr[1, 2], mr[2, 0]]
    np.testing.assert_allclose(rt.stress[0], expected, atol=1e-12 * np.abs(s).max())
    assert rt.volume[0] == pytest.approx(3.0, rel=1e-13)
    assert abs(rt.hourglass_energy) < 1e-25


def test_rubber_stress_follows_rotation():
    x0, conn = block_mesh((1, 1, 1))
    mat, curves = rubber()
    rt = runtime(x0, conn, mat, curves)
    stretch = np.diag([1.2, 1 / math.sqrt(1.2), 1 / math.sqrt(1.2)])
    f = np.zeros_like(x0)
    rt.add_forces(x0 @ stretch.T, np.zeros_like(x0), 0.0, f)
    s = rt.stress[0].copy()
    r = rot_z(0.7)
    rt.add_forces(x0 @ stretch.T @ r.T, np.zeros_like(x0), 0.0, f)
    m = np.array([[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]])
    mr = r @ m @ r.T
    expected = [mr[0, 0], mr[1, 1], mr[2, 2], mr[0, 1], mr[1, 2], mr[2, 0]]
    np.testing.assert_allclose(rt.stress[0], expected, atol=1e-12 * np.abs(s).max())


@pytest.mark.parametrize("ihq", [1, 4, 6])
def test_pure_hourglass_mode_gives_hourglass_force_but_no_strain(ihq):
    x0, conn = block_mesh((1, 1, 1), (2.0, 2.0, 2.0))
    rt = runtime(x0, conn, elastic(), ihq=ihq, qm=0.1)
    v = np.zeros_like(x0)
    for k in range(4):
        v[conn[0], k % 3] += 0.01 * HG_BASE[k]
    dt = 1e-4
    f = np.zeros_like(x0)
    for _ in range(3):
        f[:] = 0.0
        rt.add_forces(x0 + 1e-12 * v, v, dt, f)  # geometry (practically) unchanged
    assert np.abs(rt.stress).max() < 1e-15
    assert np.abs(f).max() > 0.0
    # hourglass forces oppose the hourglass motion and are self-equilibrated
    assert float((f * v).sum()) < 0.0
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-12 * np.abs(f).max())
    assert rt.hourglass_energy > 0.0


def test_viscous_hourglass_scaling():
    """a_h = QH rho c V^(2/3) / 4; f_a = -a_h sum_alpha q_alpha gamma_alpha,a."""
    h = 2.0
    x0, conn = block_mesh((1, 1, 1), (h, h, h))
    mat = elastic()
    rt = runtime(x0, conn, mat, ihq=2, qm=0.1)
    v = np.zeros_like(x0)
    v[conn[0], 2] = 0.01 * HG_BASE[0]
    f = np.zeros_like(x0)
    rt.add_forces(x0.copy(), v, 0.0, f)
    c = rt.wave_speed()[0]
    ah = 0.1 * 1e-6 * c * h**2 / 4.0
    expected = -ah * (8 * 0.01) * HG_BASE[0]  # q = v . h = 8 * 0.01 (cube: gamma = h)
    np.testing.assert_allclose(f[conn[0], 2], expected, rtol=1e-12)


def test_negative_volume_detected_and_erosion():
    x0, conn = block_mesh((3, 1, 1), (3.0, 1.0, 1.0))
    rt = runtime(x0, conn, elastic())
    x = x0.copy()
    top_of_middle = conn[1, 4:]
    x[top_of_middle, 2] = -0.5  # invert element 1 (0-based)
    f = np.zeros_like(x)
    dt, i, neg = rt.add_forces(x, np.zeros_like(x), 0.0, f)
    assert neg == 1
    assert rt.volume[1] <= 0.0
    rt.erode(np.array([neg]))
    assert not rt.alive[1]
    f[:] = 0.0
    dt, i, neg = rt.add_forces(x, np.zeros_like(x), 0.0, f)
    assert neg == -1 and i != 1 and np.isfinite(dt)


def test_all_eroded_returns_inf():
    x0, conn = block_mesh((1, 1, 1))
    rt = runtime(x0, conn, elastic())
    rt.erode(np.array([0]))
    f = np.zeros_like(x0)
    assert rt.add_forces(x0.copy(), np.zeros_like(x0), 0.0, f) == (np.inf, -1, -1)
    assert np.all(f == 0.0)


def test_bulk_viscosity_time_step_and_pressure():
    h = 1.0
    x0, conn = block_mesh((1, 1, 1), (h, h, h))
    mat = elastic()
    rt = runtime(x0, conn, mat, q1=1.5, q2=0.06)
    c = rt.wave_speed()[0]
    rate = -0.5  # 1/ms, uniaxial compression along z
    v = np.zeros_like(x0)
    v[:, 2] = rate * x0[:, 2]
    f = np.zeros_like(x0)
    dt, _, _ = rt.add_forces(x0.copy(), v, 0.0, f)
    # the quadratic term's tangent 2 Q1 l |tr D| (twice its secant) enters the step
    qv = 0.06 * c + 2.0 * 1.5 * h * abs(rate)
    assert dt == pytest.approx(h / (qv + math.sqrt(qv**2 + c**2)), rel=1e-12)
    q = 1e-6 * h * (1.5 * h * rate**2 - 0.06 * c * rate)
    # the pressure q resists the compression: it pushes the top face (z = h) up with
    # q * area (the stress itself is zero at dt = 0)
    top = x0[:, 2] > 0.5
    assert f[top, 2].sum() == pytest.approx(q * h * h, rel=1e-12)
