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

from hollowbody.io.keyword.base import Block, Cursor, SimpleKeyword, register
from hollowbody.io.keyword.cards import Field, format_card

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
@dataclass(kw_only=True)
class ElementBeam(SimpleKeyword):
    """*ELEMENT_BEAM: EID PID N1 N2 N3 RT1 RR1 RT2 RR2 LOCAL (8-column fields).

    N3 (orientation node) 0 = none; RT/RR release codes, LOCAL 2 = releases in
    the local system (default).
    """

    eid: int = 0
    pid: int = 0
    n1: int = 0
    n2: int = 0
    n3: int = 0
    rt1: int = 0
    rr1: int = 0
    rt2: int = 0
    rr2: int = 0
    local: int = 2

    KEYWORD: ClassVar[str] = "ELEMENT_BEAM"
    CARDS: ClassVar[tuple[str, ...]] = (
        "eid:8 pid:8 n1:8 n2:8 n3:8 rt1:8 rr1:8 rt2:8 rr2:8 local:8",)
    REPEAT: ClassVar[bool] = True


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
