"""Viano (1989) lateral hub impacts on PMHS: specimen curves and corridors.

Lateral impacts of a 23.4 kg, 150 mm diameter rigid hub on post-mortem human
subjects (Viano D.C., "Biomechanical responses and injuries in blunt lateral
impact", Stapp Car Crash Conference 1989, SAE 892432):

=========  ==========================  ===========================
region     impact speeds [m/s = mm/ms]  corridors
=========  ==========================  ===========================
thorax     4.4, 6.5, 9.5               force-time, force-deflection
abdomen    4.8, 6.8, 9.4               force-time, force-deflection
pelvis     5.2, 9.8                    force-time at 5.2 only
=========  ==========================  ===========================

The data (digitised by the SAFER HBM validation catalogue, Apache-2.0) ship
with hollowbody in ``hollowbody/data/viano1989`` together with their
``NOTICE.md`` and licence. Units returned here are hollowbody's: time in ms,
force in kN, deflection in mm (the files give deflection in cm; it is
converted).

File layouts (semicolon-separated, blank cells where a column has ended):

* ``TX_<v>.csv``, ``AB_<v>.csv``: one header row ``R_<id>_t;R_<id>_f;...``,
  time/force column pairs per specimen;
* ``PL_<v>.csv``: three header rows (quantity, specimen id, ``X``/``Y``); a
  pair whose id is ``corr`` is the corridor polygon, not a specimen;
* ``Thorax.csv``, ``abdomen.csv``: per speed class (LS/MS/HS) four columns
  ``force (FD); deflection; force (FT); time``. The force-time columns hold a
  closed polygon; the force-deflection columns hold an upper and a lower
  bound line, separated by a blank row.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from importlib.abc import Traversable

import numpy as np

from hollowbody.rating.corridors import Corridor

#: Deflection in the corridor files is in cm; hollowbody uses mm.
MM_PER_CM = 10.0

#: region -> (file prefix, {speed: speed class})
_REGIONS: dict[str, tuple[str, dict[float, str]]] = {
    "thorax": ("TX", {4.4: "LS", 6.5: "MS", 9.5: "HS"}),
    "abdomen": ("AB", {4.8: "LS", 6.8: "MS", 9.4: "HS"}),
    "pelvis": ("PL", {5.2: "LS", 9.8: "HS"}),
}
_CORRIDOR_FILES = {"thorax": "Thorax.csv", "abdomen": "abdomen.csv"}
KINDS = ("force_time", "force_deflection")


@dataclass(frozen=True)
class SpecimenCurve:
    """One specimen's force-time curve.

    Attributes
    ----------
    name : str
        Specimen id as in the source (e.g. ``"19"``).
    time : ndarray, shape (n,)
        Time [ms], strictly increasing.
    force : ndarray, shape (n,)
        Hub force [kN].
    """

    name: str
    time: np.ndarray
    force: np.ndarray


def data_dir() -> Traversable:
    """Folder of the packaged data files."""
    return resources.files("hollowbody").joinpath("data", "viano1989")


def _read_table(name: str) -> tuple[list[list[str]], list[list[float | None]]]:
    """Split a semicolon file into text rows and numeric rows (None = blank cell)."""
    text = data_dir().joinpath(name).read_text(encoding="utf-8")
    rows = [line.split(";") for line in text.splitlines()]
    return rows, [[None if c.strip() == "" else _number(c) for c in row] for row in rows]


def _number(cell: str) -> float | None:
    try:
        return float(cell)
    except ValueError:
        return None


def _column(values: list[list[float | None]], col: int, start: int) -> list[float | None]:
    return [row[col] if col < len(row) else None for row in values[start:]]


def _pairs(xs: list[float | None], ys: list[float | None]) -> tuple[np.ndarray, np.ndarray]:
    """Leading run of rows where both cells are filled (a column pair's data)."""
    px, py = [], []
    for x, y in zip(xs, ys):
        if x is None or y is None:
            break
        px.append(x)
        py.append(y)
    return np.array(px, dtype=np.float64), np.array(py, dtype=np.float64)


def _resolve(region: str, speed: float) -> tuple[str, str, float, str]:
    key = region.strip().lower()
    if key not in _REGIONS:
        raise ValueError(f"Viano 1989: unknown region {region!r}; choose from "
                         f"{', '.join(sorted(_REGIONS))}")
    prefix, speeds = _REGIONS[key]
    for v, cls in speeds.items():
        if abs(float(speed) - v) < 0.05:
            return key, prefix, v, cls
    raise ValueError(f"Viano 1989: no {key} tests at {speed} m/s; available: "
                     f"{', '.join(f'{v:g}' for v in speeds)} m/s")


def available() -> list[dict[str, object]]:
    """What the data set holds: one entry per region and speed.

    Returns
    -------
    list of dict
        ``{"region": str, "speed": float (m/s), "specimens": int,
        "corridors": tuple of kinds}``.
    """
    out: list[dict[str, object]] = []
    for region, (_, speeds) in _REGIONS.items():
        for v in speeds:
            kinds: tuple[str, ...] = ()
            if region in _CORRIDOR_FILES:
                kinds = KINDS
            elif region == "pelvis" and _pelvis_columns(v)[1] is not None:
                kinds = ("force_time",)
            out.append({"region": region, "speed": v,
                        "specimens": len(load_specimens(region, v)), "corridors": kinds})
    return out


def _pelvis_columns(speed: float) -> tuple[list[tuple[str, int]], int | None]:
    """Specimen (id, column) list and the corridor column of a pelvis file."""
    rows, _ = _read_table(f"PL_{speed:g}.csv")
    ids = [c.strip() for c in rows[1]]
    specimens, corr = [], None
    for col in range(0, len(ids) - 1, 2):
        if ids[col].lower() == "corr":
            corr = col
        else:
            specimens.append((ids[col], col))
    return specimens, corr


def load_specimens(region: str, speed: float) -> list[SpecimenCurve]:
    """Specimen force-time curves of one region and impact speed.

    Parameters
    ----------
    region : {"thorax", "abdomen", "pelvis"}
    speed : float
        Impact speed [m/s] (as in the table of the module docstring).

    Returns
    -------
    list of SpecimenCurve
        Time [ms] and force [kN] per specimen, in file order.
    """
    key, prefix, v, _ = _resolve(region, speed)
    name = f"{prefix}_{v:g}.csv"
    rows, values = _read_table(name)
    curves = []
    if key == "pelvis":
        cols, _ = _pelvis_columns(v)
        for sid, col in cols:
            t, f = _pairs(_column(values, col, 3), _column(values, col + 1, 3))
            curves.append(SpecimenCurve(sid, t, f))
    else:
        header = [c.strip() for c in rows[0]]
        for col in range(0, len(header) - 1, 2):
            sid = header[col].removeprefix("R_").removesuffix("_t")
            t, f = _pairs(_column(values, col, 1), _column(values, col + 1, 1))
            curves.append(SpecimenCurve(sid, t, f))
    for c in curves:
        if c.time.size < 2 or np.any(np.diff(c.time) <= 0.0):
            raise ValueError(f"Viano 1989 {name}: specimen {c.name} has no valid curve")
    return curves


def load_corridor(region: str, speed: float, kind: str = "force_time") -> Corridor:
    """Published response corridor of one region and impact speed.

    Parameters
    ----------
    region : {"thorax", "abdomen", "pelvis"}
    speed : float
        Impact speed [m/s].
    kind : {"force_time", "force_deflection"}
        Force [kN] over time [ms], or force [kN] over deflection [mm].

    Returns
    -------
    Corridor
        From the closed polygon (force-time) or from the upper and lower
        bound lines (force-deflection, over the deflections both lines cover).

    Raises
    ------
    ValueError
        For a region, speed or kind the data set has no corridor for.
    """
    key, prefix, v, cls = _resolve(region, speed)
    if kind not in KINDS:
        raise ValueError(f"Viano 1989: kind must be one of {', '.join(KINDS)}, got {kind!r}")
    label = f"Viano 1989 {key} {v:g} m/s"
    if key == "pelvis":
        _, corr = _pelvis_columns(v)
        if kind != "force_time" or corr is None:
            raise ValueError(f"Viano 1989: no {kind.replace('_', '-')} corridor for the "
                             f"pelvis at {v:g} m/s")
        _, values = _read_table(f"{prefix}_{v:g}.csv")
        px, py = _pairs(_column(values, corr, 3), _column(values, corr + 1, 3))
        return Corridor.from_polygon(px, py, name=label)
    rows, values = _read_table(_CORRIDOR_FILES[key])
    base = 4 * ("LS", "MS", "HS").index(cls)
    if kind == "force_time":
        px, py = _pairs(_column(values, base + 3, 1), _column(values, base + 2, 1))
        return Corridor.from_polygon(px, py, name=label)
    force = _column(values, base, 1)
    defl = _column(values, base + 1, 1)
    xu, yu = _pairs(defl, force)
    rest = len(xu) + 1  # skip the blank separator row
    xl, yl = _pairs(defl[rest:], force[rest:])
    if xu.size < 2 or xl.size < 2:
        raise ValueError(f"Viano 1989 {_CORRIDOR_FILES[key]}: force-deflection bounds of "
                         f"{cls} not found")
    return Corridor.from_bounds(xl * MM_PER_CM, yl, xu * MM_PER_CM, yu, name=label)
