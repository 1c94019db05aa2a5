"""The closed-form yardstick of the crush benchmark and the measures taken from a curve.

Theory: values computed by hand from the published forms (to 1e-3 relative,
the rounding of the hand values), the constants' relations that the sources
state (52.22 = 38.12 / 0.73 to the printed digits), and Alexander's
concertina form checked against a direct numerical minimum of its fold
energy over the half-fold length (1e-6 relative: the minimiser's tolerance).

Measures: the mean force of a synthetic curve P + A sin(2 pi d / lambda) over
whole periods is P (to the quadrature error, 1e-6 relative); its peaks are
lambda apart, so the half-fold estimate is lambda / (2 effective) to the 0.1
mm resampling grid.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from hollowbody.scenarios import crush_analysis as ca
from hollowbody.scenarios import crush_theory as th


def test_square_forms_by_hand():
    c, t, s = 50.0, 1.5, 0.25
    m0 = s * t * t / 4.0
    assert th.plastic_moment(s, t) == pytest.approx(0.140625)
    assert th.square_wierzbicki_abramowicz(c, t, s) == pytest.approx(
        38.12 * (c / t) ** (1 / 3) * m0, rel=1e-12)
    assert th.square_wierzbicki_abramowicz(c, t, s) == pytest.approx(17.25, rel=1e-3)
    assert th.square_abramowicz_jones(c, t, s) == pytest.approx(23.63, rel=1e-3)
    # the effective crush distance 0.73 is the ratio of the two forms
    ratio = th.square_wierzbicki_abramowicz(c, t, s) / th.square_abramowicz_jones(c, t, s)
    assert ratio == pytest.approx(th.SQUARE_EFFECTIVE, abs=5e-5)
    assert th.square_half_fold(c, t) == pytest.approx(0.99 * 1.5 ** (1 / 3) * 50 ** (2 / 3))
    ref = th.square_reference(c, t, s)
    assert ref.low == pytest.approx(17.25, rel=1e-3) and ref.high == pytest.approx(23.63, rel=1e-3)


def test_circular_forms_by_hand():
    d, t, s = 60.0, 2.0, 0.25
    m0 = 0.25
    ne = (25.23 * math.sqrt(30.0) + 15.09) * m0
    assert th.circular_abramowicz_jones(d, t, s, effective=False) == pytest.approx(ne)
    eff = 0.86 - 0.568 * math.sqrt(1 / 30.0)
    assert th.circular_abramowicz_jones(d, t, s) == pytest.approx(ne / eff)
    assert th.circular_alexander(d, t, s) == pytest.approx(22.27 * math.sqrt(30.0) * m0,
                                                           rel=2e-4)
    ref = th.circular_reference(d, t, s)
    assert ref.low == th.circular_alexander(d, t, s)
    assert ref.high == th.circular_abramowicz_jones(d, t, s)
    assert ref.effective == pytest.approx(eff)


def test_alexander_is_the_minimum_of_its_fold_energy():
    d, t, s = 60.0, 2.0, 0.25
    r, m0 = d / 2, th.plastic_moment(s, t)

    def p_of_h(h: float) -> float:  # (hinge bending + hoop stretching) / fold length 2H
        return (2 * math.pi * r * m0 * 2 * math.pi + 2 * math.pi * s * t * h * h) / (2 * h)

    best = minimize_scalar(p_of_h, bounds=(0.1, 50.0), method="bounded",
                           options={"xatol": 1e-9})
    assert best.fun == pytest.approx(th.circular_alexander(d, t, s), rel=1e-6)
    assert best.x == pytest.approx(th.circular_half_fold(d, t), rel=1e-4)


def test_flow_stress():
    assert th.flow_stress(0.25) == 0.25
    assert th.flow_stress(0.25, 0.4, eps_u=0.3) == pytest.approx(0.31)
    curve = np.array([[0.0, 0.25], [1.0, 0.65]])  # the same linear hardening as a curve
    assert th.flow_stress(0.25, curve=curve, eps_u=0.3) == pytest.approx(0.31, rel=1e-9)
    with pytest.raises(ValueError):
        th.flow_stress(0.25, eps_u=0.0)


def test_mean_force_and_fold_length_of_a_synthetic_curve():
    lam, eff, h = 20.0, 0.73, 20.0 / (2 * 0.73)
    d = np.linspace(0.0, 120.0, 1201)
    f = 30.0 + 10.0 * np.sin(2 * math.pi * d / lam)
    assert ca.mean_force(d, f, 20.0, 100.0) == pytest.approx(30.0, rel=1e-6)
    assert ca.mean_force(d, f, 20.0, 30.0) == pytest.approx(30.0 + 10.0 * 2 / math.pi, rel=1e-4)
    peaks = ca.fold_peaks(d, f, 0.0, 110.0, h, 30.0)
    assert np.allclose(np.diff(peaks), lam, atol=0.11)
    assert ca.half_fold_from_peaks(peaks, eff) == pytest.approx(h, abs=0.1)
    assert math.isnan(ca.half_fold_from_peaks(peaks[:1], eff))
    assert ca.work(d, np.full_like(d, 2.0)) == pytest.approx(240.0)
    with pytest.raises(ValueError, match="before the end"):
        ca.mean_force(d, f, 20.0, 130.0)


def test_crush_window():
    assert ca.crush_window(100.0, 14.0, 0.73) == (28.0, 70.0)
    with pytest.raises(ValueError, match="too short"):
        ca.crush_window(50.0, 14.0, 0.73)
