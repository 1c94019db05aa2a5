"""Numba kernels of the joints (docs/joints.md): one call per cycle for all joints.

- :func:`pair_forces`: penalty springs (with dashpots) that hold node pairs of two
  rigid bodies together, in all directions or across an axis only;
- :func:`universal_forces`: the universal joint's penalty on its arms' perpendicularity;
- :func:`stiffness_moments`: *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED /
  _FLEXION-TORSION moments from the relative rotation of two body-fixed frames.

Units: mm, ms, kg, kN, rad; moments kN*mm. Each kernel adds to the nodal force
(n, 3) / moment (n, 3) arrays and returns the work (J) its forces did on the
joint's relative motion over the step (trapezoidal rule): stored plus dissipated
energy, the joint's ``internal_energy`` increment.
"""

from __future__ import annotations

import numpy as np
from numba import njit

GENERALIZED = 0
FLEXION_TORSION = 1


@njit(cache=True)
def pair_forces(x, v, f, pa, pb, ax0, ax1, k, c, g_prev, f_prev, f_out):  # noqa: ANN001
    """Penalty forces of P node pairs; returns the work increment (J).

    x, v, f (n, 3): positions mm, velocities mm/ms, forces kN (added to);
    pa, pb (P,) node on body A / B; ax0, ax1 (P,) nodes of body A whose line is the
    axis across which the pair is held (ax0 < 0: held in all directions);
    k (P,) kN/mm, c (P,) kN*ms/mm; g_prev, f_prev (P, 3) the pair's gap x_B - x_A
    and force on A at the previous call (updated); f_out (P, 3) the force on B (set).
    """
    work = 0.0
    for i in range(pa.shape[0]):
        a, b = pa[i], pb[i]
        g0 = x[b, 0] - x[a, 0]
        g1 = x[b, 1] - x[a, 1]
        g2 = x[b, 2] - x[a, 2]
        d0 = v[b, 0] - v[a, 0]
        d1 = v[b, 1] - v[a, 1]
        d2 = v[b, 2] - v[a, 2]
        h0, h1, h2 = g0, g1, g2
        if ax0[i] >= 0:
            u0 = x[ax1[i], 0] - x[ax0[i], 0]
            u1 = x[ax1[i], 1] - x[ax0[i], 1]
            u2 = x[ax1[i], 2] - x[ax0[i], 2]
            nu = np.sqrt(u0 * u0 + u1 * u1 + u2 * u2)
            u0 /= nu
            u1 /= nu
            u2 /= nu
            s = h0 * u0 + h1 * u1 + h2 * u2
            h0 -= s * u0
            h1 -= s * u1
            h2 -= s * u2
            s = d0 * u0 + d1 * u1 + d2 * u2
            d0 -= s * u0
            d1 -= s * u1
            d2 -= s * u2
        F0 = k[i] * h0 + c[i] * d0
        F1 = k[i] * h1 + c[i] * d1
        F2 = k[i] * h2 + c[i] * d2
        work += 0.5 * ((F0 + f_prev[i, 0]) * (g0 - g_prev[i, 0])
                       + (F1 + f_prev[i, 1]) * (g1 - g_prev[i, 1])
                       + (F2 + f_prev[i, 2]) * (g2 - g_prev[i, 2]))
        f[a, 0] += F0
        f[a, 1] += F1
        f[a, 2] += F2
        f[b, 0] -= F0
        f[b, 1] -= F1
        f[b, 2] -= F2
        g_prev[i, 0], g_prev[i, 1], g_prev[i, 2] = g0, g1, g2
        f_prev[i, 0], f_prev[i, 1], f_prev[i, 2] = F0, F1, F2
        f_out[i, 0], f_out[i, 1], f_out[i, 2] = -F0, -F1, -F2
    return work


@njit(cache=True)
def universal_forces(x, v, f, n1, n3, n2, n4, k, c, s_prev, l_prev, m_out):  # noqa: ANN001
    """Penalty on s = (x3 - x1) . u24 (u24 = unit x4 - x2): keeps body A's arm N1->N3
    perpendicular to body B's arm N2->N4. U = k s^2 / 2; returns the work increment (J).

    n1, n3 (U,) nodes of A; n2, n4 (U,) nodes of B; k (U,) kN/mm; c (U,) kN*ms/mm;
    s_prev, l_prev (U,) s (mm) and the force k s + c ds/dt (kN) at the previous call
    (updated); m_out (U, 3) the couple on body B (kN*mm, set).
    """
    work = 0.0
    for i in range(n1.shape[0]):
        r = x[n3[i]] - x[n1[i]]
        dr = v[n3[i]] - v[n1[i]]
        q = x[n4[i]] - x[n2[i]]
        dq = v[n4[i]] - v[n2[i]]
        lq = np.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2])
        u = q / lq
        du = (dq - (dq[0] * u[0] + dq[1] * u[1] + dq[2] * u[2]) * u) / lq
        s = r[0] * u[0] + r[1] * u[1] + r[2] * u[2]
        sd = (dr[0] * u[0] + dr[1] * u[1] + dr[2] * u[2]
              + r[0] * du[0] + r[1] * du[1] + r[2] * du[2])
        lam = k[i] * s + c[i] * sd
        work += 0.5 * (lam + l_prev[i]) * (s - s_prev[i])
        rp = r - (r[0] * u[0] + r[1] * u[1] + r[2] * u[2]) * u
        for j in range(3):
            f3 = -lam * u[j]
            f4 = -lam * rp[j] / lq
            f[n3[i], j] += f3
            f[n1[i], j] -= f3
            f[n4[i], j] += f4
            f[n2[i], j] -= f4
        # couple on B: (x4 - x2) x f4 = -lam u x r
        m_out[i, 0] = -lam * (u[1] * r[2] - u[2] * r[1])
        m_out[i, 1] = -lam * (u[2] * r[0] - u[0] * r[2])
        m_out[i, 2] = -lam * (u[0] * r[1] - u[1] * r[0])
        s_prev[i] = s
        l_prev[i] = lam
    return work


@njit(cache=True)
def _interp(cx, cy, start, idx, t):  # noqa: ANN001
    """Curve ``idx`` (points cx/cy[start[idx]:start[idx+1]]) at t, linear inside and
    linearly extrapolated from the end segments; 0 when idx < 0."""
    if idx < 0:
        return 0.0
    lo, hi = start[idx], start[idx + 1]
    m = hi - lo
    if m == 1:
        return cy[lo]
    if t <= cx[lo]:
        j = lo
    elif t >= cx[hi - 1]:
        j = hi - 2
    else:
        j = lo
        while cx[j + 1] < t:
            j += 1
    w = (t - cx[j]) / (cx[j + 1] - cx[j])
    return cy[j] + w * (cy[j + 1] - cy[j])


@njit(cache=True)
def _frame(x, nodes, axis, c, out):  # noqa: ANN001
    """Rows of ``out`` (3, 3) = c (3, 3) @ the unit axes built from three nodes:
    axis ``axis`` along nodes[0] -> nodes[1], nodes[2] in the plane of that axis and
    the next one (the *DEFINE_COORDINATE_NODES construction). No allocation."""
    i, j, k = axis, (axis + 1) % 3, (axis + 2) % 3
    a0 = x[nodes[1], 0] - x[nodes[0], 0]
    a1 = x[nodes[1], 1] - x[nodes[0], 1]
    a2 = x[nodes[1], 2] - x[nodes[0], 2]
    w0 = x[nodes[2], 0] - x[nodes[0], 0]
    w1 = x[nodes[2], 1] - x[nodes[0], 1]
    w2 = x[nodes[2], 2] - x[nodes[0], 2]
    na = np.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    a0, a1, a2 = a0 / na, a1 / na, a2 / na
    n0 = a1 * w2 - a2 * w1
    n1 = a2 * w0 - a0 * w2
    n2 = a0 * w1 - a1 * w0
    nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    n0, n1, n2 = n0 / nn, n1 / nn, n2 / nn
    f = out  # the node frame first, then c @ f in place
    f[i, 0], f[i, 1], f[i, 2] = a0, a1, a2
    f[k, 0], f[k, 1], f[k, 2] = n0, n1, n2
    f[j, 0] = n1 * a2 - n2 * a1
    f[j, 1] = n2 * a0 - n0 * a2
    f[j, 2] = n0 * a1 - n1 * a0
    for q in range(3):  # out = c @ f, column by column (f's column q read first)
        f0, f1, f2 = f[0, q], f[1, q], f[2, q]
        for p in range(3):
            out[p, q] = c[p, 0] * f0 + c[p, 1] * f1 + c[p, 2] * f2


@njit(cache=True)
def _wrap(a):  # noqa: ANN001
    """Angle difference in (-pi, pi]."""
    return a - 2.0 * np.pi * np.floor((a + np.pi) / (2.0 * np.pi))


@njit(cache=True)
def _dot(a, i, b, j):  # noqa: ANN001
    return a[i, 0] * b[j, 0] + a[i, 1] * b[j, 1] + a[i, 2] * b[j, 2]


@njit(cache=True)
def _cross_rows(a, i, b, j, out, k, scale):  # noqa: ANN001
    """out[k] = scale * (a[i] x b[j])."""
    out[k, 0] = scale * (a[i, 1] * b[j, 2] - a[i, 2] * b[j, 1])
    out[k, 1] = scale * (a[i, 2] * b[j, 0] - a[i, 0] * b[j, 2])
    out[k, 2] = scale * (a[i, 0] * b[j, 1] - a[i, 1] * b[j, 0])


@njit(cache=True)
def stiffness_moments(x, mom, dt, kind, na, nb, fa_nodes, fa_axis, fa_c,  # noqa: ANN001
                      fb_nodes, fb_axis, fb_c, cx, cy, cstart, lc, dlc, lcg, es, fm, neg,
                      pos, qp, q_prev, m_prev, q_out, m_out, mb_out):
    """Joint stiffness moments of S stiffnesses; returns the work increment (J).

    Frames (rows = unit axes): CIDA's of body A = fa_c (S, 3, 3) @ the axes of its
    three nodes fa_nodes (S, 3) (construction of :func:`_frame` with fa_axis (S,));
    likewise CIDB's of body B. A body-fixed system uses three nodes of its body and
    fa_c = its axes in their frame at t = 0; a system by nodes that follows them
    (FLAG = 1) uses its own nodes and fa_c = I. kind (S,) GENERALIZED /
    FLEXION_TORSION; na, nb (S,) nodes of A / B that receive the moments (kN*mm,
    added to mom); dt (ms) the step just taken (angle rates = angle change / dt; 0
    at the start); curves packed in cx, cy with cstart (nc + 1,); lc, dlc (S, 3)
    moment-angle and damping moment-rate curves (-1: none); lcg (S,) gamma scale
    curve (FLEXION_TORSION); es (S, 3) kN*mm/rad, fm (S, 3) kN*mm, neg / pos (S, 3)
    rad stops (nan: none). History (updated): qp (S, 3) the friction springs' slip
    angles, q_prev / m_prev (S, 3) the angles and generalized moments at the previous
    call. Out: q_out / m_out (S, 3) angles (rad) and generalized moments, mb_out
    (S, 3) the moment on body B (kN*mm). No allocation inside the loop.
    """
    work = 0.0
    ea = np.empty((3, 3))
    eb = np.empty((3, 3))
    ax = np.empty((3, 3))
    dual = np.empty((3, 3))
    q = np.empty(3)
    for s in range(kind.shape[0]):
        _frame(x, fa_nodes[s], fa_axis[s], fa_c[s], ea)
        _frame(x, fb_nodes[s], fb_axis[s], fb_c[s], eb)
        scale = 1.0
        if kind[s] == GENERALIZED:
            r02 = _dot(ea, 0, eb, 2)
            phi = np.arctan2(-_dot(ea, 1, eb, 2), _dot(ea, 2, eb, 2))
            q[0] = phi
            q[1] = np.arcsin(min(1.0, max(-1.0, r02)))
            q[2] = np.arctan2(-_dot(ea, 0, eb, 1), _dot(ea, 0, eb, 0))
            cp, sp = np.cos(phi), np.sin(phi)
            for c3 in range(3):  # axes: a1 = x_A, a2 = y after phi, a3 = z_B
                ax[0, c3] = ea[0, c3]
                ax[1, c3] = cp * ea[1, c3] + sp * ea[2, c3]
                ax[2, c3] = eb[2, c3]
            _cross_rows(ax, 1, ax, 2, dual, 0, 1.0)
            det = _dot(ax, 0, dual, 0)
            if abs(det) < 1e-6:
                det = 1e-6 if det >= 0.0 else -1e-6
            _cross_rows(ax, 1, ax, 2, dual, 0, 1.0 / det)
            _cross_rows(ax, 2, ax, 0, dual, 1, 1.0 / det)
            _cross_rows(ax, 0, ax, 1, dual, 2, 1.0 / det)
        else:
            c = min(1.0, max(-1.0, _dot(ea, 2, eb, 2)))
            q[0] = np.arccos(c)
            _cross_rows(ea, 2, eb, 2, dual, 0, 1.0)
            sn = np.sqrt(_dot(dual, 0, dual, 0))
            gamma = 0.0
            if sn > 1e-12:
                for c3 in range(3):
                    dual[0, c3] /= sn
                gamma = np.arctan2(_dot(eb, 2, ea, 1), _dot(eb, 2, ea, 0))
            else:
                dual[0, 0] = dual[0, 1] = dual[0, 2] = 0.0
            q[1] = gamma
            # twist: 2 atan2(qz, qw) of the relative rotation's quaternion (qw >= 0)
            tr = _dot(ea, 0, eb, 0) + _dot(ea, 1, eb, 1) + _dot(ea, 2, eb, 2)
            q[2] = 2.0 * np.arctan2(_dot(ea, 1, eb, 0) - _dot(ea, 0, eb, 1), 1.0 + tr)
            inv = 1.0 / max(1.0 + c, 1e-6)
            for c3 in range(3):
                dual[1, c3] = 0.0
                dual[2, c3] = (ea[2, c3] + eb[2, c3]) * inv
            if lcg[s] >= 0:
                scale = _interp(cx, cy, cstart, lcg[s], gamma)
        mb0 = mb1 = mb2 = 0.0
        for i in range(3):
            dq = _wrap(q[i] - q_prev[s, i])
            rate = dq / dt if dt > 0.0 else 0.0
            m = _interp(cx, cy, cstart, lc[s, i], q[i])
            m += _interp(cx, cy, cstart, dlc[s, i], rate)
            if i == 0:
                m *= scale
            k = es[s, i]
            if k > 0.0:
                if fm[s, i] > 0.0:
                    mf = k * (q[i] - qp[s, i])
                    if abs(mf) > fm[s, i]:
                        mf = fm[s, i] if mf > 0.0 else -fm[s, i]
                        qp[s, i] = q[i] - mf / k
                    m += mf
                if q[i] > pos[s, i]:
                    m += k * (q[i] - pos[s, i])
                if q[i] < neg[s, i]:
                    m += k * (q[i] - neg[s, i])
            work += 0.5 * (m + m_prev[s, i]) * dq
            q_prev[s, i] = q[i]
            m_prev[s, i] = m
            q_out[s, i] = q[i]
            m_out[s, i] = m
            mb0 -= m * dual[i, 0]
            mb1 -= m * dual[i, 1]
            mb2 -= m * dual[i, 2]
        mom[nb[s], 0] += mb0
        mom[nb[s], 1] += mb1
        mom[nb[s], 2] += mb2
        mom[na[s], 0] -= mb0
        mom[na[s], 1] -= mb1
        mom[na[s], 2] -= mb2
        mb_out[s, 0], mb_out[s, 1], mb_out[s, 2] = mb0, mb1, mb2
    return work
