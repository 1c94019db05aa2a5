"""Efficiency and stability study: the solid and the hollow block at several speeds.

For each speed both blocks run to their end (or their death); each run gives
a row::

    {"structure": "solid", "speed_kmh": 70.0, "status": "error termination",
     "reason": "negative volume in solid element 123 ...", "end_time_ms": 4.2,
     "requested_end_time_ms": 20.0, "cycles": 812, "wall_seconds": 31.0,
     "hexahedra": 6912, "shells": 960, "peak_force_kN": 21.3,
     "peak_force_raw_kN": 80.1, "max_displacement_mm": 60.2, "eroded_elements": 0,
     "energy_ratio": 1.0, "hourglass_percent": 3.9,
     "hourglass_internal_percent": 7.2, "contact_energy_percent": 2.5,
     "contact_time_percent": 4.0, "pass_through_nodes": 0, "quality": "ok",
     "quality_reasons": "", "run_dir": "..."}

Element counts are the run's (the rigid impactor's shells included);
``eroded_elements`` is the number of elements the run deleted (the hollow
block erodes wall shells crushed in their plane; None when the run does not
report it). Peak forces are CFC-filtered
(:func:`hollowbody.curves.force_displacement.smoothed`) and raw (unfiltered, single-cycle
contact spikes included). Quality indicators from the run's summary:
``energy_ratio`` (total / initial energy at the end), ``hourglass_percent``
and ``hourglass_internal_percent`` (hourglass energy at the end in % of the
total and of the internal energy), ``contact_energy_percent`` (the contacts'
energy at the end in % of the total: negative when the contact springs did
net work on the model), ``contact_time_percent`` (the contacts' share of the
run's wall time) and ``pass_through_nodes``
(nodes the contacts reported pushed through a surface); ``quality`` the run's
verdict (ok / warning / suspect, :mod:`hollowbody.solver.verdict`) with its
reasons in one line. A suspect run's curve is not trusted: it is flagged in
every table and plot and left out of the wall-time ratios.
Runs go through a runner (:mod:`hollowbody.calibrate.runner`): serial by
default, so wall times are those of one run on the whole machine; with N
workers they are those of one single-threaded run sharing the machine. The
solver's kernels are compiled in every worker before the measured runs.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hollowbody.calibrate.evaluation import (
    contact_time_percent,
    energy_percent,
    eroded_count,
    finite_or_none,
    hourglass_percent,
    pass_through_nodes,
    speed_dir,
)
from hollowbody.calibrate.reference import read_curve_csv
from hollowbody.calibrate.runner import SerialRunner
from hollowbody.calibrate.simulate import EXCEPTION, LOST
from hollowbody.curves.force_displacement import smoothed
from hollowbody.errors import UserInputError
from hollowbody.scenarios.block import impact_outcome
from hollowbody.solver.verdict import verdict_of

STRUCTURES = ("solid", "hollow")


@dataclass
class StudyTask:
    """One run of the study (picklable). params: hollow wall values ({} = paper's fit)."""

    simulator: Any
    structure: str
    speed_kmh: float
    params: dict[str, float]
    run_dir: str
    cfc: float | None = 180.0


def _empty_row(task: StudyTask, status: str, reason: str) -> dict:
    return {"structure": task.structure, "speed_kmh": float(task.speed_kmh), "status": status,
            "reason": reason, "end_time_ms": None, "requested_end_time_ms": None,
            "cycles": None, "wall_seconds": None, "hexahedra": None, "shells": None,
            "peak_force_kN": None, "peak_force_raw_kN": None, "max_displacement_mm": None,
            "eroded_elements": None, "energy_ratio": None, "hourglass_percent": None,
            "hourglass_internal_percent": None, "contact_energy_percent": None,
            "contact_time_percent": None,
            "pass_through_nodes": None, "outcome": None, "quality": None,
            "quality_reasons": None, "run_dir": task.run_dir}


def run_study_task(task: StudyTask) -> dict:
    """Run one block; its table row (module doc). Never raises for a failed run."""
    rd = Path(task.run_dir)
    try:
        if task.structure == "solid":
            out = task.simulator.solid(task.speed_kmh, rd)
        else:
            out = task.simulator.hollow(dict(task.params), task.speed_kmh, rd)
    except Exception as exc:
        return _empty_row(task, EXCEPTION, f"{type(exc).__name__}: {exc}".splitlines()[0])
    s = out.summary or {}
    counts = s.get("element_counts", {}) or {}
    curve = out.curve
    peak = float(smoothed(curve, task.cfc).force.max()) if curve.force.size > 1 else None
    row = _empty_row(task, out.status, out.reason)
    row.update({"end_time_ms": finite_or_none(s.get("end_time_ms",
                                                    curve.time[-1] if curve.time.size else None)),
                "requested_end_time_ms": finite_or_none(s.get("requested_end_time_ms")),
                "cycles": int(out.cycles), "wall_seconds": finite_or_none(out.wall_seconds),
                "hexahedra": counts.get("hexahedra"), "shells": counts.get("shells"),
                "peak_force_kN": finite_or_none(peak),
                "peak_force_raw_kN": finite_or_none(curve.peak_force_raw),
                "max_displacement_mm": finite_or_none(curve.max_displacement),
                "eroded_elements": eroded_count(s),
                "energy_ratio": finite_or_none(s.get("energy_ratio")),
                "hourglass_percent": finite_or_none(hourglass_percent(s)),
                "hourglass_internal_percent": energy_percent(s, "hourglass", "internal"),
                "contact_energy_percent": energy_percent(s, "contact"),
                "contact_time_percent": contact_time_percent(s),
                "pass_through_nodes": pass_through_nodes(s),
                "outcome": s.get("impact_outcome",
                                 impact_outcome(finite_or_none(curve.max_displacement))),
                "run_dir": out.run_dir})
    quality, reasons = verdict_of(s)
    row["quality"] = quality
    row["quality_reasons"] = "; ".join(r["message"] for r in reasons) if quality else None
    if out.run_dir is None:
        return row
    csv = rd / "force_displacement.csv"
    if not csv.exists():
        from hollowbody.curves.force_displacement import write_csv

        rd.mkdir(parents=True, exist_ok=True)
        write_csv(curve, csv)
    return row


def _warm_up(arg: tuple[Any, dict[str, float]]) -> None:
    simulator, params = arg
    simulator.warm_up(params)


def hollow_from_calibration(path: str | Path) -> dict[str, float]:
    """Best wall parameters of a ``calibration.json`` (calibrated, fixed and defaults)."""
    from hollowbody.calibrate.wall import effective_wall

    data = _calibration_data(path)
    wall = effective_wall(data)
    if wall is None:
        raise UserInputError(f"{path}: the calibration has no valid best candidate")
    return wall


def wall_control_of_calibration(path: str | Path) -> dict:
    """The walls' hourglass control a ``calibration.json`` was run with (BlockConfig
    fields; {} for the block's default)."""
    from hollowbody.calibrate.wall import wall_control

    return wall_control(_calibration_data(path))


def wall_geometry_of_calibration(path: str | Path) -> dict:
    """The walls' geometry a ``calibration.json`` was run with (BlockConfig fields, e.g.
    ``cell``; {} for the block's)."""
    from hollowbody.calibrate.wall import wall_geometry

    return wall_geometry(_calibration_data(path))


def solid_control_of_calibration(path: str | Path) -> dict:
    """The solid reference's hourglass control a ``calibration.json`` was run with
    (BlockConfig fields ``hourglass_ihq``, ``hourglass_qh``)."""
    from hollowbody.calibrate.wall import solid_control

    return solid_control(_calibration_data(path))


def _calibration_data(path: str | Path) -> dict:
    """The content of a ``calibration.json`` (UserInputError naming the file if it is not one)."""
    p = Path(path)
    try:
        data = json.loads(p.read_text())
    except FileNotFoundError:
        raise UserInputError(f"{p}: no such calibration file") from None
    except (json.JSONDecodeError, UnicodeDecodeError):
        raise UserInputError(f"{p}: not a calibration.json file") from None
    if not isinstance(data, dict) or "best_parameters" not in data:
        raise UserInputError(f"{p}: not a calibration.json file (no best_parameters)")
    return data


def run_study(simulator: Any, speeds: Sequence[float], out_dir: str | Path,
              hollow_params: dict[str, float] | None = None, runner: Any = None,
              cfc: float | None = 180.0, structures: Sequence[str] = STRUCTURES,
              warm_up: bool = True) -> list[dict]:
    """Run every (structure, speed); rows sorted by speed then structure; writes study.json.

    Run folders: ``out_dir/<structure>/<speed>kmh``. hollow_params: wall values
    ({name: value}, units of :mod:`hollowbody.calibrate.space`; None: the
    paper's fit). warm_up: first compile the solver's kernels in every worker
    (``simulator.warm_up``, if it has one) so wall times exclude compilation.
    """
    out = Path(out_dir).resolve()  # workers may run elsewhere: absolute run folders
    out.mkdir(parents=True, exist_ok=True)
    runner = runner or SerialRunner()
    if warm_up and hasattr(simulator, "warm_up"):
        runner.broadcast(_warm_up, (simulator, dict(hollow_params or {})))
    tasks = [StudyTask(simulator, st, float(v), dict(hollow_params or {}),
                       str(out / st / speed_dir(v)), cfc)
             for v in speeds for st in structures]
    rows: list[dict | None] = [None] * len(tasks)
    for i, row, err in runner.run(run_study_task, tasks):
        rows[i] = row if err is None else _empty_row(tasks[i], LOST,
                                                      f"worker lost: {type(err).__name__}")
    done = [r for r in rows if r is not None]
    (out / "study.json").write_text(json.dumps(
        {"simulator": simulator.describe(), "speeds_kmh": [float(v) for v in speeds],
         "hollow": hollow_params or "paper's fit", "cfc": cfc,
         "runner": getattr(runner, "description", ""), "rows": done}, indent=1, default=str))
    return done


def load_curves(rows: list[dict]) -> dict[tuple[str, float], Any]:
    """{(structure, speed): ForceDisplacement} of the rows whose curve file exists."""
    curves = {}
    for r in rows:
        if not r.get("run_dir"):
            continue
        p = Path(r["run_dir"]) / "force_displacement.csv"
        if p.exists():
            curves[(r["structure"], r["speed_kmh"])] = read_curve_csv(p, r["structure"])
    return curves
