"""LS-DYNA's ASCII databases ``glstat``, ``rcforc`` and ``nodout`` as rows of hollowbody's
histories (columns of ``glstat.csv``, ``rcforc.csv``, ``nodout.csv``).

The files are in the deck's units; hollowbody's decks are in mm, ms, kg, kN, so
energies are in J (kN*mm), forces in kN, displacements in mm and velocities in
mm/ms, the units of the CSV columns. Layouts (LS-DYNA's ASCII output):

- ``glstat``: one block per output time; a ``dt of cycle N is controlled by ...``
  line gives the cycle, then ``name ........ value`` lines (``time``, ``time
  step``, ``kinetic energy``, ``internal energy``, ``hourglass energy``,
  ``sliding interface energy``, ``external work``, ``total energy``, ``total
  energy / initial energy``, ``added mass``, ...).
- ``rcforc``: one line per interface side and time: ``master|slave ID time T x
  FX y FY z FZ mass M`` (``x force``, ... in some versions).
- ``nodout``: blocks headed ``n o d a l  p r i n t  o u t  f o r  t i m e  s t e p
  N ( at time T )``, then the table ``nodal point x-disp y-disp z-disp x-vel y-vel
  z-vel x-accl ...`` (one row per node; the numbers in fixed columns may touch);
  a second table with ``x-rot`` (rotations) is skipped.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from hollowbody.solver.outputs import GLSTAT_COLUMNS

NUM = r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[EeDd][-+]?\d+)?"
_FLOAT_IN_COLUMN = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+)(?:[EeDd][-+]?\d+)?")

#: glstat names (dots and blanks removed, lower case) -> hollowbody's glstat column.
GLSTAT_NAMES = {
    "time": "time [ms]",
    "timestep": "dt [ms]",
    "kineticenergy": "kinetic [J]",
    "internalenergy": "internal [J]",
    "hourglassenergy": "hourglass [J]",
    "slidinginterfaceenergy": "contact [J]",
    "externalwork": "external_work [J]",
    "totalenergy": "total [J]",
    "totalenergy/initialenergy": "energy_ratio",
    "addedmass": "added_mass [kg]",
}
#: The columns of glstat.csv (those of hollowbody's own runs).
GLSTAT_ORDER = GLSTAT_COLUMNS


def _f(s: str) -> float:
    return float(s.replace("D", "E").replace("d", "e"))


def _text(path: str | Path) -> str:
    return Path(path).read_text(encoding="latin-1", errors="replace")


def parse_glstat(text: str) -> list[list[float]]:
    """Rows of glstat.csv (:data:`GLSTAT_ORDER`; NaN where the file has no value)."""
    rows: list[dict[str, float]] = []
    cycle = math.nan
    for line in text.splitlines():
        m = re.search(r"dt\s+of\s+cycle\s+(\d+)", line)
        if m:
            cycle = float(m.group(1))
            continue
        m = re.match(r"\s*([A-Za-z][A-Za-z /()%.-]*?)\s*\.{2,}\s*(" + NUM + r")\s*$", line)
        if not m:
            continue
        key = re.sub(r"[\s.]", "", m.group(1)).lower()
        col = GLSTAT_NAMES.get(key)
        if col is None:
            continue
        if col == "time [ms]":
            rows.append({"cycle": cycle})
        if rows:
            rows[-1][col] = _f(m.group(2))
    return [[r.get(c, math.nan) for c in GLSTAT_ORDER] for r in rows]


_RCFORC = re.compile(r"^\s*(master|slave)\s+(\d+)\s+time\s*(" + NUM + r")\s+x(?:\s+force)?\s*("
                     + NUM + r")\s+y(?:\s+force)?\s*(" + NUM + r")\s+z(?:\s+force)?\s*(" + NUM
                     + ")", re.IGNORECASE)


def parse_rcforc(text: str) -> list[list[float]]:
    """Rows of rcforc.csv: time, contact, slave fx fy fz, master fx fy fz (one row per
    contact and time; a side that is not in the file is NaN)."""
    by_key: dict[tuple[float, int], list[float]] = {}
    order: list[tuple[float, int]] = []
    for line in text.splitlines():
        m = _RCFORC.match(line)
        if not m:
            continue
        side, cid, t = m.group(1).lower(), int(m.group(2)), _f(m.group(3))
        key = (t, cid)
        if key not in by_key:
            by_key[key] = [math.nan] * 6
            order.append(key)
        off = 0 if side == "slave" else 3
        by_key[key][off:off + 3] = [_f(m.group(k)) for k in (4, 5, 6)]
    return [[t, cid, *by_key[(t, cid)]] for t, cid in order]


def parse_nodout(text: str) -> list[list[float]]:
    """Rows of nodout.csv: time, node, ux uy uz, vx vy vz (translational table only)."""
    rows: list[list[float]] = []
    t = math.nan
    table = False
    for line in text.splitlines():
        if "at time" in line:
            m = re.search(r"at\s+time\s+(" + NUM + ")", line)
            if m:
                t = _f(m.group(1))
            table = False
            continue
        low = line.lower()
        if "nodal point" in low:
            table = "x-disp" in low
            continue
        if not table:
            continue
        m = re.match(r"\s*(\d+)(.*)$", line)
        if not m:
            if line.strip():
                table = False
            continue
        vals = [_f(v) for v in _FLOAT_IN_COLUMN.findall(m.group(2))]
        if len(vals) >= 6:
            rows.append([t, int(m.group(1)), *vals[:6]])
    return rows


def read_ascii(folder: str | Path) -> dict[str, list[list[float]]]:
    """The rows of the ASCII databases present in ``folder`` ({name: rows})."""
    folder = Path(folder)
    out: dict[str, list[list[float]]] = {}
    for name, parse in (("glstat", parse_glstat), ("rcforc", parse_rcforc),
                        ("nodout", parse_nodout)):
        p = folder / name
        if p.is_file():
            out[name] = parse(_text(p))
    return out
