"""Set-up of tied contacts: which slave node is tied to which point of which segment.

:func:`build_ties` turns the model's ``tied_contacts`` into one
:class:`~hollowbody.contact.tied.tieset.TieSet` (rules in
:mod:`hollowbody.contact.tied`). The model is not changed: the coordinates
with the slaves moved onto the master surface are the tie set's ``node_x0``.
"""

from __future__ import annotations

import numpy as np

from hollowbody.contact.geometry import shape_weights
from hollowbody.contact.surface import SEG_SHELL, build_surface, model_surface
from hollowbody.contact.tied.search import closest_segments, local_offsets
from hollowbody.contact.tied.tieset import TieSet
from hollowbody.errors import DeckError
from hollowbody.model.mass import part_nodes
from hollowbody.model.model import Model, TiedContactDef

#: tol = max(THICK_FACTOR (t_s + t_m), SIZE_FACTOR d_min), see hollowbody.contact.tied.
THICK_FACTOR = 0.6
SIZE_FACTOR = 0.05
#: slave ids listed in a message
_LIST = 10



def _err(tie: TiedContactDef, message: str) -> DeckError:
    kw = "CONTACT_TIED_" + tie.kind.upper()
    return DeckError(f"tied contact {tie.cid}: {message}", tie.source.file, tie.source.line,
                     kw)


def _ids(model: Model, idx: np.ndarray) -> str:
    ids = model.node_ids[np.asarray(idx[:_LIST], dtype=np.int64)].tolist()
    return ", ".join(str(i) for i in ids) + (", ..." if idx.size > _LIST else "")


def _slave_nodes(tie: TiedContactDef, model: Model) -> np.ndarray:
    ref = tie.slave
    if ref.kind == "nodes":
        return np.unique(np.asarray(ref.nodes, dtype=np.int64))
    if ref.kind == "segments":
        return np.unique(np.asarray(ref.segments, dtype=np.int64))
    nodes = [part_nodes(model, pid) for pid in ref.pids]
    return np.unique(np.concatenate(nodes)) if nodes else np.zeros(0, np.int64)


def _constrained_nodes(model: Model) -> tuple[np.ndarray, np.ndarray]:
    """(n,) bool rigid-body nodes and (n,) bool nodes with an SPC on a translation or a
    prescribed motion."""
    n = model.n_nodes
    rigid = np.zeros(n, bool)
    for pid in model.rigid_pids():
        rigid[part_nodes(model, pid)] = True
    fixed = np.zeros(n, bool)
    for spc in model.spcs:
        fixed[np.asarray(spc.nodes)[np.asarray(spc.dofs, bool)[:, :3].any(axis=1)]] = True
    for pm in model.prescribed:
        if pm.target == "nodes" and pm.nodes is not None:
            fixed[np.asarray(pm.nodes)] = True
    return rigid, fixed


def _node_thickness(model: Model, nodes: np.ndarray) -> np.ndarray:
    """Largest shell thickness (mm) through each node, 0 for nodes on no shell."""
    t = np.zeros(model.n_nodes)
    for g in model.shell_groups:
        np.maximum.at(t, g.conn.ravel(), g.thickness.ravel())
    return t[nodes]


def _segment_size(seg: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Shorter diagonal of quadrilaterals, shortest edge of triangles, (s,) mm."""
    xs = x[seg]
    d = np.minimum(np.linalg.norm(xs[:, 2] - xs[:, 0], axis=1),
                   np.linalg.norm(xs[:, 3] - xs[:, 1], axis=1))
    tri = seg[:, 3] == seg[:, 2]
    e = np.stack([np.linalg.norm(xs[:, (a + 1) % 3] - xs[:, a], axis=1) for a in range(3)])
    d[tri] = e.min(axis=0)[tri]
    return d


class _Builder:
    """Collects the ties of a model one contact at a time (see :func:`build_ties`)."""

    def __init__(self, model: Model) -> None:
        self.model = model
        #: (n, 3) mm initial coordinates with the projected slaves moved (the result)
        self.x = model.node_x0.copy()
        self.rigid, self.fixed = _constrained_nodes(model)
        self.tied_by = np.full(model.n_nodes, -1, np.int64)  # contact id tying a node
        self.master_of = np.full(model.n_nodes, -1, np.int64)  # a contact using it as master
        self._ms = None
        self.parts: list[tuple] = []
        self.messages: list[tuple[str, str]] = []
        self.project = not model.controls.tiedprj

    def surface(self, tie: TiedContactDef):  # noqa: ANN201 - contact Surface
        ref = tie.master
        if ref.kind in ("nodes", "segments") and self._ms is None:
            self._ms = model_surface(self.model, 0.0)
        return build_surface(ref, self.model, tie.mst if tie.mst > 0.0 else 0.0,
                             self._ms if ref.kind in ("nodes", "segments") else None)

    def add(self, tie: TiedContactDef) -> None:
        model, x = self.model, self.model.node_x0  # every tie searches the deck's geometry
        surf = self.surface(tie)
        seg = np.asarray(surf.seg, dtype=np.int64)
        if seg.shape[0] == 0:
            raise _err(tie, "the master side has no segments")
        nodes = _slave_nodes(tie, model)
        why: dict[str, np.ndarray] = {}
        on_master = np.isin(nodes, seg.ravel())
        why["are nodes of the master surface (joined by the mesh, not tied)"] = nodes[on_master]
        why["are rigid-body nodes (skipped)"] = nodes[~on_master & self.rigid[nodes]]
        why["have an SPC or a prescribed motion (skipped)"] = \
            nodes[~on_master & ~self.rigid[nodes] & self.fixed[nodes]]
        keep = ~on_master & ~self.rigid[nodes] & ~self.fixed[nodes]
        again = keep & (self.tied_by[nodes] >= 0)
        why["are already tied by an earlier tied contact (skipped)"] = nodes[again]
        nodes = nodes[keep & ~again]
        # tolerance per segment and slave node
        t_m = np.where(surf.seg_kind == SEG_SHELL, surf.seg_thick, 0.0) if tie.mst <= 0.0 else \
            np.full(seg.shape[0], tie.mst)
        t_m = t_m * tie.sfmt
        t_s = (_node_thickness(model, nodes) if tie.sst <= 0.0 else
               np.full(nodes.size, tie.sst)) * tie.sfst
        size = _segment_size(seg, x)
        fixed_tol = max(-min(tie.sst, 0.0), -min(tie.mst, 0.0))
        xs = x[seg]
        reach = np.linalg.norm(xs - xs.mean(axis=1, keepdims=True), axis=2).max()
        tol_max = fixed_tol if fixed_tol > 0.0 else float(
            max(THICK_FACTOR * (t_s.max(initial=0.0) + t_m.max(initial=0.0)),
                SIZE_FACTOR * size.max(initial=0.0)))
        best, uv, dist = closest_segments(x[nodes], seg, x, float(reach + tol_max) * 1.01)
        ok = best >= 0
        tol = np.zeros(nodes.size)
        if fixed_tol > 0.0:
            tol[:] = fixed_tol
        else:
            b = np.where(ok, best, 0)
            tol = np.maximum(THICK_FACTOR * (t_s + t_m[b]), SIZE_FACTOR * size[b])
        ok &= dist <= tol
        why["are farther from the master surface than the search tolerance (not tied)"] = \
            nodes[~ok]
        nodes, sg, uv, dist = nodes[ok], seg[best[ok]], uv[ok], dist[ok]
        wts = np.zeros((nodes.size, 4))
        tri = sg[:, 3] == sg[:, 2]
        for k in range(nodes.size):
            shape_weights(uv[k, 0], uv[k, 1], bool(tri[k]), wts[k])
        # chains: a slave of this tie used as a master node by another, or the reverse
        used = np.unique(sg[wts != 0.0])
        clash = nodes[self.master_of[nodes] >= 0]
        if clash.size:
            raise _err(tie, f"slave node {model.node_ids[clash[0]]} is a master node of tied "
                       f"contact {self.master_of[clash[0]]}: chained ties are not supported")
        clash = used[self.tied_by[used] >= 0]
        if clash.size:
            raise _err(tie, f"master node {model.node_ids[clash[0]]} is a slave of tied "
                       f"contact {self.tied_by[clash[0]]}: chained ties are not supported")
        self.tied_by[nodes] = tie.cid
        self.master_of[used] = tie.cid
        keep_offset = tie.offset or not self.project
        xq = np.einsum("ka,kac->kc", wts, x[sg])
        if keep_offset:
            off = local_offsets(x[nodes], sg, uv, x)
        else:
            off = np.zeros((nodes.size, 3))
            self.x[nodes] = xq
        self.parts.append((nodes, sg, wts, uv, off, np.full(nodes.size, tie.cid),
                           np.full(nodes.size, tie.kind == "shell_edge_to_surface")))
        gap = float(dist.max(initial=0.0))
        head = f"tied contact {tie.cid} ({tie.kind})"
        self.messages.append(("info", f"{head}: {nodes.size} slave nodes tied to "
                              f"{np.unique(best[ok]).size} segments; " +
                              (f"offsets kept (largest {gap:.4g} mm)" if keep_offset else
                               f"moved onto the surface by up to {gap:.4g} mm")))
        for text, idx in why.items():
            if idx.size:
                self.messages.append(("warning", f"{head}: {idx.size} slave node(s) {text}: "
                                      f"{_ids(model, idx)}"))

    def result(self) -> TieSet:
        if self.parts:
            cols = [np.concatenate(c) for c in zip(*self.parts)]
        else:
            cols = [np.zeros(0, np.int64), np.zeros((0, 4), np.int64), np.zeros((0, 4)),
                    np.zeros((0, 2)), np.zeros((0, 3)), np.zeros(0, np.int64),
                    np.zeros(0, bool)]
        node, seg, w, uv, off, cid, edge = cols
        return TieSet(node=node.astype(np.int64), seg=seg.astype(np.int64), w=w, uv=uv,
                      off=off, cid=cid.astype(np.int64), shell_edge=edge.astype(bool),
                      node_x0=self.x, messages=self.messages, rigid_node=self.rigid,
                      fixed_node=self.fixed)


def build_ties(model: Model) -> TieSet | None:
    """The tie set of ``model.tied_contacts`` (None when it has none).

    Slave nodes tied without an offset are moved onto their segment in the
    returned set's ``node_x0`` (n, 3) mm; the model is not changed. Raises
    DeckError (at the contact's card) for a master side without segments or
    chained ties.
    """
    if not model.tied_contacts:
        return None
    b = _Builder(model)
    for tie in model.tied_contacts:
        b.add(tie)
    return b.result()
