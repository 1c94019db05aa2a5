"""The step a cycle takes, from the stable step the elements and contacts allow.

The central-difference scheme conserves energy for a constant step (up to its
bounded oscillation), not for a step that changes from cycle to cycle. With
``x^{n+1} = x^n + h_{n+1} v^{n+1/2}``, the scaled velocity ``u = x^{n+1} - x^n``
obeys ``u^{n+1/2} = (h_{n+1} / h_n) u^{n-1/2} + h_{n+1} hbar_n a^n``: the ratio of
two steps multiplies the motion like a pumped parameter. When the stable step is
set by elements whose shape vibrates (a crushed wall shell flapping after the
impactor has left, its step falling each time it is squeezed), the step rises
and falls with that vibration and feeds it (a parametric resonance of the
discrete scheme, not of the model). Measured on the hollow fat block at 40 km/h
(the walls free after the rebound): total energy 1.10 x the initial at 40 ms and
1.15 x at 80 ms, while the elements' accounted energy matched the work of their
nodal forces; with a constant step (0.020 ms) the same run stays at 1.0003 x.

So the step follows the stable step down at once (stability first) and up only
when it is lasting (:class:`StepControl`):

* a stable step below the current step: the step drops to it;
* the step rises only when the stable step has stayed at least ``(1 +
  RISE_THRESHOLD)`` times the current step for ``RISE_CYCLES`` cycles in a row,
  to the smallest stable step of those cycles.

A stable step that oscillates thus ratchets the step down to its lowest value,
where it stays; one that falls steadily (a block being crushed) is followed
cycle by cycle, as before.

The first cycle takes the stable step itself. On the fat block the run then ends
at 1.005 x (80 ms) in 3,515 cycles instead of 4,977 (steady walls keep larger
steps than flapping ones); the solid block at 40 km/h takes 0.7 % more cycles
(9,325 against 9,263). Rising after 5 cycles above 1.005 x lets the fat block
gain 2 % again; 10 cycles above 1.01 x, 20 above 1.01 x, 50 above 1.02 x and 100
above 1.05 x all end at 1.004-1.006 x, at 0.3 / 0.7 / 1.4 / 3.1 % more cycles on
the solid block.
"""

from __future__ import annotations

import math

#: Relative rise of the stable step over the current step that lets the step rise.
RISE_THRESHOLD = 0.01
#: Cycles in a row the stable step must stay that high before the step rises.
RISE_CYCLES = 20


class StepControl:
    """The step of the next cycle from the stable step of each cycle (module doc).

    State (saved in restart files through :attr:`state`): ``hold`` ms the current
    step (0 before the first cycle), ``streak`` the cycles in a row whose stable step
    allowed a rise, ``streak_min`` ms the smallest stable step of those cycles; and
    for the run's summary: ``cycles`` with a finite stable step, ``held`` of them
    with the step below the stable step, ``ratio_sum`` the sum of step / stable step.
    """

    def __init__(self, hold: float = 0.0, streak: int = 0, streak_min: float = math.inf,
                 cycles: int = 0, held: int = 0, ratio_sum: float = 0.0) -> None:
        self.hold = float(hold)
        self.streak = int(streak)
        self.streak_min = float(streak_min)
        self.cycles = int(cycles)
        self.held = int(held)
        self.ratio_sum = float(ratio_sum)

    @property
    def state(self) -> tuple[float, int, float, int, int, float]:
        """(hold ms, streak, streak_min ms, cycles, held, ratio_sum)."""
        return (self.hold, self.streak, self.streak_min, self.cycles, self.held,
                self.ratio_sum)

    def summary(self) -> dict[str, float | int | None]:
        """``held_cycles``: cycles whose step was held below the stable step;
        ``mean_step_over_stable``: the mean ratio of the step to the stable step (None
        before the first cycle)."""
        return {"held_cycles": self.held,
                "mean_step_over_stable": (self.ratio_sum / self.cycles if self.cycles
                                          else None)}

    def next_step(self, stable: float) -> float:
        """The step (ms) of the next cycle, given this cycle's stable step (ms; may be
        inf or 0: returned as is, the run loop reports it)."""
        if not (math.isfinite(stable) and stable > 0.0):
            return stable
        if self.hold <= 0.0:  # the first cycle
            self._set(stable)
        elif stable < self.hold:
            self._set(stable)
        elif stable >= (1.0 + RISE_THRESHOLD) * self.hold:
            self.streak += 1
            self.streak_min = min(self.streak_min, stable)
            if self.streak >= RISE_CYCLES:
                self._set(self.streak_min)
        else:
            self.streak = 0
            self.streak_min = math.inf
        self.cycles += 1
        self.ratio_sum += self.hold / stable
        if self.hold < stable:
            self.held += 1
        return self.hold

    def _set(self, hold: float) -> None:
        self.hold = hold
        self.streak = 0
        self.streak_min = math.inf
