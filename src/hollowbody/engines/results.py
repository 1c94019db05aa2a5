"""An external engine's results as hollowbody's own output files.

``glstat.csv``, ``rcforc.csv`` and ``nodout.csv`` with the columns and units of
:mod:`hollowbody.solver.outputs` (rows from the engine's files, see
:mod:`~hollowbody.engines.lsdyna_ascii`, :mod:`~hollowbody.engines.lsdyna_binout`,
:mod:`~hollowbody.engines.radioss_listing`), and ``summary.json`` with the
entries of a hollowbody run that the engine's files give (status, reason,
``error_*`` location, end time, cycles, energies, wall time; for an error
termination whose last energy record is the collapse itself, the record before it as
``energies_before_error_J``, as a hollowbody run keeps it) plus ``engine``,
``engine_version`` and the command lines run. A value the engine does not
report is NaN in the CSV and null in the summary.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from hollowbody.io.results.history import HistoryWriter
from hollowbody.solver.outputs import GLSTAT_COLUMNS, NODOUT_COLUMNS, RCFORC_COLUMNS
from hollowbody.solver.verdict import before_error

COLUMNS = {"glstat": GLSTAT_COLUMNS, "rcforc": RCFORC_COLUMNS, "nodout": NODOUT_COLUMNS}


def write_histories(out: Path, rows: dict[str, list[list[float]]]) -> list[Path]:
    """Write the histories in ``rows`` ({name: rows}) as ``out/<name>.csv``; returns the
    files written (a name absent from ``rows`` is not written)."""
    written = []
    for name, cols in COLUMNS.items():
        if name not in rows:
            continue
        w = HistoryWriter(Path(out) / f"{name}.csv", list(cols))
        for r in rows[name]:
            if len(r) != len(cols):
                raise ValueError(f"{name}: a row of {len(r)} values for {len(cols)} columns")
            w.write([int(v) if c in ("cycle", "contact", "node") and not _nan(v) else v
                     for c, v in zip(cols, r)])
        w.close()
        written.append(w.path)
    return written


def _nan(v: object) -> bool:
    return isinstance(v, float) and math.isnan(v)


def _clean(v: object) -> object:
    return None if _nan(v) else v


_ENERGY_NAMES = {"kinetic [J]": "kinetic", "internal [J]": "internal",
                 "hourglass [J]": "hourglass", "contact [J]": "contact",
                 "external_work [J]": "external_work", "total [J]": "total",
                 "energy_ratio": "energy_ratio", "added_mass [kg]": "added_mass"}


def last_energies(glstat: list[list[float]]) -> dict[str, float | None]:
    """The last glstat row as the summary's ``energies_J`` ({name: value})."""
    if not glstat:
        return {}
    return {_ENERGY_NAMES[c]: _clean(v) for c, v in zip(GLSTAT_COLUMNS, glstat[-1])
            if c in _ENERGY_NAMES}


def previous_energies(glstat: list[list[float]]) -> dict[str, float | None]:
    """The glstat row before the last as energies ({name: value}) with its ``time_ms``
    ({} with fewer than two rows): the record an error termination is graded on when
    its last one is the collapse itself (:func:`hollowbody.solver.verdict.before_error`)."""
    if len(glstat) < 2:
        return {}
    out = last_energies(glstat[:-1])
    out["time_ms"] = _clean(glstat[-2][GLSTAT_COLUMNS.index("time [ms]")])
    return out


def write_summary(out: Path, *, engine: str, version: str | None, status: str, reason: str,
                  where: dict, end_time_ms: float | None, requested_end_time_ms: float | None,
                  cycles: int | None, wall_seconds: float, glstat: list[list[float]],
                  commands: list[list[str]], notes: list[str]) -> dict:
    """Write ``out/summary.json`` and return it."""
    energies = last_energies(glstat)
    before = before_error(status, energies, previous_energies(glstat))
    summary = {
        "engine": engine,
        "engine_version": version,
        "status": status,
        "reason": reason,
        **{f"error_{k}": v for k, v in where.items()},
        "end_time_ms": end_time_ms,
        "requested_end_time_ms": requested_end_time_ms,
        "cycles": cycles,
        "wall_seconds": wall_seconds,
        "energy_ratio": energies.get("energy_ratio"),
        "energies_J": energies,
        **before,
        "commands": commands,
        "notes": notes,
    }
    (Path(out) / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary
