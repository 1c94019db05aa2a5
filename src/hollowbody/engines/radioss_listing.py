"""OpenRadioss's engine listing (``ROOT_0001.out``): cycles, energies, termination.

Every /PRINT cycles the engine writes a row under the header ``CYCLE TIME
TIME-STEP ELEMENT ERROR I-ENERGY K-ENERGY T K-ENERGY R EXT-WORK MAS.ERR TOTAL
MASS MASS ADDED``: the cycle (I8), time and time step (G11.4), the element type
(5 characters) and id (I10) that set the step, the energy error (F5.1 and
``%``), then internal, translational and rotational kinetic energy, external
work, the relative mass error, the total mass and the mass added (G11.4).
The run ends with ``NORMAL TERMINATION`` or ``ERROR TERMINATION`` and ``TOTAL
NUMBER OF CYCLES : N``; an inverted solid stops it with ``** STOP: ZERO OR
NEGATIVE VOLUME FOR 3D-ELEMENT ID=N`` (the id may be on the next line; the
``WARNING`` and ``DELETE`` forms of the message, eroded elements, do not end the
run). The version is on the ``OpenRadioss Engine VERSION`` title line.

The rows become glstat.csv rows (deck units: J, ms, kg); hourglass and contact
energies are not in the table (NaN), the energy ratio is hollowbody's (total /
(initial total + external work)).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from hollowbody.engines.lsdyna_ascii import GLSTAT_ORDER
from hollowbody.engines.lsdyna_status import ERROR, NORMAL, UNKNOWN

_NUM = r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[EeDd][-+]?\d+)?"
_ROW = re.compile(r"^\s*(\d+)\s+(" + _NUM + r")\s+(" + _NUM + r")\s+([A-Z_0-9]+)\s+(\d+)\s+("
                  + _NUM + r")\s*%\s+(" + _NUM + r")\s+(" + _NUM + r")\s+(" + _NUM + r")\s+("
                  + _NUM + r")(?:\s+(" + _NUM + r"))?(?:\s+(" + _NUM + r"))?(?:\s+(" + _NUM
                  + r"))?")


@dataclass
class RadiossListing:
    """status, reason and where (element, time_ms, cycle) of the run's end; rows of
    glstat.csv (:data:`GLSTAT_ORDER`); the engine's version banner; the last cycle
    and time (ms) of the table; the element type and id that set the last step."""

    status: str = UNKNOWN
    reason: str = "no termination message (the run did not finish, or its listing is missing)"
    where: dict = field(default_factory=dict)
    rows: list[list[float]] = field(default_factory=list)
    version: str | None = None
    cycles: int | None = None
    end_time_ms: float | None = None
    dt_element: tuple[str, int] | None = None


def _f(s: str) -> float:
    return float(s.replace("D", "E").replace("d", "e"))


def parse_listing(text: str) -> RadiossListing:
    """Read the engine listing's text."""
    out = RadiossListing()
    e0: float | None = None
    pending = 0  # lines left in which the id of a negative volume is looked for
    for line in text.splitlines():
        up = line.upper()
        if out.version is None and "OPENRADIOSS" in up:
            v = line.strip().strip("*").strip()
            if v:
                out.version = v
        m = _ROW.match(line)
        if m:
            cyc, t, dt = int(m.group(1)), _f(m.group(2)), _f(m.group(3))
            ie, ket, ker, work = (_f(m.group(k)) for k in (7, 8, 9, 10))
            total = ie + ket + ker
            if e0 is None:
                e0 = total
            denom = e0 + work
            ratio = total / denom if denom != 0.0 else math.nan
            row = {"time [ms]": t, "cycle": float(cyc), "dt [ms]": dt, "kinetic [J]": ket + ker,
                   "internal [J]": ie, "external_work [J]": work, "total [J]": total,
                   "energy_ratio": ratio}
            if m.group(13) is not None:
                row["added_mass [kg]"] = _f(m.group(13))
            out.rows.append([row.get(c, math.nan) for c in GLSTAT_ORDER])
            out.cycles, out.end_time_ms = cyc, t
            out.dt_element = (m.group(4), int(m.group(5)))
            continue
        sq = re.sub(r"\s+", "", up)
        if "NEGATIVEVOLUME" in sq and "WARNING" not in up and "DELETE" not in up:
            pending = 2  # the element id is on this line or the next
        if pending and "element" not in out.where:
            m = re.search(r"\bID\s*[=:]\s*(\d+)", up)
            if m:
                out.where["element"] = int(m.group(1))
                if out.end_time_ms is not None:
                    out.where["time_ms"] = out.end_time_ms
                    out.where["cycle"] = out.cycles
                near = (f" near t={out.end_time_ms:.6g} ms" if out.end_time_ms is not None
                        else "")
                out.reason = f"negative volume in solid element {m.group(1)}{near}"
                pending = 0
        pending = max(pending - 1, 0)
        m = re.search(r"TOTAL NUMBER OF CYCLES\s*:\s*(\d+)", up)
        if m:
            out.cycles = int(m.group(1))
        if "NORMALTERMINATION" in sq:
            out.status, out.reason = NORMAL, "normal termination"
        elif "ERRORTERMINATION" in sq:
            if "element" not in out.where:
                out.reason = "error termination"
            out.status = ERROR
        if "USERBREAK" in sq and out.status == UNKNOWN:
            out.status, out.reason = ERROR, "user break"
    return out


def read_listing(*paths: str | Path) -> RadiossListing:
    """:func:`parse_listing` of the listing file, followed by other files of the run
    (the engine's standard output, where messages also go); files that are missing
    are skipped (an empty result when none exists)."""
    texts = [Path(p).read_text(encoding="latin-1", errors="replace")
             for p in paths if Path(p).is_file()]
    return parse_listing("\n".join(texts))


def starter_errors(path: str | Path, limit: int = 3) -> list[str]:
    """The first ``limit`` errors of a starter listing (``ROOT_0000.out``), each as one
    line: ``error N: title; description lines`` (the message ends at the first blank
    line after its description); an empty list when there is none or no file."""
    p = Path(path)
    if not p.is_file():
        return []
    lines = p.read_text(encoding="latin-1", errors="replace").splitlines()
    out: list[str] = []
    for k, line in enumerate(lines):
        m = re.match(r"\s*ERROR ID\s*:\s*(\d+)", line)
        if not m:
            continue
        body: list[str] = []
        described = False
        for nxt in lines[k + 1:k + 12]:
            text = nxt.strip().strip("*").strip()
            if re.match(r"\s*(ERROR|WARNING) ID\s*:", nxt) or (described and not text):
                break  # the next message, or the blank line that ends this one
            if text.startswith("DESCRIPTION"):
                described = True
            elif text:
                body.append(text)
        out.append(f"error {m.group(1)}: " + "; ".join(body))
        if len(out) >= limit:
            break
    return out
