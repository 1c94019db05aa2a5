"""The step control: down at once, up only after a lasting rise of the stable step."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.solver.step_control import RISE_CYCLES, RISE_THRESHOLD, StepControl


def _feed(ctl: StepControl, stable) -> np.ndarray:  # noqa: ANN001
    return np.array([ctl.next_step(float(s)) for s in stable])


def test_first_cycle_takes_the_stable_step_and_drops_follow_at_once():
    ctl = StepControl()
    assert ctl.next_step(1.0e-3) == 1.0e-3
    steps = _feed(ctl, [0.9e-3, 0.8e-3, 0.85e-3, 0.5e-3])
    # every drop taken in the same cycle; the small rise to 0.85 is not
    assert steps.tolist() == [0.9e-3, 0.8e-3, 0.8e-3, 0.5e-3]
    assert np.all(steps <= [0.9e-3, 0.8e-3, 0.85e-3, 0.5e-3])  # never above the stable step


def test_an_oscillating_stable_step_gives_a_constant_step_at_its_lowest_value():
    """The stable step of a flapping wall: +-5 % at a period of 7 cycles. The step goes
    down to the lowest value once and then stays constant (no step-to-step modulation
    to pump the motion), always at or below the stable step."""
    ctl = StepControl()
    k = np.arange(2000)
    stable = 1.0e-2 * (1.0 + 0.05 * np.sin(2.0 * np.pi * k / 7.0))
    steps = _feed(ctl, stable)
    assert np.all(steps <= stable * (1.0 + 1e-15))
    tail = steps[50:]
    assert np.ptp(tail) <= 1e-12 * tail[0]  # constant: new lows differ by round-off only
    assert tail[0] == pytest.approx(stable.min(), rel=1e-12)


def test_the_step_rises_after_a_lasting_rise_to_the_smallest_stable_step_of_it():
    ctl = StepControl()
    ctl.next_step(1.0)
    higher = 1.0 + 3.0 * RISE_THRESHOLD
    stable = [higher + 0.01 * (i % 3) for i in range(RISE_CYCLES)]
    steps = _feed(ctl, stable)
    assert np.all(steps[:-1] == 1.0)  # held for RISE_CYCLES - 1 cycles
    assert steps[-1] == pytest.approx(higher, rel=1e-15)  # the streak's smallest


def test_a_rise_interrupted_before_it_lasted_starts_over():
    ctl = StepControl()
    ctl.next_step(1.0)
    up = 1.0 + 2.0 * RISE_THRESHOLD
    stable = [up] * (RISE_CYCLES - 1) + [1.0 + 0.5 * RISE_THRESHOLD] + [up] * (RISE_CYCLES - 1)
    assert np.all(_feed(ctl, stable) == 1.0)
    assert ctl.next_step(up) == pytest.approx(up)


def test_no_finite_stable_step_is_passed_on_unchanged():
    ctl = StepControl()
    assert ctl.next_step(math.inf) == math.inf
    assert ctl.next_step(0.0) == 0.0
    assert ctl.state == (0.0, 0, math.inf, 0, 0, 0.0)
    assert ctl.summary() == {"held_cycles": 0, "mean_step_over_stable": None}
    ctl.next_step(2.0)
    assert math.isnan(ctl.next_step(math.nan)) and ctl.hold == 2.0


def test_its_state_carries_a_run_on_bit_for_bit():
    """A restart rebuilds the control from ``state`` (a tuple of plain numbers)."""
    rng = np.random.default_rng(3)
    stable = 1.0e-3 * (1.0 + 0.1 * rng.random(500)) * np.linspace(1.0, 1.5, 500)
    whole = StepControl()
    ref = _feed(whole, stable)
    first = StepControl()
    a = _feed(first, stable[:237])
    resumed = StepControl(*first.state)
    b = _feed(resumed, stable[237:])
    assert np.array_equal(np.concatenate([a, b]), ref)
    assert all(isinstance(v, (int, float)) for v in first.state)


def test_its_summary_counts_the_held_cycles_and_the_mean_ratio():
    ctl = StepControl()
    _feed(ctl, [2.0, 1.0, 1.005, 1.5, 1.0])  # held at 1.0 below 1.005 and 1.5
    assert ctl.summary()["held_cycles"] == 2
    assert ctl.summary()["mean_step_over_stable"] == pytest.approx(
        (1.0 + 1.0 + 1.0 / 1.005 + 1.0 / 1.5 + 1.0) / 5.0, rel=1e-15)

