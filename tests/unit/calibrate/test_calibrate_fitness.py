"""Fitness: zero for identical curves, growing with scale and shift, normalised, filtered."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.calibrate.fitness import FitnessSettings, curve_distance
from hollowbody.calibrate.surrogate import surrogate_curve
from hollowbody.curves.force_displacement import ForceDisplacement


@pytest.fixture(scope="module")
def ref() -> ForceDisplacement:
    return surrogate_curve({"E": 100.0, "yield": 4.0}, 40.0)


def _scaled(c: ForceDisplacement, a: float = 1.0, b: float = 1.0, shift: float = 0.0,
            offset: float = 0.0) -> ForceDisplacement:
    return ForceDisplacement(c.time, b * c.displacement + shift, a * c.force + offset)


def test_identical_curves_have_zero_fitness(ref):
    assert curve_distance(ref, ref) == 0.0
    assert curve_distance(ref, _scaled(ref)) == 0.0


@pytest.mark.parametrize("kind", ["force_scale", "force_offset", "displacement_shift",
                                  "displacement_scale"])
def test_fitness_grows_monotonically(ref, kind):
    amounts = [0.0, 0.01, 0.05, 0.1, 0.2, 0.4, 0.8]
    makers = {
        "force_scale": lambda a: _scaled(ref, a=1.0 + a),
        "force_offset": lambda a: _scaled(ref, offset=a * ref.peak_force),
        "displacement_shift": lambda a: _scaled(ref, shift=a * ref.max_displacement),
        "displacement_scale": lambda a: _scaled(ref, b=1.0 + a),
    }
    f = [curve_distance(ref, makers[kind](a)) for a in amounts]
    assert f[0] == 0.0
    assert all(later > earlier for earlier, later in zip(f, f[1:])), f


def test_force_scale_is_linear(ref):
    # |a - 1| * rms of the reference: linear in the scale factor
    f1 = curve_distance(ref, _scaled(ref, a=1.1))
    f2 = curve_distance(ref, _scaled(ref, a=1.2))
    assert f2 == pytest.approx(2.0 * f1, rel=1e-9)
    assert curve_distance(ref, _scaled(ref, a=0.9)) == pytest.approx(f1, rel=1e-9)


def test_normalised_by_reference_peak_and_displacement(ref):
    cand = surrogate_curve({"E": 150.0, "yield": 5.0}, 40.0)
    base = curve_distance(ref, cand)
    # the same pair in other units (force x 1000, displacement x 0.001) scores the same
    r2, c2 = _scaled(ref, a=1000.0, b=0.001), _scaled(cand, a=1000.0, b=0.001)
    assert curve_distance(r2, c2) == pytest.approx(base, rel=1e-9)


def test_fitness_is_grid_independent_near_the_optimum(ref):
    cand = surrogate_curve({"E": 100.5, "yield": 4.01}, 40.0)
    coarse = curve_distance(ref, cand, FitnessSettings(points=101))
    fine = curve_distance(ref, cand, FitnessSettings(points=4001))
    assert coarse < 0.02
    assert coarse == pytest.approx(fine, rel=0.05)


def test_loading_and_unloading_both_count(ref):
    # same loading branch, different unloading: the fitness must see it
    i = int(np.argmax(ref.displacement))
    f = ref.force.copy()
    f[i + 1:] *= 0.5
    assert curve_distance(ref, ForceDisplacement(ref.time, ref.displacement, f)) > 0.05


def test_empty_candidate_gets_the_penalty(ref):
    empty = ForceDisplacement(np.zeros(0), np.zeros(0), np.zeros(0))
    assert curve_distance(ref, empty, FitnessSettings(penalty=7.0)) == 7.0
