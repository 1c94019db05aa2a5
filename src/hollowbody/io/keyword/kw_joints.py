"""Joints between rigid bodies, their stiffness, and local coordinate systems.

*CONSTRAINED_JOINT_SPHERICAL / _REVOLUTE / _CYLINDRICAL / _UNIVERSAL /
_TRANSLATIONAL / _LOCKING (each with an optional ``_ID`` card: JID, HEADING):
N1 N2 N3 N4 N5 N6 RPS DAMP (odd nodes on rigid body A, even nodes on body B).
*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED and _FLEXION-TORSION (four cards),
*DEFINE_COORDINATE_NODES (CID N1 N2 N3 FLAG DIR) and *DEFINE_COORDINATE_SYSTEM
(CID XO YO ZO XL YL ZL CIDL / XP YP ZP), each with an optional ``_TITLE``.
Lengths in mm, angles of stop cards in degrees, moments in kN*mm.
*DATABASE_JNTFORC is read by :class:`~hollowbody.io.keyword.kw_control.DatabaseAscii`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hollowbody.io.keyword.base import Block, Cursor, SimpleKeyword, register

#: The joint types of *CONSTRAINED_JOINT_<TYPE> supported.
JOINT_TYPES = ("SPHERICAL", "REVOLUTE", "CYLINDRICAL", "UNIVERSAL", "TRANSLATIONAL", "LOCKING")


@register
@dataclass(kw_only=True)
class ConstrainedJoint(SimpleKeyword):
    """*CONSTRAINED_JOINT_<TYPE>[_ID]: N1 N2 N3 N4 N5 N6 RPS DAMP.

    ``kind``: the joint type (:data:`JOINT_TYPES`); RPS relative penalty
    stiffness (0: 1.0), DAMP damping scale factor (0: 1.0; 0 < DAMP <= 0.01: none).
    """

    kind: str = "SPHERICAL"
    n1: int = 0
    n2: int = 0
    n3: int = 0
    n4: int = 0
    n5: int = 0
    n6: int = 0
    rps: float = 1.0
    damp: float = 1.0
    jid: int | None = None
    heading: str = ""

    KEYWORD: ClassVar[str] = "CONSTRAINED_JOINT_SPHERICAL"
    ALIASES: ClassVar[tuple[str, ...]] = tuple("CONSTRAINED_JOINT_" + t for t in JOINT_TYPES)
    CARDS: ClassVar[tuple[str, ...]] = ("n1 n2 n3 n4 n5 n6 rps damp",)
    REPEAT: ClassVar[bool] = True
    ID_ATTRS: ClassVar[tuple[str, str] | None] = ("jid", "heading")

    def __post_init__(self) -> None:
        self.kind = self.kind.upper()

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        return {"kind": block.base[len("CONSTRAINED_JOINT_"):]}

    def keyword_line(self) -> str:
        return "*CONSTRAINED_JOINT_" + self.kind

    def nodes(self) -> list[int]:
        """N1..N6 as given (0: not given)."""
        return [self.n1, self.n2, self.n3, self.n4, self.n5, self.n6]


@dataclass(kw_only=True)
class _JointStiffness(SimpleKeyword):
    """Card 1 shared by the joint stiffness keywords."""

    jsid: int = 0
    pida: int = 0
    pidb: int = 0
    cida: int = 0
    cidb: int = 0
    jid: int = 0
    title: str = ""

    N_REQUIRED: ClassVar[int] = 1
    TITLE_ATTR: ClassVar[str | None] = "title"


@register
@dataclass(kw_only=True)
class JointStiffnessGeneralized(_JointStiffness):
    """*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED: JSID PIDA PIDB CIDA CIDB JID /
    LCIDPH LCIDT LCIDPS DLCIDPH DLCIDT DLCIDPS / ESPH FMPH EST FMT ESPS FMPS /
    NSAPH PSAPH NSAT PSAT NSAPS PSAPS (stop angles in degrees)."""

    lcidph: int = 0
    lcidt: int = 0
    lcidps: int = 0
    dlcidph: int = 0
    dlcidt: int = 0
    dlcidps: int = 0
    esph: float = 0.0
    fmph: float = 0.0
    est: float = 0.0
    fmt: float = 0.0
    esps: float = 0.0
    fmps: float = 0.0
    nsaph: float = 0.0
    psaph: float = 0.0
    nsat: float = 0.0
    psat: float = 0.0
    nsaps: float = 0.0
    psaps: float = 0.0

    KEYWORD: ClassVar[str] = "CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"
    CARDS: ClassVar[tuple[str, ...]] = ("jsid pida pidb cida cidb jid",
                                        "lcidph lcidt lcidps dlcidph dlcidt dlcidps",
                                        "esph fmph est fmt esps fmps",
                                        "nsaph psaph nsat psat nsaps psaps")


@register
@dataclass(kw_only=True)
class JointStiffnessFlexionTorsion(_JointStiffness):
    """*CONSTRAINED_JOINT_STIFFNESS_FLEXION-TORSION: JSID PIDA PIDB CIDA CIDB JID /
    LCIDAL LCIDG LCIDBT DLCIDAL DLCIDG DLCIDBT / ESAL FMAL ESBT FMBT /
    SAAL NSABT PSABT (stop angles in degrees)."""

    lcidal: int = 0
    lcidg: int = 0
    lcidbt: int = 0
    dlcidal: int = 0
    dlcidg: int = 0
    dlcidbt: int = 0
    esal: float = 0.0
    fmal: float = 0.0
    esbt: float = 0.0
    fmbt: float = 0.0
    saal: float = 0.0
    nsabt: float = 0.0
    psabt: float = 0.0

    KEYWORD: ClassVar[str] = "CONSTRAINED_JOINT_STIFFNESS_FLEXION-TORSION"
    CARDS: ClassVar[tuple[str, ...]] = ("jsid pida pidb cida cidb jid",
                                        "lcidal lcidg lcidbt dlcidal dlcidg dlcidbt",
                                        "esal fmal esbt fmbt",
                                        "saal nsabt psabt")


@register
@dataclass(kw_only=True)
class DefineCoordinateNodes(SimpleKeyword):
    """*DEFINE_COORDINATE_NODES[_TITLE]: CID N1 N2 N3 FLAG DIR.

    DIR (X, Y or Z; blank: X) is the local axis along N1 -> N2; N3 lies in the
    plane of that axis and the next one (x-y, y-z or z-x). FLAG = 1: the system
    follows its nodes.
    """

    cid: int = 0
    n1: int = 0
    n2: int = 0
    n3: int = 0
    flag: int = 0
    dir: str = "X"
    title: str = ""

    KEYWORD: ClassVar[str] = "DEFINE_COORDINATE_NODES"
    CARDS: ClassVar[tuple[str, ...]] = ("cid n1 n2 n3 flag dir",)
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"

    def __post_init__(self) -> None:
        self.dir = (self.dir or "X").strip().upper() or "X"


@register
@dataclass(kw_only=True)
class DefineCoordinateSystem(SimpleKeyword):
    """*DEFINE_COORDINATE_SYSTEM[_TITLE]: CID XO YO ZO XL YL ZL CIDL / XP YP ZP.

    Origin O, a point L on the local x axis and a point P in the local x-y plane (mm).
    """

    cid: int = 0
    xo: float = 0.0
    yo: float = 0.0
    zo: float = 0.0
    xl: float = 0.0
    yl: float = 0.0
    zl: float = 0.0
    cidl: int = 0
    xp: float = 0.0
    yp: float = 0.0
    zp: float = 0.0
    title: str = ""

    KEYWORD: ClassVar[str] = "DEFINE_COORDINATE_SYSTEM"
    CARDS: ClassVar[tuple[str, ...]] = ("cid xo yo zo xl yl zl cidl", "xp yp zp")
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True
    TITLE_ATTR: ClassVar[str | None] = "title"
