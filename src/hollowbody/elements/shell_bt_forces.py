"""Element kernel of the Belytschko-Lin-Tsay shell and the race-free nodal gather.

One call of :func:`bt_shell_forces` does, for every live element (chunks of
``CHUNK`` elements over threads with ``prange`` for large groups):

1. strain rates from the half-step geometry ``x^{n+1/2} = x^{n+1} - dt/2 v``
   (midpoint rule: a rigid rotation of the chord velocities gives exactly zero
   in-plane strain) and the velocities / angular velocities at t^{n+1/2};
2. through-thickness integration (``nip`` points, plane stress): membrane +
   z * curvature strain increments, material update per point in the
   co-rotational frame (stress, effective plastic strain, back stress),
   resultants N = sum w s, M = sum w z s; transverse shear elastic, uniform,
   Q = SHRF * t * tau;
3. Belytschko-Tsay hourglass control of the 5 modes (in-plane x, y,
   out-of-plane w, rotations about e1, e2) from the half-step geometry;
4. nodal forces and moments from the resultants with the geometry at t^{n+1}::

       f_x = A (B1 Nxx + B2 Nxy),   f_y = A (B2 Nyy + B1 Nxy),   f_z = A (B1 Qxz + B2 Qyz)
       m_x = A (-B2 Myy - B1 Mxy - Qyz/4),   m_y = A (B1 Mxx + B2 Mxy + Qxz/4)

   (the transpose of the strain-rate operator), rotated to global axes and
   stored with a minus sign (force on the node) in ``fe`` (e, 4, 6);
5. the critical time step L_s / c, the internal and hourglass energy
   increments and a representative global stress for output.

Hourglass (per element, generalized rates q = sum_I gamma_I v_I in the local
frame; forces f_I = gamma_I Q). Reference stiffnesses (LS-DYNA's
Belytschko-Tsay stiffness form with r = 1)::

    k_m = E t A (B.B) / 8,   k_w = SHRF G t^3 (B.B) / 12,   k_r = E t^3 A (B.B) / 192

* viscous (IHQ 1, 2, 3 and others): ``Q = QH sqrt(k m) q`` with m the nodal
  mass share rho t A / 4 (k_m, k_w) or the nodal rotational inertia share
  m r^2 (k_r). For a rectangular element (|gamma| = 2) this damps each
  hourglass mode at the fraction QH of the critical damping of the mode under
  the reference stiffness, and the explicit viscous stability limit
  4 QH sqrt(k/m) dt < 2 holds for QH < 0.5 at the shell time step.
* stiffness (IHQ 4, 5): ``Q += QH k q dt`` (stored co-rotationally in ``hgq``);
  with ``kp[K_HG_TANGENT] > 0`` (opt-in, not an LS-DYNA form) the stored Q is
  then multiplied by the section's tangent ratio eta (below): in plastic flow
  the hourglass forces relax to ~eta / (1 - eta) of one step's elastic
  increment (passive; it depends on dt, so it is an experimental setting).

Tangent ratio of a step (per element): eta = W_actual / W_elastic, the
section's incremental work sum_k w_k (s_new - s_old) . de over the elastic
trial's, clipped to [TANGENT_FLOOR, 1] (1 when elastic or at rest); eta_m
with the points' weights of N (membrane modes, drilling), eta_b with the
weights z^2 of M (w and rotation modes). Unloading with the elastic stiffness
keeps the springs passive.

For warped elements the in-plane velocities of a rigid rotation about e1, e2
(omega x z_I) are removed from the membrane hourglass rates (and the
transpose added to the forces), so rigid rotations give no hourglass force.

Drilling stabilization (``kp[K_DRILL] > 0``): each node's angular velocity
about e3 is tied to the element's in-plane spin
``0.5 (B1 . vy - B2 . vx)`` by an elastic moment ``m_I += k (theta_z,I -
spin) dt``, ``k = factor * G t A``; the reaction is an in-plane couple on the
element (power-consistent; zero for rigid motion). With
``kp[K_DRILL_TANGENT] > 0`` (opt-in) the springs load with
eta_m k and unload with k: a yielded section barely loads its drilling spring.
"""

from __future__ import annotations

import math
import sys
import types
from collections.abc import Callable
from types import ModuleType

import numpy as np
from numba import get_num_threads, njit, prange

from hollowbody.elements import shell_bt_kinematics
from hollowbody.elements.kernel_cache import source_stamp
from hollowbody.elements.shell_bt_kinematics import (
    bt_bmatrix,
    bt_geometry,
    bt_hourglass_vector,
    bt_strain_rates,
    characteristic_length,
    dot3,
    rotate_to_global,
)
from hollowbody.materials.plane_stress_plasticity import (
    FASTMATH,
    KIND_ELASTIC,
    P_C,
    P_CS_C,
    P_E,
    P_FAIL,
    P_G,
    P_HK,
    P_NU,
    P_RATE_CURVE,
    YIELD_TOL,
    elastic_plane_stress,
    plane_stress_return,
    rate_factor,
    table_eval,
)

HG_NONE = -1
HG_VISCOUS = 0
HG_STIFFNESS = 1

#: Indices of the kernel control vector ``kp``.
K_SHRF = 0  # transverse shear factor
K_HG_KIND = 1  # HG_NONE, HG_VISCOUS or HG_STIFFNESS
K_QH = 2  # hourglass coefficient
K_DRILL = 3  # drilling stiffness factor (k = factor * G t A per node)
K_THICK_UPDATE = 4  # 1: thickness follows the through-thickness strain
K_DRILL_TANGENT = 5  # 1: drilling moment increments scaled by the element's tangent ratio
K_HG_TANGENT = 6  # 1: stiffness-hourglass increments scaled by the tangent ratio (opt-in)
N_CONTROLS = 7


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def tangent_ratio(w_actual, w_elastic, w_small):
    """Ratio of the actual to the elastic-trial incremental work of a section, in
    [TANGENT_FLOOR, 1]; 1 when the elastic work is below ``w_small`` (no strain
    increment beyond round-off, e.g. a rigid step: the ratio of two round-off
    numbers means nothing)."""
    if w_elastic <= w_small:
        return 1.0
    return min(1.0, max(TANGENT_FLOOR, w_actual / w_elastic))


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def tangent_step(old, inc, eta):
    """A stabilization force after one step: ``old + eta inc`` while it is loaded
    (``old inc >= 0``), ``old + inc`` while it is unloaded (elastic unloading, as a
    plastic section's). Passive: loading from m0 to m1 takes the work
    (m1^2 - m0^2) / (2 eta k) >= the energy stored, (m1^2 - m0^2) / (2 k)."""
    if old * inc >= 0.0:
        return old + eta * inc
    return old + inc


#: Smallest tangent ratio (a fully yielded, perfectly plastic section still keeps
#: this fraction of its elastic stabilization stiffness; docs/shells.md).
TANGENT_FLOOR = 0.01
#: Strain increment below which a step counts as no deformation for the tangent
#: ratio (round-off of a rigid step is ~1e-16; a real step at 1 /s and 1 ns ~1e-12).
TANGENT_STRAIN_SMALL = 1.0e-13


#: The law module of an element loop built by :func:`make_shell_kernel` (each law's
#: loop is compiled from :func:`bt_shell_range` with its own globals, where ``_law``
#: is that law's module; ``_law.KIND`` is then a compile-time constant).
_law: ModuleType | None = None
#: The compiled element loop called by the kernel wrappers (set the same way).
_range: Callable[..., None] | None = None


def bt_shell_range(lo, hi, x, v, w, dt, geom, state, params, history, kp, out):
    """Stresses, nodal forces/moments and time steps of elements ``lo <= i < hi``.

    The element loop of every shell law (Python source; :func:`make_shell_kernel`
    compiles it once per law, with ``_law`` bound to the law's module, so only
    the law's code path is compiled). x (n,3) mm at t^{n+1};
    v (n,3) mm/ms and w (n,3) rad/ms at t^{n+1/2}; dt ms.

    geom = (conn (e,4) int32, tri (e,) bool triangle flags, t0 (e,) mm initial
    thickness, mass_q (e,) kg nodal mass share, r2 (e,) mm^2 rotational inertia
    radius^2, area0 (e,) mm^2 initial areas, zeta, wts (nip,) rule on [-1, 1]).

    state, updated in place = (alive (e,) bool (set False here when every point
    failed), thick (e,) mm thickness used (updated when ``update_thickness``),
    ezz (e,) accumulated thickness log strain, sig (e,nip,3) local in-plane
    stress GPa, tau (e,2) GPa transverse shear (xz, yz), hgq (e,5)
    stiffness-hourglass generalized forces, drill (e,4) kN*mm drilling
    moments, nrm (e,3) unit normal of the last call).

    params = (mp packed material parameters, hx, hy hardening table, rx, ry
    rate curve); history = (epsp (e,nip), back (e,nip,3) or (1,1,3) when no
    kinematic hardening, pfail (e,nip) uint8): the law's, updated in place;
    kp (N_CONTROLS,) controls K_*.

    out = (fe (e,4,6) kN, kN*mm forces and moments on the element's nodes,
    dte (e,) ms critical steps (inf for dead elements), die, dhe (e,) J energy
    increments, stress_out (e,6) GPa global, pmax (e,) max eps_p over points,
    flip (e,) uint8: 1 when the element collapsed in its own plane: its area
    fell below ``COLLAPSED_AREA`` x its initial area, or its normal turned by
    more than 90 degrees in one step (crushed through zero area, inside out;
    the stored normal is then kept). The solver stops or erodes it).
    """
    conn, tri, t0, mass_q, r2, area0, zeta, wts = geom
    alive, thick, ezz, sig, tau, hgq, drill, nrm = state
    fe, dte, die, dhe, stress_out, pmax, flip = out
    mp, hx, hy, rx, ry = params
    epsp, back, pfail = history
    nip = zeta.shape[0]
    shrf = kp[K_SHRF]
    hg_kind = int(kp[K_HG_KIND])
    qh = kp[K_QH]
    drill_k = kp[K_DRILL]
    update_thickness = kp[K_THICK_UPDATE] > 0.0
    drill_tangent = kp[K_DRILL_TANGENT] > 0.0
    hg_tangent = kp[K_HG_TANGENT] > 0.0
    tangent_on = drill_tangent or hg_tangent  # the ratios below are read only then
    kind = _law.KIND
    e_mod = mp[P_E]
    nu = mp[P_NU]
    g_mod = mp[P_G]
    c_wave = mp[P_C]
    has_back = mp[P_HK] > 0.0
    rate_on = mp[P_CS_C] > 0.0 or mp[P_RATE_CURVE] > 0.0
    fail = mp[P_FAIL]
    hdt = 0.5 * dt
    for i in range(lo, hi):
        flip[i] = 0
        if not alive[i]:
            for a in range(4):
                for j in range(6):
                    fe[i, a, j] = 0.0
            dte[i] = np.inf
            die[i] = 0.0
            dhe[i] = 0.0
            continue
        n0 = conn[i, 0]
        n1 = conn[i, 1]
        n2 = conn[i, 2]
        n3 = conn[i, 3]
        v0 = (v[n0, 0], v[n0, 1], v[n0, 2])
        v1 = (v[n1, 0], v[n1, 1], v[n1, 2])
        v2 = (v[n2, 0], v[n2, 1], v[n2, 2])
        v3 = (v[n3, 0], v[n3, 1], v[n3, 2])
        w0 = (w[n0, 0], w[n0, 1], w[n0, 2])
        w1 = (w[n1, 0], w[n1, 1], w[n1, 2])
        w2 = (w[n2, 0], w[n2, 1], w[n2, 2])
        w3 = (w[n3, 0], w[n3, 1], w[n3, 2])
        # -- half-step geometry and strain rates
        e1h, e2h, e3h, xlh, ylh, zlh, ah = bt_geometry(
            (x[n0, 0] - hdt * v0[0], x[n0, 1] - hdt * v0[1], x[n0, 2] - hdt * v0[2]),
            (x[n1, 0] - hdt * v1[0], x[n1, 1] - hdt * v1[1], x[n1, 2] - hdt * v1[2]),
            (x[n2, 0] - hdt * v2[0], x[n2, 1] - hdt * v2[1], x[n2, 2] - hdt * v2[2]),
            (x[n3, 0] - hdt * v3[0], x[n3, 1] - hdt * v3[1], x[n3, 2] - hdt * v3[2]))
        b1h, b2h = bt_bmatrix(xlh, ylh, ah)
        vx = (dot3(v0, e1h), dot3(v1, e1h), dot3(v2, e1h), dot3(v3, e1h))
        vy = (dot3(v0, e2h), dot3(v1, e2h), dot3(v2, e2h), dot3(v3, e2h))
        vz = (dot3(v0, e3h), dot3(v1, e3h), dot3(v2, e3h), dot3(v3, e3h))
        tx = (dot3(w0, e1h), dot3(w1, e1h), dot3(w2, e1h), dot3(w3, e1h))
        ty = (dot3(w0, e2h), dot3(w1, e2h), dot3(w2, e2h), dot3(w3, e2h))
        dxx, dyy, gxy, kxx, kyy, kxy, gxz, gyz = bt_strain_rates(b1h, b2h, vx, vy, vz, tx, ty)
        # -- through-thickness integration
        t = thick[i]
        h2 = 0.5 * t
        nxx = 0.0
        nyy = 0.0
        nxy = 0.0
        mxx = 0.0
        myy = 0.0
        mxy = 0.0
        work = 0.0
        dzz = 0.0
        pm = 0.0
        nfail = 0
        # tangent ratios: actual / elastic-trial incremental work, uniform (membrane) and
        # z^2-weighted (bending) over the points
        wa_m = 0.0
        we_m = 0.0
        wa_b = 0.0
        we_b = 0.0
        for k in range(nip):
            z = zeta[k] * h2
            wk = wts[k] * h2
            exx = (dxx + z * kxx) * dt
            eyy = (dyy + z * kyy) * dt
            exy = (gxy + z * kxy) * dt
            s0 = sig[i, k, 0]
            s1 = sig[i, k, 1]
            s2 = sig[i, k, 2]
            # the law's point update (its code path is a compile-time constant)
            dsp = 0.0
            if kind == KIND_ELASTIC:
                q0, q1, q2 = elastic_plane_stress(s0, s1, s2, exx, eyy, exy, e_mod, nu)
            elif pfail[i, k] != 0:
                q0 = 0.0
                q1 = 0.0
                q2 = 0.0
                nfail += 1
            else:
                rf = 1.0
                if rate_on and dt > 0.0:
                    rf = rate_factor(mp, rx, ry, exx / dt, eyy / dt, exy / dt)
                a0 = 0.0
                a1 = 0.0
                a2 = 0.0
                if has_back:
                    a0 = back[i, k, 0]
                    a1 = back[i, k, 1]
                    a2 = back[i, k, 2]
                epn = epsp[i, k]
                # elastic trial and yield check here; the return mapping only when needed
                q0, q1, q2 = elastic_plane_stress(s0, s1, s2, exx, eyy, exy, e_mod, nu)
                if tangent_on:
                    dwe = (q0 - s0) * exx + (q1 - s1) * eyy + (q2 - s2) * exy
                    we_m += wk * dwe
                    we_b += wk * z * z * dwe
                x0 = q0 - a0
                x1 = q1 - a1
                x2 = q2 - a2
                sy, _ = table_eval(epn, hx, hy)
                sy *= rf
                if x0 * x0 - x0 * x1 + x1 * x1 + 3.0 * x2 * x2 > sy * sy * (1.0 + YIELD_TOL):
                    q0, q1, q2, a0, a1, a2, epn, dsp = plane_stress_return(
                        s0, s1, s2, a0, a1, a2, epn, exx, eyy, exy, e_mod, nu, mp[P_HK], hx,
                        hy, rf)
                if has_back:
                    back[i, k, 0] = a0
                    back[i, k, 1] = a1
                    back[i, k, 2] = a2
                epsp[i, k] = epn
                if tangent_on:
                    dwa = (q0 - s0) * exx + (q1 - s1) * eyy + (q2 - s2) * exy
                    wa_m += wk * dwa
                    wa_b += wk * z * z * dwa
                pm = max(pm, epn)
                if fail > 0.0 and epn >= fail:
                    pfail[i, k] = 1
                    nfail += 1
            sig[i, k, 0] = q0
            sig[i, k, 1] = q1
            sig[i, k, 2] = q2
            work += wk * 0.5 * ((s0 + q0) * exx + (s1 + q1) * eyy + (s2 + q2) * exy)
            dzz += wk * (-(nu / e_mod) * ((q0 + q1) - (s0 + s1)) - dsp)
            nxx += wk * q0
            nyy += wk * q1
            nxy += wk * q2
            mxx += wk * z * q0
            myy += wk * z * q1
            mxy += wk * z * q2
        eta_m = 1.0
        eta_b = 1.0
        if tangent_on:
            e_small = e_mod * TANGENT_STRAIN_SMALL * TANGENT_STRAIN_SMALL * t
            eta_m = tangent_ratio(wa_m, we_m, e_small)
            eta_b = tangent_ratio(wa_b, we_b, e_small * h2 * h2)
        # transverse shear: elastic, uniform through the thickness, SHRF on the resultant
        to0 = tau[i, 0]
        to1 = tau[i, 1]
        tn0 = to0 + g_mod * gxz * dt
        tn1 = to1 + g_mod * gyz * dt
        if nfail == nip and nip > 0:
            tn0 = 0.0
            tn1 = 0.0
        tau[i, 0] = tn0
        tau[i, 1] = tn1
        qxz = shrf * t * tn0
        qyz = shrf * t * tn1
        work += shrf * t * 0.5 * ((to0 + tn0) * gxz + (to1 + tn1) * gyz) * dt
        die[i] = ah * work
        ezz[i] += dzz / t
        if update_thickness:
            thick[i] = t0[i] * math.exp(ezz[i])
        pmax[i] = pm
        if nfail == nip and nip > 0:  # every point failed: delete the element
            alive[i] = False
            for a in range(4):
                for j in range(6):
                    fe[i, a, j] = 0.0
            dte[i] = np.inf
            dhe[i] = 0.0
            for j in range(6):
                stress_out[i, j] = 0.0
            continue
        # -- hourglass (half-step geometry and frame)
        gam = bt_hourglass_vector(xlh, ylh, b1h, b2h)
        # warped elements: remove the in-plane velocity of a rigid rotation about e1, e2
        # (omega_x = B2.vz, omega_y = -B1.vz) from the membrane hourglass rates
        zh = gam[0] * zlh[0] + gam[1] * zlh[1] + gam[2] * zlh[2] + gam[3] * zlh[3]
        wzx = b1h[0] * vz[0] + b1h[1] * vz[1] + b1h[2] * vz[2] + b1h[3] * vz[3]
        wzy = b2h[0] * vz[0] + b2h[1] * vz[1] + b2h[2] * vz[2] + b2h[3] * vz[3]
        qmx = gam[0] * vx[0] + gam[1] * vx[1] + gam[2] * vx[2] + gam[3] * vx[3] + zh * wzx
        qmy = gam[0] * vy[0] + gam[1] * vy[1] + gam[2] * vy[2] + gam[3] * vy[3] + zh * wzy
        qw = gam[0] * vz[0] + gam[1] * vz[1] + gam[2] * vz[2] + gam[3] * vz[3]
        qtx = gam[0] * tx[0] + gam[1] * tx[1] + gam[2] * tx[2] + gam[3] * tx[3]
        qty = gam[0] * ty[0] + gam[1] * ty[1] + gam[2] * ty[2] + gam[3] * ty[3]
        bb = 0.0
        for a in range(4):
            bb += b1h[a] * b1h[a] + b2h[a] * b2h[a]
        t3 = t * t * t
        km = e_mod * t * ah * bb * 0.125
        kw = shrf * g_mod * t3 * bb / 12.0
        kr = e_mod * t3 * ah * bb / 192.0
        hmx = 0.0
        hmy = 0.0
        hw = 0.0
        htx = 0.0
        hty = 0.0
        gg = max(gam[0] * gam[0] + gam[1] * gam[1] + gam[2] * gam[2] + gam[3] * gam[3],
                 1.0e-30)
        gm = gg + zh * zh * bb  # membrane modes with the warping coupling
        if hg_kind == HG_VISCOUS:
            mq = mass_q[i]
            cm = qh * math.sqrt(km * mq)
            cw = qh * math.sqrt(kw * mq)
            cr = qh * math.sqrt(kr * mq * r2[i])
            if dt > 0.0:  # explicit limit of a damper: c |gamma|^2 dt / m < 2
                cm = min(cm, HG_DAMP_CAP * mq / (dt * gm))
                cw = min(cw, HG_DAMP_CAP * mq / (dt * gg))
                cr = min(cr, HG_DAMP_CAP * mq * r2[i] / (dt * gg))
            hmx = cm * qmx
            hmy = cm * qmy
            hw = cw * qw
            htx = cr * qtx
            hty = cr * qty
            dhe[i] = dt * (hmx * qmx + hmy * qmy + hw * qw + htx * qtx + hty * qty)
        elif hg_kind == HG_STIFFNESS:
            if dt > 0.0:  # explicit limit of a spring: k |gamma|^2 dt^2 / m < 4
                lim = HG_SPRING_CAP * mass_q[i] / (dt * dt * qh)
                km = min(km, lim / gm)
                kw = min(kw, lim / gg)
                kr = min(kr, lim * r2[i] / gg)
            o0 = hgq[i, 0]
            o1 = hgq[i, 1]
            o2 = hgq[i, 2]
            o3 = hgq[i, 3]
            o4 = hgq[i, 4]
            hmx = o0 + qh * km * qmx * dt
            hmy = o1 + qh * km * qmy * dt
            hw = o2 + qh * kw * qw * dt
            htx = o3 + qh * kr * qtx * dt
            hty = o4 + qh * kr * qty * dt
            if hg_tangent:  # opt-in: the stored forces relax with the tangent ratio
                hmx *= eta_m
                hmy *= eta_m
                hw *= eta_b
                htx *= eta_b
                hty *= eta_b
            hgq[i, 0] = hmx
            hgq[i, 1] = hmy
            hgq[i, 2] = hw
            hgq[i, 3] = htx
            hgq[i, 4] = hty
            dhe[i] = 0.5 * dt * ((o0 + hmx) * qmx + (o1 + hmy) * qmy + (o2 + hw) * qw
                                 + (o3 + htx) * qtx + (o4 + hty) * qty)
        else:
            dhe[i] = 0.0
        # -- drilling stabilization: nodal spin about e3 tied to the element's in-plane spin
        dr0 = 0.0
        dr1 = 0.0
        dr2 = 0.0
        dr3 = 0.0
        sdr = 0.0
        if drill_k > 0.0:
            omz = 0.5 * (b1h[0] * vy[0] + b1h[1] * vy[1] + b1h[2] * vy[2] + b1h[3] * vy[3]
                         - b2h[0] * vx[0] - b2h[1] * vx[1] - b2h[2] * vx[2] - b2h[3] * vx[3])
            kd = drill_k * g_mod * t * ah * dt
            r0 = dot3(w0, e3h) - omz
            r1 = dot3(w1, e3h) - omz
            r2_ = dot3(w2, e3h) - omz
            r3 = dot3(w3, e3h) - omz
            o0 = drill[i, 0]
            o1 = drill[i, 1]
            o2 = drill[i, 2]
            o3 = drill[i, 3]
            if drill_tangent:  # loading with the section's tangent, unloading elastic
                dr0 = tangent_step(o0, kd * r0, eta_m)
                dr1 = tangent_step(o1, kd * r1, eta_m)
                dr2 = tangent_step(o2, kd * r2_, eta_m)
                dr3 = tangent_step(o3, kd * r3, eta_m)
            else:
                dr0 = o0 + kd * r0
                dr1 = o1 + kd * r1
                dr2 = o2 + kd * r2_
                dr3 = o3 + kd * r3
            drill[i, 0] = dr0
            drill[i, 1] = dr1
            drill[i, 2] = dr2
            drill[i, 3] = dr3
            dhe[i] += 0.5 * dt * ((o0 + dr0) * r0 + (o1 + dr1) * r1 + (o2 + dr2) * r2_
                                  + (o3 + dr3) * r3)
            sdr = 0.5 * (dr0 + dr1 + dr2 + dr3)
        drl = (dr0, dr1, dr2, dr3)
        # -- forces with the geometry at t^{n+1}
        e1, e2, e3, xl, yl, _, a = bt_geometry(
            (x[n0, 0], x[n0, 1], x[n0, 2]), (x[n1, 0], x[n1, 1], x[n1, 2]),
            (x[n2, 0], x[n2, 1], x[n2, 2]), (x[n3, 0], x[n3, 1], x[n3, 2]))
        b1, b2 = bt_bmatrix(xl, yl, a)
        for j in range(4):
            fx = a * (b1[j] * nxx + b2[j] * nxy)
            fy = a * (b2[j] * nyy + b1[j] * nxy)
            fz = a * (b1[j] * qxz + b2[j] * qyz)
            mx = a * (-b2[j] * myy - b1[j] * mxy - 0.25 * qyz)
            my = a * (b1[j] * mxx + b2[j] * mxy + 0.25 * qxz)
            gj = gam[j]
            gx = gj * hmx
            gy = gj * hmy
            gz = gj * hw
            gmx = gj * htx
            gmy = gj * hty
            gx += sdr * b2h[j]
            gy -= sdr * b1h[j]
            gz += zh * (b1h[j] * hmx + b2h[j] * hmy)
            gmz = drl[j]
            for c in range(3):
                fe[i, j, c] = -(fx * e1[c] + fy * e2[c] + fz * e3[c]
                                + gx * e1h[c] + gy * e2h[c] + gz * e3h[c])
                fe[i, j, 3 + c] = -(mx * e1[c] + my * e2[c] + gmx * e1h[c] + gmy * e2h[c]
                                    + gmz * e3h[c])
        dte[i] = characteristic_length(xl, yl, a, tri[i]) / c_wave
        if update_thickness:  # stiffness grows with t, the mass stays rho A0 t0
            dte[i] *= math.sqrt(t0[i] / thick[i])
        if (a < COLLAPSED_AREA * area0[i]
                or e3[0] * nrm[i, 0] + e3[1] * nrm[i, 1] + e3[2] * nrm[i, 2] < 0.0):
            flip[i] = 1
        else:
            nrm[i, 0] = e3[0]
            nrm[i, 1] = e3[1]
            nrm[i, 2] = e3[2]
        it = 1.0 / t
        s6 = rotate_to_global(e1, e2, e3, nxx * it, nyy * it, nxy * it, qxz * it, qyz * it)
        for j in range(6):
            stress_out[i, j] = s6[j]


#: Hourglass limiters. On a distorted or strongly warped element (a folded
#: wall) the hourglass vectors gamma and the warping coupling zh * B grow like
#: 1 / area while the step only shrinks like area / longest side; the viscous
#: force c q of a mode then exceeds the explicit limit of a damper (c |g|^2
#: dt / m < 2) and the element gains energy within a few cycles (measured: a
#: folded hollow-block wall element, area 1.3 % of the initial, c |g|^2 dt / m =
#: 6 to 24). Each mode's coefficient is capped so that c |g|^2 dt / m <=
#: HG_DAMP_CAP (viscous) or k |g|^2 dt^2 / m <= HG_SPRING_CAP (stiffness), half
#: and a quarter of the stability limits, with m the element's nodal mass share
#: (a lower bound of the node's mass). Regular elements are below the caps and
#: unchanged (a square at TSSFAC 0.9: c |g|^2 dt / m = 4 QH c dt / L = 0.36 for
#: QH 0.1).
HG_DAMP_CAP = 1.0
HG_SPRING_CAP = 1.0

#: An element whose area fell below this fraction of its initial area has
#: collapsed in its own plane (an in-plane strain of -99 %: a shell can no
#: longer represent it; its step is ~1/100 of the initial one). The solver
#: treats it as a solid's negative volume: error termination, or erosion.
COLLAPSED_AREA = 0.01

#: Elements per parallel chunk; groups smaller than PARALLEL_MIN run serially
#: (thread start-up, ~10-20 us, costs more than it saves on a few hundred shells;
#: 512 shells are ~0.13 ms of work). It was 2048, which left two of the hollow
#: block's three wall parts (2,016 shells each) serial on two threads.
CHUNK = 64
PARALLEL_MIN = 512


#: Fast-math flags of the shell kernels: FASTMATH without reassociation and FMA
#: contraction. With those two, the element loop compiled in the running process and
#: the same kernel loaded from the disk cache did not compute the same round-off
#: (element forces differing by up to 4e-15 kN after a few cycles), so a run's result
#: depended on whether its process had compiled the kernel (the hollow block at
#: 100 km/h: 769 or 754 cycles). Without them both are identical; cost about 5-10 %
#: of the shell kernel's time (benchmarks/bench_shell.py).
SHELL_FASTMATH = {"nsz", "arcp", "afn"}

_KERNELS: dict[str, tuple[Callable[..., None], Callable[..., None]]] = {}


def _wrappers(stamp: int) -> tuple[Callable[..., None], Callable[..., None]]:
    """Python sources of the serial and the threaded kernel (closures over ``stamp``)."""

    def shell_serial(x, v, w, dt, geom, state, params, history, kp, out):
        if stamp < 0:  # never: the digest only keys the on-disk cache
            return
        _range(0, geom[0].shape[0], x, v, w, dt, geom, state, params, history, kp, out)

    def shell_parallel(x, v, w, dt, geom, state, params, history, kp, out):
        if stamp < 0:  # never
            return
        ne = geom[0].shape[0]
        nchunk = (ne + CHUNK - 1) // CHUNK
        for c in prange(nchunk):
            _range(c * CHUNK, min(ne, (c + 1) * CHUNK), x, v, w, dt, geom, state, params,
                   history, kp, out)

    return shell_serial, shell_parallel


def _with_globals(fn, **names):
    """A copy of function ``fn`` that sees ``names`` as module globals."""
    g = types.FunctionType(fn.__code__, {**fn.__globals__, **names}, fn.__name__,
                           fn.__defaults__, fn.__closure__)
    g.__qualname__ = fn.__qualname__
    g.__doc__ = fn.__doc__
    return g


def make_shell_kernel(law: ModuleType) -> tuple[Callable[..., None], Callable[..., None]]:
    """(serial, parallel) shell kernels of one law module (built once per law).

    ``law`` provides ``KIND`` (see :mod:`hollowbody.materials.shell_laws`).
    Both kernels are called as
    ``kernel(x, v, w, dt, geom, state, params, history, kp, out)`` (arguments
    as :func:`bt_shell_range`); the parallel one runs chunks of ``CHUNK``
    elements over threads. The element loop is compiled from
    :func:`bt_shell_range` with ``_law`` bound to ``law`` (its ``KIND`` is a
    compile-time constant); the two kernels call it and are
    cached on disk: their cache key holds a digest of this module's, the
    kinematics' and the law package's sources (see kernel_cache), which tells
    the laws apart and compiles them anew after an edit. The loop itself is
    not cached separately (it is part of both kernels' compiled code).
    """
    key = law.__name__
    kernels = _KERNELS.get(key)
    if kernels is not None:
        return kernels
    stamp = source_stamp(law, sys.modules[__name__], shell_bt_kinematics)
    loop = njit(error_model="numpy", fastmath=SHELL_FASTMATH)(
        _with_globals(bt_shell_range, _law=law))
    serial_py, parallel_py = _wrappers(stamp)
    serial = njit(cache=True, error_model="numpy", fastmath=SHELL_FASTMATH)(
        _with_globals(serial_py, _range=loop))
    parallel = njit(cache=True, parallel=True)(_with_globals(parallel_py, _range=loop))
    _KERNELS[key] = (serial, parallel)
    return serial, parallel


def bt_shell_forces(law: ModuleType, x: np.ndarray, v: np.ndarray, w: np.ndarray, dt: float,
                    geom: tuple, state: tuple, params: tuple, history: tuple, kp: np.ndarray,
                    out: tuple) -> None:
    """Every element of a group (arguments as :func:`bt_shell_range`) with the
    kernels of ``law``: chunks over threads for large groups, one serial call
    for small ones or with one thread."""
    serial, parallel = make_shell_kernel(law)
    if geom[0].shape[0] >= PARALLEL_MIN and get_num_threads() > 1:
        parallel(x, v, w, dt, geom, state, params, history, kp, out)
    else:
        serial(x, v, w, dt, geom, state, params, history, kp, out)
