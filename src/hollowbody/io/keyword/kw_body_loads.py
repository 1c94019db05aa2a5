"""Loads and the planar rigid wall.

*LOAD_BODY_X / _Y / _Z (base accelerations), *LOAD_BODY_PARTS, *LOAD_NODE_POINT,
*LOAD_NODE_SET, *LOAD_RIGID_BODY, *RIGIDWALL_PLANAR (with ``_ID``; the
``_MOVING``, ``_FINITE``, ``_ORTHO`` and ``_FORCES`` options are read so that the
build can reject them by name). Accelerations mm/ms^2, forces kN, moments
kN*mm, times ms, lengths mm. See docs/loads.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hollowbody.io.keyword.base import Block, Cursor, SimpleKeyword, register

#: *LOAD_BODY_<axis> options read here (rotational and generalised forms are not).
BODY_AXES = ("X", "Y", "Z")


@register
@dataclass(kw_only=True)
class LoadBody(SimpleKeyword):
    """*LOAD_BODY_X / _Y / _Z: LCID SF LCIDDR XC YC ZC CID.

    A base acceleration ``SF * curve(t)`` along ``axis``; the body force on a
    mass m is ``-m a`` (gravity in -z is a positive value on *LOAD_BODY_Z).
    """

    axis: str = "Z"
    lcid: int = 0
    sf: float = 1.0
    lciddr: int = 0
    xc: float = 0.0
    yc: float = 0.0
    zc: float = 0.0
    cid: int = 0

    KEYWORD: ClassVar[str] = "LOAD_BODY_Z"
    ALIASES: ClassVar[tuple[str, ...]] = ("LOAD_BODY_X", "LOAD_BODY_Y")
    CARDS: ClassVar[tuple[str, ...]] = ("lcid sf lciddr xc yc zc cid",)

    def __post_init__(self) -> None:
        self.axis = self.axis.upper()

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        return {"axis": block.base[len("LOAD_BODY_"):]}

    @classmethod
    def build(cls, values: dict[str, object], block: Block) -> LoadBody:
        values.setdefault("axis", block.base[len("LOAD_BODY_"):])
        return cls(**values)  # type: ignore[arg-type]

    def keyword_line(self) -> str:
        return "*LOAD_BODY_" + self.axis


@register
@dataclass(kw_only=True)
class LoadBodyParts(SimpleKeyword):
    """*LOAD_BODY_PARTS: PSID (body loads act on the parts of this part set only)."""

    psid: int = 0

    KEYWORD: ClassVar[str] = "LOAD_BODY_PARTS"
    CARDS: ClassVar[tuple[str, ...]] = ("psid",)


@dataclass(kw_only=True)
class _PointLoad(SimpleKeyword):
    """Fields shared by *LOAD_NODE_POINT / _SET and *LOAD_RIGID_BODY."""

    dof: int = 0
    lcid: int = 0
    sf: float = 1.0
    cid: int = 0
    m1: int = 0
    m2: int = 0
    m3: int = 0

    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class LoadNodePoint(_PointLoad):
    """*LOAD_NODE_POINT: NID DOF LCID SF CID M1 M2 M3 (DOF 1-3 force, 5-7 moment)."""

    nid: int = 0

    KEYWORD: ClassVar[str] = "LOAD_NODE_POINT"
    CARDS: ClassVar[tuple[str, ...]] = ("nid dof lcid sf cid m1 m2 m3",)


@register
@dataclass(kw_only=True)
class LoadNodeSet(_PointLoad):
    """*LOAD_NODE_SET: NSID DOF LCID SF CID M1 M2 M3 (DOF 1-3 force, 5-7 moment)."""

    nsid: int = 0

    KEYWORD: ClassVar[str] = "LOAD_NODE_SET"
    CARDS: ClassVar[tuple[str, ...]] = ("nsid dof lcid sf cid m1 m2 m3",)


@register
@dataclass(kw_only=True)
class LoadRigidBody(_PointLoad):
    """*LOAD_RIGID_BODY: PID DOF LCID SF CID M1 M2 M3 (DOF 1-3 force, 5-7 moment)."""

    pid: int = 0

    KEYWORD: ClassVar[str] = "LOAD_RIGID_BODY"
    CARDS: ClassVar[tuple[str, ...]] = ("pid dof lcid sf cid m1 m2 m3",)


#: *RIGIDWALL_PLANAR options that are read but not supported (the build says so).
RIGIDWALL_UNSUPPORTED = ("MOVING", "FINITE", "ORTHO", "FORCES")


@register
@dataclass(kw_only=True)
class RigidwallPlanar(SimpleKeyword):
    """*RIGIDWALL_PLANAR[_ID]: NSID NSIDEX BOXID OFFSET BIRTH DEATH RWKSF;
    XT YT ZT XH YH ZH FRIC WVEL (the normal points from tail XT.. to head XH..).

    Cards of the unsupported options are kept in ``extra_cards``.
    """

    nsid: int = 0
    nsidex: int = 0
    boxid: int = 0
    offset: float = 0.0
    birth: float = 0.0
    death: float = 1.0e20
    rwksf: float = 1.0
    xt: float = 0.0
    yt: float = 0.0
    zt: float = 0.0
    xh: float = 0.0
    yh: float = 0.0
    zh: float = 0.0
    fric: float = 0.0
    wvel: float = 0.0
    rwid: int | None = None
    heading: str = ""
    variants: tuple[str, ...] = ()

    KEYWORD: ClassVar[str] = "RIGIDWALL_PLANAR"
    CARDS: ClassVar[tuple[str, ...]] = ("nsid nsidex boxid offset birth death rwksf",
                                        "xt yt zt xh yh zh fric wvel")
    N_REQUIRED: ClassVar[int] = 2
    ID_ATTRS: ClassVar[tuple[str, str] | None] = ("rwid", "heading")
    OPTIONS: ClassVar[frozenset[str]] = frozenset(RIGIDWALL_UNSUPPORTED)

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        return {"variants": tuple(o for o in RIGIDWALL_UNSUPPORTED if block.has(o))}

    def keyword_line(self) -> str:
        name = "*RIGIDWALL_PLANAR" + "".join("_" + o for o in self.variants)
        return name + ("_ID" if self.rwid is not None else "")
