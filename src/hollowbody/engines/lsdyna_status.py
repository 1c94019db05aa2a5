"""How an LS-DYNA run ended, from its ``d3hsp`` and ``messag`` listings.

LS-DYNA ends both files with ``N o r m a l    t e r m i n a t i o n`` or
``E r r o r   t e r m i n a t i o n`` (letters spaced out); the run's last time
and cycle follow as ``Problem time = ...`` and ``Problem cycle = ...``. A
negative volume is reported on a line naming the solid element (``negative
volume in solid element # 1234``), often with its part and the cycle or time on
the same or the next lines. The version is on the banner's ``Version :`` line.
The reader normalises the spacing and case and takes what the text gives;
what it does not give stays None.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

NORMAL = "normal termination"
ERROR = "error termination"
UNKNOWN = "unknown termination"

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"


@dataclass
class Termination:
    """status (NORMAL / ERROR / UNKNOWN), one-line reason, where the error was
    (``element``, ``part``, ``cycle``, ``time_ms``: what the listing gives), the
    problem's last time (ms) and cycle, and the engine's version."""

    status: str = UNKNOWN
    reason: str = "no termination message (the run did not finish, or its listing is missing)"
    where: dict = field(default_factory=dict)
    end_time_ms: float | None = None
    cycles: int | None = None
    version: str | None = None


def _squash(line: str) -> str:
    """Lower case without blanks: ``N o r m a l  t e r m`` -> ``normalterm``."""
    return re.sub(r"\s+", "", line).lower()


def _float(s: str) -> float:
    return float(s.replace("D", "E").replace("d", "e"))


def _negative_volume(lines: list[str], i: int) -> dict:
    """Element, part, cycle, time of the negative volume reported at line i (and the
    two lines after it)."""
    text = " ".join(lines[i:i + 3]).lower()
    where: dict = {}
    for key, pat in (("element", r"element\s*(?:#|no\.?|id|number)?\s*=?\s*(\d+)"),
                     ("part", r"part\s*(?:#|no\.?|id|number)?\s*=?\s*(\d+)"),
                     ("cycle", r"cycle\s*(?:#|no\.?|number)?\s*=?\s*(\d+)")):
        m = re.search(pat, text)
        if m:
            where[key] = int(m.group(1))
    m = re.search(r"time\s*=?\s*(" + _NUM + ")", text)
    if m:
        where["time_ms"] = _float(m.group(1))
    return where


def parse_listing(text: str, into: Termination | None = None) -> Termination:
    """Read one listing's text (d3hsp or messag) into ``into`` (or a new Termination)."""
    term = into or Termination()
    lines = text.splitlines()
    for i, line in enumerate(lines):
        sq = _squash(line)
        if term.version is None:
            m = re.search(r"\bversion\s*:\s*(.+?)\s*\|?\s*$", line, re.IGNORECASE)
            if m and m.group(1):
                term.version = m.group(1).strip()
        if "normaltermination" in sq:
            term.status, term.reason = NORMAL, "normal termination"
        elif "errortermination" in sq:
            if term.status != ERROR:
                term.reason = "error termination" if not term.where else term.reason
            term.status = ERROR
        if "negativevolume" in sq:
            where = _negative_volume(lines, i)
            if where and "element" not in term.where:
                term.where.update(where)
                desc = f"negative volume in solid element {where.get('element', '?')}"
                if "part" in where:
                    desc += f" of part {where['part']}"
                if "time_ms" in where:
                    desc += f" at t={where['time_ms']:.6g} ms"
                elif "cycle" in where:
                    desc += f" at cycle {where['cycle']}"
                term.reason = desc
        m = re.search(r"problem\s+time\s*=\s*(" + _NUM + ")", line, re.IGNORECASE)
        if m:
            term.end_time_ms = _float(m.group(1))
        m = re.search(r"problem\s+cycle\s*=\s*(\d+)", line, re.IGNORECASE)
        if m:
            term.cycles = int(m.group(1))
    if term.status == NORMAL and term.where:  # a warning of an eroded element, not the end
        term.reason = "normal termination"
    return term


def read_termination(folder: str | Path) -> Termination:
    """How the LS-DYNA run in ``folder`` ended: ``d3hsp`` first, then ``messag`` (SMP) or
    ``mes0000``, ``mes0001``, ... (MPP, one per rank), whose messages add the error's
    location when d3hsp lacks it."""
    folder = Path(folder)
    term = Termination()
    files = [folder / "d3hsp", folder / "messag", *sorted(folder.glob("mes[0-9][0-9][0-9]*"))]
    for p in files:  # MPP writes one message file per rank: mes0000, mes0001, ...
        if p.is_file():
            parse_listing(p.read_text(encoding="latin-1", errors="replace"), term)
    return term
