"""All rigid bodies of a run advanced together: one kernel per phase over every body.

A body model has 20-40 rigid bodies; advancing them one by one in Python costs
~110 us per body and cycle (benchmarks/bench_rigid.py). :class:`RigidBodySet`
stacks the bodies' arrays (``xc`` (b, 3) mm, ``rot`` (b, 3, 3), ``vel`` (b, 3)
mm/ms, ``omega`` (b, 3) rad/ms, ``force`` (b, 3) kN, ``moment`` (b, 3) kN*mm,
...) and makes each :class:`~hollowbody.solver.rigid.RigidBody`'s attributes
*views* of its row, so code that reads or writes ``body.vel[k]`` (prescribed
motion, loads on a body, joints) sees and changes the stacked values, and the
bodies stay the objects the State saves. An attribute rebound by other code
(``body.force = ...``) is taken over at the next phase (:meth:`adopt`).

The arithmetic is that of :class:`RigidBody`'s methods (same formulas, same
order of operations per body, sums in node order), so results equal the
one-body-at-a-time ones to round-off; the 3 x 3 solve is done by the adjugate
instead of LU.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: RigidBody attributes stored as rows of the set's arrays (name, trailing shape, dtype)
_VIEWS = (("xc", (3,), np.float64), ("rot", (3, 3), np.float64), ("rot_w", (3, 3), np.float64),
          ("vel", (3,), np.float64),
          ("omega", (3,), np.float64), ("force", (3,), np.float64),
          ("moment", (3,), np.float64), ("vel_free", (3,), np.float64),
          ("omega_free", (3,), np.float64), ("inertia0", (3, 3), np.float64),
          ("fixed_trans", (3,), np.bool_), ("fixed_rot", (3,), np.bool_),
          ("prescribed_trans", (3,), np.bool_), ("prescribed_rot", (3,), np.bool_))


@njit(cache=True)
def _gather(x, f, mom, nodes, offsets, xc, force, moment):  # noqa: ANN001, ANN202
    """Resultant force (b, 3) kN and moment about xc (b, 3) kN*mm of the nodal forces
    f (n, 3) and nodal moments mom (n, 3) on each body's nodes."""
    for b in range(offsets.size - 1):
        f0 = f1 = f2 = 0.0
        m0 = m1 = m2 = 0.0
        t0 = t1 = t2 = 0.0
        for j in range(offsets[b], offsets[b + 1]):
            i = nodes[j]
            r0 = x[i, 0] - xc[b, 0]
            r1 = x[i, 1] - xc[b, 1]
            r2 = x[i, 2] - xc[b, 2]
            g0, g1, g2 = f[i, 0], f[i, 1], f[i, 2]
            f0 += g0
            f1 += g1
            f2 += g2
            m0 += r1 * g2 - r2 * g1
            m1 += r2 * g0 - r0 * g2
            m2 += r0 * g1 - r1 * g0
            t0 += mom[i, 0]
            t1 += mom[i, 1]
            t2 += mom[i, 2]
        force[b, 0], force[b, 1], force[b, 2] = f0, f1, f2
        moment[b, 0], moment[b, 1], moment[b, 2] = m0 + t0, m1 + t1, m2 + t2


@njit(cache=True, inline="always")
def _rotate_inertia(i0, r, out):  # noqa: ANN001, ANN202
    """out (3, 3) = r i0 r^T: an inertia (kg*mm^2) given in the body's initial axes,
    turned by the rotation r (3, 3)."""
    for i in range(3):
        for j in range(3):
            s = 0.0
            for p in range(3):
                rp = 0.0
                for q in range(3):
                    rp += i0[p, q] * r[j, q]
                s += r[i, p] * rp
            out[i, j] = s


@njit(cache=True)
def _advance_velocity(dt, mass, inertia0, rot, rot_w, force, moment, vel, omega,  # noqa: ANN001
                      vel_free, omega_free, fixed_t, fixed_r, presc_t, presc_r,  # noqa: ANN001
                      inertia):  # noqa: ANN001
    """V, w of every body from t^{n-1/2} to t^{n+1/2} (RigidBody.advance_velocity);
    ``inertia`` (b, 3, 3) receives R I0 R^T (kg*mm^2); rot_w becomes rot."""
    iw = np.empty((3, 3))
    for b in range(mass.size):
        for k in range(3):
            acc = force[b, k] / mass[b] if mass[b] > 0.0 else 0.0
            vel_free[b, k] = 0.0 if fixed_t[b, k] else vel[b, k] + dt * acc
            if fixed_t[b, k] or presc_t[b, k]:
                acc = 0.0
            vel[b, k] = 0.0 if fixed_t[b, k] else vel[b, k] + dt * acc
        _rotate_inertia(inertia0[b], rot[b], inertia[b])  # I = R I0 R^T
        for k in range(3):
            omega_free[b, k] = omega[b, k]
        if inertia[b, 0, 0] > 0.0 or inertia[b, 1, 1] > 0.0 or inertia[b, 2, 2] > 0.0:
            # L^{n-1/2} = I(R_w) w with R_w the rotation of the last velocity update
            w0, w1, w2 = omega[b, 0], omega[b, 1], omega[b, 2]
            _rotate_inertia(inertia0[b], rot_w[b], iw)
            c0 = iw[0, 0] * w0 + iw[0, 1] * w1 + iw[0, 2] * w2 + dt * moment[b, 0]
            c1 = iw[1, 0] * w0 + iw[1, 1] * w1 + iw[1, 2] * w2 + dt * moment[b, 1]
            c2 = iw[2, 0] * w0 + iw[2, 1] * w1 + iw[2, 2] * w2 + dt * moment[b, 2]
            a = inertia[b]
            # adjugate solve of I(R^n) w = c
            k00 = a[1, 1] * a[2, 2] - a[1, 2] * a[2, 1]
            k01 = a[0, 2] * a[2, 1] - a[0, 1] * a[2, 2]
            k02 = a[0, 1] * a[1, 2] - a[0, 2] * a[1, 1]
            k10 = a[1, 2] * a[2, 0] - a[1, 0] * a[2, 2]
            k11 = a[0, 0] * a[2, 2] - a[0, 2] * a[2, 0]
            k12 = a[0, 2] * a[1, 0] - a[0, 0] * a[1, 2]
            k20 = a[1, 0] * a[2, 1] - a[1, 1] * a[2, 0]
            k21 = a[0, 1] * a[2, 0] - a[0, 0] * a[2, 1]
            k22 = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
            det = a[0, 0] * k00 + a[0, 1] * k10 + a[0, 2] * k20
            # w^{n+1/2} = I(R^n)^{-1} L^{n+1/2}; held and prescribed components keep w
            al0 = (k00 * c0 + k01 * c1 + k02 * c2) / det - w0
            al1 = (k10 * c0 + k11 * c1 + k12 * c2) / det - w1
            al2 = (k20 * c0 + k21 * c1 + k22 * c2) / det - w2
            for k in range(3):
                delta = al0 if k == 0 else (al1 if k == 1 else al2)
                omega_free[b, k] = 0.0 if fixed_r[b, k] else omega[b, k] + delta
                if fixed_r[b, k] or presc_r[b, k]:
                    delta = 0.0
                omega[b, k] = omega[b, k] + delta
        for k in range(3):
            if fixed_r[b, k]:
                omega[b, k] = 0.0
        for i in range(3):
            for j in range(3):
                rot_w[b, i, j] = rot[b, i, j]


@njit(cache=True)
def _advance_position(dt, x, v, w, set_w, x_old, nodes, offsets, local, xc, rot,  # noqa: ANN001
                      vel, omega):  # noqa: ANN001, ANN202
    """Centres and rotations over dt; the bodies' nodes placed in x (n, 3) mm with
    v = (x^{n+1} - x^n) / dt (x_old (k, 3): x^n of the flat node list) and, with
    ``set_w``, w = omega."""
    q = np.empty((3, 3))
    tmp = np.empty((3, 3))
    for b in range(offsets.size - 1):
        for k in range(3):
            xc[b, k] = xc[b, k] + dt * vel[b, k]
        p0, p1, p2 = dt * omega[b, 0], dt * omega[b, 1], dt * omega[b, 2]
        angle = np.sqrt(p0 * p0 + p1 * p1 + p2 * p2)
        if angle >= 1e-14:
            # Rodrigues: Q = I + sin(a) K + (1 - cos(a)) K K, K = [k]x, then R <- Q R
            sn, cs = np.sin(angle), 1.0 - np.cos(angle)
            e0, e1, e2 = p0 / angle, p1 / angle, p2 / angle
            for i in range(3):
                for j in range(3):
                    kk = (e0 if i == 0 else (e1 if i == 1 else e2)) * \
                        (e0 if j == 0 else (e1 if j == 1 else e2))
                    if i == j:
                        kk -= 1.0  # K K = k k^T - I for a unit k
                    kij = 0.0
                    if i != j:
                        m = 3 - i - j  # the third axis
                        em = e0 if m == 0 else (e1 if m == 1 else e2)
                        kij = -em if (j - i) % 3 == 1 else em  # K_ij = -eps_ijm k_m
                    q[i, j] = (1.0 if i == j else 0.0) + sn * kij + cs * kk
            for i in range(3):
                for j in range(3):
                    tmp[i, j] = q[i, 0] * rot[b, 0, j] + q[i, 1] * rot[b, 1, j] + \
                        q[i, 2] * rot[b, 2, j]
            for i in range(3):
                for j in range(3):
                    rot[b, i, j] = tmp[i, j]
        for j in range(offsets[b], offsets[b + 1]):
            i = nodes[j]
            for m in range(3):
                xn = xc[b, m] + (local[j, 0] * rot[b, m, 0] + local[j, 1] * rot[b, m, 1]
                                 + local[j, 2] * rot[b, m, 2])
                x[i, m] = xn
                if dt > 0.0:
                    v[i, m] = (xn - x_old[j, m]) / dt
                if set_w:
                    w[i, m] = omega[b, m]


class RigidBodySet:
    """The bodies of a plan as stacked arrays (see the module docstring).

    bodies: the RigidBody objects (their attributes become row views); nodes
    (k,) int64 every body's nodes, body after body, ``offsets`` (b + 1,) int64
    bounds; local (k, 3) mm node offsets at t = 0; mass (b,) kg.
    """

    def __init__(self, bodies: list) -> None:
        self.bodies = list(bodies)
        nb = len(self.bodies)
        self.arrays: dict[str, np.ndarray] = {}
        self._views: list[dict[str, np.ndarray]] = [{} for _ in range(nb)]
        for name, shape, dtype in _VIEWS:
            arr = np.zeros((nb, *shape), dtype=dtype)
            self.arrays[name] = arr
            setattr(self, name, arr)
            for k, b in enumerate(self.bodies):
                cur = getattr(b, name, None)
                if cur is None and name == "rot_w":
                    cur = b.rot  # not updated yet: w belongs to the current rotation
                if cur is not None:
                    arr[k] = cur
                view = arr[k]
                self._views[k][name] = view
                setattr(b, name, view)
        self.mass = np.array([float(b.mass) for b in self.bodies], dtype=np.float64)
        counts = [int(np.asarray(b.nodes).size) for b in self.bodies]
        self.offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
        self.nodes = (np.concatenate([np.asarray(b.nodes, np.int64) for b in self.bodies])
                      if nb else np.zeros(0, np.int64))
        self.local = (np.concatenate([np.asarray(b.local0, np.float64).reshape(-1, 3)
                                      for b in self.bodies]) if nb else np.zeros((0, 3)))
        self.inertia = np.zeros((nb, 3, 3))  # R I0 R^T of the last velocity update

    def matches(self, bodies: list) -> bool:
        """Whether this set was made of exactly ``bodies`` (same objects, same order)."""
        return len(bodies) == len(self.bodies) and all(
            a is b for a, b in zip(bodies, self.bodies))

    def adopt(self) -> None:
        """Take over attributes that other code rebound (``body.vel = ...``) and the
        bodies' masses, so the stacked arrays are the bodies' values again."""
        for k, b in enumerate(self.bodies):
            d = b.__dict__
            views = self._views[k]
            for name, view in views.items():
                cur = d.get(name)
                if cur is not view:
                    if cur is not None:
                        view[...] = cur
                    d[name] = view
            self.mass[k] = b.mass

    def gather(self, x: np.ndarray, f: np.ndarray, mom: np.ndarray) -> None:
        """Every body's resultant force and moment (RigidBody.gather)."""
        self.adopt()
        _gather(x, f, mom, self.nodes, self.offsets, self.xc, self.force, self.moment)

    def advance_velocity(self, dt: float) -> None:
        """Every body's V, w to t^{n+1/2} (RigidBody.advance_velocity)."""
        self.adopt()
        _advance_velocity(dt, self.mass, self.inertia0, self.rot, self.rot_w, self.force,
                          self.moment,
                          self.vel, self.omega, self.vel_free, self.omega_free,
                          self.fixed_trans, self.fixed_rot, self.prescribed_trans,
                          self.prescribed_rot, self.inertia)

    def prescribed_work(self) -> float:
        """J: work of the prescribed motions' reaction impulses in this step,
        sum of M (V - V_free) . V + (w - w_free) . I w (I from the velocity update)."""
        dv = self.vel - self.vel_free
        dw = self.omega - self.omega_free
        iw = np.einsum("bij,bj->bi", self.inertia, self.omega)
        return float((self.mass * np.einsum("bi,bi->b", dv, self.vel)).sum()
                     + np.einsum("bi,bi->", dw, iw))

    def old_positions(self, x: np.ndarray) -> np.ndarray:
        """x^n (k, 3) mm of the bodies' nodes (before the positions move)."""
        return x[self.nodes]

    def advance_position(self, dt: float, x: np.ndarray, v: np.ndarray, w: np.ndarray | None,
                         x_old: np.ndarray) -> None:
        """Centres and rotations over dt; nodes placed, their v (and w) set."""
        self.adopt()
        _advance_position(dt, x, v, v if w is None else w, w is not None, x_old, self.nodes,
                          self.offsets, self.local, self.xc, self.rot, self.vel, self.omega)


def rigid_set(plan) -> RigidBodySet:  # noqa: ANN001 - Assembly
    """The plan's RigidBodySet, made (or remade, when the bodies changed) on demand."""
    rs = getattr(plan, "_rigid_set", None)
    if rs is None or not rs.matches(plan.bodies):
        rs = RigidBodySet(plan.bodies)
        plan._rigid_set = rs
    return rs
