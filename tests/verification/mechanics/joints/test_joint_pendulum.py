"""Rigid pendulums on spherical and revolute joints under gravity (*LOAD_BODY_Z).

The pendulum: mass m = 1 kg, centre of mass d = 100 mm from the joint, radius of
gyration 30 mm about it (I_c = 900 kg*mm^2), so I = I_c + m d^2 about the joint.
Gravity is scaled so that the linear period is N cycles of the run's step (the
step is set by *MAT_RIGID's E and density, 0.045 ms): g = (2 pi / (N dt))^2 I/(m d).
The period is measured between upward zero crossings of the centre's x
coordinate (linear interpolation between cycles).

Analytical values: small amplitude T0 = 2 pi sqrt(I / (m g d)); amplitude theta0:
T = 4 sqrt(I / (m g d)) K(sin^2(theta0 / 2)) (complete elliptic integral of the
first kind, parameter m = k^2).

Tolerances: the penalty joint is a spring of stiffness k = 0.25 / (dt^2 w): the
pivot stretches by F / k under the rod force F (at most m g (1 + 2 m d^2 (1 -
cos theta0) / I)); with N = 1200 this lengthens the pendulum by up to 0.4 %,
which changes the period by about half of that (0.1-0.2 %). Central-difference
period error (w dt)^2 / 24 ~ 1e-6. Hence 0.5 % (small amplitude) and 1 %
(90 degrees), as asked, with margin; the separation bound is 2 F_max / k (the
settling from rest overshoots the static stretch by at most a factor 2).
"""

from __future__ import annotations

import numpy as np
import pytest
from joint_decks import Driver, pendulum
from scipy.special import ellipk

M, D, RG = 1.0, 100.0, 30.0
I_PIVOT = M * RG ** 2 + M * D ** 2
DT = 0.0448  # ms: 0.9 x the rigid hexahedron's step (checked below)


def _g(cycles_per_period: float) -> float:
    return (2.0 * np.pi / (cycles_per_period * DT)) ** 2 * I_PIVOT / (M * D)


def _swing(kind: str, theta0: float, cycles_per_period: float, periods: float):  # noqa: ANN202
    g = _g(cycles_per_period)
    run = Driver(pendulum(kind, theta0=theta0, d=D, radius_gyration=RG, mass=M, g=g))
    assert run.state.dt_next == pytest.approx(DT, rel=0.01)
    body = run.body(2)
    t_exact = 4.0 * np.sqrt(I_PIVOT / (M * g * D)) * ellipk(np.sin(np.radians(theta0) / 2) ** 2)
    rec = {"t": [], "x": [], "gap": [], "balance": []}

    def every(r: Driver) -> None:
        rec["t"].append(r.state.t)
        rec["x"].append(body.xc[0])
        rec["gap"].append(float(np.linalg.norm(r.joint.g_prev, axis=1).max()))
        e = r.energies()
        rec["balance"].append(e["total"] - (r.state.e0 + e["external_work"]))

    run.run_to(periods * t_exact * 1.02, every)
    t, x = np.array(rec["t"]), np.array(rec["x"])
    up = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    crossings = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    period = float(np.diff(crossings).mean())
    f_max = M * g * (1.0 + 2.0 * M * D ** 2 * (1.0 - np.cos(np.radians(theta0))) / I_PIVOT)
    k = float(run.joint.k.min())
    return period, t_exact, g, np.array(rec["gap"]), np.array(rec["balance"]), f_max, k, run


def test_spherical_small_angle_period():
    period, _, g, gap, _, f_max, k, _ = _swing("SPHERICAL", 5.0, 1200, 3)
    t0 = 2.0 * np.pi * np.sqrt(I_PIVOT / (M * g * D))
    assert period == pytest.approx(t0, rel=0.005)
    assert gap.max() < 2.0 * f_max / k
    assert gap.max() < 0.005 * D


def test_spherical_90_degree_period_elliptic():
    period, t_exact, _, gap, _, f_max, k, _ = _swing("SPHERICAL", 90.0, 1200, 2)
    assert period == pytest.approx(t_exact, rel=0.01)
    assert gap.max() < 2.0 * f_max / k


def test_spherical_energy_drift_20_periods():
    """Energy balance KE + joint energy (stored + dissipated) = work of gravity: its
    error stays below 0.5 % of m g d over 20 periods at 60 degrees (N = 500, so the
    test stays fast; the balance does not depend on the joint's compliance)."""
    period, t_exact, g, gap, balance, f_max, k, run = _swing("SPHERICAL", 60.0, 500, 20)
    assert period == pytest.approx(t_exact, rel=0.02)
    assert np.abs(balance).max() < 0.005 * M * g * D
    # the joint's own energy (stored in its springs plus what its dashpots took) stays
    # below what the springs hold at the separation bound, 2 F_max^2 / k
    assert 0.0 <= run.joint.internal_energy < 2.0 * f_max ** 2 / k
    assert gap.max() < 2.0 * f_max / k


def test_revolute_pendulum_period():
    period, t_exact, _, gap, _, f_max, k, _ = _swing("REVOLUTE", 30.0, 1200, 2)
    assert period == pytest.approx(t_exact, rel=0.005)
    assert gap.max() < 2.0 * f_max / k
