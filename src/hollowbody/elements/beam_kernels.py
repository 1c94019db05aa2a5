"""Kernels of the co-rotational two-node beam (ELFORM 1 and 2; docs/beams.md).

One pass over a group per cycle (:func:`beam_forces`), allocation-free in the
element loop. Units: mm, ms, kg, kN, GPa; x (n, 3) mm, w (n, 3) rad/ms.

Kinematics (both formulations). Each element keeps the rotation matrices
``triad`` (e, 2, 3, 3) of its two nodes since t = 0, advanced every cycle by
the nodes' rotation increments ``w dt`` (Rodrigues' formula; every element
on a node applies the same increment, so their copies agree). The
co-rotational frame ``E = (e1, e2, e3)``: e1 along the chord N1 -> N2, e2
normal to it in the plane of e1 and the mean of the two nodes' rotated s axes
(the frame follows the mean twist). The node rotations relative to this frame
(``Q_a = E R_a E0^T``, rotation vector from its skew part) are the
*natural deformations*, with the elongation:

    d = (l - L0, phi = th2_r - th1_r, th1_s, th1_t, th2_s, th2_t)

A rigid motion leaves them zero exactly (objectivity). Their work-conjugate
*natural forces* ``F = (N, T, M1s, M1t, M2s, M2t)`` come from the section law;
the nodal forces and moments follow from the virtual work of ``F . dd`` with
the variation of the chord (shear ``(M1 + M2) / l`` from equilibrium) and of
the frame's twist, so the internal force is the exact gradient of the stored
energy at any rotation.

Section laws:

* ``LAW_RESULTANT`` (ELFORM 2, Belytschko-Schwer type, elastic): total form,
  N = EA (l - L0) / L0, T = GJ phi / L0 and the end moments of the exact
  Timoshenko beam, ``M1 = EI / (L0 (1 + P)) ((4 + P) th1 + (2 - P) th2)``
  (P = 12 EI / (G SA L0^2); SA = 0: P = 0, Euler-Bernoulli).
* ``LAW_INTEGRATED`` (ELFORM 1): one point at the middle of the beam; strain
  increments from the increments of d: axial ``de0 = dl / L0``, curvatures
  ``dk_s = (dth2_s - dth1_s) / L0``, ``dk_t``, twist ``dk_r = dphi / L0``,
  transverse shears ``dg_s = -(dth1_t + dth2_t) / 2``,
  ``dg_t = (dth1_s + dth2_s) / 2``; at a point (s, t):
  ``deps = de0 - s dk_t + t dk_s``, ``dgam_s = dg_s - t dk_r``,
  ``dgam_t = dg_t + s dk_r``; point law
  :func:`~hollowbody.materials.beam_plasticity.beam_point_update`; resultants
  by the section rule, mapped back to F by the same strain-displacement
  relations (uniformly reduced integration: no shear locking, no spurious
  mode).

Internal energy: ``sum 0.5 (F_old + F_new) . (d_new - d_old)`` per cycle
(exact for the elastic resultant law, the work of the stresses otherwise).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hollowbody.materials.beam_plasticity import beam_point_update
from hollowbody.materials.plane_stress_plasticity import (
    P_CS_C,
    P_FAIL,
    P_RATE_CURVE,
    rate_factor,
)

LAW_RESULTANT = 0
LAW_INTEGRATED = 1

# indices of the packed section vector ``sec``
#: resultant: EA kN, GJ, EI_s, EI_t kN mm^2, 12 EI / (G SA) mm^2 for s and t
S_EA, S_GJ, S_EIS, S_EIT, S_PHIS, S_PHIT = 0, 1, 2, 3, 4, 5
#: integrated: E, SHRF G, kinematic modulus (GPa), 1 for a plastic law
S_E, S_GS, S_HK, S_PLASTIC = 0, 1, 2, 3
N_SEC = 6


@njit(cache=True, error_model="numpy")
def _rotate(tr, i: int, a: int, wx: float, wy: float, wz: float, dt: float) -> None:
    """tr[i, a] <- exp([w dt]x) tr[i, a] (Rodrigues)."""
    ax, ay, az = wx * dt, wy * dt, wz * dt
    ang = math.sqrt(ax * ax + ay * ay + az * az)
    if ang == 0.0:
        return
    kx, ky, kz = ax / ang, ay / ang, az / ang
    sn = math.sin(ang)
    cs = 1.0 - math.cos(ang)
    r00 = 1.0 - cs * (ky * ky + kz * kz)
    r11 = 1.0 - cs * (kx * kx + kz * kz)
    r22 = 1.0 - cs * (kx * kx + ky * ky)
    r01 = -sn * kz + cs * kx * ky
    r10 = sn * kz + cs * kx * ky
    r02 = sn * ky + cs * kx * kz
    r20 = -sn * ky + cs * kx * kz
    r12 = -sn * kx + cs * ky * kz
    r21 = sn * kx + cs * ky * kz
    for j in range(3):
        c0, c1, c2 = tr[i, a, 0, j], tr[i, a, 1, j], tr[i, a, 2, j]
        tr[i, a, 0, j] = r00 * c0 + r01 * c1 + r02 * c2
        tr[i, a, 1, j] = r10 * c0 + r11 * c1 + r12 * c2
        tr[i, a, 2, j] = r20 * c0 + r21 * c1 + r22 * c2


@njit(cache=True, error_model="numpy")
def _dot_rotated(tr, frame0, i: int, a: int, e, row: int, col: int) -> float:
    """e[row] . (R_a E0[col]): entry (row, col) of Q_a = E R_a E0^T."""
    out = 0.0
    for c in range(3):
        v = tr[i, a, c, 0] * frame0[i, col, 0] + tr[i, a, c, 1] * frame0[i, col, 1] \
            + tr[i, a, c, 2] * frame0[i, col, 2]
        out += e[row, c] * v
    return out


@njit(cache=True, error_model="numpy")
def _node_rotation(tr, frame0, i: int, a: int, e, out, k0: int) -> None:
    """Rotation vector (local r, s, t) of node a relative to the frame e (3, 3 rows)
    into out[k0:k0 + 3] (rad; from the skew part of Q_a, valid below 90 degrees)."""
    sx = 0.5 * (_dot_rotated(tr, frame0, i, a, e, 2, 1) - _dot_rotated(tr, frame0, i, a, e, 1, 2))
    sy = 0.5 * (_dot_rotated(tr, frame0, i, a, e, 0, 2) - _dot_rotated(tr, frame0, i, a, e, 2, 0))
    sz = 0.5 * (_dot_rotated(tr, frame0, i, a, e, 1, 0) - _dot_rotated(tr, frame0, i, a, e, 0, 1))
    sn = math.sqrt(sx * sx + sy * sy + sz * sz)
    fac = 1.0
    if sn > 1.0e-12:
        fac = math.asin(min(sn, 1.0)) / sn
    out[k0] = fac * sx
    out[k0 + 1] = fac * sy
    out[k0 + 2] = fac * sz


@njit(cache=True, error_model="numpy")
def _spin_moment(t0: float, t1: float, t2: float, m0: float, m1: float, m2: float
                 ) -> tuple[float, float, float]:
    """Lambda(theta)^T m: the moment conjugate to the spin of a node, given the
    moment m conjugate to its rotation vector theta (local components).

    Lambda = d theta / d omega = I - [theta]x / 2 + eta [theta]x^2,
    eta = (1 - (a / 2) cot(a / 2)) / a^2 (a = |theta|; 1/12 at 0), so
    Lambda^T m = m + theta x m / 2 + eta theta x (theta x m).
    """
    a2 = t0 * t0 + t1 * t1 + t2 * t2
    if a2 < 1.0e-8:
        eta = 1.0 / 12.0 + a2 / 720.0
    else:
        a = math.sqrt(a2)
        eta = (1.0 - 0.5 * a / math.tan(0.5 * a)) / a2
    c0 = t1 * m2 - t2 * m1
    c1 = t2 * m0 - t0 * m2
    c2 = t0 * m1 - t1 * m0
    d0 = t1 * c2 - t2 * c1
    d1 = t2 * c0 - t0 * c2
    d2 = t0 * c1 - t1 * c0
    return (m0 + 0.5 * c0 + eta * d0, m1 + 0.5 * c1 + eta * d1, m2 + 0.5 * c2 + eta * d2)


@njit(cache=True, error_model="numpy")
def beam_forces(x, w, dt: float, f, mom, conn, alive, frame0, length0, triad, nat, force,
                res, law: int, sec, pts, sig, back, eps_p, pfail, hard_x, hard_y, mp,
                rate_x, rate_y, dt0, dte, e_work, rot) -> tuple[float, int, float]:
    """Update the beams of a group and add their nodal forces and moments.

    x (n, 3) mm at t^{n+1}; w (n, 3) rad/ms at t^{n+1/2}; dt ms (0: forces of
    the current state only); f (n, 3) kN and mom (n, 3) kN mm: internal forces
    subtracted. conn (e, 2) int32; alive (e,) bool; frame0 (e, 3, 3) initial
    rows r, s, t; length0 (e,) mm; triad (e, 2, 3, 3) node rotations (updated);
    nat (e, 6) natural deformations, force (e, 6) natural forces (updated);
    res (e, 6) resultants (N, Q_s, Q_t kN; T, M_s, M_t kN mm) at the middle;
    law LAW_RESULTANT / LAW_INTEGRATED; sec (N_SEC,) packed section; pts (p, 3)
    stress points (s, t, weight); sig, back (e, p, 3) GPa; eps_p (e, p);
    pfail (e, p) uint8: failed points (effective plastic strain reached the
    material's FAIL, ``mp[P_FAIL] > 0``): no stress from then on; a beam whose
    points have all failed is deleted (alive False);
    hard_x, hard_y hardening table; mp (N_PARAMS,) the material's packed
    parameters and rate_x, rate_y its rate curve (strain-rate scaling of the
    yield stress, :func:`~hollowbody.materials.plane_stress_plasticity.rate_factor`);
    dt0 (e,) ms initial critical steps; dte (e,)
    ms out; e_work (e,) J scratch; rot (e, 6) scratch. Returns (smallest
    critical step ms, its element or -1, internal energy increment J).
    """
    ne = conn.shape[0]
    np_ = pts.shape[0]
    dmin = np.inf
    imin = -1
    de_total = 0.0
    e = np.empty((3, 3))
    qs = np.empty((2, 3))
    for i in range(ne):
        if not alive[i]:
            dte[i] = np.inf
            continue
        n1 = conn[i, 0]
        n2 = conn[i, 1]
        if dt != 0.0:
            _rotate(triad, i, 0, w[n1, 0], w[n1, 1], w[n1, 2], dt)
            _rotate(triad, i, 1, w[n2, 0], w[n2, 1], w[n2, 2], dt)
        d0 = x[n2, 0] - x[n1, 0]
        d1 = x[n2, 1] - x[n1, 1]
        d2 = x[n2, 2] - x[n1, 2]
        ln = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
        e[0, 0], e[0, 1], e[0, 2] = d0 / ln, d1 / ln, d2 / ln
        # mean rotated s axis of the two nodes
        for a in range(2):
            for c in range(3):
                qs[a, c] = triad[i, a, c, 0] * frame0[i, 1, 0] \
                    + triad[i, a, c, 1] * frame0[i, 1, 1] + triad[i, a, c, 2] * frame0[i, 1, 2]
        q0 = qs[0, 0] + qs[1, 0]
        q1 = qs[0, 1] + qs[1, 1]
        q2 = qs[0, 2] + qs[1, 2]
        t0 = e[0, 1] * q2 - e[0, 2] * q1
        t1 = e[0, 2] * q0 - e[0, 0] * q2
        t2 = e[0, 0] * q1 - e[0, 1] * q0
        tn = math.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
        e[2, 0], e[2, 1], e[2, 2] = t0 / tn, t1 / tn, t2 / tn
        e[1, 0] = e[2, 1] * e[0, 2] - e[2, 2] * e[0, 1]
        e[1, 1] = e[2, 2] * e[0, 0] - e[2, 0] * e[0, 2]
        e[1, 2] = e[2, 0] * e[0, 1] - e[2, 1] * e[0, 0]
        _node_rotation(triad, frame0, i, 0, e, rot[i], 0)
        _node_rotation(triad, frame0, i, 1, e, rot[i], 3)
        L = length0[i]
        dn0 = ln - L
        dn1 = rot[i, 3] - rot[i, 0]
        dn2, dn3, dn4, dn5 = rot[i, 1], rot[i, 2], rot[i, 4], rot[i, 5]
        old0, old1, old2 = force[i, 0], force[i, 1], force[i, 2]
        old3, old4, old5 = force[i, 3], force[i, 4], force[i, 5]
        if law == LAW_RESULTANT:
            fN = sec[S_EA] * dn0 / L
            fT = sec[S_GJ] * dn1 / L
            ps = sec[S_PHIS] / (L * L)
            cs = sec[S_EIS] / (L * (1.0 + ps))
            m1s = cs * ((4.0 + ps) * dn2 + (2.0 - ps) * dn4)
            m2s = cs * ((2.0 - ps) * dn2 + (4.0 + ps) * dn4)
            pt = sec[S_PHIT] / (L * L)
            ct = sec[S_EIT] / (L * (1.0 + pt))
            m1t = ct * ((4.0 + pt) * dn3 + (2.0 - pt) * dn5)
            m2t = ct * ((2.0 - pt) * dn3 + (4.0 + pt) * dn5)
            res[i, 0] = fN
            res[i, 1] = -(m1t + m2t) / ln
            res[i, 2] = (m1s + m2s) / ln
            res[i, 3] = fT
            res[i, 4] = 0.5 * (m2s - m1s)
            res[i, 5] = 0.5 * (m2t - m1t)
        else:
            de0 = (dn0 - nat[i, 0]) / L
            dkr = (dn1 - nat[i, 1]) / L
            dks = ((dn4 - nat[i, 4]) - (dn2 - nat[i, 2])) / L
            dkt = ((dn5 - nat[i, 5]) - (dn3 - nat[i, 3])) / L
            dgs = -0.5 * ((dn3 - nat[i, 3]) + (dn5 - nat[i, 5]))
            dgt = 0.5 * ((dn2 - nat[i, 2]) + (dn4 - nat[i, 4]))
            rn = rqs = rqt = rt = rms = rmt = 0.0
            rated = sec[S_PLASTIC] > 0.0 and dt > 0.0 and (mp[P_CS_C] > 0.0
                                                           or mp[P_RATE_CURVE] > 0.0)
            fail = mp[P_FAIL] if sec[S_PLASTIC] > 0.0 else 0.0
            n_failed = 0
            for k in range(np_):
                if pfail[i, k] != 0:
                    n_failed += 1
                    continue
                ps_ = pts[k, 0]
                pt_ = pts[k, 1]
                wk = pts[k, 2]
                pe = de0 - ps_ * dkt + pt_ * dks
                pgs = dgs - pt_ * dkr
                pgt = dgt + ps_ * dkr
                rf = 1.0
                if rated:  # von Mises rate of (axial, -axial/2, -axial/2, shears)
                    rf = rate_factor(mp, rate_x, rate_y, pe / dt, -0.5 * pe / dt,
                                     math.sqrt(pgs * pgs + pgt * pgt) / dt)
                beam_point_update(sig, back, i, k, eps_p, pe, pgs, pgt, sec[S_E], sec[S_GS],
                                  sec[S_HK], sec[S_PLASTIC] > 0.0, hard_x, hard_y, rf)
                if fail > 0.0 and eps_p[i, k] >= fail:  # the point fails: no stress
                    pfail[i, k] = 1
                    n_failed += 1
                    for c in range(3):
                        sig[i, k, c] = 0.0
                        back[i, k, c] = 0.0
                    continue
                s0 = sig[i, k, 0] * wk
                rn += s0
                rms += s0 * pt_
                rmt -= s0 * ps_
                rqs += sig[i, k, 1] * wk
                rqt += sig[i, k, 2] * wk
                rt += (sig[i, k, 2] * ps_ - sig[i, k, 1] * pt_) * wk
            if n_failed == np_:  # every point failed: the beam is deleted
                alive[i] = False
                rn = rqs = rqt = rt = rms = rmt = 0.0
            fN = rn
            fT = rt
            m1s = -rms + 0.5 * L * rqt
            m2s = rms + 0.5 * L * rqt
            m1t = -rmt - 0.5 * L * rqs
            m2t = rmt - 0.5 * L * rqs
            res[i, 0] = rn
            res[i, 1] = rqs
            res[i, 2] = rqt
            res[i, 3] = rt
            res[i, 4] = rms
            res[i, 5] = rmt
        force[i, 0] = fN
        force[i, 1] = fT
        force[i, 2] = m1s
        force[i, 3] = m1t
        force[i, 4] = m2s
        force[i, 5] = m2t
        ew = 0.5 * ((old0 + fN) * (dn0 - nat[i, 0]) + (old1 + fT) * (dn1 - nat[i, 1])
                    + (old2 + m1s) * (dn2 - nat[i, 2]) + (old3 + m1t) * (dn3 - nat[i, 3])
                    + (old4 + m2s) * (dn4 - nat[i, 4]) + (old5 + m2t) * (dn5 - nat[i, 5]))
        e_work[i] = ew
        de_total += ew
        nat[i, 0] = dn0
        nat[i, 1] = dn1
        nat[i, 2] = dn2
        nat[i, 3] = dn3
        nat[i, 4] = dn4
        nat[i, 5] = dn5
        # nodal forces and moments (internal, subtracted): the end moments
        # (-T, M1s, M1t), (T, M2s, M2t) through Lambda(theta_a)^T (_spin_moment)
        a0, a1, a2 = _spin_moment(rot[i, 0], rot[i, 1], rot[i, 2], -fT, m1s, m1t)
        b0, b1, b2 = _spin_moment(rot[i, 3], rot[i, 4], rot[i, 5], fT, m2s, m2t)
        # the frame's twist: d omega_r = (sum_a d omega_a . (q_a x e3)
        #   - (q . e1) (du2 - du1) . e3 / l) / |q_perp|, q_a the rotated s axes
        sy = (a1 + b1) / ln
        sz = (a2 + b2) / ln
        sr = (a0 + b0) / tn
        qe1 = q0 * e[0, 0] + q1 * e[0, 1] + q2 * e[0, 2]
        st = sy + sr * qe1 / ln
        for c in range(3):
            fc = fN * e[0, c] + st * e[2, c] - sz * e[1, c]
            f[n2, c] -= fc
            f[n1, c] += fc
            c1 = (c + 1) % 3
            c2 = (c + 2) % 3
            x1 = qs[0, c1] * e[2, c2] - qs[0, c2] * e[2, c1]  # (q_1 x e3)_c
            x2 = qs[1, c1] * e[2, c2] - qs[1, c2] * e[2, c1]
            mom[n1, c] -= a0 * e[0, c] + a1 * e[1, c] + a2 * e[2, c] - sr * x1
            mom[n2, c] -= b0 * e[0, c] + b1 * e[1, c] + b2 * e[2, c] - sr * x2
        if not alive[i]:  # deleted in this call (material failure)
            dte[i] = np.inf
            continue
        d = dt0[i] * ln / L
        dte[i] = d
        if d < dmin:
            dmin = d
            imin = i
    return dmin, imin, de_total
