"""The solid reference runs of a calibration, one per speed, cached on disk.

``DIR/reference/<speed>kmh/`` holds the run (deck.k, histories, summary.json,
force_displacement.csv) and ``reference.json``: the simulator description,
speed, status and reason. A reference is reused when ``reference.json``
exists, its description equals the current one, its status is normal
termination and the curve file is present; otherwise it is run again.

A reference that does not end normally stops the calibration
(:class:`ReferenceRunError`): there is nothing to fit against.
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from hollowbody.calibrate.evaluation import finite_or_none, speed_dir
from hollowbody.calibrate.simulate import EXCEPTION, NORMAL
from hollowbody.curves.force_displacement import ForceDisplacement, write_csv
from hollowbody.solver.run_lock import check_free

CURVE_FILE = "force_displacement.csv"
REFERENCE_FILE = "reference.json"


class ReferenceRunError(RuntimeError):
    """A solid reference run did not end normally."""


def read_curve_csv(path: str | Path, label: str = "") -> ForceDisplacement:
    """A curve written by :func:`~hollowbody.curves.force_displacement.write_csv`."""
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.size == 0:
        return ForceDisplacement(np.zeros(0), np.zeros(0), np.zeros(0), label)
    return ForceDisplacement(data[:, 0], data[:, 1], data[:, 2], label)


@dataclass
class ReferenceTask:
    """One solid reference run (picklable)."""

    simulator: Any
    speed_kmh: float
    run_dir: str
    description: dict


def run_reference(task: ReferenceTask) -> dict:
    """Run the solid block; write ``reference.json``; return its content."""
    rd = Path(task.run_dir)
    if rd.exists():
        check_free(rd)  # a reference still running there (another calibration): keep it
        shutil.rmtree(rd)
    rd.mkdir(parents=True)
    try:
        out = task.simulator.solid(task.speed_kmh, rd)
        status, reason = out.status, out.reason
        wall, cycles = out.wall_seconds, out.cycles
        if not (rd / CURVE_FILE).exists():
            write_csv(out.curve, rd / CURVE_FILE)
    except Exception as exc:
        status, reason = EXCEPTION, f"{type(exc).__name__}: {exc}".splitlines()[0]
        wall, cycles = None, 0
    info = {"speed_kmh": float(task.speed_kmh), "status": status, "reason": reason,
            "wall_seconds": finite_or_none(wall), "cycles": int(cycles),
            "description": task.description}
    (rd / REFERENCE_FILE).write_text(json.dumps(info, indent=2, default=str))
    return info


def load_reference(run_dir: Path, description: dict) -> ForceDisplacement | None:
    """The cached reference curve in ``run_dir`` if it is complete and matches, else None."""
    info_path = run_dir / REFERENCE_FILE
    if not (info_path.exists() and (run_dir / CURVE_FILE).exists()):
        return None
    try:
        info = json.loads(info_path.read_text())
    except json.JSONDecodeError:
        return None
    same = json.loads(json.dumps(description, default=str)) == info.get("description")
    if not same or info.get("status") != NORMAL:
        return None
    curve = read_curve_csv(run_dir / CURVE_FILE, label="solid")
    return curve if curve.displacement.size > 1 else None


def ensure_references(simulator: Any, speeds: Sequence[float], root: str | Path,
                      runner: Any) -> dict[float, ForceDisplacement]:
    """{speed: solid reference curve}, running (in parallel) only what is not cached.

    root: ``DIR/reference``; runner: a :mod:`hollowbody.calibrate.runner` runner.
    Raises :class:`ReferenceRunError` when a reference run does not end normally.
    """
    root = Path(root)
    description = simulator.describe()
    curves: dict[float, ForceDisplacement] = {}
    todo = []
    for s in speeds:
        c = load_reference(root / speed_dir(s), description)
        if c is None:
            todo.append(ReferenceTask(simulator, float(s), str(root / speed_dir(s)),
                                      description))
        else:
            curves[float(s)] = c
    failures = []
    for i, info, err in runner.run(run_reference, todo):
        task = todo[i]
        if err is not None or info["status"] != NORMAL:
            why = str(err) if err is not None else f"{info['status']}: {info['reason']}"
            failures.append(f"{task.speed_kmh:g} km/h ({why})")
            continue
        curves[task.speed_kmh] = read_curve_csv(Path(task.run_dir) / CURVE_FILE, "solid")
    if failures:
        raise ReferenceRunError("the solid reference did not end normally at "
                             + "; ".join(failures) + f" - see {root}")
    return {float(s): curves[float(s)] for s in speeds}
