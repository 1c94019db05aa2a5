"""CORA rating: interval of evaluation, corridor and cross-correlation method."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.rating.cora import (
    CoraParameters,
    UserCorridors,
    cora,
    corridor_rating,
    cross_correlation_ratings,
    evaluation_interval,
)
from hollowbody.rating.corridors import Corridor
from hollowbody.rating.signals import CurveError

T = np.arange(0.0, 100.0 + 1e-9, 0.1)
FIXED = CoraParameters(t_min=0.0, t_max=100.0)


def pulse(t, centre=40.0, width=8.0):
    return np.exp(-(((t - centre) / width) ** 2))


def test_identical_curves_rate_one_everywhere():
    r = cora(T, pulse(T), T, pulse(T))
    assert r.scores() == pytest.approx({"Z": 1, "E": 1, "P": 1, "G": 1, "V": 1, "R": 1},
                                       abs=1e-12)
    assert r.shift_samples == 0


def test_default_parameters_are_coraplus_defaults_and_reported():
    r = cora(T, pulse(T), T, pulse(T))
    assert r.parameters == {
        "A_THRES": 0.03, "B_THRES": 0.075, "A_EVAL": 0.01, "B_DELTA_END": 0.2,
        "T_MIN": None, "T_MAX": None, "K": 2.0, "a_0": 0.05, "b_0": 0.5, "D_MIN": 0.01,
        "D_MAX": 0.12, "INT_MIN": 0.8, "K_V": 10.0, "K_G": 1.0, "K_P": 1.0, "G_V": 0.5,
        "G_G": 0.25, "G_P": 0.25, "G_1": 0.5, "G_2": 0.5, "WF_NORM": True, "Y_NORM": None,
        "DT": 0.1}
    d = r.to_dict()
    assert d["method"] == "CORA" and d["parameters"]["K_V"] == 10.0


def test_changed_parameters_are_used_and_reported():
    p = CoraParameters(t_min=0.0, t_max=100.0, k_v=5.0, g_1=1.0, g_2=3.0)
    r = cora(T, pulse(T), T, pulse(T, 41.0), p)
    assert r.parameters["K_V"] == 5.0 and r.parameters["G_2"] == 3.0
    assert r.total == pytest.approx((r.corridor + 3.0 * r.cross_correlation) / 4.0)


def test_time_shifted_copy_loses_phase_rating_as_defined():
    # interval 0..100 ms: D_MIN * T = 1 ms, D_MAX * T = 12 ms; shift 5 ms
    r = cora(T, pulse(T), T, pulse(T, 45.0), FIXED)
    assert r.shift == pytest.approx(5.0)
    assert r.phase == pytest.approx((12.0 - 5.0) / (12.0 - 1.0))
    assert r.progression == pytest.approx(1.0) and r.size == pytest.approx(1.0)
    assert r.cross_correlation == pytest.approx(0.5 + 0.25 + 0.25 * 7.0 / 11.0)


def test_small_shift_is_free_and_large_shift_costs_everything():
    assert cora(T, pulse(T), T, pulse(T, 40.8), FIXED).phase == 1.0
    assert cora(T, pulse(T), T, pulse(T, 55.0), FIXED).phase == 0.0


def test_scaled_copy_loses_size_rating_as_defined():
    for s in (0.5, 1.25, 2.0):
        r = cora(T, pulse(T), T, s * pulse(T), FIXED)
        assert r.size == pytest.approx(min(s * s, 1.0 / (s * s)))
        assert r.progression == pytest.approx(1.0) and r.phase == 1.0


def test_interval_of_evaluation_by_hand():
    t = np.arange(11.0)
    x = np.array([0, 0, 1, 2, 3, 4, 3, 2, 1, 0, 0], dtype=float)
    # 3 % of 4 = 0.12 first reached at t_a = 1.12; 7.5 % = 0.3 last at t_b = 8.7
    a, b = evaluation_interval(t, x)
    span = 8.7 - 1.12
    assert a == pytest.approx(1.12 - 0.01 * span)
    assert b == 10.0  # 8.7 + 0.2 * span = 10.216 is clipped to the signal end
    a, b = evaluation_interval(t, x, CoraParameters(b_delta_end=0.1))
    assert b == pytest.approx(8.7 + 0.1 * span)
    a, b = evaluation_interval(t, -x, CoraParameters(t_min=2.0))  # sign does not matter
    assert a == 2.0 and b == 10.0


def test_reference_that_never_reaches_the_thresholds_is_an_error():
    with pytest.raises(CurveError, match="never reaches the thresholds") as info:
        cora(T, np.zeros_like(T), T, pulse(T))
    assert info.value.which == "reference"


def test_corridor_rating_by_hand():
    ref = np.zeros(5)
    il, iu, ol, ou = ref - 1.0, ref + 1.0, ref - 3.0, ref + 3.0
    cmp = np.array([0.5, 2.0, -2.0, 3.5, -1.0])
    got = corridor_rating(cmp, il, iu, ol, ou, k=2.0)
    assert got == pytest.approx([1.0, 0.25, 0.25, 0.0, 1.0])


def test_cross_correlation_ratings_by_hand():
    p = CoraParameters(int_min=1.0)  # no shift searched
    xc = cross_correlation_ratings(np.array([1.0, 1, 0, 0]), np.array([0.0, 0, 1, 1]), 1.0, p)
    assert xc["k_xy"] == 0.0 and xc["progression"] == pytest.approx(0.5 ** 10)
    xc = cross_correlation_ratings(np.array([1.0, 2, 3]), np.array([2.0, 4, 6]), 1.0, p)
    assert xc["size"] == pytest.approx(14.0 / 56.0) and xc["progression"] == pytest.approx(1.0)
    xc = cross_correlation_ratings(np.array([1.0, 2, 3]), -np.array([1.0, 2, 3]), 1.0, p)
    assert xc["progression"] == 0.0
    assert xc["cross_correlation"] == pytest.approx(0.25 * 1.0 + 0.25 * 1.0)


def test_user_corridors_replace_the_default_ones():
    ref = pulse(T)
    wide = UserCorridors(T, ref - 10.0, ref + 10.0, ref - 20.0, ref + 20.0)
    r = cora(T, ref, T, ref + 5.0, FIXED, corridors=wide)
    assert r.corridor == 1.0 and r.user_corridors
    narrow = UserCorridors(T, ref - 1.0, ref + 1.0, ref - 3.0, ref + 3.0)
    r = cora(T, ref, T, ref + 2.0, FIXED, corridors=narrow)
    assert r.corridor == pytest.approx(0.25)


def test_single_corridor_is_the_inner_one():
    ref = pulse(T)
    corr = Corridor(T, ref - 0.1, ref + 0.1)
    # outer corridor (b_0 - a_0) * Y_norm = 0.45 outside: a 0.325 offset sits half-way
    r = cora(T, ref, T, ref + 0.325, FIXED, corridors=corr)
    assert r.corridor == pytest.approx(0.25)
    part = Corridor(T[:200], ref[:200] - 0.1, ref[:200] + 0.1)  # only samples it covers
    assert cora(T, ref, T, ref, FIXED, corridors=part).corridor == 1.0
    with pytest.raises(CurveError, match="do not overlap"):
        cora(T, ref, T, ref, CoraParameters(t_min=50.0, t_max=100.0), corridors=part)


def test_user_corridor_validation():
    t = np.arange(3.0)
    with pytest.raises(ValueError, match="outer_lower"):
        UserCorridors(t, t, t - 1, t - 2, t + 2)
    with pytest.raises(ValueError, match="shape"):
        UserCorridors(t, t[:2], t, t, t)


def test_cross_correlation_ratings_are_symmetric_with_a_fixed_interval():
    rng = np.random.default_rng(7)
    a = pulse(T) + 0.1 * rng.normal(size=T.size)
    b = 0.8 * pulse(T, 44.0) + 0.1 * rng.normal(size=T.size)
    p = CoraParameters(t_min=0.0, t_max=100.0, y_norm=1.0)
    ab, ba = cora(T, a, T, b, p), cora(T, b, T, a, p)
    for key in ("phase", "size", "progression", "cross_correlation"):
        assert getattr(ab, key) == pytest.approx(getattr(ba, key), abs=1e-12)
    assert ab.shift_samples == -ba.shift_samples


@pytest.mark.parametrize("kwargs", [dict(a_thres=0.0), dict(b_delta_end=-0.1),
                                    dict(a_0=0.6), dict(d_min=0.2), dict(int_min=0.0),
                                    dict(k_v=0.0), dict(g_v=0, g_g=0, g_p=0), dict(y_norm=0.0),
                                    dict(t_min=5.0, t_max=1.0)])
def test_invalid_parameters(kwargs):
    with pytest.raises(ValueError):
        CoraParameters(**kwargs)


def test_weights_without_normalisation():
    p = CoraParameters(t_min=0.0, t_max=100.0, wf_norm=False, g_1=0.25, g_2=0.25)
    r = cora(T, pulse(T), T, pulse(T), p)
    assert r.total == pytest.approx(0.5)
