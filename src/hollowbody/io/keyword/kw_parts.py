"""Part keywords: *PART, *PART_INERTIA, *SECTION_SOLID, *SECTION_SHELL, *HOURGLASS.

Field names are the LS-DYNA ones in lower case; defaults are LS-DYNA's
(``None`` = blank, resolved by the builder where the default depends on
other cards).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

from hollowbody.io.keyword.base import Block, Cursor, SimpleKeyword, register
from hollowbody.io.keyword.cards import Field, format_card


@register
@dataclass(kw_only=True)
class Part(SimpleKeyword):
    """*PART: heading card, then PID SECID MID EOSID HGID GRAV ADPOPT TMID."""

    pid: int = 0
    secid: int = 0
    mid: int = 0
    eosid: int = 0
    hgid: int = 0
    grav: int = 0
    adpopt: int = 0
    tmid: int = 0
    title: str = ""

    KEYWORD: ClassVar[str] = "PART"
    CARDS: ClassVar[tuple[str, ...]] = ("title:80", "pid secid mid eosid hgid grav adpopt tmid")
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True
    MAIN_CARD: ClassVar[int] = 1


@dataclass(kw_only=True)
class InertiaFields:
    """Fields of the inertia cards of *PART_INERTIA and
    *CONSTRAINED_NODAL_RIGID_BODY_INERTIA: XC YC ZC (mm) TM (kg) IRCS NODEID; IXX IXY
    IXZ IYY IYZ IZZ (kg*mm^2); VTX VTY VTZ (mm/ms) VRX VRY VRZ (rad/ms); with IRCS = 1
    the local axes XL YL ZL XLIP YLIP ZLIP."""

    xc: float = 0.0
    yc: float = 0.0
    zc: float = 0.0
    tm: float = 0.0
    ircs: int = 0
    nodeid: int = 0
    ixx: float = 0.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyy: float = 0.0
    iyz: float = 0.0
    izz: float = 0.0
    vtx: float = 0.0
    vty: float = 0.0
    vtz: float = 0.0
    vrx: float = 0.0
    vry: float = 0.0
    vrz: float = 0.0
    xl: float = 0.0
    yl: float = 0.0
    zl: float = 0.0
    xlip: float = 0.0
    ylip: float = 0.0
    zlip: float = 0.0


@register
@dataclass(kw_only=True)
class PartInertia(InertiaFields, SimpleKeyword):
    """*PART_INERTIA: a part with given rigid-body mass properties.

    Cards: heading; PID..TMID; XC YC ZC TM IRCS NODEID; IXX IXY IXZ IYY IYZ
    IZZ (kg*mm^2); VTX VTY VTZ VRX VRY VRZ; (IRCS = 1) XL YL ZL XLIP YLIP ZLIP CID.
    """

    pid: int = 0
    secid: int = 0
    mid: int = 0
    eosid: int = 0
    hgid: int = 0
    grav: int = 0
    adpopt: int = 0
    tmid: int = 0
    title: str = ""
    cid: int = 0

    KEYWORD: ClassVar[str] = "PART_INERTIA"
    CARDS: ClassVar[tuple[str, ...]] = (
        "title:80", "pid secid mid eosid hgid grav adpopt tmid",
        "xc yc zc tm ircs nodeid", "ixx ixy ixz iyy iyz izz",
        "vtx vty vtz vrx vry vrz", "xl yl zl xlip ylip zlip cid")
    N_REQUIRED: ClassVar[int] = 6
    REPEAT: ClassVar[bool] = True
    MAIN_CARD: ClassVar[int] = 1

    @classmethod
    def want_card(cls, index: int, values: dict[str, object]) -> bool:
        return index < 5 or values.get("ircs", 0) == 1


@register
@dataclass(kw_only=True)
class SectionSolid(SimpleKeyword):
    """*SECTION_SOLID: SECID ELFORM AET (ELFORM 0 or blank = 1)."""

    secid: int = 0
    elform: int = 1
    aet: int = 0
    title: str = ""

    KEYWORD: ClassVar[str] = "SECTION_SOLID"
    CARDS: ClassVar[tuple[str, ...]] = ("secid elform aet",)
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"


@register
@dataclass(kw_only=True)
class SectionShell(SimpleKeyword):
    """*SECTION_SHELL: SECID ELFORM SHRF NIP PROPT QR/IRID ICOMP SETYP; T1 T2 T3 T4 NLOC
    MAREA IDOF EDGSET.

    Blank NIP is 2 (as LS-DYNA); T2..T4 blank or 0 take T1 (builder). With
    ICOMP = 1 the ply angles B1.. follow (``angles``, ceil(NIP/8) cards).
    """

    secid: int = 0
    elform: int = 2
    shrf: float = 1.0
    nip: int = 2
    propt: float = 1.0
    qr: float = 0.0
    icomp: int = 0
    setyp: int = 1
    t1: float = 0.0
    t2: float = 0.0
    t3: float = 0.0
    t4: float = 0.0
    nloc: float = 0.0
    marea: float = 0.0
    idof: float = 0.0
    edgset: int = 0
    angles: list[float] = field(default_factory=list)
    title: str = ""

    KEYWORD: ClassVar[str] = "SECTION_SHELL"
    CARDS: ClassVar[tuple[str, ...]] = ("secid elform shrf nip propt qr icomp setyp",
                                        "t1 t2 t3 t4 nloc marea idof edgset")
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"

    _ANGLES: ClassVar[tuple[Field, ...]] = tuple(Field(f"b{k}", 10, "f") for k in range(1, 9))

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        if values.get("icomp", 0) != 1:
            return {}
        nip = int(values.get("nip", 2) or 2)  # type: ignore[arg-type]
        angles: list[float] = []
        for _ in range(math.ceil(nip / 8)):
            _, vals = cur.parse(cls._ANGLES, "ply angles B1..B8 (ICOMP=1)")
            angles += [float(vals.get(f.name, 0.0)) for f in cls._ANGLES]  # type: ignore[arg-type]
        return {"angles": angles[:nip]}

    def tail_lines(self, fmt: str) -> list[str]:
        if self.icomp != 1:
            return []
        out = []
        for k in range(0, len(self.angles), 8):
            chunk = {f"b{j + 1}": a for j, a in enumerate(self.angles[k:k + 8])}
            out.append(format_card({f.name: chunk.get(f.name) for f in self._ANGLES},
                                   self._ANGLES, fmt))
        return out


@register
@dataclass(kw_only=True)
class Hourglass(SimpleKeyword):
    """*HOURGLASS: HGID IHQ QM IBQ Q1 Q2 QB/VDC QW.

    IHQ 0 takes the *CONTROL_HOURGLASS type; Q1 / Q2 blank take the
    *CONTROL_BULK_VISCOSITY values (builder).
    """

    hgid: int = 0
    ihq: int = 0
    qm: float = 0.1
    ibq: int = 0
    q1: float | None = None
    q2: float | None = None
    qb: float = 0.1
    qw: float = 0.1
    title: str = ""

    KEYWORD: ClassVar[str] = "HOURGLASS"
    CARDS: ClassVar[tuple[str, ...]] = ("hgid ihq qm ibq q1 q2 qb qw",)
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"
