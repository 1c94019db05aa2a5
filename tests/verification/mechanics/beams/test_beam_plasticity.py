"""Plastic hinge of ELFORM 1 (cross-section integration) with perfect plasticity.

The tip rotation of a 2-element cantilever is driven (rotational velocity
imposed, translations free) to 20 times the first-yield curvature over 25 ms
(10 first periods: quasi-static): pure bending, the same moment in both
elements. Elastic-perfectly-plastic *MAT_PLASTIC_KINEMATIC (ETAN 0), sigma_y
0.25 GPa. At 20 kappa_y the exact moment is M_p (1 - (1/3)(1/20)^2) = 0.9992 M_p
(rectangle). References: rectangle M_p = sigma_y b h^2 / 4, tube M_p =
sigma_y (D^3 - d^3) / 6. Tolerance 3 %; what the rules give:

* rectangle with an *INTEGRATION_BEAM rule of 2 x 10 Gauss points (10 through
  the depth): +0.75 % (10-point Gauss integrates |t| with that error);
* the standard 4 x 4 Gauss rule (QR 5) gives +4.3 % (Gauss rules over-estimate
  the fully plastic moment: sum w |xi| = 1.043), checked here as what it is;
* tube, QR 3 (16 points around x 3 through the wall): +0.4 %.
"""

from __future__ import annotations

import numpy as np
import pytest
from beam_runs import E, L, add_load, engine, run_until

SIGY = 0.25


def _hinge(tmp_path, h: float, **deck) -> np.ndarray:  # noqa: ANN003
    n, t_end = 2, 25.0
    run = engine(tmp_path, n=n, elform=1, sigy=SIGY, etan=0.0, **deck)
    kappa_y = 2.0 * SIGY / (E * h)
    rate = 20.0 * kappa_y * L / (0.95 * t_end)
    add_load(run, n, spin=lambda t: np.array(
        [0.0, -rate * min(1.0, t / (0.1 * t_end)), 0.0]))
    run_until(run, t_end)
    return run.plan.elements[0]


def test_rectangle_user_rule_reaches_mp(tmp_path):
    b = h = 5.0
    rt = _hinge(tmp_path, h, width=b, height=h, gauss_rule=(2, 10))
    mp = SIGY * b * h * h / 4.0
    m = -rt.resultants[:, 4]
    assert np.allclose(m / mp, 1.0, atol=0.03)
    assert rt.plastic_strain.max() > 0.0


def test_rectangle_qr5_overestimates_mp(tmp_path):
    b = h = 5.0
    rt = _hinge(tmp_path, h, width=b, height=h, qr=5)
    mp = SIGY * b * h * h / 4.0
    x, w = np.polynomial.legendre.leggauss(4)
    rule_mp = mp * float((w * np.abs(x)).sum())  # the rule's fully plastic moment
    assert np.allclose(-rt.resultants[:, 4] / rule_mp, 1.0, atol=0.005)


def test_tube_reaches_mp(tmp_path):
    d_out, d_in = 10.0, 8.0
    rt = _hinge(tmp_path, d_out, tube=(d_out, d_in), qr=3)
    mp = SIGY * (d_out ** 3 - d_in ** 3) / 6.0
    assert np.allclose(-rt.resultants[:, 4] / mp, 1.0, atol=0.03)


def test_elastic_unloading_and_dissipation(tmp_path):
    """Bilinear hardening (ETAN = E/100): bend to 5 kappa_y, then reverse the tip
    rotation: on the unloading branch the section responds elastically,
    dM/dkappa = E I (from the element's own moment and curvature, so the
    vibration the reversal excites does not matter; 1e-6), while the loading
    branch was softer (yielded); the internal energy left is positive."""
    b = h = 5.0
    n = 2
    run = engine(tmp_path, n=n, elform=1, width=b, height=h, sigy=SIGY, etan=2.0,
                 gauss_rule=(2, 10))
    kappa_y = 2.0 * SIGY / (E * h)
    rate = 5.0 * kappa_y * L / 10.0
    add_load(run, n, spin=lambda t: np.array([0.0, -rate if t < 10.0 else 0.5 * rate, 0.0]))
    rt = run.plan.elements[0]

    def state():  # noqa: ANN202
        kappa = (rt.nat[0, 4] - rt.nat[0, 2]) / rt.length0[0]
        return kappa, rt.resultants[0, 4]

    run_until(run, 8.0)
    k1, m1 = state()
    run_until(run, 9.0)
    k2, m2 = state()
    i_s = b * h ** 3 / 12.0
    assert (m2 - m1) / (k2 - k1) < 0.5 * E * i_s  # yielded: softer than elastic
    run_until(run, 11.0)
    k3, m3 = state()
    run_until(run, 13.0)
    k4, m4 = state()
    assert (m4 - m3) / (k4 - k3) == pytest.approx(E * i_s, rel=1e-6)
    assert rt.plastic_strain.max() > 0.0
    assert rt.internal_energy > 0.0


@pytest.mark.parametrize("speed", [0.5, 2.0])
def test_cowper_symonds_rate_scaling(tmp_path, speed):
    """One ELFORM 1 element pulled at constant speed v (end velocity imposed):
    uniform strain rate v / L; elastic-perfectly-plastic *MAT_PLASTIC_KINEMATIC
    with SRC = 0.04 /ms, SRP = 5: the axial force after yield is
    A sigma_y (1 + (v / (L SRC))^(1/5)) (0.5 %; the element's own force, so
    the bar's inertia does not enter)."""
    src, srp = 0.04, 5.0
    run = engine(tmp_path, n=1, elform=1, sigy=SIGY, etan=0.0, src=src, srp=srp)
    add_load(run, 1, velocity=lambda t: np.array([speed, 0.0, 0.0]))
    rate = speed / L
    run_until(run, 3.0 * SIGY * 2.5 / (E * rate))  # well past yield (rate factor < 2.5)
    rt = run.plan.elements[0]
    factor = 1.0 + (rate / src) ** (1.0 / srp)
    assert rt.resultants[0, 0] / (25.0 * SIGY * factor) == pytest.approx(1.0, abs=0.005)
    assert rt.plastic_strain[0] > 0.0


def test_energy_balance_with_plastic_work(tmp_path):
    """Cantilever (10 ELFORM 1 elements, 2 x 10 rule, ETAN = E/100) under a tip
    load ramped over 3 ms to 1.25 times first yield at the root (collapse is at
    1.5; the ramp's dynamic overshoot stays below it), undamped: the stress
    work (elastic + plastic) plus kinetic energy equals the load's work at
    every cycle (1e-5 of the work; measured 9e-8)."""
    from beam_runs import energy_sum, smooth

    n, b, h = 10, 5.0, 5.0
    run = engine(tmp_path, n=n, elform=1, width=b, height=h, sigy=SIGY, etan=2.0,
                 gauss_rule=(2, 10))
    p_yield = SIGY * b * h * h / 6.0 / L
    term = add_load(run, n, force=lambda t: np.array([0.0, 0.0,
                                                      -1.25 * p_yield * smooth(t, 3.0)]))
    worst = [0.0]

    def watch(r):  # noqa: ANN001
        ie, ke, w = energy_sum(r)
        worst[0] = max(worst[0], abs(ie + ke - w))

    run_until(run, 6.0, watch)
    rt = run.plan.elements[0]
    assert rt.plastic_strain[0] > 0.0 and rt.plastic_strain[-1] == 0.0
    assert worst[0] < 1e-5 * term.external_work


def test_fail_deletes_the_beam_when_every_point_failed(tmp_path):
    """*MAT_PIECEWISE_LINEAR_PLASTICITY with FAIL = 0.02, perfectly plastic: a
    single beam pulled at 2 mm/ms (uniform strain) fails at every point at once
    when eps_p = FAIL, i.e. at t = (FAIL + sigma_y / E) L / v; the beam is
    deleted there (within a step) and carries no force after."""
    fail, speed = 0.02, 2.0
    run = engine(tmp_path, n=1, elform=1, sigy=SIGY, etan=0.0, fail=fail)
    add_load(run, 1, velocity=lambda t: np.array([speed, 0.0, 0.0]))
    rt = run.plan.elements[0]
    t_fail = (fail + SIGY / E) * L / speed
    dt = run.state.dt_next
    run_until(run, t_fail - 2.0 * dt)
    assert rt.alive[0] and rt.resultants[0, 0] == pytest.approx(25.0 * SIGY, rel=1e-6)
    while rt.alive[0] and run.t < t_fail + 2.0 * dt:  # (nothing sets a step after)
        run.step()
    assert abs(run.t - t_fail) < dt
    assert not rt.alive[0] and rt.failed == [0]
    assert rt.resultants[0, 0] == 0.0 and np.isinf(rt.dt_elem[0])


def test_fail_in_bending_takes_the_outer_fibres_first(tmp_path):
    """Pure bending to a curvature whose outer-fibre plastic strain passes FAIL
    while the inner fibres stay below: the outer points fail (no stress), the
    beam stays (its inner points carry the moment), the moment falls below the
    intact section's."""
    fail = 0.01
    h = 5.0
    run = engine(tmp_path, n=2, elform=1, width=5.0, height=h, sigy=SIGY, etan=0.0,
                 fail=fail, gauss_rule=(2, 10))
    kappa = 2.0 * (fail + SIGY / E) / h  # outer fibre at FAIL (points sit inside it)
    rate = 1.4 * kappa * L / 20.0
    add_load(run, 2, spin=lambda t: np.array([0.0, -rate * min(1.0, t / 2.0), 0.0]))
    rt = run.plan.elements[0]
    run_until(run, 21.0)
    assert rt.alive.all()
    assert rt.pfail.any() and not rt.pfail.all()
    assert -rt.resultants[0, 4] < 0.9 * SIGY * 5.0 * h * h / 4.0
