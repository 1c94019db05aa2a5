"""ISO/TS 18571 rating: exact cases, predicted losses, parameters and errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.rating.iso18571 import (
    IsoParameters,
    corridor_score,
    grade,
    iso18571,
    magnitude_error,
    phase_score,
    rate_sampled,
)
from hollowbody.rating.signals import CurveError

T = np.arange(0.0, 100.0 + 1e-9, 0.1)  # 1001 samples at 10 kHz


def pulse(t, centre=40.0, width=8.0):
    return np.exp(-(((t - centre) / width) ** 2))


def test_identical_curves_score_one_everywhere():
    r = iso18571(T, pulse(T), T, pulse(T))
    assert r.scores() == {"Z": 1.0, "EP": 1.0, "EM": 1.0, "ES": 1.0, "R": 1.0}
    assert r.grade == "excellent" and r.shift_samples == 0 and r.rho == pytest.approx(1.0)
    assert r.n_samples == 1001 and (r.t_start, r.t_end) == pytest.approx((0.0, 100.0))


def test_time_shifted_copy_loses_phase_as_defined():
    # candidate 5 ms = 50 samples late; N = 1001, allowed shift eps_p * N = 200.2
    r = iso18571(T, pulse(T), T, pulse(T, centre=45.0))
    assert r.shift_samples == 50 and r.shift == pytest.approx(5.0)
    assert r.rho == pytest.approx(1.0, abs=1e-12)
    assert r.phase == pytest.approx((200.2 - 50) / 200.2)
    # after the alignment the curves coincide
    assert r.magnitude == pytest.approx(1.0) and r.slope == pytest.approx(1.0)
    # early candidate: same loss
    r2 = iso18571(T, pulse(T), T, pulse(T, centre=35.0))
    assert r2.shift_samples == -50 and r2.phase == pytest.approx(r.phase)


def test_shift_at_the_edge_of_the_search_range_scores_zero_phase():
    # N = 1000 samples: shifts up to eps_p * N = 200 samples are searched; the true
    # shift (300) lies beyond, so the best lag is the edge, rated 0
    t = np.arange(1000) * 0.1
    r = iso18571(t, pulse(t, 30.0), t, pulse(t, 60.0))
    assert r.shift_samples == 200 and r.phase == 0.0


def test_pearson_phase_search_can_miss_far_shifts_of_narrow_pulses():
    # documented behaviour of the metric: narrow pulses that never overlap within the
    # search range correlate best unshifted (Pearson's mean removal dominates)
    r = iso18571(T, pulse(T, 30.0, 3.0), T, pulse(T, 60.0, 3.0))
    assert r.shift_samples == 0 and r.magnitude == 0.0


def test_scaled_copy_loses_slope_and_magnitude_as_defined():
    s = 1.3
    r = iso18571(T, pulse(T), T, s * pulse(T))
    assert r.shift_samples == 0 and r.phase == 1.0
    # slopes scale with s: eps_slope = s - 1, E_S = (2 - 0.3) / 2
    assert r.eps_slope == pytest.approx(s - 1.0)
    assert r.slope == pytest.approx((2.0 - (s - 1.0)) / 2.0)
    # without warping (band radius 1) the magnitude error is s - 1
    diag = iso18571(T, pulse(T), T, s * pulse(T), IsoParameters(dtw_window=0.0))
    assert diag.eps_mag == pytest.approx(s - 1.0)
    assert diag.magnitude == pytest.approx((0.5 - 0.3) / 0.5)
    # warping can only lower the error
    assert 0.0 < r.eps_mag <= diag.eps_mag
    assert r.magnitude >= diag.magnitude


def test_corridor_score_by_hand():
    ref = np.array([0.0, 1.0, 2.0, 4.0, 2.0])     # t_norm 4: delta_i 0.2, delta_o 2
    dev = np.array([0.0, 0.1, 1.1, 2.5, 0.2])
    z, t_norm = corridor_score(ref, ref + dev)
    assert t_norm == 4.0
    assert z == pytest.approx((1 + 1 + ((2 - 1.1) / 1.8) ** 2 + 0 + 1) / 5)


def test_phase_score_formula():
    assert phase_score(0, 100) == 1.0
    assert phase_score(10, 100) == pytest.approx(0.5)
    assert phase_score(-10, 100, k_p=2.0) == pytest.approx(0.25)
    assert phase_score(20, 100) == 0.0


def test_magnitude_error_of_identical_and_zero_reference():
    x = np.array([0.0, 1.0, 0.0])
    assert magnitude_error(x, x) == 0.0
    assert magnitude_error(np.zeros(3), np.zeros(3)) == 0.0
    assert math.isinf(magnitude_error(np.zeros(3), x))


@pytest.mark.parametrize(("r", "name"), [(0.95, "excellent"), (0.94, "good"), (0.81, "good"),
                                         (0.80, "fair"), (0.59, "fair"), (0.58, "poor"),
                                         (0.0, "poor")])
def test_grades(r, name):
    assert grade(r) == name


def test_weights_and_parameters_are_reported():
    p = IsoParameters(w_z=1.0, w_p=1.0, w_m=1.0, w_s=1.0)  # normalised by the sum
    r = iso18571(T, pulse(T), T, 1.3 * pulse(T), p)
    assert r.overall == pytest.approx((r.corridor + r.phase + r.magnitude + r.slope) / 4)
    d = r.to_dict()
    assert d["parameters"]["w_z"] == 1.0 and d["parameters"]["dt"] == 0.1
    assert d["method"] == "ISO/TS 18571"
    for key in ("corridor", "phase", "magnitude", "slope", "overall", "eps_mag", "rho"):
        assert key in d


def test_interval_is_the_common_range_and_can_be_narrowed():
    t_short = np.arange(10.0, 80.0 + 1e-9, 0.5)
    r = iso18571(T, pulse(T), t_short, pulse(t_short))
    assert (r.t_start, r.t_end) == pytest.approx((10.0, 80.0))
    r = iso18571(T, pulse(T), T, pulse(T), IsoParameters(t_start=20.0, t_end=60.0, dt=0.5))
    assert (r.t_start, r.t_end, r.n_samples) == (20.0, 60.0, 81)


def test_zero_reference_is_an_error():
    with pytest.raises(CurveError, match="zero") as info:
        iso18571(T, np.zeros_like(T), T, pulse(T))
    assert info.value.which == "reference"


@pytest.mark.parametrize("kwargs", [dict(a_0=0.5, b_0=0.5), dict(eps_p=1.0), dict(k_z=0.0),
                                    dict(smooth_points=4), dict(w_z=-1.0), dict(dt=0.0),
                                    dict(dtw_window=2.0)])
def test_invalid_parameters(kwargs):
    with pytest.raises(ValueError):
        IsoParameters(**kwargs)


def test_invariant_to_common_scaling_and_time_offset():
    rng = np.random.default_rng(3)
    ref = pulse(T) + 0.05 * np.sin(T)
    cmp = 1.1 * pulse(T, 43.0) + 0.02 * rng.normal(size=T.size)
    a = iso18571(T, ref, T, cmp)
    b = iso18571(T + 500.0, 7.0 * ref, T + 500.0, 7.0 * cmp)
    for k, v in a.scores().items():
        assert b.scores()[k] == pytest.approx(v, abs=1e-9)


def test_rate_sampled_equals_full_call_on_sampled_data():
    ref, cmp = pulse(T), 0.9 * pulse(T, 41.0)
    assert rate_sampled(ref, cmp).scores() == pytest.approx(iso18571(T, ref, T, cmp).scores())
