"""Continue a validation in its output folder (``hollowbody validate --resume``).

A full validation with hollow tissue runs for hours; it can be stopped (Ctrl-C,
SIGTERM, a closed laptop, a batch system's time limit) and continued later.
Each run of a validation writes a restart file every few minutes of wall time
and one more when it ends (the newest kept; :mod:`hollowbody.solver.dump_policy`).
For one run folder ``<case>/<speed>ms/<tissue>/``, :func:`resume_action` says
what a resumed validation does with it:

* **keep**: it ended normally at (or past) the end time asked for, or with an
  error (running it again would end the same way), or its restart file is at or
  past the end time asked for (a shorter run is not made from a longer one): it
  is read and rated again;
* **resume**: it was stopped (or killed) before its end time, or ended normally
  earlier than a later ``--end-time`` asks for, and has a restart file: it
  continues from the newest one, with the deck and set-up already in the folder;
* **start**: nothing usable is there (no set-up, no restart file): it is set up
  and run from the start.
"""

from __future__ import annotations

import json
from pathlib import Path

from hollowbody import __version__
from hollowbody.solver import restart as rs
from hollowbody.solver.step import ERROR, NORMAL
from hollowbody.validation.setup import Setup

KEEP, RESUME, START = "keep", "resume", "start"

#: Relative tolerance on end times (a run "reached" 40 ms at 39.99999999 ms).
_TOL = 1e-9


def _summary(folder: Path) -> dict:
    p = folder / "summary.json"
    try:
        return json.loads(p.read_text()) if p.is_file() else {}
    except (OSError, ValueError):
        return {}


def _setup_end(folder: Path) -> float | None:
    try:
        return float(json.loads((folder / "setup.json").read_text())["end_time"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def resume_action(folder: Path, end_time: float | None = None) -> tuple[str, str]:
    """What a resumed validation does with the run in ``folder``, and why (one line).

    ``end_time`` ms: the end time asked for (None: the set-up's own)."""
    folder = Path(folder)
    own = _setup_end(folder)
    if own is None or not (folder / "deck.k").is_file():
        return START, "no set-up in its folder: set up and run from the start"
    target = own if end_time is None else float(end_time)
    d = _summary(folder)
    status, reached = d.get("status"), d.get("end_time_ms")
    if status == ERROR:
        return KEEP, f"ended with an error at t={reached:.6g} ms: kept as it is"
    if status == NORMAL and reached is not None and reached >= target * (1.0 - _TOL):
        return KEEP, f"ended normally at t={reached:.6g} ms: kept"
    dumps = rs.dump_files(folder)
    if dumps:
        try:
            head = rs.read_header(dumps[-1])
        except rs.RestartError as err:
            return START, f"its restart file cannot be used ({err}): run from the start"
        if head.get("version") != __version__ or head.get("format") != rs.FORMAT:
            return START, (f"its restart file {dumps[-1].name} was written by hollowbody "
                           f"{head.get('version')}, this is {__version__}: run from the start")
        if head["time_ms"] >= target * (1.0 - _TOL):
            return KEEP, (f"its restart file {dumps[-1].name} is at t={head['time_ms']:.6g} ms, "
                          f"at or past the end time asked for ({target:g} ms): kept as it is")
        what = "ended normally" if status == NORMAL else "stopped"
        at = f" at t={reached:.6g} ms" if reached is not None else ""
        return RESUME, (f"{what}{at}: resumed from {dumps[-1].name} (t={head['time_ms']:.6g} "
                        f"ms) to {target:g} ms")
    if status == NORMAL:
        return START, (f"ended normally at t={reached:.6g} ms without a restart file: run "
                       f"again to {target:g} ms")
    return START, "stopped without a restart file: run from the start"


def update_end_time(folder: Path, end_time: float | None) -> Setup:
    """The set-up of ``folder`` with its end time set to ``end_time`` (None: kept);
    ``setup.json`` is rewritten when it changes (the deck is not touched: the run is
    given the end time)."""
    path = Path(folder) / "setup.json"
    d = json.loads(path.read_text())
    if end_time is not None and float(end_time) != float(d["end_time"]):
        d["end_time"] = float(end_time)
        path.write_text(json.dumps(d, indent=1) + "\n")
    return Setup.from_json(d)
