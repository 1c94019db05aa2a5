"""An analytic stand-in for the block test (tests, benchmarks, dry runs).

The 5 kg impactor (DESIGN.md section 5) strikes a one-dimensional
elastic-plastic spring whose properties follow the wall parameters:

- elastic stiffness ``k = 0.008 * E * t`` kN/mm (E MPa, t mm),
- yield force ``F_y = 2 * yield * t`` kN, linear hardening
  ``k_h = k * etan / E``,
- a compaction term ``0.5 * (x / 60 mm)^4`` kN that does not depend on the
  parameters (the block bottoming out),

with contact only in compression (the impactor leaves when the spring force
would pull). With E = 100 MPa, yield = 4 MPa, t = 1.5 mm the curve resembles
the solid muscle block at 40 km/h (peak ~12 kN at ~30 mm). The motion is
integrated with the central difference method (step 0.01 ms) and sampled
every 0.02 ms.

``solid()`` is the surrogate at :attr:`SurrogateSimulator.reference` (the
"true" parameters a calibration should recover). ``fail_above`` makes
candidates fail in error termination (e.g. ``{"E": 350}``: every E above
350 MPa "dies by negative volume"), ``cost_seconds`` burns CPU for that long
per run (benchmarks of the parallel runner). Not a model of anything real.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hollowbody.calibrate.simulate import ERROR, NORMAL, RunOutcome
from hollowbody.curves.force_displacement import ForceDisplacement, write_csv
from hollowbody.units import kmh_to_mm_per_ms

MASS = 5.0  # kg
DEFAULTS = {"E": 100.0, "yield": 4.0, "etan": 0.0, "thickness": 1.5}


def surrogate_curve(params: dict[str, float], speed_kmh: float, end_time: float = 20.0,
                    dt: float = 0.01, output_dt: float = 0.02,
                    label: str = "surrogate") -> ForceDisplacement:
    """Force-displacement of the surrogate; time (k,) ms, displacement (k,) mm, force (k,) kN."""
    p = {**DEFAULTS, **params}
    e, sy, et, th = p["E"], p["yield"], p["etan"], p["thickness"]
    k = 0.008 * e * th
    fy = 2.0 * sy * th
    kh = k * et / e if e > 0 else 0.0
    x, v = 0.0, kmh_to_mm_per_ms(speed_kmh)  # compression positive
    xp, alpha = 0.0, 0.0  # plastic displacement, hardening variable
    n = int(round(end_time / dt))
    every = max(1, int(round(output_dt / dt)))
    ts, xs, fs = [0.0], [0.0], [0.0]
    force = 0.0
    for i in range(1, n + 1):
        v -= force / MASS * dt
        x += v * dt
        trial = k * (x - xp)
        limit = fy + kh * alpha
        if trial > limit:  # plastic loading: return to the yield surface
            dg = (trial - limit) / (k + kh)
            xp += dg
            alpha += dg
            trial = k * (x - xp)
        if trial < 0.0:  # the spring does not pull: its unstressed length follows
            xp = x
            trial = 0.0
        force = trial + (0.5 * (x / 60.0) ** 4 if x > 0.0 else 0.0)
        if i % every == 0:
            ts.append(i * dt)
            xs.append(x)
            fs.append(force)
    return ForceDisplacement(np.array(ts), np.array(xs), np.array(fs), label)


def _burn(seconds: float) -> None:
    """Keep one core busy for ``seconds`` (stands in for a solver run)."""
    t_end = time.perf_counter() + seconds
    a = np.random.default_rng(0).random((64, 64))
    while time.perf_counter() < t_end:
        a = np.tanh(a @ a.T * 1e-3)


@dataclass(frozen=True)
class SurrogateSimulator:
    """Simulator protocol (see :mod:`hollowbody.calibrate.simulate`) over the analytic model.

    reference: (name, value) pairs of the parameters that make the "solid"
    curve; fail_above: (name, limit) pairs; cost_seconds: CPU time per run;
    end_time: ms; write_files: write force_displacement.csv and summary.json.
    """

    reference: tuple[tuple[str, float], ...] = (("E", 100.0), ("yield", 4.0))
    fail_above: tuple[tuple[str, float], ...] = ()
    cost_seconds: float = 0.0
    end_time: float = 20.0
    write_files: bool = True

    def _outcome(self, params: dict[str, float], speed_kmh: float, run_dir: Path,
                 label: str) -> RunOutcome:
        t0 = time.perf_counter()
        if self.cost_seconds > 0.0:
            _burn(self.cost_seconds)
        status, reason = NORMAL, f"end time {self.end_time:g} ms reached"
        for name, limit in self.fail_above:
            if params.get(name, DEFAULTS.get(name, 0.0)) > limit:
                status = ERROR
                reason = (f"negative volume (surrogate: {name} = {params[name]:g} above "
                          f"{limit:g})")
        curve = surrogate_curve(params, speed_kmh, self.end_time, label=label)
        if status != NORMAL:  # a run that dies stops early
            keep = curve.time <= 0.3 * self.end_time
            curve = ForceDisplacement(curve.time[keep], curve.displacement[keep],
                                      curve.force[keep], label)
        wall = time.perf_counter() - t0
        summary = {"status": status, "reason": reason,
                   "end_time_ms": float(curve.time[-1]) if curve.time.size else 0.0,
                   "cycles": int(round(float(curve.time[-1]) / 0.01)) if curve.time.size else 0,
                   "wall_seconds": wall,
                   "element_counts": {"hexahedra": 0, "shells": 0}, "surrogate": True}
        if self.write_files:
            run_dir = Path(run_dir)
            run_dir.mkdir(parents=True, exist_ok=True)
            write_csv(curve, run_dir / "force_displacement.csv")
            import json

            (run_dir / "summary.json").write_text(json.dumps(summary, indent=2))
        return RunOutcome(curve, status, reason, wall, summary["cycles"],
                          str(run_dir) if self.write_files else None, summary)

    def solid(self, speed_kmh: float, run_dir: Path) -> RunOutcome:
        return self._outcome(dict(self.reference), speed_kmh, run_dir, "solid (surrogate)")

    def hollow(self, params: dict[str, float], speed_kmh: float, run_dir: Path) -> RunOutcome:
        return self._outcome(dict(params), speed_kmh, run_dir, "hollow (surrogate)")

    def describe(self) -> dict:
        return {"kind": "surrogate", "reference": dict(self.reference),
                "fail_above": dict(self.fail_above), "end_time": self.end_time}
