"""Tied contacts as kinematic constraints (*CONTACT_TIED_..._TO_SURFACE).

As LS-DYNA's constraint-based tied contacts: every slave node is bound to a
point of its closest master segment and follows it exactly; no penalty
spring, no time-step limit, linear momentum conserved.

**Set-up** (:func:`build_ties`, once, before masses and elements):

1. Slave nodes: the node set (SSTYP 4) or the nodes of the slave segments /
   parts; master segments: the segment set (matched to the model's shells and
   solid faces) or the shells and exterior solid faces of the parts.
2. Each slave node is projected onto its closest master segment (natural
   coordinates u, v, see :mod:`hollowbody.solver.tied_search`). It is tied
   when its distance ``d`` to that segment is within the search tolerance::

       tol = max(0.6 (t_s + t_m), 0.05 d_min)

   with ``t_s`` the slave node's shell thickness (SST when > 0) times SFST,
   ``t_m`` the segment's shell thickness (MST when > 0; 0 for solid faces)
   times SFMT, and ``d_min`` the segment's shorter diagonal (shortest edge of
   a triangle). A negative SST or MST sets the tolerance itself (the larger
   |value|). This is our rule, modelled on LS-DYNA's (thickness-based for
   shells, a fraction of the segment size for solids).
3. Without ``_OFFSET`` and with TIEDPRJ = 0 (*CONTROL_CONTACT, the default)
   the tied slave nodes are **moved onto the surface** (``model.node_x0`` is
   replaced by the projected coordinates), as LS-DYNA does; with ``_OFFSET``,
   ``_CONSTRAINED_OFFSET`` or TIEDPRJ = 1 they stay where they are and their
   offset, stored in the segment's frame (e1, e2, n), follows the segment.
4. Not tied, and listed once in the run's messages with a count: nodes
   farther than the tolerance; nodes of rigid bodies, with an SPC on a
   translation, or with a prescribed motion (a constraint would fight the
   tie); nodes that are nodes of the master surface (already joined by the
   mesh); nodes already tied by an earlier tie. A slave node that is a node of
   a segment another tie uses (a chain) is an error.

**Masses** (:meth:`TieSet.transfer_mass`): each slave's mass is added to
its segment's nodes with the shape-function weights N_j and the slave keeps
none (likewise rotational inertia where rotations are coupled). The
effective masses m'_j = m_j + sum_s N_j(s) m_s make the constraint
momentum-exact: the momentum sum_i m_i v_i of the true masses equals
sum_j m'_j v_j.

**Every cycle** (numba kernels over the tie arrays, nothing allocated):

- :meth:`TieSet.distribute` (after element and contact forces): f_j += N_j
  f_s, f_s = 0 (and the moments of rotation-coupled slaves);
- the masters' accelerations follow from f / m' as for every node;
- :meth:`TieSet.follow` (after the positions are updated and constraints
  imposed): x_s = sum N_j x_j + R d_loc, v_s = sum N_j v_j + (R^{n+1} -
  R^n) d_loc / dt (R: the segment frame, d_loc the stored offset; 0 when
  projected), and for rotation-coupled slaves w_s = sum N_j w_j.

**Rotations.** *CONTACT_TIED_SHELL_EDGE_TO_SURFACE couples the rotational
velocity of a slave that is a shell node (6 DOFs) to the interpolated
rotational velocity of its segment's nodes when these have rotational DOFs
(shell masters or rigid-body nodes): the shell edge is clamped to the
surface, as a shared node would be. On solid faces (no rotational DOFs) only
translations are tied and the shell edge is a hinge along the surface.
NODES_TO_SURFACE and SURFACE_TO_SURFACE tie translations only (the slave's
rotations, if any, stay free). SURFACE_TO_SURFACE ties the slave surface's
nodes to the master surface (one way, like NODES_TO_SURFACE).

**Limits.** With an offset, forces are distributed with the shape functions
only (the moment of the force about the offset arm is not passed on); exact
for projected nodes. A rigid master part with *PART_INERTIA keeps its given
mass (the slave mass moved to its nodes is lost).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from hollowbody.contact.surface import SEG_SHELL, build_surface, model_surface
from hollowbody.errors import DeckError
from hollowbody.model.mass import part_nodes
from hollowbody.model.model import Model, TiedContactDef
from hollowbody.solver.tied_search import (
    closest_segments,
    frame,
    local_offsets,
    shape_weights,
)

#: tol = max(THICK_FACTOR (t_s + t_m), SIZE_FACTOR d_min), see the module docstring.
THICK_FACTOR = 0.6
SIZE_FACTOR = 0.05
#: slave ids listed in a message
_LIST = 10


@dataclass
class TieSet:
    """Every tied slave node of a model (all tied contacts together).

    node: (k,) int64 slave node indices; seg: (k, 4) int64 master node indices
    (triangles N4 == N3); w: (k, 4) shape-function weights N_j; uv: (k, 2)
    natural coordinates; off: (k, 3) mm offset in the segment frame (e1, e2,
    n), zero for projected nodes; rot: (k,) bool rotations coupled (set by
    :meth:`transfer_mass`); cid: (k,) int64 contact id of each slave.
    ``messages``: (level, text) to log at the start of a run.
    """

    node: np.ndarray
    seg: np.ndarray
    w: np.ndarray
    uv: np.ndarray
    off: np.ndarray
    cid: np.ndarray
    shell_edge: np.ndarray  # (k,) bool, SHELL_EDGE_TO_SURFACE
    rot: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    messages: list[tuple[str, str]] = field(default_factory=list)
    rigid_node: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))
    fixed_node: np.ndarray = field(default_factory=lambda: np.zeros(0, bool))

    def __post_init__(self) -> None:
        if self.rot.shape[0] != self.node.shape[0]:
            self.rot = np.zeros(self.node.shape[0], bool)
        self.has_offset = bool(np.any(self.off != 0.0))
        # work arrays of the follow kernel (segment corners, tangents, two frames)
        self._xs, self._g = np.zeros((4, 3)), np.zeros((2, 3))
        self._e_new, self._e_old = np.zeros((3, 3)), np.zeros((3, 3))

    @property
    def n_tied(self) -> int:
        return int(self.node.shape[0])

    # -- set-up ------------------------------------------------------------------
    def transfer_mass(self, node_mass: np.ndarray, rot_inertia: np.ndarray) -> None:
        """Move slave masses (n,) kg and, where rotations are coupled, rotational
        inertias (n,) kg mm^2 to the master nodes, in place (see module docstring)."""
        s, seg, w = self.node, self.seg, self.w
        if rot_inertia.shape[0] == node_mass.shape[0]:
            has_rot = (rot_inertia > 0.0) | self.rigid_node[: rot_inertia.shape[0]]
            self.rot = self.shell_edge & (rot_inertia[s] > 0.0) & \
                np.all(has_rot[seg] | (w == 0.0), axis=1)
        self.slave_mass = node_mass[s].copy()
        self.mass = node_mass
        node_mass[s] = 0.0
        np.add.at(node_mass, seg.ravel(), (w * self.slave_mass[:, None]).ravel())
        self.slave_inertia = np.where(self.rot, rot_inertia[s] if rot_inertia.size else 0.0,
                                      0.0)
        self.inertia = rot_inertia
        if self.rot.any():
            r = self.rot
            rot_inertia[s[r]] = 0.0
            np.add.at(rot_inertia, seg[r].ravel(), (w[r] * self.slave_inertia[r, None]).ravel())
        self.messages.append(("info", f"tied contacts: {self.n_tied} slave nodes, "
                              f"{int(self.rot.sum())} with rotations coupled"))

    def log(self, log: Callable[[str, str], None]) -> None:
        """Pass the set-up messages to ``log(level, text)`` (level 'info' / 'warning')."""
        for level, text in self.messages:
            log(level, text)

    def start(self, x: np.ndarray, v: np.ndarray, w: np.ndarray) -> None:
        """At t = 0: the slaves' initial momentum (and angular momentum of rotation-coupled
        slaves) passed to their master nodes, then the slaves placed on their segments.

        Master velocities become v_j + sum_s N_j m_s (v_s - sum_k N_k v_k) / m'_j (an
        inelastic joining that keeps the total momentum, and changes nothing when the
        slaves already move with their segments); rigid-body and constrained master
        nodes keep theirs. x (n, 3) mm, v (n, 3) mm/ms, w (n, 3) rad/ms.
        """
        if hasattr(self, "mass"):
            free = ~(self.rigid_node | self.fixed_node)
            _join(self.node, self.seg, self.w, self.slave_mass, self.mass, free, v,
                  np.ones(self.node.shape[0], np.bool_))
            if self.rot.any() and self.inertia.size:
                _join(self.node, self.seg, self.w, self.slave_inertia, self.inertia, free, w,
                      self.rot)
        self.follow(x, v, w, 0.0)

    # -- the cycle -------------------------------------------------------------------
    def distribute(self, f: np.ndarray, mom: np.ndarray) -> None:
        """Slave forces f (n, 3) kN (and moments mom (n, 3) kN mm of rotation-coupled
        slaves) added to their master nodes with the weights N_j; the slaves' set to 0."""
        _distribute(self.node, self.seg, self.w, self.rot, f, mom)

    def follow(self, x: np.ndarray, v: np.ndarray, w: np.ndarray, dt: float) -> None:
        """Place the slaves on their segments: x (n, 3) mm at t^{n+1}, v (n, 3) mm/ms
        at t^{n+1/2}, w (n, 3) rad/ms (rotation-coupled slaves); dt ms (0: set-up)."""
        _follow(self.node, self.seg, self.w, self.uv, self.off, self.rot, self.has_offset,
                x, v, w, dt, self._xs, self._g, self._e_new, self._e_old)


@njit(cache=True)
def _distribute(node, seg, wt, rot, f, mom):  # noqa: ANN001, ANN202 - numba kernel
    for k in range(node.shape[0]):
        s = node[k]
        for a in range(4):
            wa = wt[k, a]
            if wa == 0.0:
                continue
            j = seg[k, a]
            for c in range(3):
                f[j, c] += wa * f[s, c]
            if rot[k]:
                for c in range(3):
                    mom[j, c] += wa * mom[s, c]
        for c in range(3):
            f[s, c] = 0.0
            if rot[k]:
                mom[s, c] = 0.0


@njit(cache=True)
def _join(node, seg, wt, ms, mass, free, v, use):  # noqa: ANN001, ANN202 - numba kernel
    dv = np.zeros((mass.shape[0], 3))
    for k in range(node.shape[0]):
        if not use[k]:
            continue
        s = node[k]
        for c in range(3):
            excess = v[s, c]  # the slave's velocity beyond the segment's
            for a in range(4):
                excess -= wt[k, a] * v[seg[k, a], c]
            for a in range(4):
                j = seg[k, a]
                if wt[k, a] != 0.0 and free[j] and mass[j] > 0.0:
                    dv[j, c] += wt[k, a] * ms[k] * excess / mass[j]
    for j in range(mass.shape[0]):
        for c in range(3):
            v[j, c] += dv[j, c]


@njit(cache=True)
def _follow(node, seg, wt, uv, off, rot, has_offset, x, v, w, dt,  # noqa: ANN001, ANN202
            xs, g, e_new, e_old):
    for k in range(node.shape[0]):
        s = node[k]
        for c in range(3):
            xm = 0.0
            vm = 0.0
            wm = 0.0
            for a in range(4):
                j = seg[k, a]
                xm += wt[k, a] * x[j, c]
                vm += wt[k, a] * v[j, c]
                wm += wt[k, a] * w[j, c]
            x[s, c] = xm
            v[s, c] = vm
            if rot[k]:
                w[s, c] = wm
        if not has_offset or (off[k, 0] == 0.0 and off[k, 1] == 0.0 and off[k, 2] == 0.0):
            continue
        tri = seg[k, 3] == seg[k, 2]
        for a in range(4):
            for c in range(3):
                xs[a, c] = x[seg[k, a], c]
        if not frame(xs, uv[k, 0], uv[k, 1], tri, g, e_new):
            continue
        for c in range(3):
            x[s, c] += off[k, 0] * e_new[0, c] + off[k, 1] * e_new[1, c] + \
                off[k, 2] * e_new[2, c]
        if dt <= 0.0:
            continue
        for a in range(4):
            for c in range(3):
                xs[a, c] = x[seg[k, a], c] - dt * v[seg[k, a], c]
        if not frame(xs, uv[k, 0], uv[k, 1], tri, g, e_old):
            continue
        for c in range(3):
            dn = off[k, 0] * e_new[0, c] + off[k, 1] * e_new[1, c] + off[k, 2] * e_new[2, c]
            do = off[k, 0] * e_old[0, c] + off[k, 1] * e_old[1, c] + off[k, 2] * e_old[2, c]
            v[s, c] += (dn - do) / dt


# ---------------------------------------------------------------------------
# set-up


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
        model, x = self.model, self.model.node_x0
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
                      messages=self.messages, rigid_node=self.rigid,
                      fixed_node=self.fixed)


def build_ties(model: Model) -> TieSet | None:
    """The tie arrays of ``model.tied_contacts`` (None when it has none).

    Slave nodes tied without an offset are moved onto their segment:
    ``model.node_x0`` is replaced by a new array with the projected
    coordinates (the old array is not modified). Raises DeckError (at the
    contact's card) for a master side without segments or chained ties.
    """
    if not model.tied_contacts:
        return None
    b = _Builder(model)
    for tie in model.tied_contacts:
        b.add(tie)
    if not np.array_equal(b.x, model.node_x0):
        model.node_x0 = b.x
    return b.result()

