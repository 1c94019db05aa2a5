"""Assumed-strain hourglass stiffness of the one-point hexahedron (LS-DYNA IHQ 6).

The physical stabilization of Belytschko & Bindeman (CMAME 105, 1993): the
hourglass forces are the work-conjugates of the hourglass part of an assumed
strain field, with the material's elastic constants, so that the stabilized
element bends like a rectangular element with incompatible modes: exact pure
bending for a rectangular element at QH = 1, no shear locking and no
volumetric locking as nu -> 1/2. The derivation is in docs/elements.md
("Assumed-strain hourglass stiffness"); the result, in the element's
co-rotational frame ``e_0, e_1, e_2`` (columns of the current Jacobian at the
centre, Gram-Schmidt) with the half-lengths ``a_0, a_1, a_2`` and volume V of the
element's initial shape (norms of the initial Jacobian columns), for the local hourglass
amplitudes ``q[i][alpha]`` (direction i, mode alpha = xi eta, eta zeta,
zeta xi, xi eta zeta; the FB amplitudes of :mod:`~hollowbody.elements.hourglass`)::

    c_mn = 1 / (8 a_m a_n),   w_m = QH V a_m^2 / 3
    block m (strain linear in x_m; n < l the other two directions):
        e_nn = c_mn q[n][{mn}],  e_ll = c_ml q[l][{ml}],
        g_nl = (c_ml q[n][{ml}] + c_mn q[l][{mn}]) / 2
        W_m  = w_m (Ebar/2 (e_nn^2 + e_ll^2 + 2 nu e_nn e_ll) + 2 G g_nl^2)
    mode xi eta zeta:  W_4 = sum_i QH V / 1152 (E / a_i^2 + G / a_j^2 + G / a_k^2) q[i][3]^2

with ``Ebar = E / (1 - nu^2)``; the generalised hourglass forces are
``Q = dW/dq``. They are a state (as in the FB stiffness form): rotated with the
element (Hughes-Winget) and incremented by ``dt dQ/dq . qd`` in the current
frame, so the form is co-rotational and incremental. The moduli follow the law's
current tangent; when they change, the stored state is first rescaled by
:func:`passive_scale` so that its stored energy is kept to first order in G / K and
never raised (docs/elements.md, "Passive rule"). Units: mm, mm/ms, kN, GPa.
"""

from __future__ import annotations

import math

from numba import njit

from hollowbody.elements.hourglass import rotate_rows

_TINY = 1e-300


@njit(cache=True, inline="always", fastmath={"contract"})
def element_frame(xe, fr):
    """Kernel: co-rotational frame and half-lengths of a hexahedron.

    xe (8, 3) mm nodal positions (any origin); fr (3, 3) receives the unit
    vectors ``e_k`` as its *columns* (``fr[:, 0]`` along the Jacobian column
    d x / d xi at the centre, ``fr[:, 1]`` in the xi-eta plane, ``fr[:, 2]`` their
    cross product). Returns the half-lengths (a_0, a_1, a_2) mm, the norms of the
    centre Jacobian's columns (the semi-axes of a rectangular element).
    """
    # centre Jacobian columns j_k = (1/8) sum_a xi_k,a x_a (LS-DYNA node order)
    j00 = j01 = j02 = j10 = j11 = j12 = j20 = j21 = j22 = 0.0
    for i in range(3):
        p0, p1, p2, p3 = xe[0, i], xe[1, i], xe[2, i], xe[3, i]
        p4, p5, p6, p7 = xe[4, i], xe[5, i], xe[6, i], xe[7, i]
        gx = 0.125 * (-p0 + p1 + p2 - p3 - p4 + p5 + p6 - p7)
        gy = 0.125 * (-p0 - p1 + p2 + p3 - p4 - p5 + p6 + p7)
        gz = 0.125 * (-p0 - p1 - p2 - p3 + p4 + p5 + p6 + p7)
        if i == 0:
            j00, j10, j20 = gx, gy, gz
        elif i == 1:
            j01, j11, j21 = gx, gy, gz
        else:
            j02, j12, j22 = gx, gy, gz
    # j0 = (j00, j01, j02), j1 = (j10, j11, j12), j2 = (j20, j21, j22)
    a0 = math.sqrt(j00 * j00 + j01 * j01 + j02 * j02)
    a1 = math.sqrt(j10 * j10 + j11 * j11 + j12 * j12)
    a2 = math.sqrt(j20 * j20 + j21 * j21 + j22 * j22)
    s = 1.0 / max(a0, _TINY)
    u0, u1, u2 = j00 * s, j01 * s, j02 * s
    d = j10 * u0 + j11 * u1 + j12 * u2
    w0, w1, w2 = j10 - d * u0, j11 - d * u1, j12 - d * u2
    s = 1.0 / max(math.sqrt(w0 * w0 + w1 * w1 + w2 * w2), _TINY)
    w0 *= s
    w1 *= s
    w2 *= s
    fr[0, 0], fr[1, 0], fr[2, 0] = u0, u1, u2
    fr[0, 1], fr[1, 1], fr[2, 1] = w0, w1, w2
    fr[0, 2] = u1 * w2 - u2 * w1
    fr[1, 2] = u2 * w0 - u0 * w2
    fr[2, 2] = u0 * w1 - u1 * w0
    return max(a0, _TINY), max(a1, _TINY), max(a2, _TINY)


@njit(cache=True, inline="always", fastmath={"contract"})
def _plane(w, ebar, nu, g2, cn, cl, rn, rl, sn, sl):
    """Block of one strain-gradient direction: returns (dQ_nn, dQ_ll, dQ_n-shear, dQ_l-shear).

    rn, rl: rates of the two normal-strain amplitudes; sn, sl: rates of the two
    shear amplitudes (sn with factor cl, sl with factor cn); w weight, cn, cl the
    1/(8 a a) factors; g2 = 2 G.
    """
    enn = cn * rn
    ell = cl * rl
    gnl = 0.5 * (cl * sn + cn * sl)
    snn = ebar * (enn + nu * ell)
    sll = ebar * (ell + nu * enn)
    t = g2 * gnl
    return w * snn * cn, w * sll * cl, w * t * cl, w * t * cn


@njit(cache=True, inline="always", fastmath={"contract"})
def assumed_strain_product(qh, e_mod, nu, shear, vol, fr, a0, a1, a2, qd, out):
    """Kernel: out (4, 3) = K qd, the assumed-strain hourglass stiffness times qd.

    qh: QH; e_mod, nu, shear: Young's modulus (GPa), Poisson ratio, shear modulus
    (GPa); vol mm^3; fr (3, 3) frame and a0..a2 half-lengths from
    :func:`element_frame`; qd (4, 3) hourglass amplitudes (or rates; global
    components). Units of out: kN per mm of qd (kN/ms for rates).
    """
    # local amplitudes r[i][alpha] = e_i . qd_alpha
    r00 = fr[0, 0] * qd[0, 0] + fr[1, 0] * qd[0, 1] + fr[2, 0] * qd[0, 2]
    r10 = fr[0, 1] * qd[0, 0] + fr[1, 1] * qd[0, 1] + fr[2, 1] * qd[0, 2]
    r20 = fr[0, 2] * qd[0, 0] + fr[1, 2] * qd[0, 1] + fr[2, 2] * qd[0, 2]
    r01 = fr[0, 0] * qd[1, 0] + fr[1, 0] * qd[1, 1] + fr[2, 0] * qd[1, 2]
    r11 = fr[0, 1] * qd[1, 0] + fr[1, 1] * qd[1, 1] + fr[2, 1] * qd[1, 2]
    r21 = fr[0, 2] * qd[1, 0] + fr[1, 2] * qd[1, 1] + fr[2, 2] * qd[1, 2]
    r02 = fr[0, 0] * qd[2, 0] + fr[1, 0] * qd[2, 1] + fr[2, 0] * qd[2, 2]
    r12 = fr[0, 1] * qd[2, 0] + fr[1, 1] * qd[2, 1] + fr[2, 1] * qd[2, 2]
    r22 = fr[0, 2] * qd[2, 0] + fr[1, 2] * qd[2, 1] + fr[2, 2] * qd[2, 2]
    r03 = fr[0, 0] * qd[3, 0] + fr[1, 0] * qd[3, 1] + fr[2, 0] * qd[3, 2]
    r13 = fr[0, 1] * qd[3, 0] + fr[1, 1] * qd[3, 1] + fr[2, 1] * qd[3, 2]
    r23 = fr[0, 2] * qd[3, 0] + fr[1, 2] * qd[3, 1] + fr[2, 2] * qd[3, 2]
    ebar = e_mod / (1.0 - nu * nu)
    g2 = 2.0 * shear
    c01 = 0.125 / (a0 * a1)
    c12 = 0.125 / (a1 * a2)
    c02 = 0.125 / (a0 * a2)
    s = qh * vol / 3.0
    # mode index: 0 = {0,1} (xi eta), 1 = {1,2} (eta zeta), 2 = {2,0} (zeta xi)
    # block m = 0 (n, l = 1, 2): normal q[1][{01}], q[2][{02}]; shear q[1][{02}], q[2][{01}]
    d10, d22, d12, d20 = _plane(s * a0 * a0, ebar, nu, g2, c01, c02, r10, r22, r12, r20)
    # block m = 1 (n, l = 0, 2): normal q[0][{01}], q[2][{12}]; shear q[0][{12}], q[2][{01}]
    d00, d21, d01, t20 = _plane(s * a1 * a1, ebar, nu, g2, c01, c12, r00, r21, r01, r20)
    # block m = 2 (n, l = 0, 1): normal q[0][{02}], q[1][{12}]; shear q[0][{12}], q[1][{02}]
    d02, d11, t01, t12 = _plane(s * a2 * a2, ebar, nu, g2, c02, c12, r02, r11, r01, r12)
    d20 += t20
    d01 += t01
    d12 += t12
    # mode xi eta zeta: diagonal, QH V / 576 (E / a_i^2 + G / a_j^2 + G / a_k^2)
    k4 = qh * vol / 576.0
    i0 = 1.0 / (a0 * a0)
    i1 = 1.0 / (a1 * a1)
    i2 = 1.0 / (a2 * a2)
    d03 = k4 * (e_mod * i0 + shear * (i1 + i2)) * r03
    d13 = k4 * (e_mod * i1 + shear * (i0 + i2)) * r13
    d23 = k4 * (e_mod * i2 + shear * (i0 + i1)) * r23
    for m in range(4):
        if m == 0:
            l0, l1, l2 = d00, d10, d20
        elif m == 1:
            l0, l1, l2 = d01, d11, d21
        elif m == 2:
            l0, l1, l2 = d02, d12, d22
        else:
            l0, l1, l2 = d03, d13, d23
        # back to global components: sum_i e_i dQ[i]
        out[m, 0] = fr[0, 0] * l0 + fr[0, 1] * l1 + fr[0, 2] * l2
        out[m, 1] = fr[1, 0] * l0 + fr[1, 1] * l1 + fr[1, 2] * l2
        out[m, 2] = fr[2, 0] * l0 + fr[2, 1] * l1 + fr[2, 2] * l2


@njit(cache=True, inline="always", fastmath={"contract"})
def passive_scale(g_new, g_old, bulk):
    """The factor on the stored state when the shear modulus moves from g_old to g_new.

    ``K_as(G) = G A + P(G) B + E(G) C`` with fixed positive semi-definite A, B, C
    (geometry) and the plane-stress modulus ``P = E / (1 - nu) = 18 K G / (3K + 4G)``,
    ``E = 9 K G / (3K + G)`` (bulk K fixed). The moduli's ratios ``r_G = g_new / g_old``,
    ``r_P``, ``r_E`` satisfy ``min(r_G, r_P) <= r_E <= max(r_G, r_P)``, hence
    ``min(r_G, r_P) K_old <= K_new <= max(r_G, r_P) K_old`` (Loewner order).
    Returns ``sqrt(min(r_G, r_P))``: scaling the stored forces Q (IHQ 6) by it gives
    ``Q . K_new^-1 Q <= Q . K_old^-1 Q`` unchanged or smaller, equal to first order
    in G / K (exactly, for the G part). For the stored displacement d (IHQ 7) call it
    with g_new and g_old swapped: ``sqrt(min(1 / r_G, 1 / r_P))``, and
    ``d . K_new d <= d . K_old d``. Returns 1 when g_old <= 0 (first call).
    """
    if g_old <= 0.0 or g_new == g_old:
        return 1.0
    r_g = g_new / g_old
    r_p = r_g * (3.0 * bulk + 4.0 * g_old) / (3.0 * bulk + 4.0 * g_new)
    return math.sqrt(min(r_g, r_p))


@njit(cache=True, inline="always", fastmath={"contract"})
def assumed_strain_hourglass(qh, e_mod, nu, shear, bulk, vol, dt, rot, fr, a0, a1, a2, qd,
                             state, hgmod, e, qf):
    """Kernel: incremental assumed-strain hourglass forces (IHQ 6) of element ``e``.

    Moduli, vol, fr, a0..a2 as :func:`assumed_strain_product`; dt ms; rot (3, 3)
    incremental rotation; qd (4, 3) mm/ms hourglass rates (global components);
    bulk GPa the bulk modulus; state (e, 4, 3) kN generalised hourglass forces,
    rotated, scaled by ``passive_scale(shear, hgmod[e], bulk)`` and incremented by
    ``dt K qd`` in place;
    hgmod (e,) GPa the shear modulus of the last call (set to ``shear``); qf (4, 3)
    receives the forces. Returns the work increment
    ``dt (Q_old_rotated + Q_new) / 2 . qd`` (J) with the forces of the last call.
    """
    s = passive_scale(shear, hgmod[e], bulk)
    hgmod[e] = shear
    assumed_strain_product(qh, e_mod, nu, shear, vol, fr, a0, a1, a2, qd, qf)
    w = 0.0
    for m in range(4):
        r0, r1, r2 = rotate_rows(rot, state, e, m)
        n0 = s * r0 + dt * qf[m, 0]
        n1 = s * r1 + dt * qf[m, 1]
        n2 = s * r2 + dt * qf[m, 2]
        w += 0.5 * dt * ((r0 + n0) * qd[m, 0] + (r1 + n1) * qd[m, 1] + (r2 + n2) * qd[m, 2])
        state[e, m, 0] = n0
        state[e, m, 1] = n1
        state[e, m, 2] = n2
        qf[m, 0] = n0
        qf[m, 1] = n1
        qf[m, 2] = n2
    return w


@njit(cache=True, inline="always", fastmath={"contract"})
def assumed_strain_total(qh, e_mod, nu, shear, bulk, vol, dt, rot, fr, a0, a1, a2, qd, state,
                         disp, hgmod, e, qf, work):
    """Kernel: total-displacement assumed-strain hourglass forces (IHQ 7) of element ``e``.

    As :func:`assumed_strain_hourglass`, but the state is the hourglass
    displacement ``disp`` (e, 4, 3) mm (rotated with the element, scaled by
    ``passive_scale(hgmod[e], shear, bulk)`` and incremented by ``dt qd``) and the forces
    are ``Q = K disp`` with the current stiffness; state (e, 4, 3) keeps the forces
    of the last call (work of the step); hgmod (e,) GPa as there. work (4, 3)
    scratch. Returns the work increment (J).
    """
    s = passive_scale(hgmod[e], shear, bulk)
    hgmod[e] = shear
    for m in range(4):
        d0, d1, d2 = rotate_rows(rot, disp, e, m)
        disp[e, m, 0] = s * d0 + dt * qd[m, 0]
        disp[e, m, 1] = s * d1 + dt * qd[m, 1]
        disp[e, m, 2] = s * d2 + dt * qd[m, 2]
        work[m, 0] = disp[e, m, 0]
        work[m, 1] = disp[e, m, 1]
        work[m, 2] = disp[e, m, 2]
    assumed_strain_product(qh, e_mod, nu, shear, vol, fr, a0, a1, a2, work, qf)
    w = 0.0
    for m in range(4):
        o0, o1, o2 = rotate_rows(rot, state, e, m)
        n0, n1, n2 = qf[m, 0], qf[m, 1], qf[m, 2]
        w += 0.5 * dt * ((o0 + n0) * qd[m, 0] + (o1 + n1) * qd[m, 1] + (o2 + n2) * qd[m, 2])
        state[e, m, 0] = n0
        state[e, m, 1] = n1
        state[e, m, 2] = n2
    return w
