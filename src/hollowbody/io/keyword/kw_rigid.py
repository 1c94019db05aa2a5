"""Rigid-body constraint keywords.

*CONSTRAINED_RIGID_BODIES (PIDM PIDS IFLAG; newer manuals call them PIDL,
PIDC), *CONSTRAINED_RIGID_BODIES_SET (PIDM and a part set),
*CONSTRAINED_EXTRA_NODES_NODE (PID NID IFLAG) / _SET (PID NSID IFLAG),
*CONSTRAINED_NODAL_RIGID_BODY with its options _SPC (CMO CON1 CON2 card after
card 1) and _INERTIA (XC YC ZC TM IRCS NODEID; IXX IXY IXZ IYY IYZ IZZ;
VTX VTY VTZ VRX VRY VRZ; with IRCS = 1 XL YL ZL XLIP YLIP ZLIP CID2), in either
order (_SPC_INERTIA, _INERTIA_SPC), each with the _TITLE option (a title card
first).

Field names are the LS-DYNA ones in lower case, defaults LS-DYNA's (blank =
0). Units: mm, kg, kg*mm^2, mm/ms, rad/ms. Meaning and validation of the
fields: :mod:`hollowbody.build.rigid_constraints`, docs/rigid_bodies.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hollowbody.io.keyword.base import SimpleKeyword, register
from hollowbody.io.keyword.kw_parts import InertiaFields


@register
@dataclass(kw_only=True)
class ConstrainedRigidBodies(SimpleKeyword):
    """*CONSTRAINED_RIGID_BODIES: PIDM PIDS IFLAG (one pair per card, repeating).

    The rigid part PIDS becomes part of the rigid body of PIDM. IFLAG (only
    meaningful when PIDM has *PART_INERTIA): 0 keeps PIDM's *PART_INERTIA
    properties, 1 adds PIDS's mass and inertia to them.
    """

    pidm: int = 0
    pids: int = 0
    iflag: int = 0

    KEYWORD: ClassVar[str] = "CONSTRAINED_RIGID_BODIES"
    CARDS: ClassVar[tuple[str, ...]] = ("pidm pids iflag",)
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class ConstrainedRigidBodiesSet(SimpleKeyword):
    """*CONSTRAINED_RIGID_BODIES_SET: PIDM PSID IFLAG (every part of the part set
    PSID merged into PIDM; repeating)."""

    pidm: int = 0
    psid: int = 0
    iflag: int = 0

    KEYWORD: ClassVar[str] = "CONSTRAINED_RIGID_BODIES_SET"
    CARDS: ClassVar[tuple[str, ...]] = ("pidm psid iflag",)
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class ConstrainedExtraNodesNode(SimpleKeyword):
    """*CONSTRAINED_EXTRA_NODES_NODE: PID NID IFLAG (repeating).

    Node NID moves with the rigid body of part PID. IFLAG (only meaningful
    when PID has *PART_INERTIA): 0 keeps the *PART_INERTIA properties, 1 adds
    the node's mass to them.
    """

    pid: int = 0
    nid: int = 0
    iflag: int = 0

    KEYWORD: ClassVar[str] = "CONSTRAINED_EXTRA_NODES_NODE"
    CARDS: ClassVar[tuple[str, ...]] = ("pid nid iflag",)
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class ConstrainedExtraNodesSet(SimpleKeyword):
    """*CONSTRAINED_EXTRA_NODES_SET: PID NSID IFLAG (repeating); as _NODE for
    every node of the node set NSID."""

    pid: int = 0
    nsid: int = 0
    iflag: int = 0

    KEYWORD: ClassVar[str] = "CONSTRAINED_EXTRA_NODES_SET"
    CARDS: ClassVar[tuple[str, ...]] = ("pid nsid iflag",)
    REPEAT: ClassVar[bool] = True


_NRB_CARD = "pid cid nsid pnode iprt drflag rrflag"
_SPC_CARD = "cmo con1 con2"
_AXES_CARD = "xl yl zl xlip ylip zlip cid2"
_INERTIA_CARDS = ("xc yc zc tm ircs nodeid", "ixx ixy ixz iyy iyz izz",
                  "vtx vty vtz vrx vry vrz", _AXES_CARD)


@dataclass(kw_only=True)
class ConstrainedNodalRigidBodyKeyword(InertiaFields, SimpleKeyword):
    """Fields of every *CONSTRAINED_NODAL_RIGID_BODY variant.

    Card 1: PID (the body's id, used for output and joints) CID (output system)
    NSID (node set; 0 = PID) PNODE (optional node placed at the centre of
    mass) IPRT (rbdout: 2 = not written) DRFLAG RRFLAG (release flags of
    two-node bodies). ``has_spc`` / ``has_inertia``: the variant's option cards.
    """

    pid: int = 0
    cid: int = 0
    nsid: int = 0
    pnode: int = 0
    iprt: int = 0
    drflag: int = 0
    rrflag: int = 0
    cmo: float = 0.0
    con1: float = 0.0
    con2: float = 0.0
    cid2: int = 0
    title: str = ""

    TITLE_ATTR: ClassVar[str | None] = "title"
    has_spc: ClassVar[bool] = False
    has_inertia: ClassVar[bool] = False

    @classmethod
    def want_card(cls, index: int, values: dict[str, object]) -> bool:
        """The local-axes card follows the _INERTIA cards only with IRCS = 1."""
        return cls.CARDS[index] != _AXES_CARD or values.get("ircs", 0) == 1


@register
@dataclass(kw_only=True)
class ConstrainedNodalRigidBody(ConstrainedNodalRigidBodyKeyword):
    """*CONSTRAINED_NODAL_RIGID_BODY(_TITLE): card 1 only (repeating)."""

    KEYWORD: ClassVar[str] = "CONSTRAINED_NODAL_RIGID_BODY"
    CARDS: ClassVar[tuple[str, ...]] = (_NRB_CARD,)
    REPEAT: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class ConstrainedNodalRigidBodySpc(ConstrainedNodalRigidBodyKeyword):
    """*CONSTRAINED_NODAL_RIGID_BODY_SPC(_TITLE): card 1, then CMO CON1 CON2
    (as *MAT_RIGID; repeating)."""

    KEYWORD: ClassVar[str] = "CONSTRAINED_NODAL_RIGID_BODY_SPC"
    CARDS: ClassVar[tuple[str, ...]] = (_NRB_CARD, _SPC_CARD)
    N_REQUIRED: ClassVar[int] = 2
    REPEAT: ClassVar[bool] = True
    has_spc: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class ConstrainedNodalRigidBodyInertia(ConstrainedNodalRigidBodyKeyword):
    """*CONSTRAINED_NODAL_RIGID_BODY_INERTIA(_TITLE): card 1, then XC YC ZC TM IRCS
    NODEID; IXX IXY IXZ IYY IYZ IZZ (kg*mm^2, about the centre of mass, global
    axes; with IRCS = 1 principal moments IXX, IYY, IZZ about the local axes of
    the card XL YL ZL XLIP YLIP ZLIP CID2 that follows); VTX VTY VTZ VRX VRY VRZ
    (optional). One body per keyword."""

    KEYWORD: ClassVar[str] = "CONSTRAINED_NODAL_RIGID_BODY_INERTIA"
    CARDS: ClassVar[tuple[str, ...]] = (_NRB_CARD, *_INERTIA_CARDS)
    N_REQUIRED: ClassVar[int] = 3
    has_inertia: ClassVar[bool] = True


@register
@dataclass(kw_only=True)
class ConstrainedNodalRigidBodySpcInertia(ConstrainedNodalRigidBodyKeyword):
    """*CONSTRAINED_NODAL_RIGID_BODY_SPC_INERTIA (also written _INERTIA_SPC): card
    1, the SPC card, then the three _INERTIA cards (the last optional)."""

    KEYWORD: ClassVar[str] = "CONSTRAINED_NODAL_RIGID_BODY_SPC_INERTIA"
    ALIASES: ClassVar[tuple[str, ...]] = ("CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC",)
    CARDS: ClassVar[tuple[str, ...]] = (_NRB_CARD, _SPC_CARD, *_INERTIA_CARDS)
    N_REQUIRED: ClassVar[int] = 4
    has_spc: ClassVar[bool] = True
    has_inertia: ClassVar[bool] = True
