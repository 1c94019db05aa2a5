"""The tie set: every tied slave node of a run, and the kernels of one cycle.

Built by :func:`hollowbody.contact.tied.build.build_ties`; the solver calls
:meth:`TieSet.transfer_mass` once, :meth:`TieSet.start` at t = 0, then every
cycle :meth:`TieSet.distribute` (after the forces) and :meth:`TieSet.follow`
(after the positions are updated). See :mod:`hollowbody.contact.tied`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numba import njit

from hollowbody.contact.tied.frame import tie_frame


@dataclass
class TieSet:
    """Every tied slave node of a model (all tied contacts together).

    node: (k,) int64 slave node indices; seg: (k, 4) int64 master node indices
    (triangles N4 == N3); w: (k, 4) shape-function weights N_j; uv: (k, 2)
    natural coordinates; off: (k, 3) mm offset in the segment frame (e1, e2,
    n), zero for projected nodes; rot: (k,) bool rotations coupled (set by
    :meth:`transfer_mass`); cid: (k,) int64 contact id of each slave.
    node_x0: (n, 3) float64 mm initial coordinates of every node with the slaves
    tied without an offset moved onto their segments (a copy of the model's
    when nothing moves): the reference configuration of the run. ``messages``:
    (level, text) to log at the start of a run.

    Nothing of a TieSet changes in time: the kernels read the tie arrays and
    write x, v, w, f and the moments only; the old segment frame R^n of the
    offset velocity is rebuilt every cycle from x^{n+1} - dt v^{n+1/2}.
    """

    #: time-varying attributes (none, see above)
    STATE_FIELDS: ClassVar[tuple[str, ...]] = ()

    node: np.ndarray
    seg: np.ndarray
    w: np.ndarray
    uv: np.ndarray
    off: np.ndarray
    cid: np.ndarray
    shell_edge: np.ndarray  # (k,) bool, SHELL_EDGE_TO_SURFACE
    node_x0: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
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
        inertias (n,) kg mm^2 to the master nodes, in place (see :mod:`hollowbody.contact.tied`)."""
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
        if not tie_frame(xs, uv[k, 0], uv[k, 1], tri, g, e_new):
            continue
        for c in range(3):
            x[s, c] += off[k, 0] * e_new[0, c] + off[k, 1] * e_new[1, c] + \
                off[k, 2] * e_new[2, c]
        if dt <= 0.0:
            continue
        for a in range(4):
            for c in range(3):
                xs[a, c] = x[seg[k, a], c] - dt * v[seg[k, a], c]
        if not tie_frame(xs, uv[k, 0], uv[k, 1], tri, g, e_old):
            continue
        for c in range(3):
            dn = off[k, 0] * e_new[0, c] + off[k, 1] * e_new[1, c] + off[k, 2] * e_new[2, c]
            do = off[k, 0] * e_old[0, c] + off[k, 1] * e_old[1, c] + off[k, 2] * e_old[2, c]
            v[s, c] += (dn - do) / dt
