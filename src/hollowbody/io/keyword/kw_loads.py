"""Boundary conditions and initial conditions.

*BOUNDARY_SPC_NODE / _SET, *BOUNDARY_PRESCRIBED_MOTION_NODE / _SET / _RIGID
(each with an optional ``_ID`` card: ``bid`` and ``heading``),
*INITIAL_VELOCITY_GENERATION, *INITIAL_VELOCITY_NODE, *INITIAL_VELOCITY.
Velocities in mm/ms, angular velocities in rad/ms, times in ms.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hollowbody.io.keyword.base import SimpleKeyword, register


@dataclass(kw_only=True)
class _Spc(SimpleKeyword):
    cid: int = 0
    dofx: int = 0
    dofy: int = 0
    dofz: int = 0
    dofrx: int = 0
    dofry: int = 0
    dofrz: int = 0
    bid: int | None = None
    heading: str = ""

    REPEAT: ClassVar[bool] = True
    ID_ATTRS: ClassVar[tuple[str, str] | None] = ("bid", "heading")

    def dofs(self) -> list[bool]:
        """Fixed DOFs x, y, z, rx, ry, rz."""
        return [bool(getattr(self, n)) for n in ("dofx", "dofy", "dofz", "dofrx", "dofry",
                                                 "dofrz")]


@register
@dataclass(kw_only=True)
class BoundarySpcNode(_Spc):
    """*BOUNDARY_SPC_NODE: NID CID DOFX DOFY DOFZ DOFRX DOFRY DOFRZ (1 = fixed)."""

    nid: int = 0

    KEYWORD: ClassVar[str] = "BOUNDARY_SPC_NODE"
    CARDS: ClassVar[tuple[str, ...]] = ("nid cid dofx dofy dofz dofrx dofry dofrz",)


@register
@dataclass(kw_only=True)
class BoundarySpcSet(_Spc):
    """*BOUNDARY_SPC_SET: NSID CID DOFX DOFY DOFZ DOFRX DOFRY DOFRZ (1 = fixed)."""

    nsid: int = 0

    KEYWORD: ClassVar[str] = "BOUNDARY_SPC_SET"
    CARDS: ClassVar[tuple[str, ...]] = ("nsid cid dofx dofy dofz dofrx dofry dofrz",)


@dataclass(kw_only=True)
class PrescribedMotionKeyword(SimpleKeyword):
    """Fields shared by the *BOUNDARY_PRESCRIBED_MOTION_NODE / _SET / _RIGID cards."""

    dof: int = 0
    vad: int = 0
    lcid: int = 0
    sf: float = 1.0
    vid: int = 0
    death: float = 1.0e28
    birth: float = 0.0
    bid: int | None = None
    heading: str = ""

    REPEAT: ClassVar[bool] = True
    ID_ATTRS: ClassVar[tuple[str, str] | None] = ("bid", "heading")


@register
@dataclass(kw_only=True)
class PrescribedMotionNode(PrescribedMotionKeyword):
    """*BOUNDARY_PRESCRIBED_MOTION_NODE: NID DOF VAD LCID SF VID DEATH BIRTH."""

    nid: int = 0

    KEYWORD: ClassVar[str] = "BOUNDARY_PRESCRIBED_MOTION_NODE"
    CARDS: ClassVar[tuple[str, ...]] = ("nid dof vad lcid sf vid death birth",)


@register
@dataclass(kw_only=True)
class PrescribedMotionSet(PrescribedMotionKeyword):
    """*BOUNDARY_PRESCRIBED_MOTION_SET: NSID DOF VAD LCID SF VID DEATH BIRTH."""

    nsid: int = 0

    KEYWORD: ClassVar[str] = "BOUNDARY_PRESCRIBED_MOTION_SET"
    CARDS: ClassVar[tuple[str, ...]] = ("nsid dof vad lcid sf vid death birth",)


@register
@dataclass(kw_only=True)
class PrescribedMotionRigid(PrescribedMotionKeyword):
    """*BOUNDARY_PRESCRIBED_MOTION_RIGID: PID DOF VAD LCID SF VID DEATH BIRTH."""

    pid: int = 0

    KEYWORD: ClassVar[str] = "BOUNDARY_PRESCRIBED_MOTION_RIGID"
    CARDS: ClassVar[tuple[str, ...]] = ("pid dof vad lcid sf vid death birth",)


@register
@dataclass(kw_only=True)
class InitialVelocityGeneration(SimpleKeyword):
    """*INITIAL_VELOCITY_GENERATION.

    Card 1: ID STYP OMEGA VX VY VZ IVATN ICID (STYP 1 part set, 2 part, 3 node
    set; ID 0 = all nodes); card 2: XC YC ZC NX NY NZ PHASE IRIGID (rotation
    axis through XC..ZC along NX..NZ, OMEGA rad/ms).
    """

    id: int = 0
    styp: int = 1
    omega: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    vz: float = 0.0
    ivatn: int = 0
    icid: int = 0
    xc: float = 0.0
    yc: float = 0.0
    zc: float = 0.0
    nx: float = 0.0
    ny: float = 0.0
    nz: float = 0.0
    phase: int = 0
    irigid: int = 0

    KEYWORD: ClassVar[str] = "INITIAL_VELOCITY_GENERATION"
    CARDS: ClassVar[tuple[str, ...]] = ("id styp omega vx vy vz ivatn icid",
                                        "xc yc zc nx ny nz phase irigid")
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class InitialVelocityNode(SimpleKeyword):
    """*INITIAL_VELOCITY_NODE: NID VX VY VZ VXR VYR VZR ICID."""

    nid: int = 0
    vx: float = 0.0
    vy: float = 0.0
    vz: float = 0.0
    vxr: float = 0.0
    vyr: float = 0.0
    vzr: float = 0.0
    icid: int = 0

    KEYWORD: ClassVar[str] = "INITIAL_VELOCITY_NODE"
    CARDS: ClassVar[tuple[str, ...]] = ("nid vx vy vz vxr vyr vzr icid",)
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class InitialVelocity(SimpleKeyword):
    """*INITIAL_VELOCITY: NSID NSIDEX BOXID IRIGID ICID; VX VY VZ VXR VYR VZR;
    (NSIDEX > 0) VXE VYE VZE VXRE VYRE VZRE for the exempted nodes. NSID 0 = all nodes.
    """

    nsid: int = 0
    nsidex: int = 0
    boxid: int = 0
    irigid: int = 0
    icid: int = 0
    vx: float = 0.0
    vy: float = 0.0
    vz: float = 0.0
    vxr: float = 0.0
    vyr: float = 0.0
    vzr: float = 0.0
    vxe: float = 0.0
    vye: float = 0.0
    vze: float = 0.0
    vxre: float = 0.0
    vyre: float = 0.0
    vzre: float = 0.0

    KEYWORD: ClassVar[str] = "INITIAL_VELOCITY"
    CARDS: ClassVar[tuple[str, ...]] = ("nsid nsidex boxid irigid icid",
                                        "vx vy vz vxr vyr vzr", "vxe vye vze vxre vyre vzre")
    N_REQUIRED: ClassVar[int] = 3

    @classmethod
    def want_card(cls, index: int, values: dict[str, object]) -> bool:
        return index < 2 or int(values.get("nsidex", 0) or 0) > 0  # type: ignore[arg-type]
