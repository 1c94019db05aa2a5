"""Patch tests of the Belytschko-Lin-Tsay shell on the distorted MacNeal-Harder patch.

Membrane: a linear displacement field on the boundary gives the exact constant
stress in every element (interior nodes free, found by damped dynamics).
Bending: a constant-curvature rotation field (with the matching deflection)
gives the exact constant moments M = D (kappa_xx + nu kappa_yy), ... in every
element, whatever the distortion.
"""

import numpy as np
import pytest
from shell_driver import ShellDriver, elastic, patch_mesh, section

from hollowbody.elements.shell_bt_kinematics import bt_geometry

E, NU, RHO, T = 210.0, 0.3, 7.85e-6, 0.5


def plane_stress(exx, eyy, gxy):
    c = E / (1 - NU ** 2)
    return np.array([c * (exx + NU * eyy), c * (eyy + NU * exx), E / (2 * (1 + NU)) * gxy])


def test_membrane_patch_free_interior():
    x, conn, bnd = patch_mesh()
    # damping near critical for the patch's lowest mode (~700 rad/ms)
    d = ShellDriver(x, conn, elastic(E, NU, RHO), section(3), thickness=T, damping=1000.0)
    grad = 1e-5 * np.array([[1.0, 0.5, 0.0], [0.5, -0.6, 0.0], [0.0, 0.0, 0.0]])
    t_load = 0.02
    mask = np.zeros((8, 3), dtype=bool)
    mask[bnd] = True
    d.prescribed = (mask, lambda t: (x @ grad.T) / t_load if t < t_load else 0.0 * x)
    d.fix_v[:, 2] = True
    d.fix_w[:] = True
    d.dt_fixed = t_load / np.ceil(t_load / (0.9 * d.dt_crit))  # the ramp ends on a step
    d.run(0.6)
    u = d.x - x
    assert u == pytest.approx(x @ grad.T, abs=5e-5 * np.abs(x @ grad.T).max())
    s = d.rt.stress
    exact = plane_stress(grad[0, 0], grad[1, 1], 2 * grad[0, 1])
    for e in range(5):
        assert s[e, [0, 1, 3]] == pytest.approx(exact, rel=1e-4)
        # equal to round-off in a linear analysis; here the remainder is second order
        # (rate form, finite strain and rotation during the transient): O(strain) = 1e-5
        assert s[e] == pytest.approx(s[0], rel=2e-5, abs=1e-9 * np.abs(exact).max())
    assert np.abs(s[:, [2, 4, 5]]).max() < 1e-9 * np.abs(exact).max()


def test_bending_patch_constant_curvature():
    x, conn, _ = patch_mesh()
    d = ShellDriver(x, conn, elastic(E, NU, RHO), section(5), thickness=T)
    kxx, kyy, kxy = 1e-4, -4e-5, 6e-5  # curvatures (1/mm), kxy engineering twist
    t_load = 0.01

    def rates(_t):
        # theta_y = kxx x + kxy y / 2, theta_x = -(kyy y + kxy x / 2); w = -(kxx x^2 + kyy y^2
        # + kxy x y) / 2 keeps the transverse shear zero (rates over t_load)
        px, py = x[:, 0], x[:, 1]
        v = np.zeros_like(x)
        w = np.zeros_like(x)
        v[:, 2] = -(kxx * px ** 2 + kyy * py ** 2 + kxy * px * py) / 2
        w[:, 0] = -(kyy * py + kxy * px / 2)
        w[:, 1] = kxx * px + kxy * py / 2
        return v / t_load, w / t_load

    mask = np.ones((8, 3), dtype=bool)
    d.prescribed = (mask, lambda t: rates(t)[0])
    d.prescribed_w = (mask, lambda t: rates(t)[1])
    d.dt_fixed = t_load / 200
    d.run(t_load * (1 - 1e-9))
    rt = d.rt
    z = rt.zeta * T / 2
    wk = rt.weights * T / 2
    dflex = E * T ** 3 / (12 * (1 - NU ** 2))
    m_exact = np.array([dflex * (kxx + NU * kyy), dflex * (kyy + NU * kxx),
                        dflex * (1 - NU) / 2 * kxy])
    for e in range(5):
        ml = (wk[:, None] * z[:, None] * rt.sig[e]).sum(axis=0)  # element axes
        n = (wk[:, None] * rt.sig[e]).sum(axis=0)
        e1, e2, *_ = bt_geometry(*[tuple(p) for p in d.x[conn[e]]])
        r = np.array([e1, e2])[:, :2].T  # columns: element axes in global xy
        mg = r @ np.array([[ml[0], ml[2]], [ml[2], ml[1]]]) @ r.T
        assert [mg[0, 0], mg[1, 1], mg[0, 1]] == pytest.approx(m_exact, rel=2e-3)
        # membrane forces only from the second-order (von Karman) strains of the slopes
        slope = 2e-3 * 24 * np.abs([kxx, kyy, kxy]).max() / 1e-4
        assert np.abs(n).max() < E * T * slope ** 2
