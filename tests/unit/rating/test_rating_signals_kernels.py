"""Curve checks, time base, lag selection and the numba kernels of the ratings."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.errors import UserInputError
from hollowbody.rating.kernels import dtw_band_path, sliding_correlation
from hollowbody.rating.signals import (
    CurveError,
    best_lag,
    check_curve,
    common_interval,
    on_common_base,
    shifted_pair,
    uniform_grid,
)


def test_check_curve_accepts_lists_and_returns_float_arrays():
    t, y = check_curve([0, 1, 2], [1, 2, 3])
    assert t.dtype == np.float64 and y.dtype == np.float64


@pytest.mark.parametrize(
    ("t", "y", "words"),
    [
        ([0.0, 1.0], [1.0], "2 time values but 1"),
        ([0.0], [1.0], "at least 2"),
        ([0.0, 1.0, 1.0], [0.0, 1.0, 2.0], "increase strictly"),
        ([0.0, 2.0, 1.0], [0.0, 1.0, 2.0], "increase strictly"),
        ([0.0, 1.0], [0.0, np.nan], "NaN"),
        ([[0.0, 1.0]], [[0.0, 1.0]], "1-D"),
    ],
)
def test_check_curve_rejects_bad_curves(t, y, words):
    with pytest.raises(CurveError, match=words) as info:
        check_curve(t, y, "candidate")
    assert info.value.which == "candidate"
    assert isinstance(info.value, UserInputError) and isinstance(info.value, ValueError)


def test_common_interval_and_grid():
    a, b = common_interval(np.array([0.0, 10.0]), np.array([2.0, 20.0]))
    assert (a, b) == (2.0, 10.0)
    assert common_interval(np.array([0.0, 10.0]), np.array([0.0, 10.0]), 1.0, 4.0) == (1.0, 4.0)
    with pytest.raises(CurveError, match="do not overlap"):
        common_interval(np.array([0.0, 1.0]), np.array([2.0, 3.0]))
    g = uniform_grid(0.0, 1.0, 0.1)
    assert g.size == 11 and g[-1] == pytest.approx(1.0)
    assert uniform_grid(0.0, 1.05, 0.1).size == 11


def test_on_common_base_needs_three_samples():
    t = np.array([0.0, 1.0])
    with pytest.raises(CurveError, match="smaller time step"):
        on_common_base(t, t, t, t, 0.6, 0.0, 1.0)


def test_shifted_pair_and_best_lag_tie_rules():
    x = np.arange(5.0)
    r, c = shifted_pair(x, x + 10, 2)
    assert list(r) == [0, 1, 2] and list(c) == [12, 13, 14]
    r, c = shifted_pair(x, x + 10, -1)
    assert list(r) == [1, 2, 3, 4] and list(c) == [10, 11, 12, 13]
    # scores for lags -2..2
    assert best_lag(np.array([0.9, 0.5, 0.9, 0.5, 0.9]), 2) == 0      # unshifted wins ties
    assert best_lag(np.array([0.9, 0.5, 0.1, 0.5, 0.9]), 2) == 2      # late candidate wins
    assert best_lag(np.array([0.95, 0.5, 0.1, 0.5, 0.9]), 2) == -2
    assert best_lag(np.array([0.8, 0.5, 0.1, 0.5, 0.9]), 2) == 2
    assert best_lag(np.full(5, np.nan), 2) == 0
    assert best_lag(np.array([0.9, 0.5, 0.1, 0.5, 0.9 - 1e-14]), 2) == 2  # round-off tie


@pytest.mark.parametrize("centred", [True, False])
def test_sliding_correlation_matches_direct_formula(centred):
    rng = np.random.default_rng(1)
    x = rng.normal(size=60)
    y = rng.normal(size=60) + 0.5 * x
    max_lag = 12
    got = sliding_correlation(x, y, max_lag, centred)
    for k, lag in enumerate(range(-max_lag, max_lag + 1)):
        a, b = shifted_pair(x, y, lag)
        if centred:
            want = np.corrcoef(a, b)[0, 1]
        else:
            want = np.dot(a, b) / np.sqrt(np.dot(a, a) * np.dot(b, b))
        assert got[k] == pytest.approx(want, abs=1e-12)


def test_sliding_correlation_undefined_for_constant_parts():
    x = np.ones(10)
    y = np.arange(10.0)
    assert np.all(np.isnan(sliding_correlation(x, y, 2, True)))
    assert np.all(np.isnan(sliding_correlation(np.zeros(10), y, 2, False)))


def _dtw_cost_bruteforce(x, y, radius):
    n = x.size
    d = np.full((n, n), np.inf)
    for i in range(n):
        for j in range(n):
            if abs(i - j) >= radius:
                continue
            c = (x[i] - y[j]) ** 2
            if i == 0 and j == 0:
                d[i, j] = c
                continue
            prev = min(d[i - 1, j - 1] if i and j else np.inf,
                       d[i - 1, j] if i else np.inf,
                       d[i, j - 1] if j else np.inf)
            d[i, j] = c + prev
    return d[n - 1, n - 1]


@pytest.mark.parametrize("radius", [1, 2, 3, 7, 40])
def test_dtw_path_is_valid_and_optimal(radius):
    rng = np.random.default_rng(radius)
    x = np.cumsum(rng.normal(size=25))
    y = np.cumsum(rng.normal(size=25))
    ix, iy = dtw_band_path(x, y, radius)
    assert (ix[0], iy[0]) == (0, 0) and (ix[-1], iy[-1]) == (24, 24)
    steps = set(zip(np.diff(ix), np.diff(iy)))
    assert steps <= {(1, 0), (0, 1), (1, 1)}
    assert np.all(np.abs(ix - iy) < radius)
    cost = np.sum((x[ix] - y[iy]) ** 2)
    assert cost == pytest.approx(_dtw_cost_bruteforce(x, y, radius), rel=1e-12)


def test_dtw_radius_one_is_the_diagonal_and_prefers_diagonal_on_ties():
    x = np.array([0.0, 1.0, 2.0])
    ix, iy = dtw_band_path(x, x + 5.0, 1)
    assert list(ix) == [0, 1, 2] and list(iy) == [0, 1, 2]
    z = np.zeros(6)
    ix, iy = dtw_band_path(z, z, 3)  # every path costs 0: the diagonal is taken
    assert list(ix) == list(range(6)) and list(iy) == list(range(6))
