"""Static records of loads and rigid walls (``Model.loads``, ``Model.rigid_walls``).

Built by :mod:`hollowbody.build.loads`, run by :mod:`hollowbody.solver.loads` and
:mod:`hollowbody.solver.rigidwall`. Node references are 0-based node indices.
Units: mm, ms, kg, kN; the value of a load at time t is ``sf * curve(t)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.source import Source


@dataclass
class BodyLoad:
    """*LOAD_BODY_X / _Y / _Z: base acceleration a(t) = sf * curve(t) (mm/ms^2) along
    ``axis`` (0 x, 1 y, 2 z); the body force on a mass m is -m a(t).

    pids: the parts loaded (*LOAD_BODY_PARTS), None for the whole model.
    lciddr (dynamic relaxation curve) and centre (XC, YC, ZC, used by the rotational
    body loads only) are kept as read.
    """

    axis: int
    lcid: int
    sf: float
    lciddr: int = 0
    centre: np.ndarray = field(default_factory=lambda: np.zeros(3))
    pids: list[int] | None = None
    source: Source = field(default_factory=Source)


@dataclass
class NodeLoad:
    """*LOAD_NODE_POINT / *LOAD_NODE_SET: force (dof 1-3, kN) or moment (dof 5-7,
    kN*mm) ``sf * curve(t)`` on each of ``nodes`` ((k,) int64 node indices)."""

    nodes: np.ndarray
    dof: int
    lcid: int
    sf: float
    source: Source = field(default_factory=Source)


@dataclass
class RigidBodyLoad:
    """*LOAD_RIGID_BODY: force (dof 1-3, kN) or moment (dof 5-7, kN*mm, about the
    centre of mass) ``sf * curve(t)`` on the rigid body of part ``pid``."""

    pid: int
    dof: int
    lcid: int
    sf: float
    source: Source = field(default_factory=Source)


@dataclass
class RigidWallDef:
    """*RIGIDWALL_PLANAR (stationary, infinite).

    nodes: (k,) int64 slave node indices (NSID, or every node, minus NSIDEX);
    tail: (3,) mm a point of the wall; normal: (3,) unit vector from tail to head,
    pointing to the side the nodes are kept on. fric: 0 frictionless, (0, 1)
    Coulomb coefficient, 1 no sliding. birth / death (ms): when the wall acts.
    rwksf: scale of the penalty stiffness used on rigid-body nodes. offset (mm): > 0,
    only the nodes starting within this distance in front of the wall are slaves.
    """

    rwid: int
    nodes: np.ndarray
    tail: np.ndarray
    normal: np.ndarray
    fric: float = 0.0
    birth: float = 0.0
    death: float = 1.0e20
    rwksf: float = 1.0
    offset: float = 0.0
    title: str = ""
    source: Source = field(default_factory=Source)


def loads_summary(model) -> dict[str, list[dict]]:  # noqa: ANN001 - Model
    """For ``hollowbody check``: {"loads": [{kind, dof or axis, curve, sf, target}],
    "rigid_walls": [{rwid, point, normal, nodes, fric}]} (ids as in the deck)."""
    axes = "xyz"
    loads = []
    for ld in model.loads:
        if isinstance(ld, BodyLoad):
            loads.append({"kind": f"LOAD_BODY_{axes[ld.axis].upper()}", "curve": ld.lcid,
                          "sf": ld.sf, "target": "all parts" if ld.pids is None else
                          f"parts {', '.join(map(str, ld.pids))}"})
        elif isinstance(ld, NodeLoad):
            loads.append({"kind": "LOAD_NODE", "dof": ld.dof, "curve": ld.lcid, "sf": ld.sf,
                          "target": f"{ld.nodes.size} node(s)"})
        elif isinstance(ld, RigidBodyLoad):
            loads.append({"kind": "LOAD_RIGID_BODY", "dof": ld.dof, "curve": ld.lcid,
                          "sf": ld.sf, "target": f"part {ld.pid}"})
    walls = [{"rwid": w.rwid, "point": [float(v) for v in w.tail],
              "normal": [float(v) for v in w.normal], "nodes": int(w.nodes.size),
              "fric": float(w.fric)} for w in model.rigid_walls]
    return {"loads": loads, "rigid_walls": walls}
