"""Records of the rigid-body constraints (``Model.rigid_merges``,
``Model.nodal_rigid_bodies``, ``Model.extra_nodes``), built by
:mod:`hollowbody.build.rigid_constraints` from *CONSTRAINED_RIGID_BODIES,
*CONSTRAINED_NODAL_RIGID_BODY(_SPC, _INERTIA) and *CONSTRAINED_EXTRA_NODES.

Node references are 0-based node indices; units mm, kg, kg*mm^2, mm/ms, rad/ms.
The mass properties of the bodies they make: :mod:`hollowbody.model.rigid_bodies`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.source import Source


@dataclass
class RigidMerge:
    """*CONSTRAINED_RIGID_BODIES: rigid part ``constrained`` (PIDS) joins the body of
    rigid part ``lead`` (PIDM). iflag: 1 adds PIDS's mass to a lead given by
    *PART_INERTIA, 0 keeps the lead's *PART_INERTIA values (no effect otherwise)."""

    lead: int
    constrained: int
    iflag: int = 0
    source: Source = field(default_factory=Source)
    keyword: str = "CONSTRAINED_RIGID_BODIES"


@dataclass
class ExtraNodes:
    """*CONSTRAINED_EXTRA_NODES_NODE/_SET: deformable nodes carried by the rigid body
    of part ``pid``. nodes: (k,) int64 node indices. iflag as :class:`RigidMerge`."""

    pid: int
    nodes: np.ndarray
    iflag: int = 0
    source: Source = field(default_factory=Source)
    keyword: str = "CONSTRAINED_EXTRA_NODES_NODE"


@dataclass
class NodalInertia:
    """The _INERTIA cards of a nodal rigid body: they replace the lumped masses.

    centre: (3,) mm centre of mass; mass: kg (TM); inertia: (3, 3) kg*mm^2 about
    the centre, global axes; v0: (3,) mm/ms, w0: (3,) rad/ms initial velocities
    (used when not all zero; else the nodes' initial velocities are fitted).
    """

    centre: np.ndarray
    mass: float
    inertia: np.ndarray
    v0: np.ndarray
    w0: np.ndarray


@dataclass
class NodalRigidBody:
    """*CONSTRAINED_NODAL_RIGID_BODY: a rigid body made of the nodes of a node set.

    pid: the body's id (rbdout, joints, prescribed motion); nodes: (k,) int64
    sorted unique node indices (PNODE included); pnode: index of the node placed at
    the centre of mass (-1: none); fixed_trans / fixed_rot: (3,) bool global
    axes held (_SPC, CMO = 1); iprt: 2 = not written to rbdout; inertia: the
    _INERTIA values or None (lumped nodal masses).
    """

    pid: int
    nodes: np.ndarray
    pnode: int = -1
    fixed_trans: np.ndarray = field(default_factory=lambda: np.zeros(3, dtype=bool))
    fixed_rot: np.ndarray = field(default_factory=lambda: np.zeros(3, dtype=bool))
    iprt: int = 0
    inertia: NodalInertia | None = None
    title: str = ""
    source: Source = field(default_factory=Source)
    keyword: str = "CONSTRAINED_NODAL_RIGID_BODY"
