"""Elastic cantilever strip under a small tip load, quasi-static, against beam theory."""

import numpy as np
import pytest
from shell_driver import ShellDriver, elastic, plate_mesh, section

E, RHO = 210.0, 7.85e-6


def test_tip_deflection_matches_beam_theory():
    # 100 x 10 x 2 mm strip, 20 x 2 shells, clamped at x = 0, nu = 0 so that the plate
    # strip and the beam agree (no anticlastic / plate-strip stiffening to argue about)
    length, width, t = 100.0, 10.0, 2.0
    x, conn = plate_mesh(length, width, 20, 2)
    d = ShellDriver(x, conn, elastic(E, 0.0, RHO), section(5), thickness=t, damping=2.0)
    root = np.isclose(x[:, 0], 0.0)
    tip = np.isclose(x[:, 0], length)
    d.fix_v[root] = True
    d.fix_w[root] = True
    p = 1.0e-3  # kN: tip deflection ~ 0.24 mm = 0.12 t, a linear problem
    share = np.where(np.isclose(x[tip, 1], width / 2), 0.5, 0.25)

    def load(t_now, drv):
        f = np.zeros_like(drv.x)
        f[tip, 2] = p * share * min(t_now / 5.0, 1.0)
        return f, np.zeros_like(drv.x)

    d.load = load
    d.run(40.0)  # ~6 periods of the first mode, damping 2/ms ~ 0.95 of critical
    inertia = width * t ** 3 / 12.0
    shear = p * length / (5.0 / 6.0 * E / 2.0 * width * t)
    exact = p * length ** 3 / (3.0 * E * inertia) + shear
    # one-point Mindlin elements with 20 along the span: discretisation error ~1/(4 N^2)
    # < 0.1 %; 1 % leaves room for the residual dynamics of the damped run
    assert d.x[tip, 2].mean() == pytest.approx(exact, rel=0.01)
    assert np.abs(d.x[tip, 2] - d.x[tip, 2].mean()).max() < 1e-6 * exact
    assert d.rt.hourglass_energy < 1e-3 * d.rt.internal_energy
