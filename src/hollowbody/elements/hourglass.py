"""Flanagan-Belytschko hourglass control of the one-point hexahedron.

Hourglass shape vectors (FB 1981), one per base vector h_alpha of
:data:`~hollowbody.elements.hex8_kinematics.HG_BASE` (entries +-1, not
normalised)::

    gamma_alpha,a = h_alpha,a - (sum_b h_alpha,b x_b) . b_a

They are orthogonal to every linear field (``sum_a gamma_alpha,a x_a = 0``),
so rigid motion and uniform strain produce no hourglass force, whatever the
element's shape. Hourglass rates ``qd_alpha = sum_a v_a gamma_alpha,a`` (3,)
per mode are computed without forming gamma::

    qd_alpha = sum_a h_alpha,a v_a - L_end (sum_a h_alpha,a x_a)

with ``L_end = sum_a v_a (x) b_a``; forces ``f_a = -sum_alpha Q_alpha gamma_alpha,a``
likewise as ``-(sum_alpha Q_alpha h_alpha,a - M b_a)``, ``M = sum_alpha Q_alpha (x) hx_alpha``.

Viscous form (IHQ 1, 2, 3; all treated as FB viscous, see docs/elements.md):
``Q_alpha = a_h qd_alpha``, ``a_h = QH rho c V^(2/3) / 4`` (LS-DYNA's
scaling; kg/ms). Power dissipated ``a_h sum |qd|^2 >= 0``; the work is
accounted trapezoidally with the previous forces (kept per element), as the
central-difference scheme does it.

Stiffness form (IHQ 4, 5): ``Q_alpha`` is a state, rotated with the element
(Hughes-Winget increment) and incremented ``Q += kappa dt qd`` with
``kappa = QH (K + 4G/3) V (b . b) / 24`` (kN/mm; FB's ``eps (lambda+2mu)
b_iI b_iI V / 3`` for normalised shape vectors gamma / sqrt(8)).
Units: mm, mm/ms, kN.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, inline="always", fastmath={"contract"})
def _h_dot(p0, p1, p2, p3, p4, p5, p6, p7):
    """The four sums sum_a h_alpha,a p_a (butterfly over the +-1 entries of HG_BASE)."""
    a = p0 - p1
    b = p2 - p3
    c = p4 - p5
    d = p6 - p7
    return (a + b + c + d, (p0 + p1) - (p2 + p3) - (p4 + p5) + (p6 + p7),
            a - b - c + d, -a - b + c + d)


@njit(cache=True, inline="always", fastmath={"contract"})
def hourglass_hx(xe, hx):
    """Kernel: hx (4, 3) = sum_a h_alpha,a x_a (mm); xe (8, 3) mm."""
    for i in range(3):
        h0, h1, h2, h3 = _h_dot(xe[0, i], xe[1, i], xe[2, i], xe[3, i],
                                xe[4, i], xe[5, i], xe[6, i], xe[7, i])
        hx[0, i] = h0
        hx[1, i] = h1
        hx[2, i] = h2
        hx[3, i] = h3


@njit(cache=True, inline="always", fastmath={"contract"})
def hourglass_rates(ve, lg_end, hx, qd):
    """Kernel: qd (4, 3) mm/ms, hourglass rates of the 4 modes.

    ve (8, 3) mm/ms; lg_end (3, 3) 1/ms velocity gradient with the
    end-of-step gradients; hx (4, 3) from :func:`hourglass_hx`.
    """
    for i in range(3):
        h0, h1, h2, h3 = _h_dot(ve[0, i], ve[1, i], ve[2, i], ve[3, i],
                                ve[4, i], ve[5, i], ve[6, i], ve[7, i])
        l0, l1, l2 = lg_end[i, 0], lg_end[i, 1], lg_end[i, 2]
        qd[0, i] = h0 - (l0 * hx[0, 0] + l1 * hx[0, 1] + l2 * hx[0, 2])
        qd[1, i] = h1 - (l0 * hx[1, 0] + l1 * hx[1, 1] + l2 * hx[1, 2])
        qd[2, i] = h2 - (l0 * hx[2, 0] + l1 * hx[2, 1] + l2 * hx[2, 2])
        qd[3, i] = h3 - (l0 * hx[3, 0] + l1 * hx[3, 1] + l2 * hx[3, 2])


@njit(cache=True, inline="always", fastmath={"contract"})
def hourglass_add_forces(qf, hx, b, fwork, e):
    """Kernel: fwork[e, a] -= sum_alpha qf_alpha gamma_alpha,a (kN).

    qf (4, 3) kN generalised hourglass forces; hx (4, 3) mm; b (8, 3) 1/mm
    uniform gradients; fwork (e, 8, 3) kN element nodal forces (accumulated).
    """
    for i in range(3):
        q0, q1, q2, q3 = qf[0, i], qf[1, i], qf[2, i], qf[3, i]
        # M_i. = sum_alpha q_alpha hx_alpha
        m0 = q0 * hx[0, 0] + q1 * hx[1, 0] + q2 * hx[2, 0] + q3 * hx[3, 0]
        m1 = q0 * hx[0, 1] + q1 * hx[1, 1] + q2 * hx[2, 1] + q3 * hx[3, 1]
        m2 = q0 * hx[0, 2] + q1 * hx[1, 2] + q2 * hx[2, 2] + q3 * hx[3, 2]
        # sum_alpha q_alpha h_alpha,a for the 8 nodes (columns of HG_BASE)
        s01 = q0 + q1
        s23 = q2 - q3
        t01 = q0 - q1
        t23 = q2 + q3
        g0 = s01 + s23
        g1 = -t01 - s23
        g2 = t01 - t23
        g3 = -s01 + t23
        g4 = t01 - s23
        g5 = -s01 + s23
        g6 = s01 + t23
        g7 = -t01 - t23
        fwork[e, 0, i] -= g0 - (m0 * b[0, 0] + m1 * b[0, 1] + m2 * b[0, 2])
        fwork[e, 1, i] -= g1 - (m0 * b[1, 0] + m1 * b[1, 1] + m2 * b[1, 2])
        fwork[e, 2, i] -= g2 - (m0 * b[2, 0] + m1 * b[2, 1] + m2 * b[2, 2])
        fwork[e, 3, i] -= g3 - (m0 * b[3, 0] + m1 * b[3, 1] + m2 * b[3, 2])
        fwork[e, 4, i] -= g4 - (m0 * b[4, 0] + m1 * b[4, 1] + m2 * b[4, 2])
        fwork[e, 5, i] -= g5 - (m0 * b[5, 0] + m1 * b[5, 1] + m2 * b[5, 2])
        fwork[e, 6, i] -= g6 - (m0 * b[6, 0] + m1 * b[6, 1] + m2 * b[6, 2])
        fwork[e, 7, i] -= g7 - (m0 * b[7, 0] + m1 * b[7, 1] + m2 * b[7, 2])


@njit(cache=True, inline="always", fastmath={"contract"})
def hourglass_viscous(ah, dt, rot, qd, state, e, qf):
    """Kernel: viscous form, qf = ah * qd (kN), kept in state[e] (e, 4, 3).

    Returns the work increment of the hourglass forces over the step,
    ``dt (Q^n + Q^{n+1}) / 2 . qd`` with the previous forces (rotated by ``rot``)
    from ``state`` -- the central-difference work, as for the total energy.
    """
    w = 0.0
    for m in range(4):
        r0, r1, r2 = rotate_rows(rot, state, e, m)
        n0 = ah * qd[m, 0]
        n1 = ah * qd[m, 1]
        n2 = ah * qd[m, 2]
        w += 0.5 * dt * ((r0 + n0) * qd[m, 0] + (r1 + n1) * qd[m, 1] + (r2 + n2) * qd[m, 2])
        state[e, m, 0] = n0
        state[e, m, 1] = n1
        state[e, m, 2] = n2
        qf[m, 0] = n0
        qf[m, 1] = n1
        qf[m, 2] = n2
    return w


@njit(cache=True, inline="always", fastmath={"contract"})
def rotate_rows(rot, arr, e, m):
    """Kernel: rot (3, 3) . arr[e, m] (3 floats) of a (e, 4, 3) array."""
    s0, s1, s2 = arr[e, m, 0], arr[e, m, 1], arr[e, m, 2]
    return (rot[0, 0] * s0 + rot[0, 1] * s1 + rot[0, 2] * s2,
            rot[1, 0] * s0 + rot[1, 1] * s1 + rot[1, 2] * s2,
            rot[2, 0] * s0 + rot[2, 1] * s1 + rot[2, 2] * s2)


@njit(cache=True, inline="always", fastmath={"contract"})
def advance_rotated(rot, state, e, scale, inc, dt, qd, qf):
    """Kernel: the stored hourglass forces of element ``e``, rotated by ``rot`` (3, 3)
    and advanced: ``state[e] = rot state[e] + scale inc`` (kN; inc (4, 3) may be
    ``qf`` itself), copied to qf (4, 3). Returns the work increment
    ``dt (Q_old_rotated + Q_new) / 2 . qd`` (J); qd (4, 3) mm/ms."""
    w = 0.0
    for m in range(4):
        r0, r1, r2 = rotate_rows(rot, state, e, m)
        n0 = r0 + scale * inc[m, 0]
        n1 = r1 + scale * inc[m, 1]
        n2 = r2 + scale * inc[m, 2]
        w += 0.5 * dt * ((r0 + n0) * qd[m, 0] + (r1 + n1) * qd[m, 1] + (r2 + n2) * qd[m, 2])
        state[e, m, 0] = n0
        state[e, m, 1] = n1
        state[e, m, 2] = n2
        qf[m, 0] = n0
        qf[m, 1] = n1
        qf[m, 2] = n2
    return w


@njit(cache=True, inline="always", fastmath={"contract"})
def hourglass_stiffness(kappa, dt, rot, qd, state, e, qf):
    """Kernel: incremental FB stiffness form for element ``e``.

    state (e, 4, 3) kN generalised hourglass forces, rotated by ``rot`` (3, 3)
    and incremented by ``kappa * dt * qd``; the result is copied to qf (4, 3).
    Returns the work increment dt * (Q_old_rotated + Q_new)/2 . qd (J).
    """
    return advance_rotated(rot, state, e, kappa * dt, qd, dt, qd, qf)
