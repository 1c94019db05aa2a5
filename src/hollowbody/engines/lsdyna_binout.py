"""LS-DYNA's ``binout`` (glstat, rcforc, nodout) as rows of hollowbody's histories,
read with lasso-python (``lasso.dyna.Binout``; optional extra
``pip install 'hollowbody[d3plot]'``).

The binout holds one folder per database (``glstat``, ``rcforc``, ``nodout``)
with its variables as arrays over the output times (``time``, then
``kinetic_energy``, ...; per node or per interface side the arrays have one
column per entry of ``ids``). Units are the deck's (see
:mod:`hollowbody.engines.lsdyna_ascii`).
"""

from __future__ import annotations

import glob
import math
from pathlib import Path

import numpy as np

from hollowbody.engines.lsdyna_ascii import GLSTAT_ORDER

#: binout glstat variable -> hollowbody's glstat column.
GLSTAT_VARIABLES = {
    "time": "time [ms]", "cycle": "cycle", "time_step": "dt [ms]",
    "kinetic_energy": "kinetic [J]", "internal_energy": "internal [J]",
    "hourglass_energy": "hourglass [J]", "sliding_interface_energy": "contact [J]",
    "external_work": "external_work [J]", "total_energy": "total [J]",
    "energy_ratio": "energy_ratio", "added_mass": "added_mass [kg]",
}


def available() -> bool:
    """Whether lasso-python is installed."""
    try:
        import lasso.dyna  # noqa: F401
    except ImportError:
        return False
    return True


def _read(binout, *path: str) -> np.ndarray | None:
    try:
        return np.asarray(binout.read(*path))
    except (KeyError, ValueError, IndexError, TypeError, AttributeError):
        return None


def _has(binout, name: str) -> bool:
    try:
        return name in binout.read()
    except (KeyError, ValueError, TypeError):
        return False


def _variables(binout, db: str) -> set[str]:
    """Names of the variables of database ``db`` (lasso lists the ``dNNNNNN`` state
    folders instead when the database has no metadata folder)."""
    names = list(binout.read(db))
    states = [n for n in names if len(n) == 7 and n[0] == "d" and n[1:].isdigit()]
    found = {n for n in names if n not in states and n != "metadata"}
    if states:
        found |= set(binout.read(db, sorted(states)[0]))
    if "metadata" in names:
        found |= set(binout.read(db, "metadata"))
    return found


def glstat_rows(binout) -> list[list[float]]:
    """Rows of glstat.csv from the binout's glstat (NaN where it has no variable)."""
    if not _has(binout, "glstat"):
        return []
    t = _read(binout, "glstat", "time")
    if t is None:
        return []
    n = t.shape[0]
    cols = {c: np.full(n, math.nan) for c in GLSTAT_ORDER}
    names = _variables(binout, "glstat")
    for var, col in GLSTAT_VARIABLES.items():
        if var in names:
            a = _read(binout, "glstat", var)
            if a is not None and a.shape[:1] == (n,):
                cols[col] = a.astype(np.float64).reshape(n)
    return [[float(cols[c][i]) for c in GLSTAT_ORDER] for i in range(n)]


def _per_entry(binout, db: str, var: str, n: int, k: int) -> np.ndarray:
    a = _read(binout, db, var)
    if a is None:
        return np.full((n, k), math.nan)
    return a.astype(np.float64).reshape(n, k)


def nodout_rows(binout) -> list[list[float]]:
    """Rows of nodout.csv: time, node, displacements, velocities."""
    if not _has(binout, "nodout"):
        return []
    t = _read(binout, "nodout", "time")
    ids = _read(binout, "nodout", "ids")
    if t is None or ids is None:
        return []
    ids = ids.reshape(-1).astype(np.int64)
    n, k = t.shape[0], ids.shape[0]
    parts = [_per_entry(binout, "nodout", f"{a}_{q}", n, k)
             for q in ("displacement", "velocity") for a in "xyz"]
    return [[float(t[i]), int(ids[j]), *(float(p[i, j]) for p in parts)]
            for i in range(n) for j in range(k)]


def rcforc_rows(binout) -> list[list[float]]:
    """Rows of rcforc.csv: time, contact, slave and master force components.

    The binout's rcforc has one column per interface side: ``ids`` (interface id)
    and, when present, ``side`` (0: slave, otherwise master). Without ``side`` the
    first column of an interface is taken as its slave side and the second as its
    master side (the order LS-DYNA writes them in rcforc). This layout has been
    checked against synthetic files only (docs/engines.md)."""
    if not _has(binout, "rcforc"):
        return []
    t = _read(binout, "rcforc", "time")
    ids = _read(binout, "rcforc", "ids")
    if t is None or ids is None:
        return []
    ids = ids.reshape(-1).astype(np.int64)
    n, k = t.shape[0], ids.shape[0]
    side = _read(binout, "rcforc", "side")
    if side is not None and side.size == k:
        master = side.reshape(-1).astype(np.int64) != 0
    else:
        master = np.array([bool(np.count_nonzero(ids[:j] == ids[j])) for j in range(k)])
    comps = [_per_entry(binout, "rcforc", f"{a}_force", n, k) for a in "xyz"]
    contacts = sorted(set(int(i) for i in ids))
    rows = []
    for i in range(n):
        for cid in contacts:
            row = [math.nan] * 6
            for j in np.nonzero(ids == cid)[0]:
                off = 3 if master[j] else 0
                row[off:off + 3] = [float(c[i, j]) for c in comps]
            rows.append([float(t[i]), cid, *row])
    return rows


def read_binout(folder: str | Path) -> dict[str, list[list[float]]]:
    """Rows of glstat, rcforc and nodout from ``folder``'s binout files (``binout*``);
    empty when there is none. ImportError when lasso-python is not installed."""
    from lasso.dyna import Binout

    files = sorted(glob.glob(str(Path(folder) / "binout*")))
    if not files:
        return {}
    b = Binout(str(Path(folder) / "binout*"))
    out = {"glstat": glstat_rows(b), "rcforc": rcforc_rows(b), "nodout": nodout_rows(b)}
    return {k: v for k, v in out.items() if v}
