"""Beam keywords: *SECTION_BEAM, *ELEMENT_BEAM, *INTEGRATION_BEAM (docs/beams.md).

Field names are the LS-DYNA ones in lower case (``qr`` is QR/IRID); defaults
are LS-DYNA's. The second card of *SECTION_BEAM depends on ELFORM: for the
integrated beams (ELFORM 1, 11) TS1 TS2 TT1 TT2 NSLOC NTLOC, for the resultant
beams (ELFORM 2, 12, 13) A ISS ITT J SA IST; other formulations are read
with their second card in the A .. IST fields and rejected by the builder.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from hollowbody.io.keyword import bulk
from hollowbody.io.keyword.base import Block, Cursor, KeywordItem, SimpleKeyword, register
from hollowbody.io.keyword.cards import Field, field_width, format_card

#: ELFORM values whose second card is the integrated-section card (TS1 ...).
INTEGRATED_ELFORMS = (1, 11)
#: ELFORM values whose second card is the resultant card (A ISS ITT ...).
RESULTANT_ELFORMS = (2, 12, 13)


@register
@dataclass(kw_only=True)
class SectionBeam(SimpleKeyword):
    """*SECTION_BEAM: SECID ELFORM SHRF QR/IRID CST SCOOR NSM NAUPD; then
    TS1 TS2 TT1 TT2 NSLOC NTLOC (ELFORM 1, 11) or A ISS ITT J SA IST (ELFORM 2,
    12, 13). Lengths mm, areas mm^2, second moments mm^4, NSM kg/mm. The second
    card of the other formulations (truss, discrete, ...) is kept positionally in
    the A .. IST fields so that the builder can name the ELFORM it rejects."""

    secid: int = 0
    elform: int = 1
    shrf: float = 1.0
    qr: int = 2
    cst: int = 0
    scoor: float = 0.0
    nsm: float = 0.0
    naupd: int = 0
    ts1: float = 0.0
    ts2: float = 0.0
    tt1: float = 0.0
    tt2: float = 0.0
    nsloc: float = 0.0
    ntloc: float = 0.0
    a: float = 0.0
    iss: float = 0.0
    itt: float = 0.0
    j: float = 0.0
    sa: float = 0.0
    ist: float = 0.0
    title: str = ""

    KEYWORD: ClassVar[str] = "SECTION_BEAM"
    CARDS: ClassVar[tuple[str, ...]] = ("secid elform shrf qr cst scoor nsm naupd",
                                        "ts1 ts2 tt1 tt2 nsloc ntloc",
                                        "a iss itt j sa ist")
    N_REQUIRED: ClassVar[int] = 3
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"

    @classmethod
    def want_card(cls, index: int, values: dict[str, object]) -> bool:
        elform = int(values.get("elform", 1) or 1)  # type: ignore[arg-type]
        if index == 1:
            return elform in INTEGRATED_ELFORMS
        if index == 2:  # also the second card of the other formulations (rejected later)
            return elform not in INTEGRATED_ELFORMS
        return True


@register
@dataclass(kw_only=True, eq=False)
class ElementBeam(KeywordItem):
    """*ELEMENT_BEAM: rows EID PID N1 N2 N3 RT1 RR1 RT2 RR2 LOCAL (8-column fields).

    Arrays (k rows): ids, pids; conn (k, 3) node ids N1 N2 N3 (N3 0 = none);
    releases (k, 4) RT1 RR1 RT2 RR2; local (k,) (blank = 2, releases in the
    local system); row_lines (k,) the file line of each row.
    """

    ids: np.ndarray
    pids: np.ndarray
    conn: np.ndarray
    releases: np.ndarray | None = None
    local: np.ndarray | None = None
    row_lines: np.ndarray | None = field(default=None, repr=False)

    KEYWORD: ClassVar[str] = "ELEMENT_BEAM"
    _NAMES: ClassVar[list[str]] = ["eid", "pid", "n1", "n2", "n3", "rt1", "rr1", "rt2",
                                   "rr2", "local"]

    def __post_init__(self) -> None:
        self.ids = np.asarray(self.ids, dtype=np.int64).reshape(-1)
        k = self.ids.shape[0]
        self.pids = np.broadcast_to(np.asarray(self.pids, dtype=np.int64), (k,)).copy()
        self.conn = np.asarray(self.conn, dtype=np.int64).reshape(k, 3)
        self.releases = np.zeros((k, 4), np.int64) if self.releases is None else \
            np.asarray(self.releases, dtype=np.int64).reshape(k, 4)
        self.local = np.full(k, 2, np.int64) if self.local is None else \
            np.broadcast_to(np.asarray(self.local, dtype=np.int64), (k,)).copy()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ElementBeam):
            return NotImplemented
        return all(np.array_equal(getattr(self, a), getattr(other, a))
                   for a in ("ids", "pids", "conn", "releases", "local"))

    def line_of(self, row: int) -> int:
        """File line of row ``row`` (the block's line when unknown)."""
        if self.row_lines is not None and len(self.row_lines) > row:
            return int(self.row_lines[row])
        return self.source.line

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        w = field_width(8, block.fmt)
        t = bulk.row_table(block, 10 * w)
        vals = bulk.parse_ints(t, 0, w, 10, cls._NAMES, 0)
        local = vals[:, 9].copy()
        local[local == 0] = 2
        line = int(t.lines[0]) if t.n else block.line
        return [cls(ids=vals[:, 0], pids=vals[:, 1], conn=vals[:, 2:5], releases=vals[:, 5:9],
                    local=local, row_lines=t.lines, source=block.source(line))]

    def to_lines(self, fmt: str = "standard") -> list[str]:
        if fmt == "standard" and int(np.abs(np.column_stack(
                [self.ids, self.pids, self.conn])).max(initial=0)) >= 10 ** 8:
            fmt = "long"
        w = field_width(8, fmt)
        rows = bulk.int_rows(np.column_stack([self.ids, self.pids, self.conn, self.releases,
                                              self.local]), w)
        return ["*ELEMENT_BEAM" + {"long": " +", "i10": " %"}.get(fmt, ""), *rows]


@register
@dataclass(kw_only=True)
class IntegrationBeam(SimpleKeyword):
    """*INTEGRATION_BEAM: IRID NIP RA ICST K; with ICST = 0, NIP cards S T WF PID
    (``points``: rows [S, T, WF, PID]; S, T normalised coordinates in [-1, 1],
    WF the point's share of the area). Standard sections (ICST > 0, with the
    dimension card D1..D6) are read by the class but rejected by the builder.
    """

    irid: int = 0
    nip: int = 0
    ra: float = 0.0
    icst: int = 0
    k: int = 0
    d1: float = 0.0
    d2: float = 0.0
    d3: float = 0.0
    d4: float = 0.0
    sref: float = 0.0
    tref: float = 0.0
    d5: float = 0.0
    d6: float = 0.0
    points: list[list[float]] = field(default_factory=list)
    title: str = ""

    KEYWORD: ClassVar[str] = "INTEGRATION_BEAM"
    CARDS: ClassVar[tuple[str, ...]] = ("irid nip ra icst k",
                                        "d1 d2 d3 d4 sref tref d5 d6")
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"

    _POINT: ClassVar[tuple[Field, ...]] = (Field("s", 10, "f"), Field("t", 10, "f"),
                                           Field("wf", 10, "f"), Field("pid", 10, "i"))

    @classmethod
    def want_card(cls, index: int, values: dict[str, object]) -> bool:
        return index == 0 or int(values.get("icst", 0) or 0) > 0  # type: ignore[arg-type]

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        if int(values.get("icst", 0) or 0) > 0:  # type: ignore[arg-type]
            return {}
        pts: list[list[float]] = []
        for k in range(int(values.get("nip", 0) or 0)):  # type: ignore[arg-type]
            _, vals = cur.parse(cls._POINT, f"integration point {k + 1} (S, T, WF, PID)")
            pts.append([float(vals.get(f.name, 0) or 0) for f in cls._POINT])  # type: ignore[arg-type]
        return {"points": pts}

    def tail_lines(self, fmt: str) -> list[str]:
        if self.icst > 0:
            return []
        return [format_card({"s": p[0], "t": p[1], "wf": p[2], "pid": int(p[3])},
                            self._POINT, fmt) for p in self.points]
