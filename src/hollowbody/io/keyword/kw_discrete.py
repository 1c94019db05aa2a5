"""Discrete-element keywords: *SECTION_DISCRETE, *ELEMENT_DISCRETE and the spring and
damper materials *MAT_SPRING_ELASTIC (S01), *MAT_DAMPER_VISCOUS (S02),
*MAT_SPRING_NONLINEAR_ELASTIC (S04), *MAT_SPRING_GENERAL_NONLINEAR (S06).

Cards and defaults as in the LS-DYNA Keyword User's Manual. Units: forces kN,
deflections mm (torsional: moments kN*mm, rotations rad), stiffness kN/mm or
kN*mm/rad, damping kN*ms/mm or kN*mm*ms/rad. See docs/discrete.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hollowbody.io.keyword.base import SimpleKeyword, register
from hollowbody.io.keyword.kw_materials import Material


@register
@dataclass(kw_only=True)
class SectionDiscrete(SimpleKeyword):
    """*SECTION_DISCRETE: SECID DRO KD V0 CL FD; CDL TDL.

    DRO 0: translational spring/damper, 1: torsional. KD dynamic magnification,
    V0 test velocity, CL clearance, FD failure deflection (rotation for DRO 1),
    CDL / TDL deflection limits in compression / tension.
    """

    secid: int = 0
    dro: int = 0
    kd: float = 0.0
    v0: float = 0.0
    cl: float = 0.0
    fd: float = 0.0
    cdl: float = 0.0
    tdl: float = 0.0
    title: str = ""

    KEYWORD: ClassVar[str] = "SECTION_DISCRETE"
    CARDS: ClassVar[tuple[str, ...]] = ("secid dro kd v0 cl fd", "cdl tdl")
    #: both cards are read (a blank line is a card of defaults), as LS-DYNA does
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"


@register
@dataclass(kw_only=True)
class ElementDiscrete(SimpleKeyword):
    """*ELEMENT_DISCRETE (one item per element card): EID PID N1 N2 VID S PF OFFSET.

    Widths 8 8 8 8 8 16 8 16. N2 = 0: grounded. S: force scale factor (blank or 0 =
    1). PF: print flag (0: written to deforc). OFFSET: initial deflection (mm or
    rad): a positive offset gives a tensile force at t = 0.
    """

    eid: int = 0
    pid: int = 0
    n1: int = 0
    n2: int = 0
    vid: int = 0
    s: float = 1.0
    pf: int = 0
    offset: float = 0.0

    KEYWORD: ClassVar[str] = "ELEMENT_DISCRETE"
    CARDS: ClassVar[tuple[str, ...]] = ("eid:8 pid:8 n1:8 n2:8 vid:8 s:16 pf:8 offset:16",)
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class DefineSdOrientation(SimpleKeyword):
    """*DEFINE_SD_ORIENTATION: VID IOP XT YT ZT NID1 NID2 (IOP 0: fixed vector)."""

    vid: int = 0
    iop: int = 0
    xt: float = 0.0
    yt: float = 0.0
    zt: float = 0.0
    nid1: int = 0
    nid2: int = 0
    title: str = ""

    KEYWORD: ClassVar[str] = "DEFINE_SD_ORIENTATION"
    CARDS: ClassVar[tuple[str, ...]] = ("vid iop xt yt zt nid1 nid2",)
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"


@register
@dataclass(kw_only=True)
class MatSpringElastic(Material):
    """*MAT_SPRING_ELASTIC / *MAT_S01: MID K (kN/mm; torsional kN*mm/rad)."""

    k: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_SPRING_ELASTIC"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_S01",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid k",)
    KIND: ClassVar[str] = "spring_elastic"


@register
@dataclass(kw_only=True)
class MatDamperViscous(Material):
    """*MAT_DAMPER_VISCOUS / *MAT_S02: MID DC (kN*ms/mm; torsional kN*mm*ms/rad)."""

    dc: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_DAMPER_VISCOUS"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_S02",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid dc",)
    KIND: ClassVar[str] = "damper_viscous"


@register
@dataclass(kw_only=True)
class MatSpringNonlinearElastic(Material):
    """*MAT_SPRING_NONLINEAR_ELASTIC / *MAT_S04: MID LCD LCR.

    LCD: force (kN) vs deflection (mm) curve, or moment vs rotation; LCR: scale
    factor vs deflection rate (optional)."""

    lcd: int = 0
    lcr: int = 0

    KEYWORD: ClassVar[str] = "MAT_SPRING_NONLINEAR_ELASTIC"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_S04",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid lcd lcr",)
    KIND: ClassVar[str] = "spring_nonlinear"


@register
@dataclass(kw_only=True)
class MatSpringGeneralNonlinear(Material):
    """*MAT_SPRING_GENERAL_NONLINEAR / *MAT_S06: MID LCDL LCDU BETA TYI CYI.

    LCDL loading, LCDU unloading curve (force vs deflection); BETA hardening
    (0: tensile and compressive yield independent, softening allowed; 1:
    isotropic; otherwise kinematic); TYI (> 0) / CYI (< 0) initial yield forces.
    """

    lcdl: int = 0
    lcdu: int = 0
    beta: float = 0.0
    tyi: float = 0.0
    cyi: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_SPRING_GENERAL_NONLINEAR"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_S06",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid lcdl lcdu beta tyi cyi",)
    KIND: ClassVar[str] = "spring_general"
