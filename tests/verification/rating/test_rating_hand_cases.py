"""Small cases worked by hand for every sub-score of ISO/TS 18571 and CORA.

Each test states the arithmetic in its comments so that the expected number can
be checked with pencil and paper.
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.rating.cora import CoraParameters, cora, evaluation_interval
from hollowbody.rating.iso18571 import (
    IsoParameters,
    corridor_score,
    magnitude_error,
    phase_score,
    phase_shift,
    rate_sampled,
    smoothed_slope,
)


# ----------------------------------------------------------------- ISO/TS 18571
def test_iso_corridor_score():
    # t_norm = 4 -> inner half-width 0.05 * 4 = 0.2, outer 0.5 * 4 = 2
    # deviations 0, 0.1, 1.1, 2.5, 0.2 -> scores 1, 1, ((2 - 1.1) / 1.8)^2 = 0.25, 0, 1
    ref = np.array([0.0, 1.0, 2.0, 4.0, 2.0])
    cmp = ref + np.array([0.0, 0.1, 1.1, 2.5, 0.2])
    z, _ = corridor_score(ref, cmp)
    assert z == pytest.approx(3.25 / 5)


def test_iso_phase_score():
    # N = 10, eps_p * N = 2 samples may be searched; the candidate is one sample late:
    # ref[0:9] and cmp[1:10] coincide (rho = 1) -> E_P = (2 - 1) / 2 = 0.5
    ref = np.array([0, 0, 1, 3, 1, 0, 0, 0, 0, 0], dtype=float)
    cmp = np.roll(ref, 1)
    lag, rho = phase_shift(ref, cmp, 0.2)
    assert (lag, rho) == (1, pytest.approx(1.0))
    assert phase_score(lag, ref.size) == pytest.approx(0.5)


def test_iso_magnitude_error_with_and_without_warping():
    x = np.array([0.0, 1.0, 2.0, 1.0, 0.0])
    y = np.array([0.0, 0.0, 1.0, 2.0, 1.0])
    # band radius 1 = no warping: sum|y - x| = 0+1+1+1+1 = 4, sum|x| = 4 -> eps = 1
    assert magnitude_error(x, y, window=0.0) == pytest.approx(1.0)
    # radius ceil(0.4 * 5) = 2: the cheapest path (0,0)(0,1)(1,2)(2,3)(3,4)(4,4) costs 1;
    # warped x = 0 0 1 2 1 0, y = 0 0 1 2 1 1 -> eps = 1 / 4
    assert magnitude_error(x, y, window=0.4) == pytest.approx(0.25)


def test_iso_smoothed_slope():
    # unit impulse at i = 4 (dt = 1): central differences d3 = 0.5, d5 = -0.5, others 0.
    # 9-point average shrinking at the ends: i=2 averages d0..d4 -> 0.5 / 5 = 0.1,
    # i=7 averages d4..d10 -> -0.5 / 7, every other window holds both or neither.
    y = np.zeros(11)
    y[4] = 1.0
    want = np.zeros(11)
    want[2] = 0.1
    want[7] = -0.5 / 7
    assert smoothed_slope(y, 1.0) == pytest.approx(want, abs=1e-15)


def test_iso_overall_rating_of_a_ramp_pair():
    # ref = 0, 1, ..., 9 and cmp = 1.5 * ref, dt = 1 (slopes 1 and 1.5 everywhere).
    # Corridor: t_norm 9, delta_i 0.45, delta_o 4.5, deviation 0.5 * i:
    #   i = 0 -> 1; i = 1..8 -> ((4.5 - 0.5 i) / 4.05)^2; i = 9 -> 0
    # Phase: Pearson is 1 at lag 0 (linear relation) and at every other lag too (a
    # shifted ramp is still a ramp); the tie goes to the unshifted position -> E_P = 1.
    # Magnitude, radius ceil(0.1 * 10) = 1 (diagonal): eps = 0.5 -> E_M = 0.
    # Slope: eps = 0.5 -> E_S = (2 - 0.5) / 2 = 0.75.
    ref = np.arange(10.0)
    r = rate_sampled(ref, 1.5 * ref, IsoParameters(dt=1.0))
    i = np.arange(1, 9)
    z = (1.0 + np.sum(((4.5 - 0.5 * i) / 4.05) ** 2)) / 10
    assert r.corridor == pytest.approx(z)
    assert r.phase == 1.0
    assert r.eps_mag == pytest.approx(0.5) and r.magnitude == pytest.approx(0.0)
    assert r.slope == pytest.approx(0.75)
    assert r.overall == pytest.approx(0.4 * z + 0.2 + 0.0 + 0.2 * 0.75)


# ------------------------------------------------------------------------- CORA
def test_cora_interval_of_evaluation():
    # max|x| = 4; 3 % = 0.12 first reached between t=1 (0) and t=2 (1): t_a = 1.12;
    # 7.5 % = 0.3 last reached between t=8 (1) and t=9 (0): t_b = 8.7;
    # start = 1.12 - 0.01 * 7.58, end = min(10, 8.7 + 0.2 * 7.58) = 10
    t = np.arange(11.0)
    x = np.array([0, 0, 1, 2, 3, 4, 3, 2, 1, 0, 0], dtype=float)
    assert evaluation_interval(t, x) == pytest.approx((1.12 - 0.0758, 10.0))


def test_cora_all_ratings_of_a_shifted_scaled_pulse():
    # Interval fixed to 0..40 ms (T = 40), dt = 1 ms. Reference: triangle 0..4..0 on
    # t = 10..18; candidate: the same triangle 2 ms later and twice as high.
    # Shift 2 ms: D_MIN*T = 0.4, D_MAX*T = 4.8 -> P = (4.8 - 2) / (4.8 - 0.4) = 7/11.
    # After the shift the shapes coincide: K_xy = 1 -> V = 1;
    # energies 1 : 4 -> G = 0.25.
    # Corridor (Y_norm = 4: inner 0.2, outer 2): where both are zero d = 0 -> 1;
    # d = |y - x| on t = 10..20 with x = tri(t-10), y = 2 tri(t-12).
    t = np.arange(0.0, 41.0)
    tri = np.interp(t, [10, 14, 18], [0, 4, 0])
    cand = 2.0 * np.interp(t, [12, 16, 20], [0, 4, 0])
    p = CoraParameters(t_min=0.0, t_max=40.0, dt=1.0)
    r = cora(t, tri, t, cand, p)
    assert r.shift == 2.0
    assert r.phase == pytest.approx(7.0 / 11.0)
    assert r.progression == pytest.approx(1.0) and r.size == pytest.approx(0.25)
    d = np.abs(cand - tri)
    c = np.where(d <= 0.2, 1.0, np.clip((2.0 - d) / 1.8, 0.0, 1.0) ** 2)
    assert r.corridor == pytest.approx(c.mean())
    e = 0.5 * 1.0 + 0.25 * 0.25 + 0.25 * 7.0 / 11.0
    assert r.cross_correlation == pytest.approx(e)
    assert r.total == pytest.approx(0.5 * c.mean() + 0.5 * e)
