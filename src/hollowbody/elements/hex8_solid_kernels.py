"""Fused element kernels: one-point hexahedron + material, one per material law.

Each kernel runs, per element (``prange`` over chunks of elements, so every
chunk allocates its small scratch arrays once and reduces its own energies
and minimum time step, race-free):

1. gather nodal positions (relative to node N1, for round-off) and velocities;
2. exact volume and uniform gradients b (hex8_kinematics); ``L_end = sum v (x) b``,
   mid-step ``L_mid = (I - dt/2 L_end)^-1 L_end``, ``D = sym(L_mid)``,
   Hughes-Winget rotation ``Q`` from ``W = skew(L_mid)``;
3. material update (stress at t^{n+1});
4. bulk viscosity ``q = rho l (Q1 l trD^2 - Q2 c trD)`` for trD < 0 (LS-DYNA; l = V^(1/3));
5. nodal forces ``f_a = -V (sigma - q I) b_a`` written to the element's own slots of
   ``fwork`` (e, 8, 3), plus the hourglass forces (hourglass);
6. critical time step ``L_e / (Q + sqrt(Q^2 + c^2))`` (time_step).

Energies (J) per chunk. The work of each element's forces over the step is
computed as the central-difference scheme does it,
``-dt v^{n+1/2} . (f^n + f^{n+1}) / 2`` (``f^n`` is still in ``fwork`` when the
element is reached), so internal + hourglass energy balances the kinetic
energy to the scheme's accuracy. Hourglass = the hourglass part (trapezoidal
with the previous generalised hourglass forces kept per element); internal =
the rest (stress work including bulk viscosity and material damping).
``out`` (nchunk, 5) receives (internal, hourglass, dt_min, index of dt_min,
first index with V <= 0 or -1). Dead elements (alive False) get zero forces
and dt = inf.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from hollowbody.elements.hex8_kinematics import (
    hex8_max_face_area,
    hex8_volume_derivatives,
    hughes_winget,
    midpoint_velocity_gradient,
    rotate_sym,
    velocity_gradient,
)
from hollowbody.elements.hourglass import (
    hourglass_add_forces,
    hourglass_hx,
    hourglass_rates,
    hourglass_stiffness,
    hourglass_viscous,
)
from hollowbody.elements.time_step import critical_time_step
from hollowbody.materials import mat001_elastic as m001
from hollowbody.materials import mat181_simplified_rubber as m181
from hollowbody.materials.mat001_elastic import elastic_update
from hollowbody.materials.mat181_simplified_rubber import rubber_deviatoric, rubber_friction

#: Indices into the hourglass/bulk-viscosity parameter vector ``hg``.
H_IHQ, H_QH, H_Q1, H_Q2 = range(4)

_THIRD = 1.0 / 3.0


@njit(cache=True, inline="always", fastmath={"contract"})
def _kinematics(e, conn, x, v, dt, xe, ve, bt, lg, lm, rot):
    """Gather element e and compute b (in bt), L_end (lg), L_mid (lm), Q (rot); returns V."""
    n0 = conn[e, 0]
    ox, oy, oz = x[n0, 0], x[n0, 1], x[n0, 2]
    for a in range(8):
        n = conn[e, a]
        xe[a, 0] = x[n, 0] - ox
        xe[a, 1] = x[n, 1] - oy
        xe[a, 2] = x[n, 2] - oz
        ve[a, 0] = v[n, 0]
        ve[a, 1] = v[n, 1]
        ve[a, 2] = v[n, 2]
    vol = hex8_volume_derivatives(xe, bt)
    if vol <= 0.0:
        return vol
    inv = 1.0 / vol
    for a in range(8):
        bt[a, 0] *= inv
        bt[a, 1] *= inv
        bt[a, 2] *= inv
    velocity_gradient(ve, bt, lg)
    for i in range(3):
        for j in range(3):
            lm[i, j] = lg[i, j]
    midpoint_velocity_gradient(lm, dt)
    hughes_winget(lm, dt, rot)
    return vol


@njit(cache=True, inline="always", fastmath={"contract"})
def _stress_forces(vol, s0, s1, s2, s3, s4, s5, b, fwork, e):
    """fwork[e, a] = -V sigma b_a (kN) (overwrites the element's slots).

    Arrays are indexed, never sliced, inside the parallel loop: a slice would
    update the shared array's reference count atomically from every thread.
    """
    for a in range(8):
        bx, by, bz = b[a, 0], b[a, 1], b[a, 2]
        fwork[e, a, 0] = -vol * (s0 * bx + s3 * by + s5 * bz)
        fwork[e, a, 1] = -vol * (s3 * bx + s1 * by + s4 * bz)
        fwork[e, a, 2] = -vol * (s5 * bx + s4 * by + s2 * bz)


@njit(cache=True, inline="always", fastmath={"contract"})
def _power(ve, fwork, e):
    """sum_a v_a . fwork[e, a] (J/ms)."""
    p = 0.0
    for a in range(8):
        p += ve[a, 0] * fwork[e, a, 0] + ve[a, 1] * fwork[e, a, 1] + ve[a, 2] * fwork[e, a, 2]
    return p


@njit(cache=True, inline="always", fastmath={"contract"})
def _zero(fwork, e):
    for a in range(8):
        fwork[e, a, 0] = 0.0
        fwork[e, a, 1] = 0.0
        fwork[e, a, 2] = 0.0


@njit(cache=True, inline="always", fastmath={"contract"})
def _hourglass(e, ihq, qh, rho, modulus, c, vol, l, dt, xe, ve, b, lg, rot, hx, qd, qf,
               hgstate, fwork):
    """Adds hourglass forces to fwork[e]; returns the hourglass work increment (J)."""
    hourglass_hx(xe, hx)
    hourglass_rates(ve, lg, hx, qd)
    if ihq >= 4:
        bb = 0.0
        for a in range(8):
            bb += b[a, 0] * b[a, 0] + b[a, 1] * b[a, 1] + b[a, 2] * b[a, 2]
        kappa = qh * modulus * vol * bb / 24.0
        w = hourglass_stiffness(kappa, dt, rot, qd, hgstate, e, qf)
    else:
        ah = 0.25 * qh * rho * c * l * l
        w = hourglass_viscous(ah, dt, rot, qd, hgstate, e, qf)
    hourglass_add_forces(qf, hx, b, fwork, e)
    return w


@njit(cache=True, inline="always", fastmath={"contract"})
def _bulk_q(rho, l, c, trd, q1, q2):
    """Bulk-viscosity pressure (GPa), > 0 in compression, 0 in expansion."""
    if trd < 0.0:
        return rho * l * (q1 * l * trd * trd - q2 * c * trd)
    return 0.0


@njit(cache=True, parallel=True, fastmath={"contract"})
def hex8_elastic_kernel(conn, x, v, dt, alive, lfac, stress, volume, volume0, hgstate,
                        fwork, dt_elem, c_elem, mp, hg, bounds, out):
    """Hexahedron + *MAT_ELASTIC for one group (see module docstring).

    conn (e, 8) int32; x, v (n, 3); dt ms; alive (e,) bool; lfac (e,) length
    factor (1, or 3 for tetrahedra); stress (e, 6) GPa in/out; volume (e,) in
    (previous) / out (current) mm^3; volume0 (e,); hgstate (e, 4, 3) kN
    generalised hourglass forces of the last call; fwork (e, 8, 3) kN out;
    dt_elem, c_elem (e,) out; mp packed elastic parameters; hg (4,) ihq, QH,
    Q1, Q2; bounds (nchunk + 1,) element ranges; out (nchunk, 5).
    """
    lam = mp[m001.P_LAMBDA]
    mu = mp[m001.P_MU]
    rho0 = mp[m001.P_RHO]
    c = mp[m001.P_C]
    modulus = lam + 2.0 * mu
    ihq = int(hg[H_IHQ])
    qh, q1, q2 = hg[H_QH], hg[H_Q1], hg[H_Q2]
    nchunk = bounds.shape[0] - 1
    for ck in prange(nchunk):
        xe = np.empty((8, 3))
        ve = np.empty((8, 3))
        bt = np.empty((8, 3))
        lg = np.empty((3, 3))
        lm = np.empty((3, 3))
        rot = np.empty((3, 3))
        hx = np.empty((4, 3))
        qd = np.empty((4, 3))
        qf = np.empty((4, 3))
        eint = 0.0
        ehg = 0.0
        dtmin = np.inf
        imin = -1
        ineg = -1
        for e in range(bounds[ck], bounds[ck + 1]):
            if not alive[e]:
                _zero(fwork, e)
                dt_elem[e] = np.inf
                continue
            vol = _kinematics(e, conn, x, v, dt, xe, ve, bt, lg, lm, rot)
            volume[e] = vol
            w_old = _power(ve, fwork, e)
            if vol <= 0.0:
                if ineg < 0:
                    ineg = e
                eint -= 0.5 * dt * w_old
                _zero(fwork, e)
                dt_elem[e] = np.inf
                continue
            d0 = dt * lm[0, 0]
            d1 = dt * lm[1, 1]
            d2 = dt * lm[2, 2]
            d3 = 0.5 * dt * (lm[0, 1] + lm[1, 0])
            d4 = 0.5 * dt * (lm[1, 2] + lm[2, 1])
            d5 = 0.5 * dt * (lm[2, 0] + lm[0, 2])
            r0, r1, r2, r3, r4, r5 = rotate_sym(rot, stress[e, 0], stress[e, 1], stress[e, 2],
                                                stress[e, 3], stress[e, 4], stress[e, 5])
            n0, n1, n2, n3, n4, n5 = elastic_update(r0, r1, r2, r3, r4, r5,
                                                    d0, d1, d2, d3, d4, d5, lam, mu)
            stress[e, 0] = n0
            stress[e, 1] = n1
            stress[e, 2] = n2
            stress[e, 3] = n3
            stress[e, 4] = n4
            stress[e, 5] = n5
            rho = rho0 * volume0[e] / vol
            l = vol ** _THIRD
            trd = lm[0, 0] + lm[1, 1] + lm[2, 2]
            qb = _bulk_q(rho, l, c, trd, q1, q2)
            _stress_forces(vol, n0 - qb, n1 - qb, n2 - qb, n3, n4, n5, bt, fwork, e)
            dhg = 0.0
            if qh > 0.0:
                dhg = _hourglass(e, ihq, qh, rho, modulus, c, vol, l, dt, xe, ve, bt, lg,
                                 rot, hx, qd, qf, hgstate, fwork)
            dw = -0.5 * dt * (w_old + _power(ve, fwork, e))
            eint += dw - dhg
            ehg += dhg
            amax = hex8_max_face_area(xe)
            dte = critical_time_step(lfac[e] * vol / amax, c, l, trd, q1, q2)
            dt_elem[e] = dte
            c_elem[e] = c
            if dte < dtmin:
                dtmin = dte
                imin = e
        out[ck, 0] = eint
        out[ck, 1] = ehg
        out[ck, 2] = dtmin
        out[ck, 3] = imin
        out[ck, 4] = ineg


@njit(cache=True, parallel=True, fastmath={"contract"})
def hex8_rubber_kernel(conn, x, v, dt, alive, lfac, stress, volume, volume0, hgstate,
                       fwork, dt_elem, c_elem, b0, fric, eig, mp, ftab, gtab, hg, bounds, out):
    """Hexahedron + MAT_181 simplified rubber for one group.

    As :func:`hex8_elastic_kernel`, plus b0 (e, 8, 3) 1/mm reference uniform
    gradients (F = sum_a x_a (x) b0_a), fric (e, 6) GPa frictional damping
    stress (may be (1, 6) when G = 0), eig (e, 3, 3) eigenvectors of F F^T of the
    last call (warm start of the eigen-solver), mp packed MAT_181 parameters, ftab/gtab
    (N,) GPa tables of f and its tangent.
    """
    bulk = mp[m181.P_BULK]
    mu_d = mp[m181.P_MU]
    g0 = mp[m181.P_G0]
    rho0 = mp[m181.P_RHO]
    cs = mp[m181.P_CS]
    gf = mp[m181.P_GF]
    sigf = mp[m181.P_SIGF]
    ln0 = mp[m181.P_LN0]
    invd = mp[m181.P_INVD]
    use_fric = gf > 0.0 and sigf > 0.0
    ihq = int(hg[H_IHQ])
    qh, q1, q2 = hg[H_QH], hg[H_Q1], hg[H_Q2]
    nchunk = bounds.shape[0] - 1
    for ck in prange(nchunk):
        xe = np.empty((8, 3))
        ve = np.empty((8, 3))
        bt = np.empty((8, 3))
        lg = np.empty((3, 3))
        lm = np.empty((3, 3))
        rot = np.empty((3, 3))
        vec = np.empty((3, 3))
        hx = np.empty((4, 3))
        qd = np.empty((4, 3))
        qf = np.empty((4, 3))
        eint = 0.0
        ehg = 0.0
        dtmin = np.inf
        imin = -1
        ineg = -1
        for e in range(bounds[ck], bounds[ck + 1]):
            if not alive[e]:
                _zero(fwork, e)
                dt_elem[e] = np.inf
                continue
            vol = _kinematics(e, conn, x, v, dt, xe, ve, bt, lg, lm, rot)
            volume[e] = vol
            w_old = _power(ve, fwork, e)
            if vol <= 0.0:
                if ineg < 0:
                    ineg = e
                eint -= 0.5 * dt * w_old
                _zero(fwork, e)
                dt_elem[e] = np.inf
                continue
            # deformation gradient from the reference gradients
            f00 = f01 = f02 = f10 = f11 = f12 = f20 = f21 = f22 = 0.0
            for a in range(8):
                xa, ya, za = xe[a, 0], xe[a, 1], xe[a, 2]
                ba0, ba1, ba2 = b0[e, a, 0], b0[e, a, 1], b0[e, a, 2]
                f00 += xa * ba0
                f01 += xa * ba1
                f02 += xa * ba2
                f10 += ya * ba0
                f11 += ya * ba1
                f12 += ya * ba2
                f20 += za * ba0
                f21 += za * ba1
                f22 += za * ba2
            for i in range(3):
                vec[i, 0] = eig[e, i, 0]
                vec[i, 1] = eig[e, i, 1]
                vec[i, 2] = eig[e, i, 2]
            t0, t1, t2, t3, t4, t5, gt = rubber_deviatoric(f00, f01, f02, f10, f11, f12,
                                                           f20, f21, f22, vec, ftab, gtab,
                                                           ln0, invd)
            for i in range(3):
                eig[e, i, 0] = vec[i, 0]
                eig[e, i, 1] = vec[i, 1]
                eig[e, i, 2] = vec[i, 2]
            jac = vol / volume0[e]
            rho = rho0 / jac
            l = vol ** _THIRD
            gtan = max(g0, gt)
            modulus = bulk + 4.0 / 3.0 * (gtan + gf)
            c = math.sqrt(modulus / rho)
            d0 = lm[0, 0]
            d1 = lm[1, 1]
            d2 = lm[2, 2]
            d3 = 0.5 * (lm[0, 1] + lm[1, 0])
            d4 = 0.5 * (lm[1, 2] + lm[2, 1])
            d5 = 0.5 * (lm[2, 0] + lm[0, 2])
            trd = d0 + d1 + d2
            dm = trd * _THIRD
            eta2 = 2.0 * mu_d * rho * cs * l
            p = bulk * (jac - 1.0)
            ij = 1.0 / jac
            n0 = t0 * ij + p + eta2 * (d0 - dm)
            n1 = t1 * ij + p + eta2 * (d1 - dm)
            n2 = t2 * ij + p + eta2 * (d2 - dm)
            n3 = t3 * ij + eta2 * d3
            n4 = t4 * ij + eta2 * d4
            n5 = t5 * ij + eta2 * d5
            if use_fric:
                r0, r1, r2, r3, r4, r5 = rotate_sym(rot, fric[e, 0], fric[e, 1], fric[e, 2],
                                                    fric[e, 3], fric[e, 4], fric[e, 5])
                r0, r1, r2, r3, r4, r5 = rubber_friction(
                    r0, r1, r2, r3, r4, r5, dt * (d0 - dm), dt * (d1 - dm), dt * (d2 - dm),
                    dt * d3, dt * d4, dt * d5, gf, sigf)
                fric[e, 0] = r0
                fric[e, 1] = r1
                fric[e, 2] = r2
                fric[e, 3] = r3
                fric[e, 4] = r4
                fric[e, 5] = r5
                n0 += r0
                n1 += r1
                n2 += r2
                n3 += r3
                n4 += r4
                n5 += r5
            stress[e, 0] = n0
            stress[e, 1] = n1
            stress[e, 2] = n2
            stress[e, 3] = n3
            stress[e, 4] = n4
            stress[e, 5] = n5
            qb = _bulk_q(rho, l, c, trd, q1, q2)
            _stress_forces(vol, n0 - qb, n1 - qb, n2 - qb, n3, n4, n5, bt, fwork, e)
            dhg = 0.0
            if qh > 0.0:
                dhg = _hourglass(e, ihq, qh, rho, modulus, c, vol, l, dt, xe, ve, bt, lg,
                                 rot, hx, qd, qf, hgstate, fwork)
            dw = -0.5 * dt * (w_old + _power(ve, fwork, e))
            eint += dw - dhg
            ehg += dhg
            amax = hex8_max_face_area(xe)
            dte = critical_time_step(lfac[e] * vol / amax, c, l, trd, q1, q2)
            dt_elem[e] = dte
            c_elem[e] = c
            if dte < dtmin:
                dtmin = dte
                imin = e
        out[ck, 0] = eint
        out[ck, 1] = ehg
        out[ck, 2] = dtmin
        out[ck, 3] = imin
        out[ck, 4] = ineg
