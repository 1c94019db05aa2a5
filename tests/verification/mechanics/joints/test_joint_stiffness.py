"""*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED and _FLEXION-TORSION against their curves.

Set-up (:func:`joint_decks.stiffness_pair`): body 2 (centre on its joint: spherical
for moments about x, revolute about y or z for moments about y or z, see there why;
isotropic inertia 10 kg*mm^2) turns under a moment about one global axis
(*LOAD_RIGID_BODY) applied as a staircase: three levels, each reached
in 2 ms and held for 28 ms. A damping curve (moment = c * rate, c about 0.6 of
critical at the stiffest point) settles each level in a few periods (about 9 ms).
The angle is measured from the body's rotation matrix (not from the joint's own
output), at the end of each hold, and the curve's moment at that angle is compared
with the applied moment: within 2 % (settling leaves < 0.1 %; the curve is
interpolated linearly between 121 points, which is the curve the test compares to).
Stops: the angle settles at theta_s + (M - curve(theta)) / ES (the elastic stop
stiffness ES, a straight line), within 2 % of the overshoot past the stop; friction:
an elastic-perfectly-plastic spring (ES, FM) leaves a residual angle after unloading.
"""

from __future__ import annotations

import numpy as np
import pytest
from joint_decks import Driver, curve, stiffness_pair

from hollowbody.io.keyword import DefineCurve

LEVELS = (1.0 / 3.0, 2.0 / 3.0, 1.0)
HOLD, RAMP = 28.0, 2.0


def _stairs(m_max: float) -> list[tuple[float, float]]:
    pts, t, prev = [(0.0, 0.0)], 0.0, 0.0
    for lv in LEVELS:
        pts += [(t + RAMP, lv * m_max), (t + RAMP + HOLD, lv * m_max)]
        t += RAMP + HOLD
        prev = lv * m_max
    return pts + [(1.0e4, prev)]


def _angle(rot: np.ndarray, axis: int) -> float:
    """Rotation angle (rad) of a rotation about global axis ``axis`` (0, 1, 2)."""
    j, k = (axis + 1) % 3, (axis + 2) % 3
    return float(np.arctan2(rot[k, j], rot[j, j]))


def _holds(run: Driver, axis: int, n: int = len(LEVELS)) -> list[float]:
    """The angle at the end of each hold."""
    out = []
    for i in range(n):
        run.run_to((i + 1) * (RAMP + HOLD) - 0.5)
        out.append(_angle(run.body(2).rot, axis))
    return out


MOMENT_CURVES = {  # kN*mm against rad: stiffening, softening, S-shaped
    0: lambda q: 5.0 * q + 10.0 * q ** 3,
    1: lambda q: 3.0 * q + 20.0 * q * abs(q),
    2: lambda q: 8.0 * np.tanh(2.0 * q) + 2.0 * q,
}
CARD = {0: ("lcidph", "dlcidph"), 1: ("lcidt", "dlcidt"), 2: ("lcidps", "dlcidps")}


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_generalized_moment_follows_its_curve(axis):
    """phi, theta, psi: moments about x, y, z (each alone, so each angle is the
    rotation about that axis)."""
    f = MOMENT_CURVES[axis]
    m_max = f(0.8)
    deck = stiffness_pair("GENERALIZED", dof=5 + axis, moment=_stairs(m_max),
                          **{CARD[axis][0]: 10, CARD[axis][1]: 11})
    pts = curve(deck, 10, f)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))  # c = 30
    run = Driver(deck)
    for lv, q in zip(LEVELS, _holds(run, axis)):
        assert np.interp(q, pts[:, 0], pts[:, 1]) == pytest.approx(lv * m_max, rel=0.02)
    # the joint's own output agrees with the measured angle
    assert run.joint.q_out[0, axis] == pytest.approx(q, abs=1e-6)
    others = np.delete(run.joint.q_out[0], axis)
    assert np.abs(others).max() < 1e-6


@pytest.mark.parametrize("es", [200.0, 2000.0])
def test_generalized_stop_engages_at_its_angle(es):
    """Soft curve M = 2 theta; positive stop 20 degrees with stiffness ES; moments up to
    12 kN*mm would turn the body 6 rad without the stop."""
    stop = np.radians(20.0)
    deck = stiffness_pair("GENERALIZED", dof=6, moment=_stairs(12.0), lcidt=10, dlcidt=11,
                          est=es, psat=20.0, nsat=20.0)
    curve(deck, 10, lambda q: 2.0 * q)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    run = Driver(deck)
    for lv, q in zip(LEVELS, _holds(run, 1)):
        m = lv * 12.0  # 4, 8, 12 kN*mm: past the stop (2 theta_s = 0.7 kN*mm)
        expected = (m + es * stop) / (2.0 + es) if m > 2.0 * stop else m / 2.0
        assert q - stop == pytest.approx(expected - stop, rel=0.02, abs=1e-4)
        assert q < stop + 13.0 / es  # held near the stop, closer the stiffer it is


def test_generalized_negative_stop_and_friction():
    """Negative stop (NSAT given as a negative number: the same stop as 15): load to
    -12 kN*mm about y, then unload (curve M = 10 theta brings the body back)."""
    stop = np.radians(15.0)
    es = 500.0
    pts = [(0.0, 0.0), (2.0, -12.0), (30.0, -12.0), (32.0, 0.0), (1.0e4, 0.0)]
    deck = stiffness_pair("GENERALIZED", dof=6, moment=pts, lcidt=10, dlcidt=11, est=es,
                          nsat=-15.0)
    curve(deck, 10, lambda q: 10.0 * q)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    run = Driver(deck)
    run.run_to(29.5)
    q = _angle(run.body(2).rot, 1)
    assert q + stop == pytest.approx((-12.0 - es * stop) / (10.0 + es) + stop, rel=0.02)
    run.run_to(59.5)  # unloaded: the curve brings it back to 0 (no friction on theta)
    assert abs(_angle(run.body(2).rot, 1)) < 2e-3


def test_friction_leaves_a_residual_angle():
    """theta: curve M = 5 theta, friction FM = 1 kN*mm with ES = 500 kN*mm/rad. Loading
    to 3 kN*mm the friction spring slips: 5 theta + FM = 3, theta = 0.4. Unloading to
    0 it slips back until the curve's moment equals FM: 5 theta = 1, theta = 0.2 (the
    residual angle FM / 5)."""
    pts = [(0.0, 0.0), (2.0, 3.0), (40.0, 3.0), (42.0, 0.0), (1.0e4, 0.0)]
    deck = stiffness_pair("GENERALIZED", dof=6, moment=pts, lcidt=10, dlcidt=11,
                          est=500.0, fmt=1.0)
    curve(deck, 10, lambda q: 5.0 * q)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    run = Driver(deck)
    run.run_to(39.5)
    assert _angle(run.body(2).rot, 1) == pytest.approx(0.4, rel=0.02)
    run.run_to(90.0)
    assert _angle(run.body(2).rot, 1) == pytest.approx(0.2, rel=0.02)
    e = run.energies()
    assert abs(e["total"] - (run.state.e0 + e["external_work"])) < 0.01 * 3.0 * 0.4


def test_flexion_torsion_bending_with_gamma_scale_and_twist():
    """Bending about x: alpha = rotation angle, gamma = -90 degrees, the alpha moment
    scaled by LCIDG(gamma) = 0.5; twist about z: beta = rotation angle."""
    f = MOMENT_CURVES[0]
    m_max = 0.5 * f(0.8)
    deck = stiffness_pair("FLEXION-TORSION", dof=5, moment=_stairs(m_max), lcidal=10,
                          lcidg=12, dlcidal=11)
    pts = curve(deck, 10, f, lo=0.0, hi=3.0)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    deck.add(DefineCurve(lcid=12, points=[[-4.0, 0.5], [4.0, 0.5]]))
    run = Driver(deck)
    for lv, q in zip(LEVELS, _holds(run, 0)):
        assert 0.5 * np.interp(q, pts[:, 0], pts[:, 1]) == pytest.approx(lv * m_max, rel=0.02)
    assert run.joint.q_out[0, 1] == pytest.approx(-np.pi / 2, abs=1e-6)
    g = MOMENT_CURVES[2]
    deck = stiffness_pair("FLEXION-TORSION", dof=7, moment=_stairs(g(0.8)), lcidbt=10,
                          dlcidbt=11)
    pts = curve(deck, 10, g)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    run = Driver(deck)
    for lv, q in zip(LEVELS, _holds(run, 2)):
        assert np.interp(q, pts[:, 0], pts[:, 1]) == pytest.approx(lv * g(0.8), rel=0.02)
    assert abs(run.joint.q_out[0, 0]) < 1e-6  # no bending


def test_stiffness_energy_is_stored_and_dissipated():
    """The joint stiffness's internal energy: the curve's stored energy (its integral
    up to the final angle) plus what the damping curve took; with the balance
    KE + internal = work of the applied moment within 0.5 %."""
    f = MOMENT_CURVES[1]
    deck = stiffness_pair("GENERALIZED", dof=6, moment=_stairs(f(0.8)), lcidt=10, dlcidt=11)
    pts = curve(deck, 10, f)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    run = Driver(deck)
    q = _holds(run, 1)[-1]
    e = run.energies()
    assert abs(e["total"] - (run.state.e0 + e["external_work"])) < 0.005 * e["external_work"]
    xs = np.linspace(0.0, q, 2001)
    stored = np.trapezoid(np.interp(xs, pts[:, 0], pts[:, 1]), xs)
    assert run.joint.internal_energy > stored  # plus the dissipated share
    assert run.joint.internal_energy < e["external_work"] * 1.001
