"""Stationary planar rigid walls, *RIGIDWALL_PLANAR (see :mod:`hollowbody.solver.terms`
and docs/loads.md).

Deformable slave nodes: a velocity constraint, LS-DYNA's default. After v^{n+1/2}
is known (``constrain``), a node whose predicted position x^n + dt v^{n+1/2} is
behind the wall gets the normal velocity that puts it on the wall at t^{n+1}; its
tangential velocity is reduced by at most FRIC times the normal change (Coulomb at
the velocity level: the tangential impulse is at most FRIC times the normal one),
or set to zero with FRIC = 1 (no sliding). The wall's force on the node is
m dv / dt_avg; its work, m dv . (v^{n-1/2} + v^{n+1/2}) / 2 (the force times the
node's mean displacement per step, as for prescribed motion), enters the
balance as ``contact_energy`` (what the wall dissipates: impacts on it are
perfectly plastic in the normal direction).

Nodes of rigid bodies are placed by their body, so a velocity constraint cannot
act on them: they get a penalty force (``add_forces``, before the bodies gather
their resultants). Per node: normal stiffness k = 0.1 RWKSF M / (N dt0^2) (M the
body's mass, N its slave nodes, dt0 the first step; all N nodes on the wall give
omega dt0 = 0.32, stable), a critical normal damping for the body's
translation on the nodes in contact, no adhesion; friction by a stored
tangential spring of the same stiffness and damping (elastic stick, then
Coulomb): per node in contact ``f_e <- f_e - k v_t dt``, trial ``f_e - c v_t``,
capped at FRIC F_n (the stored ``f_e`` then the capped trial; FRIC = 1: no cap,
no sliding); a node that leaves the wall forgets it. Without the stored part (a
friction that only stopped the tangential velocity of each step) a lightly
loaded foot crept under a small oscillating tangential load. The work of these
forces (trapezoidal) is also ``contact_energy`` (stored plus dissipated).
"""

from __future__ import annotations

import numpy as np

from hollowbody.model.loads import RigidWallDef
from hollowbody.solver.rigidwall_kernels import behind, moving_in

#: penalty stiffness as a fraction of the stability limit of a body on all its nodes
PENALTY_FRACTION = 0.1
#: normal damping of the penalty, fraction of critical for the body's translation
PENALTY_DAMPING = 1.0


def rigidwall_terms(model, plan) -> list:  # noqa: ANN001 - Model, Assembly
    """One :class:`RigidWallTerm` per *RIGIDWALL_PLANAR."""
    return [RigidWallTerm(model, plan, w) for w in model.rigid_walls]


class RigidWallTerm:
    """One stationary infinite planar wall (see the module docstring).

    ``force`` (3,) kN: the force of the wall on the model in the last cycle (for
    rwforc); ``contact_energy`` J: minus the work of the wall's forces.
    """

    STATE_FIELDS = ("contact_energy", "dt_prev", "f_prev", "ft", "k", "force",
                    "force_constraint")

    def __init__(self, model, plan, wall: RigidWallDef) -> None:  # noqa: ANN001
        self.wall = wall
        self.rwid = wall.rwid
        self.n = np.asarray(wall.normal, dtype=float)
        self.tail = np.asarray(wall.tail, dtype=float)
        x0 = plan.node_x0 if plan.node_x0.shape == (model.n_nodes, 3) else model.node_x0
        nodes = np.asarray(wall.nodes, dtype=np.int64)
        # nodes that start behind the wall are not its slaves (they would be thrown out);
        # OFFSET > 0: only the nodes starting within that distance in front of it
        gap0 = (x0[nodes] - self.tail) @ self.n
        keep = gap0 >= -1e-9
        if wall.offset > 0.0:
            keep &= gap0 <= wall.offset
        nodes = nodes[keep]
        self.excluded = int(wall.nodes.size - nodes.size)
        self.nodes = nodes[plan.deformable[nodes]]
        self.bodies = []
        rigid_rows = []
        for bd in plan.bodies:
            on = np.intersect1d(bd.nodes, nodes)
            if on.size:
                self.bodies.append(bd)
                rigid_rows.append(on)
        self.rigid_nodes = [r.astype(np.int64) for r in rigid_rows]
        self.f_prev = [np.zeros((r.size, 3)) for r in rigid_rows]
        #: (c, 3) kN per body: the stored (elastic) tangential friction force per node
        self.ft = [np.zeros((r.size, 3)) for r in rigid_rows]
        self.k = np.full(len(self.bodies), np.nan)
        self.contact_energy = 0.0
        self.dt_prev = 0.0
        self.force = np.zeros(3)
        self.force_constraint = np.zeros(3)

    def active(self, t: float) -> bool:
        return self.wall.birth <= t <= self.wall.death

    # -- deformable nodes: velocity constraint --------------------------------------
    def _scratch(self) -> tuple[np.ndarray, np.ndarray]:
        """Work rows (k,) int64 and gaps (k,) mm for the kernels (made once)."""
        if getattr(self, "_rows", None) is None or self._rows.size != self.nodes.size:
            self._rows = np.empty(self.nodes.size, dtype=np.int64)
            self._gaps = np.empty(self.nodes.size)
        return self._rows, self._gaps

    def constrain(self, state, dt: float) -> None:  # noqa: ANN001
        """Stop the deformable slave nodes that would pass the wall during this step."""
        self.force_constraint = np.zeros(3)
        if not self.active(state.t) or dt <= 0.0 or self.nodes.size == 0:
            return
        nodes = self.nodes
        rows, gaps = self._scratch()
        m = behind(state.x, state.v, nodes, self.tail, self.n, dt, rows, gaps)
        if m == 0:
            return
        i = nodes[rows[:m]]
        v_free = state.v[i]
        dvn = -gaps[:m] / dt  # > 0: normal velocity change that lands the node on the wall
        vn = v_free @ self.n
        vt = v_free - vn[:, None] * self.n
        fric = self.wall.fric
        if fric >= 1.0:
            vt_new = np.zeros_like(vt)
        elif fric > 0.0:
            speed = np.sqrt((vt * vt).sum(axis=1))
            cut = np.minimum(speed, fric * dvn)
            scale = np.where(speed > 0.0, 1.0 - cut / np.where(speed > 0.0, speed, 1.0), 1.0)
            vt_new = vt * scale[:, None]
        else:
            vt_new = vt
        v_new = v_free + dvn[:, None] * self.n + (vt_new - vt)
        state.v[i] = v_new
        dt_avg = 0.5 * dt if state.cycle == 0 else 0.5 * (self.dt_prev + dt)
        m = state.node_mass[i]
        dv = v_new - v_free
        v_old = v_free - dt_avg * state.f[i] * state.inv_m[i, None]
        self.contact_energy -= float((m[:, None] * dv * 0.5 * (v_old + v_new)).sum())
        self.force_constraint = (m[:, None] * dv).sum(axis=0) / dt_avg

    def full_step_velocity(self, state, v: np.ndarray) -> None:  # noqa: ANN001
        """Full-step velocity estimates ``v`` (n, 3) of the energies: a deformable slave
        node on the wall (gap <= 1e-9 mm) does not move into it (the constraint of the
        next step stops it), as an SPC'd degree of freedom stays at zero."""
        if not self.active(state.t) or self.nodes.size == 0:
            return
        nodes = self.nodes
        rows, _ = self._scratch()
        m = moving_in(state.x, v, nodes, self.tail, self.n, 1e-9, rows)
        if m == 0:
            return
        i = nodes[rows[:m]]
        dvn = -(v[i] @ self.n)
        vi = v[i] + dvn[:, None] * self.n
        fric = self.wall.fric
        if fric > 0.0:
            vt = vi - (vi @ self.n)[:, None] * self.n
            speed = np.sqrt((vt * vt).sum(axis=1))
            cut = speed if fric >= 1.0 else np.minimum(speed, fric * dvn)
            scale = np.where(speed > 0.0, cut / np.where(speed > 0.0, speed, 1.0), 0.0)
            vi = vi - vt * scale[:, None]
        v[i] = vi

    # -- rigid-body nodes: penalty ---------------------------------------------------
    def add_forces(self, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
        if dt > 0.0:
            self.dt_prev = dt
        total = self.force_constraint.copy()
        on = self.active(state.t)
        for b, (bd, nodes) in enumerate(zip(self.bodies, self.rigid_nodes)):
            if np.isnan(self.k[b]) and dt > 0.0:
                self.k[b] = PENALTY_FRACTION * self.wall.rwksf * bd.mass / (nodes.size * dt * dt)
            v = state.v[nodes]
            f_new = np.zeros((nodes.size, 3))
            ft = self.ft[b]
            hit = np.zeros(nodes.size, dtype=bool)
            if on and not np.isnan(self.k[b]):
                gap = (state.x[nodes] - self.tail) @ self.n
                hit = gap < 0.0
                if hit.any():
                    f_new[hit], ft[hit] = self._penalty(bd, self.k[b], gap[hit], v[hit], dt,
                                                        ft[hit])
            ft[~hit] = 0.0  # off the wall (or the wall not active): the stick is forgotten
            if dt > 0.0:
                self.contact_energy -= dt * 0.5 * float(((self.f_prev[b] + f_new) * v).sum())
            self.f_prev[b] = f_new
            state.f[nodes] += f_new
            total += f_new.sum(axis=0)
        self.force = total
        return np.inf, -1, -1

    def _penalty(self, bd, k: float, gap: np.ndarray, v: np.ndarray,  # noqa: ANN001
                 dt: float, ft: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Penalty forces (c, 3) kN on the body's nodes in contact (gap < 0 mm) and
        their new stored tangential forces (c, 3) kN from the old ones ``ft``."""
        m_share = bd.mass / gap.size
        vn = v @ self.n
        c = 2.0 * PENALTY_DAMPING * np.sqrt(k * m_share)
        fn = np.maximum(k * (-gap) - c * vn, 0.0)
        f = fn[:, None] * self.n
        fric = self.wall.fric
        if fric <= 0.0 or dt <= 0.0:
            return f, np.zeros_like(ft)
        vt = v - vn[:, None] * self.n
        fe = ft - (ft @ self.n)[:, None] * self.n - k * dt * vt
        trial = fe - c * vt
        if fric < 1.0:
            mag = np.sqrt((trial * trial).sum(axis=1))
            slip = mag > fric * fn
            if slip.any():
                trial[slip] *= (fric * fn[slip] / mag[slip])[:, None]
                fe[slip] = trial[slip]
        return f + trial, fe

    def normal_force(self) -> float:
        """kN: the wall's normal force on the model in the last cycle (pushing > 0)."""
        return float(self.force @ self.n)

    def tangential_force(self) -> float:
        """kN: magnitude of the wall's tangential force on the model in the last cycle."""
        ft = self.force - (self.force @ self.n) * self.n
        return float(np.sqrt(ft @ ft))
