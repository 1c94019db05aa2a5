"""Deck -> Model for the rigid-body constraints (see :mod:`hollowbody.build.mechanics`).

*CONSTRAINED_RIGID_BODIES(_SET) -> ``model.rigid_merges``,
*CONSTRAINED_NODAL_RIGID_BODY(_SPC, _INERTIA) -> ``model.nodal_rigid_bodies``,
*CONSTRAINED_EXTRA_NODES_NODE/_SET -> ``model.extra_nodes``. Every reference is
checked, and so is the rule that a node belongs to at most one rigid body: a
node of two bodies that are not merged and a nodal prescribed motion on a node
of a rigid body (the body moves it, the motion would be silently ignored) are
DeckErrors at the card that makes the conflict, naming both. An SPC on a node of
a rigid body holds the body (:mod:`hollowbody.model.rigid_bodies`).
Mass properties: :mod:`hollowbody.model.rigid_bodies`.
"""

from __future__ import annotations

import numpy as np

from hollowbody.build.common import item_error
from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    ConstrainedExtraNodesNode,
    ConstrainedExtraNodesSet,
    ConstrainedNodalRigidBodyKeyword,
    ConstrainedRigidBodies,
    ConstrainedRigidBodiesSet,
    KeywordItem,
    PrescribedMotionNode,
    PrescribedMotionSet,
)
from hollowbody.model.mass import part_nodes
from hollowbody.model.model import Model
from hollowbody.model.rigid_bodies import CON_AXES, lead_of, local_axes_inertia
from hollowbody.model.rigid_constraints import (
    ExtraNodes,
    NodalInertia,
    NodalRigidBody,
    RigidMerge,
)

_HOLD = "prescribe the body's motion instead: *BOUNDARY_PRESCRIBED_MOTION_RIGID with its PID"


def build(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """Read the rigid-body constraints of ``b`` into ``model`` (DeckError on bad input)."""
    model.rigid_merges = _merges(b, model)
    model.extra_nodes = _extra_nodes(b, model)
    model.nodal_rigid_bodies = _nodal_bodies(b, model)
    owner, labels, _ = _ownership(model)
    _no_nodal_constraints(b, model, owner, labels)


def _rigid_part(model: Model, pid: int, item: KeywordItem, what: str) -> None:
    if pid not in model.parts:
        raise item_error(item, f"{what} {pid} is not a defined part")
    mat = model.material_of(pid)
    if mat.kind != "rigid":
        raise item_error(item, f"{what} {pid} is not rigid (its material {mat.mid} is "
                         f"*{mat.keyword or mat.kind}; a rigid body needs *MAT_RIGID)")


def _flag(item: KeywordItem, value: int, name: str = "IFLAG") -> int:
    if value not in (0, 1):
        raise item_error(item, f"{name}={value} must be 0 or 1")
    return int(value)


def _merges(b, model: Model) -> list[RigidMerge]:  # noqa: ANN001
    out: list[RigidMerge] = []
    pairs: list[tuple[int, int, KeywordItem]] = []
    for it in b.of(ConstrainedRigidBodies):
        pairs.append((it.pidm, it.pids, it))
    for it in b.of(ConstrainedRigidBodiesSet):
        if it.psid not in model.part_sets:
            raise item_error(it, f"part set {it.psid} is not defined")
        pairs += [(it.pidm, p, it) for p in model.part_sets[it.psid]]
    lead_by: dict[int, tuple[int, KeywordItem]] = {}
    for lead, pid, it in pairs:
        _rigid_part(model, lead, it, "PIDM: part")
        _rigid_part(model, pid, it, "PIDS: part")
        if lead == pid:
            raise item_error(it, f"part {pid} is constrained to itself")
        if pid in lead_by:
            if lead_by[pid][0] == lead:
                continue  # the same pair again
            first = lead_by[pid][1].source
            raise item_error(it, f"part {pid} is already constrained to part "
                             f"{lead_by[pid][0]} (at {first}); a part joins one lead only")
        lead_by[pid] = (lead, it)
        cur, chain = lead, [pid, lead]
        while cur in lead_by:  # the pair closes a cycle A <- B <- ... <- A
            cur = lead_by[cur][0]
            if cur == pid:
                raise item_error(it, f"parts {sorted(set(chain))} are constrained to each "
                                 "other in a cycle: one of them must lead")
            chain.append(cur)
        out.append(RigidMerge(lead, pid, _flag(it, it.iflag), it.source,
                              it.keyword_line().lstrip("*")))
    return out


def _extra_nodes(b, model: Model) -> list[ExtraNodes]:  # noqa: ANN001
    out = []
    for it in b.of(ConstrainedExtraNodesNode) + b.of(ConstrainedExtraNodesSet):
        _rigid_part(model, it.pid, it, "PID: part")
        if isinstance(it, ConstrainedExtraNodesSet):
            if it.nsid not in model.node_sets:
                raise item_error(it, f"node set {it.nsid} is not defined")
            nodes = np.asarray(model.node_sets[it.nsid], dtype=np.int64)
        else:
            nodes = np.asarray(b.node_list([it.nid], it, "extra node"), dtype=np.int64)
        out.append(ExtraNodes(it.pid, nodes, _flag(it, it.iflag), it.source,
                              it.keyword_line().lstrip("*")))
    return out


def _inertia(b, model: Model, it) -> NodalInertia:  # noqa: ANN001
    if it.ircs not in (0, 1):
        raise item_error(it, f"IRCS={it.ircs} must be 0 (global tensor) or 1 (principal "
                         "moments about local axes)")
    if it.tm <= 0.0:
        raise item_error(it, f"TM={it.tm:g}: the _INERTIA option needs the body's mass TM > 0")
    centre = np.array([it.xc, it.yc, it.zc], dtype=float)
    if it.nodeid:
        centre = model.node_x0[b.node_list([it.nodeid], it, "NODEID")[0]].astype(float).copy()
    inertia = np.array([[it.ixx, it.ixy, it.ixz], [it.ixy, it.iyy, it.iyz],
                        [it.ixz, it.iyz, it.izz]], dtype=float)
    if it.ircs == 1:
        inertia = _local_inertia(it)
    eig = np.linalg.eigvalsh(inertia)
    if eig[0] < -1e-12 * max(abs(eig[-1]), 1e-300) or eig[-1] <= 0.0:
        raise item_error(it, "the inertia tensor IXX..IZZ is not positive (principal "
                         f"moments {', '.join(f'{e:.4g}' for e in eig)} kg*mm^2)")
    return NodalInertia(centre, float(it.tm), inertia,
                        np.array([it.vtx, it.vty, it.vtz], dtype=float),
                        np.array([it.vrx, it.vry, it.vrz], dtype=float))


def _local_inertia(it) -> np.ndarray:  # noqa: ANN001 - nodal rigid body item
    """IRCS = 1: principal moments IXX, IYY, IZZ about the local axes of the card
    XL..ZLIP (:func:`local_axes_inertia`; IXY, IXZ, IYZ are not used)."""
    if it.cid2:
        raise item_error(it, f"CID2={it.cid2}: local axes from a coordinate system are not "
                         "supported; give XL YL ZL and XLIP YLIP ZLIP")
    try:
        return local_axes_inertia([it.ixx, it.iyy, it.izz], [it.xl, it.yl, it.zl],
                                  [it.xlip, it.ylip, it.zlip])
    except ValueError as exc:
        raise item_error(it, f"IRCS=1: {exc}") from None


def _nodal_bodies(b, model: Model) -> list[NodalRigidBody]:  # noqa: ANN001
    out: list[NodalRigidBody] = []
    seen: dict[int, KeywordItem] = {}
    for it in b.of(ConstrainedNodalRigidBodyKeyword):
        pid = int(it.pid)
        if pid <= 0:
            raise item_error(it, f"PID={pid}: a nodal rigid body needs a positive id")
        if pid in seen:
            raise item_error(it, f"nodal rigid body {pid} is defined twice (first at "
                             f"{seen[pid].source})")
        if pid in model.parts:
            raise item_error(it, f"PID {pid} is already a *PART (at {model.parts[pid].source}): "
                             "a nodal rigid body needs an id of its own")
        seen[pid] = it
        if it.cid:
            raise item_error(it, f"CID={it.cid} (output in a local system) is not supported; "
                             "leave it 0 (output in global axes)")
        if it.drflag or it.rrflag:
            raise item_error(it, f"DRFLAG={it.drflag}/RRFLAG={it.rrflag} (released DOFs of "
                             "two-node bodies) are not supported; leave them 0")
        if it.iprt not in (0, 1, 2):
            raise item_error(it, f"IPRT={it.iprt} must be 0, 1 or 2")
        nsid = int(it.nsid) or pid
        if nsid not in model.node_sets:
            raise item_error(it, f"node set {nsid} (NSID{'' if it.nsid else ' = PID'}) is "
                             "not defined")
        nodes = np.asarray(model.node_sets[nsid], dtype=np.int64)
        pnode = -1
        if it.pnode:
            pnode = int(b.node_list([abs(it.pnode)], it, "PNODE")[0])
        nodes = np.unique(np.concatenate([nodes, [pnode] if pnode >= 0 else []])
                          ).astype(np.int64)
        if nodes.size == 0:
            raise item_error(it, f"node set {nsid} is empty")
        fixed_t = np.zeros(3, dtype=bool)
        fixed_r = np.zeros(3, dtype=bool)
        if it.has_spc:
            cmo = int(it.cmo)
            if cmo == -1:
                raise item_error(it, "CMO=-1 (constraints in a local system) is not supported; "
                                 "use CMO=1 with global constraints")
            if cmo not in (0, 1):
                raise item_error(it, f"CMO={it.cmo:g} must be 0 or 1")
            if cmo == 1:
                c1, c2 = int(it.con1), int(it.con2)
                if c1 not in CON_AXES or c2 not in CON_AXES:
                    raise item_error(it, f"CON1={it.con1:g}/CON2={it.con2:g} must be 0-7")
                fixed_t[list(CON_AXES[c1])] = True
                fixed_r[list(CON_AXES[c2])] = True
        inertia = _inertia(b, model, it) if it.has_inertia else None
        out.append(NodalRigidBody(pid, nodes, pnode, fixed_t, fixed_r, int(it.iprt), inertia,
                                  it.title, it.source, it.keyword_line().lstrip("*")))
    return out


def _ownership(model: Model) -> tuple[np.ndarray, list[str], list]:
    """owner (n,) int: index of the body each node belongs to (-1: none); labels and
    the (file, line, keyword) of each body. DeckError for a node on two bodies."""
    owner = np.full(model.n_nodes, -1, dtype=np.int64)
    labels: list[str] = []
    where: list = []
    leads = lead_of(model)
    body_of_lead: dict[int, int] = {}

    def claim(k: int, nodes: np.ndarray, src, keyword: str) -> None:  # noqa: ANN001
        nodes = np.asarray(nodes, dtype=np.int64)
        cur = owner[nodes]
        clash = np.flatnonzero((cur >= 0) & (cur != k))
        if clash.size:
            i = int(nodes[clash[0]])
            other = int(cur[clash[0]])
            raise DeckError(f"node {int(model.node_ids[i])} is on {labels[k]} and on "
                            f"{labels[other]} (defined at {where[other][0]}:"
                            f"{where[other][1]}): a node belongs to one rigid body only "
                            "(merge them with *CONSTRAINED_RIGID_BODIES)",
                            src.file, src.line, keyword)
        owner[nodes] = k

    for pid in model.rigid_pids():
        lead = leads[pid]
        if lead not in body_of_lead:
            body_of_lead[lead] = len(labels)
            labels.append(f"rigid body {lead} (part {lead})" if lead == pid else
                          f"rigid body {lead}")
            part = model.parts[lead]
            where.append((part.source.file, part.source.line, "PART"))
        k = body_of_lead[lead]
        if pid != lead:
            labels[k] = f"rigid body {lead} (parts {lead} + merged)"
        part = model.parts[pid]
        claim(k, part_nodes(model, pid), part.source, "PART")
    for ex in model.extra_nodes:
        claim(body_of_lead[leads[ex.pid]], ex.nodes, ex.source, ex.keyword)
    for nrb in model.nodal_rigid_bodies:
        k = len(labels)
        labels.append(f"nodal rigid body {nrb.pid}")
        where.append((nrb.source.file, nrb.source.line, nrb.keyword))
        claim(k, nrb.nodes, nrb.source, nrb.keyword)
    return owner, labels, where


def _no_nodal_constraints(b, model: Model, owner: np.ndarray,  # noqa: ANN001
                          labels: list[str]) -> None:
    """A nodal prescribed motion on a node of a rigid body is a DeckError (SPCs on them
    hold the body instead: :func:`hollowbody.model.rigid_bodies.rigid_body_defs`)."""
    if not labels:
        return

    def check(item: KeywordItem, nodes: np.ndarray) -> None:
        nodes = np.asarray(nodes, dtype=np.int64).reshape(-1)
        on = np.flatnonzero(owner[nodes] >= 0)
        if on.size:
            i = int(nodes[on[0]])
            raise item_error(item, f"a prescribed motion on node {int(model.node_ids[i])}, "
                             f"which is on {labels[int(owner[i])]}: the body moves its nodes "
                             f"and would ignore it; {_HOLD}")

    for it in b.of(PrescribedMotionNode):
        check(it, b.index([it.nid])[0])
    for it in b.of(PrescribedMotionSet):
        if it.nsid in model.node_sets:
            check(it, model.node_sets[it.nsid])
