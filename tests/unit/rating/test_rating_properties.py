"""Property-based checks of both ratings: ranges, identity, symmetry, invariance."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from hollowbody.rating.cora import CoraParameters, cora
from hollowbody.rating.iso18571 import IsoParameters, iso18571

FAST = settings(max_examples=50, deadline=None)
# magnitudes below 1e-6 are zero: the ratings' numerical floors (zero-curve and
# zero-variance checks) are absolute, so denormal curves are not scale-invariant
values = st.floats(min_value=-100.0, max_value=100.0, allow_nan=False,
                   allow_infinity=False).map(lambda v: 0.0 if abs(v) < 1e-6 else v)


@st.composite
def curve_pairs(draw):
    n = draw(st.integers(min_value=5, max_value=60))
    ref = draw(arrays(np.float64, n, elements=values))
    cmp = draw(arrays(np.float64, n, elements=values))
    assume(np.max(np.abs(ref)) > 1e-3)
    return np.arange(n, dtype=np.float64), ref, cmp


ISO = IsoParameters(dt=1.0)
CORA = CoraParameters(dt=0.1)


def in_unit_range(scores):
    return all(np.isfinite(v) and -1e-12 <= v <= 1.0 + 1e-12 for v in scores.values())


@FAST
@given(curve_pairs())
def test_iso_scores_stay_in_range(pair):
    t, ref, cmp = pair
    r = iso18571(t, ref, t, cmp, ISO)
    assert in_unit_range(r.scores())
    assert r.grade in ("excellent", "good", "fair", "poor")


@FAST
@given(curve_pairs())
def test_cora_ratings_stay_in_range(pair):
    t, ref, cmp = pair
    r = cora(t, ref, t, cmp, CORA)
    assert in_unit_range(r.scores())


@FAST
@given(curve_pairs())
def test_identical_curves_rate_one(pair):
    t, ref, _ = pair
    assert all(abs(v - 1.0) < 1e-9 for v in iso18571(t, ref, t, ref, ISO).scores().values())
    r = cora(t, ref, t, ref, CORA)
    assert abs(r.total - 1.0) < 1e-9 and abs(r.corridor - 1.0) < 1e-12


@FAST
@given(curve_pairs())
def test_phase_and_cross_correlation_are_symmetric(pair):
    t, ref, cmp = pair
    assume(np.max(np.abs(cmp)) > 1e-3)
    a, b = iso18571(t, ref, t, cmp, ISO), iso18571(t, cmp, t, ref, ISO)
    assert a.phase == b.phase and abs(a.shift_samples) == abs(b.shift_samples)
    p = CoraParameters(dt=0.1, t_min=0.0, t_max=float(t[-1]), y_norm=1.0)
    c, d = cora(t, ref, t, cmp, p), cora(t, cmp, t, ref, p)
    assert abs(c.shift_samples) == abs(d.shift_samples)
    assert c.phase == d.phase and abs(c.progression - d.progression) < 1e-9
    if c.shift_samples == -d.shift_samples:  # not a tie between +m and -m
        assert abs(c.size - d.size) < 1e-12


@FAST
@given(curve_pairs(), st.floats(min_value=0.01, max_value=100.0),
       st.floats(min_value=-1000.0, max_value=1000.0))
def test_ratings_ignore_units_and_time_origin(pair, scale, offset):
    t, ref, cmp = pair
    a = iso18571(t, ref, t, cmp, ISO).scores()
    b = iso18571(t + offset, scale * ref, t + offset, scale * cmp, ISO).scores()
    assert all(abs(a[k] - b[k]) < 1e-6 for k in a)
    c = cora(t, ref, t, cmp, CORA).scores()
    d = cora(t + offset, scale * ref, t + offset, scale * cmp, CORA).scores()
    assert all(abs(c[k] - d[k]) < 1e-6 for k in c)
