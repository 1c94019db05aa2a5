"""Deck -> Model for loads and the planar rigid wall (docs/loads.md).

*LOAD_BODY_X / _Y / _Z and *LOAD_BODY_PARTS -> ``BodyLoad``; *LOAD_NODE_POINT /
_SET -> ``NodeLoad``; *LOAD_RIGID_BODY -> ``RigidBodyLoad`` (all in
``model.loads``); *RIGIDWALL_PLANAR -> ``RigidWallDef`` in ``model.rigid_walls``.
Every reference (curve, node, node set, part, part set) is checked here.
"""

from __future__ import annotations

import numpy as np

from hollowbody.build.common import item_error, or_default
from hollowbody.io.keyword import (
    KeywordItem,
    LoadBody,
    LoadBodyParts,
    LoadNodePoint,
    LoadNodeSet,
    LoadRigidBody,
    RigidwallPlanar,
)
from hollowbody.model.loads import BodyLoad, NodeLoad, RigidBodyLoad, RigidWallDef
from hollowbody.model.model import Model

_AXIS = {"X": 0, "Y": 1, "Z": 2}
_LOAD_DOFS = (1, 2, 3, 5, 6, 7)


def build(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """Read the loads and rigid walls of ``b``'s deck into ``model``."""
    model.loads.extend(_body_loads(b, model))
    model.loads.extend(_node_loads(b, model))
    model.loads.extend(_rigid_body_loads(b, model))
    model.rigid_walls.extend(_rigid_walls(b, model))


def _curve(model: Model, item: KeywordItem, lcid: int, what: str = "LCID") -> int:
    if lcid not in model.curves:
        raise item_error(item, f"{what}={lcid}: curve {lcid} is not defined")
    return lcid


def _no_cid(item: KeywordItem, cid: int) -> None:
    if cid:
        raise item_error(item, f"CID={cid}: loads in a local coordinate system are not "
                         "supported (give the components in global axes, CID=0)")


def _node_set(model: Model, item: KeywordItem, sid: int, what: str) -> np.ndarray:
    if sid not in model.node_sets:
        raise item_error(item, f"{what}={sid}: node set {sid} is not defined")
    return np.asarray(model.node_sets[sid], dtype=np.int64)


def _body_parts(b, model: Model) -> list[int] | None:  # noqa: ANN001
    """Parts of the *LOAD_BODY_PARTS part sets (their union), None without one."""
    items = b.of(LoadBodyParts)
    if not items:
        return None
    pids: set[int] = set()
    for it in items:
        if it.psid not in model.part_sets:
            raise item_error(it, f"PSID={it.psid}: part set {it.psid} is not defined")
        for pid in model.part_sets[it.psid]:
            if pid not in model.parts:
                raise item_error(it, f"part set {it.psid} refers to part {pid} which is "
                                 "not defined")
            pids.add(int(pid))
    return sorted(pids)


def _body_loads(b, model: Model) -> list[BodyLoad]:  # noqa: ANN001
    out = []
    items = b.of(LoadBody)
    pids = _body_parts(b, model) if items else None
    for it in items:
        if it.axis not in _AXIS:
            raise item_error(it, f"*LOAD_BODY_{it.axis} is not supported (X, Y, Z only)")
        _no_cid(it, it.cid)
        lcid = _curve(model, it, it.lcid)
        if it.lciddr:
            _curve(model, it, it.lciddr, "LCIDDR")
        out.append(BodyLoad(axis=_AXIS[it.axis], lcid=lcid, sf=or_default(it.sf, 1.0),
                            lciddr=it.lciddr, centre=np.array([it.xc, it.yc, it.zc]),
                            pids=pids, source=it.source))
    return out


def _check_dof(it: KeywordItem) -> None:
    if it.dof in (4, 8):
        raise item_error(it, f"DOF={it.dof} (follower force / moment) is not supported; "
                         "use DOF 1-3 (force) or 5-7 (moment) in global axes")
    if it.dof not in _LOAD_DOFS:
        raise item_error(it, f"DOF={it.dof} is not valid (1-3 force, 5-7 moment)")


def _node_loads(b, model: Model) -> list[NodeLoad]:  # noqa: ANN001
    out = []
    for it in [*b.of(LoadNodePoint), *b.of(LoadNodeSet)]:
        _check_dof(it)
        _no_cid(it, it.cid)
        lcid = _curve(model, it, it.lcid)
        if isinstance(it, LoadNodeSet):
            nodes = _node_set(model, it, it.nsid, "NSID")
        else:
            nodes = np.asarray(b.node_list([it.nid], it, "load"), dtype=np.int64)
        out.append(NodeLoad(nodes=nodes, dof=int(it.dof), lcid=lcid,
                            sf=or_default(it.sf, 1.0), source=it.source))
    return out


def _rigid_body_loads(b, model: Model) -> list[RigidBodyLoad]:  # noqa: ANN001
    out = []
    for it in b.of(LoadRigidBody):
        _check_dof(it)
        _no_cid(it, it.cid)
        lcid = _curve(model, it, it.lcid)
        if it.pid not in model.parts:
            raise item_error(it, f"PID={it.pid}: part {it.pid} is not defined")
        if model.material_of(it.pid).kind != "rigid":
            raise item_error(it, f"part {it.pid} is not rigid (*LOAD_RIGID_BODY needs a "
                             "*MAT_RIGID part)")
        out.append(RigidBodyLoad(pid=int(it.pid), dof=int(it.dof), lcid=lcid,
                                 sf=or_default(it.sf, 1.0), source=it.source))
    return out


def _rigid_walls(b, model: Model) -> list[RigidWallDef]:  # noqa: ANN001
    out = []
    for k, it in enumerate(b.of(RigidwallPlanar)):
        if it.variants:
            opts = ", ".join("_" + o for o in it.variants)
            raise item_error(it, f"*RIGIDWALL_PLANAR option(s) {opts} not supported "
                             "(stationary infinite planar walls only; docs/loads.md)")
        if it.boxid:
            raise item_error(it, f"BOXID={it.boxid}: boxes are not supported (give the "
                             "slave nodes as NSID)")
        if it.fric > 1.0 or it.fric < 0.0:
            raise item_error(it, f"FRIC={it.fric:g} is not supported (0 frictionless, "
                             "0-1 Coulomb, 1 no sliding)")
        tail = np.array([it.xt, it.yt, it.zt], dtype=float)
        head = np.array([it.xh, it.yh, it.zh], dtype=float)
        length = float(np.linalg.norm(head - tail))
        if not length > 0.0:
            raise item_error(it, "the wall normal is zero: the head (XH, YH, ZH) must "
                             "differ from the tail (XT, YT, ZT)")
        if it.nsid:
            nodes = _node_set(model, it, it.nsid, "NSID")
        else:
            nodes = np.arange(model.n_nodes, dtype=np.int64)
        if it.nsidex:
            nodes = np.setdiff1d(nodes, _node_set(model, it, it.nsidex, "NSIDEX"))
        death = it.death if it.death > 0.0 else 1.0e20
        rwid = it.rwid if it.rwid is not None else k + 1
        out.append(RigidWallDef(rwid=int(rwid), nodes=np.unique(nodes).astype(np.int64),
                                tail=tail, normal=(head - tail) / length,
                                fric=float(it.fric), birth=float(it.birth), death=death,
                                rwksf=or_default(it.rwksf, 1.0), offset=float(it.offset),
                                title=it.heading, source=it.source))
    return out
