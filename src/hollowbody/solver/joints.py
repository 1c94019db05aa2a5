"""Joints between rigid bodies and joint stiffnesses as one force term of the cycle
(:mod:`hollowbody.solver.terms`; docs/joints.md).

Formulation: penalty, as LS-DYNA. Every joint is a set of node pairs (one node on
body A, one on body B) held together by a spring with a dashpot, in all directions
or across the joint's axis only (cylindrical, translational), plus, for the
universal joint, a penalty on the perpendicularity of its two arms. The forces go
to the joint nodes, which the rigid bodies gather into their resultant force and
moment. The stiffness of a pair is set once, at the run's first step dt1:

    k = RPS * KAPPA / (dt1^2 * w),   w = n_A lam_A + n_B lam_B

lam_X is the largest eigenvalue of body X's inverse mass matrix at the node
(1/M + r x I^-1 x r, 0 for a body whose 6 DOFs are fixed or prescribed) and n_X
the number of penalty pairs on body X, so that k dt^2 w = KAPPA * RPS well below
the central-difference limit 4 (KAPPA = 0.25: k dt^2 w = 0.25). The dashpot is
DAMP * ZETA0 of the pair's critical damping 2 sqrt(k m), m = 1 / (lam_A + lam_B).
The term reports the step its springs allow (2/omega (sqrt(1 + zeta^2) - zeta)).

Joint stiffness moments (GENERALIZED, FLEXION-TORSION) act on the bodies PIDA and
PIDB through the nodal moments of one node of each; their stable step comes from
the curves' largest slopes, the stop / friction stiffness and the bodies' inertia.
"""

from __future__ import annotations

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.model.joints import JOINT_PAIRS, axes_from_points
from hollowbody.solver.joint_kernels import (
    FLEXION_TORSION,
    GENERALIZED,
    pair_forces,
    stiffness_moments,
    universal_forces,
)

#: k dt1^2 w of a pair at RPS = 1 (central-difference limit: 4).
KAPPA = 0.25
#: Fraction of a pair's critical damping at DAMP = 1.
ZETA0 = 0.1


def joint_terms(model, plan) -> list:  # noqa: ANN001 - Model, Assembly
    """The joint term of ``model`` (none without joints or joint stiffnesses)."""
    if not model.joints and not model.joint_stiffness:
        return []
    return [JointTerm(model, plan)]


def _error(rec, message: str) -> DeckError:  # noqa: ANN001 - Joint / JointStiffness
    return DeckError(message, rec.source.file, rec.source.line, rec.keyword)


def _fixed(body) -> bool:  # noqa: ANN001 - RigidBody
    """All 6 DOFs of the body fixed or prescribed (it does not yield to a joint)."""
    t = np.asarray(body.fixed_trans) | np.asarray(getattr(body, "prescribed_trans", False))
    r = np.asarray(body.fixed_rot) | np.asarray(getattr(body, "prescribed_rot", False))
    return bool(np.all(t) and np.all(r))


def _inv_inertia(body) -> np.ndarray:  # noqa: ANN001
    inertia = np.asarray(body.inertia(), float)
    return np.linalg.pinv(inertia) if np.linalg.det(inertia) <= 0.0 else np.linalg.inv(inertia)


def _lam(body, point: np.ndarray) -> float:  # noqa: ANN001
    """1/kg: largest eigenvalue of the body's inverse mass matrix at ``point`` (mm)."""
    if _fixed(body):
        return 0.0
    r = point - np.asarray(body.xc, float)
    rx = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    w = np.eye(3) / body.mass + rx.T @ _inv_inertia(body) @ rx
    return float(np.linalg.eigvalsh(0.5 * (w + w.T))[-1])


def _critical(k: np.ndarray, c: np.ndarray, inv_m: np.ndarray) -> float:
    """ms: smallest stable step of springs k with dashpots c on masses 1/inv_m."""
    ok = (inv_m > 0.0) & ((k > 0.0) | (c > 0.0))
    if not ok.any():
        return np.inf
    k, c, w = k[ok], c[ok], inv_m[ok]
    omega = np.sqrt(k * w)
    with np.errstate(divide="ignore", invalid="ignore"):
        zeta = np.where(omega > 0.0, 0.5 * c * w / np.where(omega > 0, omega, 1.0), np.inf)
        dt = np.where(omega > 0.0, 2.0 / np.where(omega > 0, omega, 1.0)
                      * (np.sqrt(1.0 + zeta ** 2) - zeta), 2.0 / (c * w))
    return float(dt.min())


class JointTerm:
    """All joints and joint stiffnesses of a model (see the module docstring)."""

    STATE_FIELDS = ("k", "c", "g_prev", "f_prev", "f_out", "uk", "uc", "s_prev", "l_prev",
                    "um_out", "qp", "q_prev", "m_prev", "q_out", "m_out", "mb_out",
                    "frozen", "dt_pairs", "internal_energy")

    def __init__(self, model, plan) -> None:  # noqa: ANN001 - Model, Assembly
        self.joints = list(model.joints)
        self.stiffnesses = list(model.joint_stiffness)
        self.bodies = list(plan.bodies)
        x0 = np.asarray(plan.node_x0 if plan.node_x0.size else model.node_x0, float)
        self.node_ids = model.node_ids
        self.internal_energy = 0.0
        self.frozen = False
        self.dt_pairs = np.inf
        self._joints_setup(model, x0)
        self._stiffness_setup(model, x0)

    # -- set-up ------------------------------------------------------------------
    def _body_map(self, n: int) -> np.ndarray:
        body_of = np.full(n, -1, dtype=np.int64)
        for k, b in enumerate(self.bodies):
            body_of[np.asarray(b.nodes, dtype=np.int64)] = k
        return body_of

    def _joints_setup(self, model, x0: np.ndarray) -> None:  # noqa: ANN001
        body_of = self._body_map(model.n_nodes)
        pa, pb, ax0, ax1, pj, lam_a, lam_b, body_a, body_b = ([] for _ in range(9))
        uni = []
        self.joint_bodies = []
        for j, jt in enumerate(self.joints):
            nodes = np.asarray(jt.nodes, dtype=np.int64)
            bodies = body_of[nodes]
            for k, (node, b) in enumerate(zip(nodes, bodies)):
                if b < 0:
                    raise _error(jt, f"{jt.kind} joint {jt.jid}: node {self.node_ids[node]} "
                                 f"(N{k + 1}) is not on a rigid body; joints connect rigid "
                                 "bodies")
            ba, bb = int(bodies[0]), int(bodies[1])
            for k, b in enumerate(bodies):
                want = ba if k % 2 == 0 else bb
                if b != want:
                    raise _error(jt, f"{jt.kind} joint {jt.jid}: N{k + 1} (node "
                                 f"{self.node_ids[nodes[k]]}) is on rigid part "
                                 f"{self.bodies[b].pid}, not on the body of "
                                 f"N{1 if k % 2 == 0 else 2} (part {self.bodies[want].pid})")
            if ba == bb:
                raise _error(jt, f"{jt.kind} joint {jt.jid}: nodes {self.node_ids[nodes[0]]} "
                             f"and {self.node_ids[nodes[1]]} are both on rigid part "
                             f"{self.bodies[ba].pid}; a joint connects two different bodies")
            self.joint_bodies.append((ba, bb))
            for a, c, full in JOINT_PAIRS[jt.kind]:
                pa.append(nodes[a])
                pb.append(nodes[c])
                ax0.append(-1 if full else nodes[0])
                ax1.append(-1 if full else nodes[2])
                pj.append(j)
                lam_a.append(_lam(self.bodies[ba], x0[nodes[a]]))
                lam_b.append(_lam(self.bodies[bb], x0[nodes[c]]))
                body_a.append(ba)
                body_b.append(bb)
            if jt.kind == "UNIVERSAL":
                uni.append((j, nodes[0], nodes[2], nodes[1], nodes[3],
                            _lam(self.bodies[ba], x0[nodes[2]]),
                            _lam(self.bodies[bb], x0[nodes[3]]), ba, bb))
        i64 = np.int64
        self.pa, self.pb = np.array(pa, i64), np.array(pb, i64)
        self.ax0, self.ax1 = np.array(ax0, i64), np.array(ax1, i64)
        self.pair_joint = np.array(pj, i64)
        self.uj = np.array([u[0] for u in uni], i64)
        self.u1, self.u3 = np.array([u[1] for u in uni], i64), np.array([u[2] for u in uni], i64)
        self.u2, self.u4 = np.array([u[3] for u in uni], i64), np.array([u[4] for u in uni], i64)
        # penalty rows per body: pairs and universal constraints
        count = np.zeros(len(self.bodies))
        for b in (*body_a, *body_b, *(u[7] for u in uni), *(u[8] for u in uni)):
            count[b] += 1.0
        la, lb = np.array(lam_a), np.array(lam_b)
        ua, ub = np.array([u[5] for u in uni]), np.array([u[6] for u in uni])
        ba_, bb_ = np.array(body_a, i64), np.array(body_b, i64)
        uba, ubb = np.array([u[7] for u in uni], i64), np.array([u[8] for u in uni], i64)
        #: 1/kg: the bound w of each pair / universal row, and 1/m of its own two bodies
        self.w_pair = count[ba_] * la + count[bb_] * lb if la.size else np.zeros(0)
        self.inv_m_pair = la + lb
        self.w_uni = count[uba] * ua + count[ubb] * ub if ua.size else np.zeros(0)
        self.inv_m_uni = ua + ub
        self.rps_pair = np.array([self.joints[j].rps for j in pj])
        self.damp_pair = np.array([self.joints[j].damp for j in pj])
        self.rps_uni = np.array([self.joints[j].rps for j in self.uj])
        self.damp_uni = np.array([self.joints[j].damp for j in self.uj])
        p, u = self.pa.size, self.uj.size
        self.k, self.c = np.zeros(p), np.zeros(p)
        self.g_prev = x0[self.pb] - x0[self.pa] if p else np.zeros((0, 3))
        self.f_prev, self.f_out = np.zeros((p, 3)), np.zeros((p, 3))
        self.uk, self.uc = np.zeros(u), np.zeros(u)
        self.s_prev, self.l_prev, self.um_out = np.zeros(u), np.zeros(u), np.zeros((u, 3))
        if u:
            q = x0[self.u4] - x0[self.u2]
            self.s_prev = np.einsum("ij,ij->i", x0[self.u3] - x0[self.u1],
                                    q / np.linalg.norm(q, axis=1)[:, None])

    def _stiffness_setup(self, model, x0: np.ndarray) -> None:  # noqa: ANN001
        by_pid = {b.pid: k for k, b in enumerate(self.bodies)}
        self._refs: dict[int, np.ndarray] = {}
        curve_ids = sorted({int(v) for st in self.stiffnesses
                            for v in (*st.lc, *st.dlc, st.lc_gamma) if v})
        index = {lcid: i for i, lcid in enumerate(curve_ids)}
        xs = [np.asarray(model.curves[c].x, float) for c in curve_ids]
        ys = [np.asarray(model.curves[c].y, float) for c in curve_ids]
        self.cx = np.concatenate(xs) if xs else np.zeros(1)
        self.cy = np.concatenate(ys) if ys else np.zeros(1)
        self.cstart = np.concatenate([[0], np.cumsum([len(v) for v in xs])]).astype(np.int64)
        s = len(self.stiffnesses)
        self.kind = np.zeros(s, np.int64)
        self.sna, self.snb = np.zeros(s, np.int64), np.zeros(s, np.int64)
        self.fa_nodes, self.fb_nodes = np.zeros((s, 3), np.int64), np.zeros((s, 3), np.int64)
        self.fa_axis, self.fb_axis = np.zeros(s, np.int64), np.zeros(s, np.int64)
        self.fa_c, self.fb_c = np.zeros((s, 3, 3)), np.zeros((s, 3, 3))
        self.lc = np.full((s, 3), -1, np.int64)
        self.dlc = np.full((s, 3), -1, np.int64)
        self.lcg = np.full(s, -1, np.int64)
        self.es, self.fm = np.zeros((s, 3)), np.zeros((s, 3))
        self.neg, self.pos = np.full((s, 3), np.nan), np.full((s, 3), np.nan)
        dts = [np.inf]
        for i, st in enumerate(self.stiffnesses):
            for name, pid in (("PIDA", st.pida), ("PIDB", st.pidb)):
                if pid not in by_pid:
                    raise _error(st, f"joint stiffness {st.jsid}: {name}={pid} is not a "
                                 "rigid body (a *MAT_RIGID part or a nodal rigid body)")
            ba, bb = by_pid[st.pida], by_pid[st.pidb]
            self.kind[i] = GENERALIZED if st.kind == "GENERALIZED" else FLEXION_TORSION
            self.sna[i] = int(np.asarray(self.bodies[ba].nodes)[0])
            self.snb[i] = int(np.asarray(self.bodies[bb].nodes)[0])
            csa = model.coordinate_systems[st.cida]
            csb = model.coordinate_systems[st.cidb]
            for cs, b, follow, nodes, axis, c in (
                    (csa, ba, csa.follow, self.fa_nodes, self.fa_axis, self.fa_c),
                    (csb, bb, csb.follow and st.cidb != st.cida, self.fb_nodes, self.fb_axis,
                     self.fb_c)):
                if follow and cs.nodes is not None:  # FLAG = 1: the system's own nodes
                    nodes[i], axis[i], c[i] = cs.nodes, cs.dir, np.eye(3)
                else:  # fixed in its body: its axes in the frame of three body nodes
                    ref = self._reference_nodes(b, x0, st)
                    nodes[i], axis[i] = ref, 0
                    c[i] = cs.axes @ axes_from_points(*x0[ref], 0).T
            for j in range(3):
                self.lc[i, j] = index[int(st.lc[j])] if st.lc[j] else -1
                self.dlc[i, j] = index[int(st.dlc[j])] if st.dlc[j] else -1
            self.lcg[i] = index[st.lc_gamma] if st.lc_gamma else -1
            self.es[i], self.fm[i] = st.es, st.fm
            self.neg[i], self.pos[i] = st.neg_stop, st.pos_stop
            dts.append(self._stiffness_step(model, st, ba, bb))
        self.dt_stiff = float(min(dts))
        self.qp, self.q_prev, self.m_prev = np.zeros((s, 3)), np.zeros((s, 3)), np.zeros((s, 3))
        self.q_out, self.m_out, self.mb_out = np.zeros((s, 3)), np.zeros((s, 3)), np.zeros((s, 3))
        if s:  # the angles at t = 0: the first step's increment starts there; friction
            # springs start unloaded
            self._stiffness(x0, np.zeros((model.n_nodes, 3)), 0.0)
            self.qp[:] = self.q_prev
            self.m_prev[:] = 0.0

    def _reference_nodes(self, b: int, x0: np.ndarray, st) -> np.ndarray:  # noqa: ANN001
        """Three nodes of body ``b`` spanning a well-shaped triangle (frames fixed in it)."""
        cached = self._refs.get(b)
        if cached is not None:
            return cached
        nodes = np.asarray(self.bodies[b].nodes, dtype=np.int64)
        p = x0[nodes]
        i0 = 0
        i1 = int(np.argmax(np.linalg.norm(p - p[i0], axis=1)))
        area = np.linalg.norm(np.cross(p[i1] - p[i0], p - p[i0]), axis=1)
        i2 = int(np.argmax(area))
        size = float(np.linalg.norm(p[i1] - p[i0]))
        if size <= 0.0 or area[i2] <= 1e-6 * size * size:
            raise _error(st, f"joint stiffness {st.jsid}: rigid part {self.bodies[b].pid} has "
                         "no three nodes off one line to carry its coordinate system")
        self._refs[b] = nodes[[i0, i1, i2]]
        return self._refs[b]

    def _stiffness(self, x: np.ndarray, mom: np.ndarray, dt: float) -> float:
        return stiffness_moments(
            x, mom, dt, self.kind, self.sna, self.snb, self.fa_nodes, self.fa_axis, self.fa_c,
            self.fb_nodes, self.fb_axis, self.fb_c, self.cx, self.cy, self.cstart, self.lc,
            self.dlc, self.lcg, self.es, self.fm, self.neg, self.pos, self.qp, self.q_prev,
            self.m_prev, self.q_out, self.m_out, self.mb_out)

    def _stiffness_step(self, model, st, ba: int, bb: int) -> float:  # noqa: ANN001
        """ms: stable step of one joint stiffness's rotational springs and dashpots."""
        inv_i = 0.0
        for b in (self.bodies[ba], self.bodies[bb]):
            if not _fixed(b):
                inv_i += float(np.linalg.eigvalsh(_inv_inertia(b))[-1])
        if inv_i <= 0.0:
            return np.inf

        def slope(lcid: int) -> float:
            if not lcid:
                return 0.0
            cv = model.curves[int(lcid)]
            if len(cv.x) < 2:
                return 0.0
            return float(np.max(np.abs(np.diff(cv.y) / np.diff(cv.x))))

        scale = 1.0
        if st.lc_gamma:
            scale = max(1.0, float(np.max(np.abs(model.curves[st.lc_gamma].y))))
        k = np.array([slope(st.lc[j]) * (scale if j == 0 else 1.0) + 2.0 * st.es[j]
                      for j in range(3)])
        c = np.array([slope(st.dlc[j]) for j in range(3)])
        return _critical(k, c, np.full(3, inv_i))

    # -- the cycle ---------------------------------------------------------------
    def _freeze(self, dt: float) -> None:
        """Pair stiffness and damping from the run's first step ``dt`` (ms)."""
        with np.errstate(divide="ignore"):
            for w, inv_m, rps, damp, k, c in (
                    (self.w_pair, self.inv_m_pair, self.rps_pair, self.damp_pair, self.k, self.c),
                    (self.w_uni, self.inv_m_uni, self.rps_uni, self.damp_uni, self.uk, self.uc)):
                ok = w > 0.0
                k[:] = np.where(ok, rps * KAPPA / (dt * dt * np.where(ok, w, 1.0)), 0.0)
                c[:] = np.where(inv_m > 0.0, damp * ZETA0 * 2.0
                                * np.sqrt(k / np.where(inv_m > 0.0, inv_m, 1.0)), 0.0)
        self.dt_pairs = min(_critical(self.k, self.c, self.w_pair),
                            _critical(self.uk, self.uc, self.w_uni))
        self.frozen = True

    def add_forces(self, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
        """Joint forces into ``state.f`` and stiffness moments into ``state.mom``."""
        if not self.frozen and dt > 0.0:
            self._freeze(dt)
        work = 0.0
        if self.pa.size:
            work += pair_forces(state.x, state.v, state.f, self.pa, self.pb, self.ax0,
                                self.ax1, self.k, self.c, self.g_prev, self.f_prev, self.f_out)
        if self.uj.size:
            work += universal_forces(state.x, state.v, state.f, self.u1, self.u3, self.u2,
                                     self.u4, self.uk, self.uc, self.s_prev, self.l_prev,
                                     self.um_out)
        if self.kind.size:
            work += self._stiffness(state.x, state.mom, dt)
        self.internal_energy += work
        return min(self.dt_pairs, self.dt_stiff), -1, -1

    # -- output ------------------------------------------------------------------
    def joint_resultants(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(J, 3) force (kN) and (J, 3) moment (kN*mm, about N2) the joints put on
        their body B, from the last cycle."""
        n = len(self.joints)
        force, moment = np.zeros((n, 3)), np.zeros((n, 3))
        if self.pa.size:
            np.add.at(force, self.pair_joint, self.f_out)
            ref = np.array([j.nodes[1] for j in self.joints], dtype=np.int64)
            arm = x[self.pb] - x[ref[self.pair_joint]]
            np.add.at(moment, self.pair_joint, np.cross(arm, self.f_out))
        if self.uj.size:
            np.add.at(moment, self.uj, self.um_out)
        return force, moment

    #: columns of jntforc.csv (:mod:`hollowbody.solver.outputs`)
    JNTFORC_COLUMNS = ("time [ms]", "joint", "jsid", "fx [kN]", "fy [kN]", "fz [kN]",
                       "f [kN]", "mx [kN*mm]", "my [kN*mm]", "mz [kN*mm]", "m [kN*mm]",
                       "angle1 [rad]", "angle2 [rad]", "angle3 [rad]", "moment1 [kN*mm]",
                       "moment2 [kN*mm]", "moment3 [kN*mm]")

    def jntforc_rows(self, t: float, x: np.ndarray) -> list[list[float]]:
        """Rows of jntforc.csv at time t (ms): one per joint (force and moment on body
        B; with the angles and generalized moments of the stiffness whose JID names
        it), then one per stiffness that names no joint (joint 0). Angles: phi,
        theta, psi (GENERALIZED) or alpha, gamma, beta (FLEXION-TORSION)."""
        force, moment = self.joint_resultants(x)
        by_jid = {st.jid: i for i, st in enumerate(self.stiffnesses) if st.jid}
        nan3 = [np.nan] * 3
        rows = []
        for j, jt in enumerate(self.joints):
            s = by_jid.get(jt.jid)
            extra = ([self.stiffnesses[s].jsid, *self.q_out[s], *self.m_out[s]]
                     if s is not None else [0, *nan3, *nan3])
            rows.append([t, jt.jid, extra[0], *force[j], float(np.linalg.norm(force[j])),
                         *moment[j], float(np.linalg.norm(moment[j])), *extra[1:]])
        jids = {jt.jid for jt in self.joints}
        for s, st in enumerate(self.stiffnesses):
            if st.jid not in jids:
                mb = self.mb_out[s]
                rows.append([t, 0, st.jsid, 0.0, 0.0, 0.0, 0.0, *mb,
                             float(np.linalg.norm(mb)), *self.q_out[s], *self.m_out[s]])
        return rows
