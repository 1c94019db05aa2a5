"""One candidate's evaluation: hollow runs at every speed, fitness, a JSON record.

:func:`evaluate_candidate` runs in a worker process (or in-process) and never
raises for a bad candidate: a run ending in error termination, or a Python
exception, becomes a record with a penalty fitness and its reason; so does a
run that ends normally with a ``suspect`` verdict (status ``"suspect run"``,
:mod:`hollowbody.solver.verdict`: its curve is not trusted). A record::

    {"key": "E=100.0,yield=4.0", "context": "3f2a...", "params": {"E": 100.0, ...},
     "fitness": 0.0123, "status": "normal termination", "reason": "",
     "wall_seconds": 12.3,
     "runs": [{"speed_kmh": 40.0, "status": ..., "reason": ..., "fitness": ...,
               "wall_seconds": ..., "cycles": ..., "peak_force_kN": ...,
               "max_displacement_mm": ..., "eroded_elements": ..., "quality": "ok",
               "run_dir": ...}, ...]}

The fitness of a record is the sum over speeds of
:func:`~hollowbody.calibrate.fitness.curve_distance`, or
``penalty * len(speeds)`` when any run fails or is suspect (the remaining
speeds are then skipped).
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hollowbody.calibrate.fitness import FitnessSettings, curve_distance
from hollowbody.calibrate.simulate import EXCEPTION, NORMAL, SUSPECT
from hollowbody.curves.force_displacement import ForceDisplacement, smoothed, write_csv
from hollowbody.solver.verdict import SUSPECT as SUSPECT_QUALITY
from hollowbody.solver.verdict import headline, quality_of, verdict_of


def speed_dir(speed_kmh: float) -> str:
    """Folder name of one speed's run, e.g. '40kmh'."""
    return f"{speed_kmh:g}kmh"


def context_hash(simulator_description: dict, speeds: tuple[float, ...],
                 fitness: FitnessSettings) -> str:
    """Short hash of what makes an evaluation's result (cache context)."""
    blob = json.dumps({"simulator": simulator_description, "speeds": list(speeds),
                       "fitness": fitness.to_dict()}, sort_keys=True, default=str)
    return hashlib.sha1(blob.encode()).hexdigest()[:12]


def finite_or_none(v: Any) -> float | None:
    """JSON-safe number: non-finite -> None."""
    try:
        f = float(v)
    except (TypeError, ValueError):
        return None
    return f if math.isfinite(f) else None


def eroded_count(summary: dict | None) -> int | None:
    """Elements a run deleted (its summary's ``eroded_elements``; None if not reported)."""
    v = (summary or {}).get("eroded_elements")
    try:
        return None if v is None else int(v)
    except (TypeError, ValueError):
        return None


def energy_percent(summary: dict | None, part: str, of: str = "total") -> float | None:
    """Energy ``part`` at the end of a run in % of energy ``of`` (keys of the summary's
    ``energies_J``: kinetic, internal, hourglass, contact, total, ...); None when either
    is not reported or ``of`` is not positive. An error termination's failing cycle can
    be unbalanced: its last balanced record (``energies_before_error_J``) is read."""
    s = summary or {}
    e = s.get("energies_before_error_J") or s.get("energies_J") or {}
    if not isinstance(e, dict):
        return None
    a, b = finite_or_none(e.get(part)), finite_or_none(e.get(of))
    if a is None or b is None or b <= 0.0:
        return None
    return 100.0 * a / b


def hourglass_percent(summary: dict | None) -> float | None:
    """Hourglass energy at the end of a run in % of its total energy (None if not reported).

    A quality indicator: above ~10 % the zero-energy modes carry a large share
    of the work and the force-displacement curve is questionable."""
    return energy_percent(summary, "hourglass")


def contact_time_percent(summary: dict | None) -> float | None:
    """Wall time of a run's contacts (search, forces, step limit) in % of the run's
    wall time (``timing_seconds.contact`` over ``wall_seconds_total``, which counts
    the earlier parts of a restarted run as the timings do; None if not reported)."""
    s = summary or {}
    t = s.get("timing_seconds")
    wall = finite_or_none(s.get("wall_seconds_total", s.get("wall_seconds")))
    c = finite_or_none(t.get("contact")) if isinstance(t, dict) else None
    if c is None or wall is None or wall <= 0.0:
        return None
    return 100.0 * c / wall


def pass_through_nodes(summary: dict | None) -> int | None:
    """Nodes the run's contacts reported pushed through a surface (summed over contacts)."""
    c = (summary or {}).get("contact_pass_through")
    if not isinstance(c, dict):
        return None
    try:
        return int(sum(int((v or {}).get("nodes", 0)) for v in c.values()))
    except (TypeError, ValueError, AttributeError):
        return None


@dataclass
class CandidateTask:
    """Everything a worker needs to evaluate one candidate (picklable).

    references: {speed km/h: reference curve}; run_dir: folder of this
    candidate's runs (one sub-folder per speed).
    """

    simulator: Any
    params: dict[str, float]
    key: str
    context: str
    speeds: tuple[float, ...]
    references: dict[float, ForceDisplacement]
    run_dir: str
    fitness: FitnessSettings


def _run_entry(speed: float, out, cfc: float | None) -> dict:
    curve = out.curve
    peak = float(smoothed(curve, cfc).force.max()) if curve.force.size > 1 else None
    return {"speed_kmh": float(speed), "status": out.status, "reason": out.reason,
            "fitness": None, "wall_seconds": finite_or_none(out.wall_seconds),
            "cycles": int(out.cycles), "peak_force_kN": finite_or_none(peak),
            "max_displacement_mm": finite_or_none(curve.max_displacement),
            "eroded_elements": eroded_count(out.summary),
            "quality": quality_of(out.summary), "run_dir": out.run_dir}


def evaluate_candidate(task: CandidateTask) -> dict:
    """Run the hollow block at every speed and score it; returns the record (module doc)."""
    t0 = time.perf_counter()
    n = len(task.speeds)
    runs: list[dict] = []
    total = 0.0
    status, reason = NORMAL, ""
    try:
        for speed in task.speeds:
            rd = Path(task.run_dir) / speed_dir(speed)
            out = task.simulator.hollow(dict(task.params), speed, rd)
            if out.run_dir is not None and not (rd / "force_displacement.csv").exists():
                rd.mkdir(parents=True, exist_ok=True)
                write_csv(out.curve, rd / "force_displacement.csv")
            entry = _run_entry(speed, out, task.fitness.cfc)
            runs.append(entry)
            if out.status != NORMAL:
                status, reason = out.status, f"{speed:g} km/h: {out.reason}"
                break
            if entry["quality"] == SUSPECT_QUALITY:
                verdict = headline(*verdict_of(out.summary))
                status, reason = SUSPECT, f"{speed:g} km/h: {verdict}"
                break
            f = curve_distance(task.references[speed], out.curve, task.fitness)
            entry["fitness"] = f
            total += f
    except Exception as exc:  # a broken candidate must not stop the calibration
        status, reason = EXCEPTION, f"{type(exc).__name__}: {exc}".splitlines()[0]
    fitness = total if status == NORMAL else task.fitness.penalty * n
    return {"key": task.key, "context": task.context, "params": dict(task.params),
            "fitness": float(fitness), "status": status, "reason": reason,
            "wall_seconds": time.perf_counter() - t0, "runs": runs}
