"""Material keywords: *MAT_ELASTIC (001), *MAT_PLASTIC_KINEMATIC (003),
*MAT_NULL (009), *MAT_RIGID (020), *MAT_PIECEWISE_LINEAR_PLASTICITY (024),
*MAT_SIMPLIFIED_RUBBER (181).

Deck units: density kg/mm^3, moduli and stresses GPa. Each material is one
keyword block (optional ``_TITLE``); cards beyond the ones read here (e.g.
MAT_181 Prony terms) are kept in ``extra_cards``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hollowbody.io.keyword.base import SimpleKeyword, register


@dataclass(kw_only=True)
class Material(SimpleKeyword):
    """Common fields of all materials: MID, RO (kg/mm^3), title."""

    mid: int = 0
    ro: float = 0.0
    title: str = ""

    TITLE_ATTR: ClassVar[str | None] = "title"
    #: ``MaterialDef.kind`` of this keyword.
    KIND: ClassVar[str] = ""


@register
@dataclass(kw_only=True)
class MatElastic(Material):
    """*MAT_ELASTIC / *MAT_001: MID RO E PR DA DB K."""

    e: float = 0.0
    pr: float = 0.0
    da: float = 0.0
    db: float = 0.0
    k: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_ELASTIC"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_001",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid ro e pr da db k",)
    KIND: ClassVar[str] = "elastic"


@register
@dataclass(kw_only=True)
class MatPlasticKinematic(Material):
    """*MAT_PLASTIC_KINEMATIC / *MAT_003: MID RO E PR SIGY ETAN BETA; SRC SRP FS VP."""

    e: float = 0.0
    pr: float = 0.0
    sigy: float = 0.0
    etan: float = 0.0
    beta: float = 0.0
    src: float = 0.0
    srp: float = 0.0
    fs: float = 0.0
    vp: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_PLASTIC_KINEMATIC"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_003",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid ro e pr sigy etan beta", "src srp fs vp")
    KIND: ClassVar[str] = "plastic003"


@register
@dataclass(kw_only=True)
class MatRigid(Material):
    """*MAT_RIGID / *MAT_020: MID RO E PR N COUPLE M ALIAS; CMO CON1 CON2; LCO/A1 A2 A3 V1 V2 V3."""

    e: float = 0.0
    pr: float = 0.0
    n: float = 0.0
    couple: float = 0.0
    m: float = 0.0
    alias: str = ""
    cmo: float = 0.0
    con1: float = 0.0
    con2: float = 0.0
    a1: float = 0.0
    a2: float = 0.0
    a3: float = 0.0
    v1: float = 0.0
    v2: float = 0.0
    v3: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_RIGID"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_020",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid ro e pr n couple m alias", "cmo con1 con2",
                                        "a1 a2 a3 v1 v2 v3")
    KIND: ClassVar[str] = "rigid"


@register
@dataclass(kw_only=True)
class MatPiecewiseLinearPlasticity(Material):
    """*MAT_PIECEWISE_LINEAR_PLASTICITY / *MAT_024.

    MID RO E PR SIGY ETAN FAIL TDEL; C P LCSS LCSR VP; EPS1..EPS8; ES1..ES8.
    """

    e: float = 0.0
    pr: float = 0.0
    sigy: float = 0.0
    etan: float = 0.0
    fail: float = 1.0e21
    tdel: float = 0.0
    c: float = 0.0
    p: float = 0.0
    lcss: int = 0
    lcsr: int = 0
    vp: float = 0.0
    eps1: float = 0.0
    eps2: float = 0.0
    eps3: float = 0.0
    eps4: float = 0.0
    eps5: float = 0.0
    eps6: float = 0.0
    eps7: float = 0.0
    eps8: float = 0.0
    es1: float = 0.0
    es2: float = 0.0
    es3: float = 0.0
    es4: float = 0.0
    es5: float = 0.0
    es6: float = 0.0
    es7: float = 0.0
    es8: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_PIECEWISE_LINEAR_PLASTICITY"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_024",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid ro e pr sigy etan fail tdel", "c p lcss lcsr vp",
                                        "eps1 eps2 eps3 eps4 eps5 eps6 eps7 eps8",
                                        "es1 es2 es3 es4 es5 es6 es7 es8")
    KIND: ClassVar[str] = "pwl024"


@register
@dataclass(kw_only=True)
class MatSimplifiedRubber(Material):
    """*MAT_SIMPLIFIED_RUBBER(/FOAM) / *MAT_181.

    Card 1: MID RO KM MU G SIGF REF PRTEN; card 2: SGL SW ST LC/TBID (``lcid``)
    TENSION RTYPE AVGOPT PR/BETA; optional card 3: LCUNLD HU SHAPE STOL VISCO
    HISOUT. Blank MU is 0.1, blank SGL / SW / ST are 1.
    """

    km: float = 0.0
    mu: float = 0.1
    g: float = 0.0
    sigf: float = 0.0
    ref: float = 0.0
    prten: float = 0.0
    sgl: float = 1.0
    sw: float = 1.0
    st: float = 1.0
    lcid: int = 0
    tension: float = -1.0
    rtype: float = 0.0
    avgopt: float = 0.0
    pr: float = 0.0
    lcunld: int = 0
    hu: float = 1.0
    shape: float = 0.0
    stol: float = 0.0
    visco: float = 0.0
    hisout: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_SIMPLIFIED_RUBBER"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_181", "MAT_SIMPLIFIED_RUBBER/FOAM")
    CARDS: ClassVar[tuple[str, ...]] = ("mid ro km mu g sigf ref prten",
                                        "sgl sw st lcid tension rtype avgopt pr",
                                        "lcunld hu shape stol visco hisout")
    N_REQUIRED: ClassVar[int] = 2
    KIND: ClassVar[str] = "rubber181"


#: All material keyword classes (for the builder).
MATERIALS: tuple[type[Material], ...] = (MatElastic, MatPlasticKinematic, MatRigid,
                                         MatPiecewiseLinearPlasticity, MatSimplifiedRubber)


@register
@dataclass(kw_only=True)
class MatNull(Material):
    """*MAT_NULL / *MAT_009: MID RO PC MU TEROD CEROD YM PR.

    Shells of this material have mass and no stiffness (contact surfaces);
    YM, PR set their contact stiffness. Solids need an equation of state (not
    supported).
    """

    pc: float = 0.0
    mu: float = 0.0
    terod: float = 0.0
    cerod: float = 0.0
    ym: float = 0.0
    pr: float = 0.0

    KEYWORD: ClassVar[str] = "MAT_NULL"
    ALIASES: ClassVar[tuple[str, ...]] = ("MAT_009",)
    CARDS: ClassVar[tuple[str, ...]] = ("mid ro pc mu terod cerod ym pr",)
    KIND: ClassVar[str] = "null"
