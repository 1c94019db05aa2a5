"""Joints between rigid bodies, joint stiffnesses and local coordinate systems
(static records of the Model; docs/joints.md).

- :class:`CoordinateSystem`: *DEFINE_COORDINATE_NODES / _SYSTEM -> ``model.coordinate_systems``
  (by CID);
- :class:`Joint`: *CONSTRAINED_JOINT_<TYPE> -> ``model.joints``;
- :class:`JointStiffness`: *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED /
  _FLEXION-TORSION -> ``model.joint_stiffness``.

Node indices are 0-based indices into the Model's node arrays. Units: mm, rad,
kN*mm (moments), kN*mm/rad (stiffnesses), kN*mm*ms/rad (damping).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.source import Source

#: Node pairs (0-based positions in N1..N6) each joint type holds coincident, and
#: whether the pair is held in all directions (False: only across the axis N1 -> N3,
#: free to slide along it).
JOINT_PAIRS: dict[str, tuple[tuple[int, int, bool], ...]] = {
    "SPHERICAL": ((0, 1, True),),
    "REVOLUTE": ((0, 1, True), (2, 3, True)),
    "CYLINDRICAL": ((0, 1, False), (2, 3, False)),
    "UNIVERSAL": ((0, 1, True),),
    "TRANSLATIONAL": ((0, 1, False), (2, 3, False), (4, 5, False)),
    "LOCKING": ((0, 1, True), (2, 3, True), (4, 5, True)),
}
#: Number of nodes N1.. each joint type needs.
JOINT_NODE_COUNT = {"SPHERICAL": 2, "REVOLUTE": 4, "CYLINDRICAL": 4, "UNIVERSAL": 4,
                    "TRANSLATIONAL": 6, "LOCKING": 6}


@dataclass
class CoordinateSystem:
    """A local coordinate system.

    ``axes``: (3, 3) rows = unit local x, y, z axes in global coordinates at
    t = 0; ``origin`` (3,) mm. By nodes (``nodes`` (3,) indices N1, N2, N3,
    ``dir`` 0/1/2 = axis along N1 -> N2): with ``follow`` (FLAG = 1) the system
    is rebuilt from its nodes' current positions every cycle.
    """

    cid: int
    axes: np.ndarray
    origin: np.ndarray
    nodes: np.ndarray | None = None
    dir: int = 0
    follow: bool = False
    keyword: str = "DEFINE_COORDINATE_SYSTEM"
    source: Source = field(default_factory=Source)


@dataclass
class Joint:
    """*CONSTRAINED_JOINT_<kind>: ``nodes`` (k,) node indices N1..Nk (odd positions
    on body A, even on body B), ``rps`` relative penalty stiffness, ``damp``
    damping scale factor (0 = no damping), ``jid`` its id (given or numbered)."""

    jid: int
    kind: str
    nodes: np.ndarray
    rps: float = 1.0
    damp: float = 1.0
    heading: str = ""
    keyword: str = "CONSTRAINED_JOINT_SPHERICAL"
    source: Source = field(default_factory=Source)


@dataclass
class JointStiffness:
    """*CONSTRAINED_JOINT_STIFFNESS_<kind> (``kind`` GENERALIZED or FLEXION-TORSION).

    Per rotation (GENERALIZED: phi, theta, psi; FLEXION-TORSION: alpha, -, beta
    with gamma scaling the alpha moment): ``lc`` (3,) moment-angle curve ids,
    ``dlc`` (3,) damping moment-rate curve ids (0: none), ``es`` (3,) kN*mm/rad
    elastic stiffness of friction and stops, ``fm`` (3,) kN*mm friction moment
    (0: none), ``neg_stop`` / ``pos_stop`` (3,) rad (nan: no stop; neg_stop <= 0).
    FLEXION-TORSION: ``lc_gamma`` / ``dlc_gamma`` scale-factor curves of gamma.
    ``cida`` / ``cidb``: coordinate systems of bodies A and B (cidb = cida when 0).
    """

    jsid: int
    kind: str
    pida: int
    pidb: int
    cida: int
    cidb: int
    jid: int
    lc: np.ndarray
    dlc: np.ndarray
    es: np.ndarray
    fm: np.ndarray
    neg_stop: np.ndarray
    pos_stop: np.ndarray
    lc_gamma: int = 0
    dlc_gamma: int = 0
    keyword: str = "CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"
    source: Source = field(default_factory=Source)


def axes_from_points(o: np.ndarray, a: np.ndarray, p: np.ndarray, axis: int = 0) -> np.ndarray:
    """(3, 3) rows = local x, y, z: axis ``axis`` (0, 1, 2) along o -> a, the point p
    in the plane of that axis and the next one (x-y, y-z, z-x). Raises ValueError
    when o, a, p do not span a plane."""
    e = [np.zeros(3)] * 3
    u = np.asarray(a, float) - np.asarray(o, float)
    w = np.asarray(p, float) - np.asarray(o, float)
    nu = float(np.linalg.norm(u))
    if nu <= 0.0:
        raise ValueError("the first two points coincide")
    i, j, k = axis, (axis + 1) % 3, (axis + 2) % 3
    e[i] = u / nu
    n = np.cross(e[i], w)
    nn = float(np.linalg.norm(n))
    if nn <= 1e-9 * nu * max(float(np.linalg.norm(w)), 1e-300):
        raise ValueError("the three points are on one line")
    e[k] = n / nn
    e[j] = np.cross(e[k], e[i])
    return np.array(e)


def joint_summary(model) -> dict[str, list[dict]]:  # noqa: ANN001 - Model
    """For ``hollowbody check``: {"joints": [{jid, type, nodes, parts}], "joint_stiffness":
    [{jsid, type, parts, cid, jid}]}; ``parts``: the rigid parts (PIDA, PIDB) of the
    joint's nodes N1 and N2 (None: on no *MAT_RIGID part)."""
    from hollowbody.model.mass import part_nodes

    owner = np.full(model.n_nodes, -1, dtype=np.int64)
    for pid in model.rigid_pids():
        owner[part_nodes(model, pid)] = pid
    joints = []
    for j in model.joints:
        pids = [int(owner[n]) if owner[n] >= 0 else None for n in j.nodes[:2]]
        joints.append({"jid": j.jid, "type": j.kind,
                       "nodes": [int(model.node_ids[n]) for n in j.nodes], "parts": pids})
    stiff = [{"jsid": s.jsid, "type": s.kind, "parts": [s.pida, s.pidb],
              "cid": [s.cida, s.cidb], "jid": s.jid} for s in model.joint_stiffness]
    return {"joints": joints, "joint_stiffness": stiff}
