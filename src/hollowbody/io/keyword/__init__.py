"""LS-DYNA keyword decks: reader, writer and the keyword items.

>>> from hollowbody.io.keyword import read_deck, write_deck
>>> deck = read_deck("model.k")          # doctest: +SKIP
>>> write_deck(deck, "copy.k")           # doctest: +SKIP

See ``docs/keyword.md`` for the supported keywords and the deck-building API.
"""

from hollowbody.io.keyword.base import KeywordItem, RawKeyword, SimpleKeyword, Title
from hollowbody.io.keyword.deck import Deck, Include
from hollowbody.io.keyword.kw_beams import ElementBeam, IntegrationBeam, SectionBeam
from hollowbody.io.keyword.kw_body_loads import (
    LoadBody,
    LoadBodyParts,
    LoadNodePoint,
    LoadNodeSet,
    LoadRigidBody,
    RigidwallPlanar,
)
from hollowbody.io.keyword.kw_contact import (
    CONTACT_TYPES,
    TIED_OFFSETS,
    TIED_TYPES,
    Contact,
    TiedContact,
)
from hollowbody.io.keyword.kw_control import (
    ControlBulkViscosity,
    ControlContact,
    ControlHourglass,
    ControlShell,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3dump,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    DatabaseHistoryNodeSet,
)
from hollowbody.io.keyword.kw_discrete import (
    DefineSdOrientation,
    ElementDiscrete,
    MatDamperViscous,
    MatSpringElastic,
    MatSpringGeneralNonlinear,
    MatSpringNonlinearElastic,
    SectionDiscrete,
)
from hollowbody.io.keyword.kw_joints import (
    JOINT_TYPES,
    ConstrainedJoint,
    DefineCoordinateNodes,
    DefineCoordinateSystem,
    JointStiffnessFlexionTorsion,
    JointStiffnessGeneralized,
)
from hollowbody.io.keyword.kw_loads import (
    BoundarySpcNode,
    BoundarySpcSet,
    InitialVelocity,
    InitialVelocityGeneration,
    InitialVelocityNode,
    PrescribedMotionKeyword,
    PrescribedMotionNode,
    PrescribedMotionRigid,
    PrescribedMotionSet,
)
from hollowbody.io.keyword.kw_materials import (
    MatElastic,
    Material,
    MatNull,
    MatPiecewiseLinearPlasticity,
    MatPlasticKinematic,
    MatRigid,
    MatSimplifiedRubber,
)
from hollowbody.io.keyword.kw_mesh import MassElements, Nodes, ShellElements, SolidElements
from hollowbody.io.keyword.kw_parts import Hourglass, Part, PartInertia, SectionShell, SectionSolid
from hollowbody.io.keyword.kw_rigid import (
    ConstrainedExtraNodesNode,
    ConstrainedExtraNodesSet,
    ConstrainedNodalRigidBody,
    ConstrainedNodalRigidBodyInertia,
    ConstrainedNodalRigidBodyKeyword,
    ConstrainedNodalRigidBodySpc,
    ConstrainedNodalRigidBodySpcInertia,
    ConstrainedRigidBodies,
    ConstrainedRigidBodiesSet,
)
from hollowbody.io.keyword.kw_sets import (
    DefineCurve,
    SetNodeList,
    SetNodeListGenerate,
    SetPartList,
    SetPartListGenerate,
    SetSegment,
)
from hollowbody.io.keyword.reader import (
    PartialRead,
    UnsupportedKeywordWarning,
    read_deck,
    read_deck_partial,
    read_deck_text,
)
from hollowbody.io.keyword.writer import deck_lines, write_deck

__all__ = [
    "CONTACT_TYPES", "BoundarySpcNode", "ConstrainedExtraNodesNode", "ConstrainedExtraNodesSet",
    "ConstrainedNodalRigidBody", "ConstrainedNodalRigidBodyInertia",
    "ConstrainedNodalRigidBodyKeyword", "ConstrainedNodalRigidBodySpc",
    "ConstrainedNodalRigidBodySpcInertia", "ConstrainedRigidBodies", "ConstrainedRigidBodiesSet",
    "BoundarySpcSet", "Contact", "ControlBulkViscosity",
    "ControlContact", "ControlHourglass", "ControlShell", "ControlTermination", "ControlTimestep",
    "DatabaseAscii", "DatabaseBinaryD3dump", "DatabaseBinaryD3plot", "DatabaseHistoryNode",
    "DatabaseHistoryNodeSet",
    "Deck", "DefineCurve", "DefineSdOrientation", "ElementBeam", "ElementDiscrete",
    "Hourglass", "Include", "InitialVelocity", "InitialVelocityGeneration",
    "InitialVelocityNode", "IntegrationBeam", "KeywordItem", "LoadBody", "LoadBodyParts",
    "LoadNodePoint", "LoadNodeSet", "LoadRigidBody", "MassElements", "MatDamperViscous",
    "MatElastic", "MatNull", "MatPiecewiseLinearPlasticity", "MatPlasticKinematic", "MatRigid",
    "MatSimplifiedRubber", "MatSpringElastic", "MatSpringGeneralNonlinear",
    "MatSpringNonlinearElastic", "Material", "Nodes", "Part", "PartInertia", "PartialRead",
    "PrescribedMotionKeyword", "PrescribedMotionNode", "PrescribedMotionRigid",
    "PrescribedMotionSet", "RawKeyword", "RigidwallPlanar", "SectionBeam", "SectionDiscrete",
    "SectionShell",
    "SectionSolid", "SetNodeList", "SetNodeListGenerate", "SetPartList", "SetPartListGenerate",
    "SetSegment", "ShellElements", "SimpleKeyword", "SolidElements", "TIED_OFFSETS",
    "TIED_TYPES", "TiedContact", "Title",
    "JOINT_TYPES", "ConstrainedJoint", "DefineCoordinateNodes", "DefineCoordinateSystem",
    "JointStiffnessFlexionTorsion", "JointStiffnessGeneralized",
    "UnsupportedKeywordWarning", "deck_lines", "read_deck", "read_deck_partial",
    "read_deck_text", "write_deck",
]
