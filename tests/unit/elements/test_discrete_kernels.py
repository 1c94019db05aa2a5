"""Helpers of the discrete-element kernels: curves, tangents, the step limit."""

from __future__ import annotations

import numpy as np

from hollowbody.elements.discrete_group import critical_step
from hollowbody.elements.discrete_kernels import (
    curve_inverse,
    curve_slope_near,
    curve_value,
    step_limit,
)

X = np.array([-1.0, 0.0, 2.0, 3.0])
Y = np.array([-4.0, 0.0, 2.0, 12.0])


def test_curve_interpolates_and_extrapolates_with_end_slopes():
    assert curve_value(X, Y, 1.0) == 1.0
    assert curve_value(X, Y, 2.5) == 7.0
    assert curve_value(X, Y, 4.0) == 22.0  # end slope 10
    assert curve_value(X, Y, -2.0) == -8.0  # first slope 4
    for t in (-3.0, -0.5, 0.3, 2.9, 5.0):
        assert abs(curve_inverse(X, Y, curve_value(X, Y, t)) - t) < 1e-12


def test_tangent_looks_one_segment_ahead():
    # segment slopes 4, 1, 10: t = 0.5 lies in segment 1, its neighbours are 0 and 2
    assert curve_slope_near(X, Y, 0.5) == 10.0
    assert curve_slope_near(X, Y, -5.0) == 4.0  # before the start: segments 0 and 1
    assert curve_slope_near(X, Y, 10.0) == 10.0


def test_step_limit_closed_forms():
    # spring alone: 2 / omega; damper alone: 2 m / c; both: the damped limit
    assert abs(step_limit(4.0, 0.0, 1.0) - 1.0) < 1e-15
    assert abs(step_limit(0.0, 0.5, 1.0) - 4.0) < 1e-15
    xi = 0.3
    om = 1.0
    want = 2.0 / om * (np.sqrt(1.0 + xi ** 2) - xi)
    assert abs(step_limit(1.0, 0.6, 1.0) - want) < 1e-15
    assert step_limit(0.0, 0.0, 1.0) == np.inf and step_limit(1.0, 1.0, 0.0) == np.inf
    got = critical_step(np.array([4.0, 0.0, 1.0, 0.0]), np.array([0.0, 0.5, 0.6, 0.0]),
                        np.ones(4))
    assert np.allclose(got[:3], [1.0, 4.0, want]) and got[3] == np.inf
