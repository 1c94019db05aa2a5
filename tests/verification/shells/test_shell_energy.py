"""Energy conservation of a freely vibrating simply supported plate strip (no damping)."""

import numpy as np
import pytest
from shell_driver import ShellDriver, elastic, plate_mesh, section

E, NU, RHO = 210.0, 0.3, 7.85e-6


def test_free_vibration_conserves_energy():
    length, width, t = 100.0, 20.0, 2.0
    x, conn = plate_mesh(length, width, 20, 4)
    d = ShellDriver(x, conn, elastic(E, NU, RHO), section(5), thickness=t)
    ends = np.isclose(x[:, 0], 0.0) | np.isclose(x[:, 0], length)
    d.fix_v[ends, 2] = True  # simply supported ends
    d.fix_v[np.isclose(x[:, 0], 0.0), 0] = True
    d.fix_v[0, 1] = True
    # first bending mode: w = a sin(pi x / L), rotation theta_y = -dw/dx
    k = np.pi / length
    v0 = 0.5  # mm/ms
    d.v[:, 2] = v0 * np.sin(k * x[:, 0])
    d.w[:, 1] = -v0 * k * np.cos(k * x[:, 0])
    d.v[d.fix_v] = 0.0
    e0 = d.kinetic_energy()
    omega = k * k * np.sqrt(E * t ** 2 / (12 * (1 - NU ** 2) * RHO))  # plate strip
    period = 2 * np.pi / omega
    ke_prev = d.kinetic_energy()
    totals, internal = [], []
    while d.t < 3 * period:
        d.step()
        ke = d.kinetic_energy()
        total = 0.5 * (ke + ke_prev) + d.rt.internal_energy + d.rt.hourglass_energy
        ke_prev = ke
        totals.append(total)
        internal.append(d.rt.internal_energy)
    totals = np.array(totals)
    # the energy swings between kinetic and internal ...
    assert max(internal) == pytest.approx(e0, rel=0.05)
    # ... and the sum stays within 0.5 % (central differences with half-step kinetic
    # energies: O((omega dt)^2) for the resolved mode, hypoelastic rate form)
    assert np.abs(totals / e0 - 1.0).max() < 5e-3
    assert d.rt.hourglass_energy < 1e-4 * e0  # the mode has no hourglass content
