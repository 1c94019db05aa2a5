"""OpenRadioss's time history (``ROOTT01`` through ``th_to_csv``) as rcforc and nodout rows.

``th_to_csv ROOTT01`` writes ``ROOTT01.csv``: a header of quoted column names,
``"time"`` first, then the global variables (``"INTERNAL ENERGY"``, ...), then
one column per variable of each object of each time-history group, named
``"<group title> <object id> <object title> <variable>"`` when the engine input
asks for titles (``/TH/TITLE``, which hollowbody's engine file does); then one
row per time-history time (``%e`` values, comma separated; the converter
leaves the last value of the last row out, so that row is dropped). Contact
forces are stored as impulses and differentiated into forces by the converter.

hollowbody's native starter input (:mod:`hollowbody.engines.radioss_contact`)
asks for the groups :data:`~hollowbody.engines.radioss_contact.TH_INTER_TITLE`
(FNX FNY FNZ FTX FTY FTZ of every contact) and
:data:`~hollowbody.engines.radioss_contact.TH_NODE_TITLE` (DX DY DZ VX VY VZ of
the history nodes). Units are the deck's (kN, mm, mm/ms).

Contact force: normal + tangential. OpenRadioss's FN + FT of a TYPE25
contact is the force on its secondary (slave) side: on a real run the
impulse of minus that force on the rigid impactor (the master side) equals the
impactor's momentum change within 0.4 %. The master side gets the opposite
force (the penalty forces act in pairs): ``master = MASTER_SIGN (FN + FT)``,
``slave = -master``.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from hollowbody.engines.radioss_contact import TH_INTER_TITLE, TH_NODE_TITLE

#: Sign that turns OpenRadioss's contact force (FN + FT, the slave side's) into the
#: force on the master side, checked on a real run against the impactor's momentum.
MASTER_SIGN = -1.0


def read_th_csv(path: str | Path) -> tuple[list[str], np.ndarray]:
    """(column names with runs of blanks made single, (n_rows, n_columns) values) of
    a ``th_to_csv`` file; rows with a missing value are dropped."""
    with open(path, newline="", encoding="latin-1") as fh:
        reader = csv.reader(fh)
        header = next(reader, [])
        names = [" ".join(h.split()) for h in header]
        rows = []
        for r in reader:
            vals = [v for v in r if v.strip() != ""]
            if len(vals) != len(names):
                continue
            try:
                rows.append([float(v) for v in vals])
            except ValueError:
                continue
    data = np.array(rows, dtype=float).reshape(-1, len(names))
    return names, data


def _group(names: list[str], title: str) -> dict[int, dict[str, int]]:
    """{object id: {variable: column}} of the time-history group ``title``."""
    out: dict[int, dict[str, int]] = {}
    head = title + " "
    for k, name in enumerate(names):
        if not name.startswith(head):
            continue
        rest = name[len(head):].split()
        if len(rest) < 2 or not rest[0].lstrip("-").isdigit():
            continue
        out.setdefault(int(rest[0]), {})[rest[-1].upper()] = k
    return out


def histories(path: str | Path) -> dict[str, list[list[float]]]:
    """``{"rcforc": rows, "nodout": rows}`` (hollowbody's columns, see
    :mod:`hollowbody.solver.outputs`) from a ``th_to_csv`` file; a history whose
    group is absent is left out."""
    names, data = read_th_csv(path)
    out: dict[str, list[list[float]]] = {}
    if data.shape[0] == 0 or not names or names[0].lower() != "time":
        return out
    t = data[:, 0]
    inters = _group(names, TH_INTER_TITLE)
    if inters:
        rows = []
        for i in range(t.size):
            for cid in sorted(inters):
                cols = inters[cid]
                f = [sum(data[i, cols[v]] for v in (f"FN{c}", f"FT{c}") if v in cols)
                     if any(v in cols for v in (f"FN{c}", f"FT{c}")) else math.nan
                     for c in "XYZ"]
                m = [MASTER_SIGN * v for v in f]
                rows.append([float(t[i]), float(cid), *(-v for v in m), *m])
        out["rcforc"] = rows
    nodes = _group(names, TH_NODE_TITLE)
    if nodes:
        rows = []
        for i in range(t.size):
            for nid in sorted(nodes):
                cols = nodes[nid]
                vals = [float(data[i, cols[v]]) if v in cols else math.nan
                        for v in ("DX", "DY", "DZ", "VX", "VY", "VZ")]
                rows.append([float(t[i]), float(nid), *vals])
        out["nodout"] = rows
    return out


def energies_at(path: str | Path, times: np.ndarray) -> dict[str, np.ndarray]:
    """The time history's global hourglass and contact energies (J) at ``times`` (ms;
    linear interpolation, NaN outside the history): ``{"hourglass [J]": ...,
    "contact [J]": ...}``; a variable the file lacks is left out."""
    names, data = read_th_csv(path)
    out: dict[str, np.ndarray] = {}
    if data.shape[0] == 0 or not names:
        return out
    t = data[:, 0]
    for col, name in (("HOURGLASS ENERGY", "hourglass [J]"), ("CONTACT ENERGY", "contact [J]")):
        if col in names:
            v = data[:, names.index(col)]
            out[name] = np.interp(times, t, v, left=math.nan, right=math.nan)
    return out
