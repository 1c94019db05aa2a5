"""Load terms (see :mod:`hollowbody.solver.terms`): body loads, nodal loads, loads
on rigid bodies (docs/loads.md).

External work is accumulated with the trapezoidal force over the step times the
step's displacement: ``W += dt * (F^n + F^{n+1}) / 2 . v^{n+1/2}`` (``dt * v^{n+1/2}``
is exactly ``x^{n+1} - x^n`` in the central-difference scheme). For a constant
force this is ``F . (x^{n+1} - x^0)`` to round-off, which is what the kinetic
energy of a free fall or the strain energy of a loaded spring must balance.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hollowbody.errors import DeckError
from hollowbody.model.loads import BodyLoad, NodeLoad, RigidBodyLoad
from hollowbody.model.mass import part_nodes


def load_terms(model, plan) -> list:  # noqa: ANN001 - Model, Assembly
    """The load terms of ``model``: one per kind of load present."""
    body = [ld for ld in model.loads if isinstance(ld, BodyLoad)]
    node = [ld for ld in model.loads if isinstance(ld, NodeLoad)]
    rigid = [ld for ld in model.loads if isinstance(ld, RigidBodyLoad)]
    out: list = []
    if body:
        out.append(BodyLoadTerm(model, plan, body))
    if node:
        out.append(NodeLoadTerm(model, plan, node))
    if rigid:
        out.append(RigidBodyLoadTerm(model, plan, rigid))
    return out


class _Curves:
    """Distinct curves of a list of loads, evaluated once per cycle."""

    def __init__(self, model, lcids: list[int]) -> None:  # noqa: ANN001
        self.ids = sorted(set(lcids))
        self.curves = [model.curves[i] for i in self.ids]
        pos = {lc: k for k, lc in enumerate(self.ids)}
        self.index = np.array([pos[lc] for lc in lcids], dtype=np.int64)

    def values(self, t: float) -> np.ndarray:
        """Curve value of each load (in ``lcids`` order) at t ms."""
        return np.array([c(t) for c in self.curves])[self.index]


def _group_nodes(model, pid: int) -> np.ndarray:  # noqa: ANN001
    """Node indices of part ``pid`` (solids, shells, and the groups of other element
    families that carry ``pid`` and a connectivity; beams: their two end nodes)."""
    nodes = [part_nodes(model, pid)]
    for g in [*model.beam_groups, *model.discrete_groups]:
        if getattr(g, "pid", None) == pid and getattr(g, "conn", None) is not None:
            conn = np.asarray(g.conn)
            nodes.append(conn[:, :2].ravel() if conn.ndim == 2 else conn.ravel())
    return np.unique(np.concatenate(nodes)).astype(np.int64)


class BodyLoadTerm:
    """*LOAD_BODY_X/_Y/_Z (+ *LOAD_BODY_PARTS): body force -m a(t) on every
    deformable node (nodal mass of the State, which includes mass scaling: the
    acceleration of a free body is exactly -a) and -M a(t) on every rigid body at its
    centre of mass (``after_gather``; *PART_INERTIA masses are honoured).

    ``g`` (3,) mm/ms^2 is the body-force acceleration -a(t) of the last call.
    """

    STATE_FIELDS = ("g", "external_work")

    def __init__(self, model, plan, loads: list[BodyLoad]) -> None:  # noqa: ANN001
        self.loads = loads
        self.curves = _Curves(model, [ld.lcid for ld in loads])
        self.axis = np.array([ld.axis for ld in loads], dtype=np.int64)
        self.sf = np.array([ld.sf for ld in loads])
        pids = loads[0].pids
        if pids is None:
            self.nodes = np.flatnonzero(plan.deformable).astype(np.int64)
            self.bodies = list(plan.bodies)
        else:
            sel = [_group_nodes(model, p) for p in pids]
            nodes = np.unique(np.concatenate(sel)) if sel else np.zeros(0, np.int64)
            self.nodes = nodes[plan.deformable[nodes]].astype(np.int64)
            self.bodies = [bd for bd in plan.bodies if bd.pid in set(pids)]
        self.g = np.zeros(3)
        self.external_work = 0.0

    def acceleration(self, t: float) -> np.ndarray:
        """Body-force acceleration (3,) mm/ms^2 at t: minus the base acceleration."""
        g = np.zeros(3)
        np.add.at(g, self.axis, -self.sf * self.curves.values(t))
        return g

    def add_forces(self, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
        g = self.acceleration(state.t)
        mom = np.zeros(3)
        _body_force(self.nodes, state.node_mass, state.v, g, state.f, mom)
        if dt > 0.0:
            mom += sum(bd.mass * bd.vel for bd in self.bodies)
            self.external_work += dt * 0.5 * float((self.g + g) @ mom)
        self.g = g
        return np.inf, -1, -1

    def after_gather(self, state, bodies: list, dt: float) -> None:  # noqa: ANN001
        for bd in self.bodies:
            bd.force = bd.force + bd.mass * self.g


@njit(cache=True)
def _body_force(nodes, mass, v, g, f, mom):
    """f[n] += m_n g for the nodes (N,) int64; mom (3,) += sum m_n v_n (kg mm/ms).

    mass (n,) kg, v (n, 3) mm/ms, g (3,) mm/ms^2, f (n, 3) kN. One pass: the
    gravity of a body of 70,000 nodes cost 5 ms per cycle as numpy gathers and
    scatters."""
    for k in range(nodes.shape[0]):
        i = nodes[k]
        m = mass[i]
        for a in range(3):
            f[i, a] += m * g[a]
            mom[a] += m * v[i, a]


_AX = {1: 0, 2: 1, 3: 2, 5: 0, 6: 1, 7: 2}


class NodeLoadTerm:
    """*LOAD_NODE_POINT / _SET: nodal forces (kN) and moments (kN*mm) in global axes.

    One row per (node, dof) of every load; forces and moments on the nodes of a
    rigid body reach the body through its resultant (``RigidBody.gather``). A moment
    on a deformable node needs a rotational degree of freedom (a shell or beam
    node): DeckError otherwise. ``f_prev`` (r,) is the last value of each row.
    """

    STATE_FIELDS = ("f_prev", "external_work")

    def __init__(self, model, plan, loads: list[NodeLoad]) -> None:  # noqa: ANN001
        rows_node, rows_load = [], []
        for k, ld in enumerate(loads):
            rows_node.append(ld.nodes)
            rows_load.append(np.full(ld.nodes.size, k, dtype=np.int64))
            if ld.dof >= 5:
                nodes = ld.nodes
                rot = plan.node_rot_inertia[nodes] > 0.0 if plan.node_rot_inertia.size \
                    else np.zeros(nodes.size, bool)
                bad = nodes[~rot & plan.deformable[nodes]]
                if bad.size:
                    src = ld.source
                    raise DeckError(f"DOF={ld.dof}: node {int(model.node_ids[bad[0]])} has no "
                                    "rotational degree of freedom (no shell or beam on it, "
                                    "not on a rigid body): a moment cannot act on it",
                                    src.file, src.line, "LOAD_NODE")
        self.node = np.concatenate(rows_node).astype(np.int64)
        load = np.concatenate(rows_load)
        dof = np.array([ld.dof for ld in loads], dtype=np.int64)[load]
        self.comp = np.array([_AX[int(d)] for d in dof], dtype=np.int64)
        self.moment = dof >= 5
        self.curves = _Curves(model, [loads[int(k)].lcid for k in load])
        self.sf = np.array([ld.sf for ld in loads])[load]
        # rows on rigid-body nodes: their rotation is the body's
        body_of = np.full(model.n_nodes, -1, dtype=np.int64)
        for k, bd in enumerate(plan.bodies):
            body_of[bd.nodes] = k
        self.bodies = list(plan.bodies)
        self.rigid_moment = np.flatnonzero(self.moment & (body_of[self.node] >= 0))
        self.rigid_body = body_of[self.node[self.rigid_moment]]
        self.f_prev = np.zeros(self.node.size)
        self.external_work = 0.0

    def add_forces(self, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
        val = self.sf * self.curves.values(state.t)
        mom, force = self.moment, ~self.moment
        if dt > 0.0:
            vel = np.where(mom, state.w[self.node, self.comp], state.v[self.node, self.comp])
            for r, b in zip(self.rigid_moment, self.rigid_body):
                vel[r] = self.bodies[b].omega[self.comp[r]]
            self.external_work += dt * 0.5 * float(((self.f_prev + val) * vel).sum())
        np.add.at(state.f, (self.node[force], self.comp[force]), val[force])
        if mom.any():
            np.add.at(state.mom, (self.node[mom], self.comp[mom]), val[mom])
        self.f_prev = val
        return np.inf, -1, -1


class RigidBodyLoadTerm:
    """*LOAD_RIGID_BODY: force (kN) / moment (kN*mm, about the centre of mass) on the
    rigid body of a part, added to its resultant after the gather."""

    STATE_FIELDS = ("f_prev", "external_work")

    def __init__(self, model, plan, loads: list[RigidBodyLoad]) -> None:  # noqa: ANN001
        by_pid = {bd.pid: k for k, bd in enumerate(plan.bodies)}
        for ld in loads:
            if ld.pid not in by_pid:
                raise DeckError(f"part {ld.pid} has no nodes: no rigid body to load",
                                ld.source.file, ld.source.line, "LOAD_RIGID_BODY")
        self.bodies = list(plan.bodies)
        self.body = np.array([by_pid[ld.pid] for ld in loads], dtype=np.int64)
        self.comp = np.array([_AX[ld.dof] for ld in loads], dtype=np.int64)
        self.moment = np.array([ld.dof >= 5 for ld in loads])
        self.curves = _Curves(model, [ld.lcid for ld in loads])
        self.sf = np.array([ld.sf for ld in loads])
        self.f_prev = np.zeros(len(loads))
        self.external_work = 0.0

    def add_forces(self, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
        val = self.sf * self.curves.values(state.t)
        if dt > 0.0:
            vel = np.array([(self.bodies[b].omega if m else self.bodies[b].vel)[c]
                            for b, c, m in zip(self.body, self.comp, self.moment)])
            self.external_work += dt * 0.5 * float(((self.f_prev + val) * vel).sum())
        self.f_prev = val
        return np.inf, -1, -1

    def after_gather(self, state, bodies: list, dt: float) -> None:  # noqa: ANN001
        for k, (b, c) in enumerate(zip(self.body, self.comp)):
            bd = self.bodies[b]
            if self.moment[k]:
                bd.moment = bd.moment.copy()
                bd.moment[c] += self.f_prev[k]
            else:
                bd.force = bd.force.copy()
                bd.force[c] += self.f_prev[k]
