"""Run monitors: warn (once each) when a run starts to go wrong.

- total-energy ratio outside 0.9-1.1: names the part whose energy grew most
  since the previous check (the likely spurious source);
- hourglass energy above 10% of internal energy: names the part with the
  largest hourglass energy (and its element when the runtime tracks it);
- time step below 1/100 of the initial step: names the element and part that
  set it.

Warnings go to the run log (and through it to the terminal) and are returned
for summary.json.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from hollowbody.solver.verdict import Thresholds

# the warning limits of the run's verdict (one home for the numbers)
_LIMITS = Thresholds()
ENERGY_RATIO_BAND = (1.0 - _LIMITS.energy_ratio_warn, 1.0 + _LIMITS.energy_ratio_warn)
HOURGLASS_FRACTION = _LIMITS.hourglass_warn
DT_DROP_FACTOR = _LIMITS.dt_drop_warn
NEGLIGIBLE = _LIMITS.negligible


@dataclass
class Monitors:
    """State of the three monitors; ``warnings`` collects every message issued."""

    #: time-varying attributes (saved by the run's State)
    STATE_FIELDS = ("dt_initial", "warnings", "_fired", "_last_part_energy")

    dt_initial: float
    warnings: list[dict] = field(default_factory=list)
    _fired: set[str] = field(default_factory=set)
    _last_part_energy: dict[int, float] = field(default_factory=dict)

    def _fire(self, kind: str, message: str, t: float, **where: object) -> dict | None:
        if kind in self._fired:
            return None
        self._fired.add(kind)
        entry = {"kind": kind, "time_ms": t, "message": message, **where}
        self.warnings.append(entry)
        return entry

    def check(self, t: float, energy_ratio: float, internal: float, hourglass: float,
              part_energy: dict[int, float], part_hourglass: dict[int, tuple[float, int]],
              dt: float, dt_elem: int, dt_part: int, total: float | None = None
              ) -> list[dict]:
        """Run all monitors at time t (ms); returns the warnings newly issued.

        part_energy: {pid: KE+IE+HG J}; part_hourglass: {pid: (HG J, element id
        with the largest hourglass energy or -1)}.
        """
        new = []
        lo, hi = ENERGY_RATIO_BAND
        if not lo <= energy_ratio <= hi and self._last_part_energy:
            growth = {pid: e - self._last_part_energy.get(pid, 0.0)
                      for pid, e in part_energy.items()}
            pid = max(growth, key=lambda p: growth[p]) if growth else -1
            w = self._fire("energy_ratio",
                           f"total-energy ratio {energy_ratio:.3f} left {lo}-{hi} at "
                           f"t={t:.4g} ms; largest energy growth in part {pid}", t, part=pid)
            if w:
                new.append(w)
        self._last_part_energy = dict(part_energy)
        scale = max(abs(total or 0.0), internal + abs(hourglass))
        if (internal > 0.0 and hourglass > HOURGLASS_FRACTION * internal and part_hourglass
                and (total is None or hourglass > NEGLIGIBLE * scale)):
            pid = max(part_hourglass, key=lambda p: part_hourglass[p][0])
            eid = part_hourglass[pid][1]
            where = f"part {pid}" + (f", element {eid}" if eid >= 0 else "")
            w = self._fire("hourglass",
                           f"hourglass energy {hourglass:.4g} J is "
                           f"{100 * hourglass / internal:.1f}% of internal energy at "
                           f"t={t:.4g} ms; largest in {where}", t, part=pid, element=eid)
            if w:
                new.append(w)
        if dt < DT_DROP_FACTOR * self.dt_initial:
            w = self._fire("time_step",
                           f"time step {dt:.4g} ms fell below 1/100 of the initial "
                           f"{self.dt_initial:.4g} ms at t={t:.4g} ms; set by element "
                           f"{dt_elem} (part {dt_part})", t, part=dt_part, element=dt_elem)
            if w:
                new.append(w)
        return new
