"""Fully integrated, selectively reduced hexahedron (LS-DYNA *SECTION_SOLID ELFORM 2).

Why. The one-point hexahedron (ELFORM 1) has twelve hourglass modes that its
stress does not resist; the hourglass control that holds them is either far
too stiff for nearly incompressible rubber (the stiffness form scales with the
bulk modulus) or too soft for it to stop a crushing impact (the assumed-strain
form scales with the small shear modulus), and its energy is not the tissue's.
This element has no hourglass modes, so it gives the reference a user can
compare the one-point results with.

Formulation (our own, after the selective-reduced integration of Hughes, IJNME
15 (1980) 1413, and Belytschko, Liu & Moran, *Nonlinear Finite Elements*):

* the law's stress is evaluated at the 2 x 2 x 2 Gauss points
  ``xi_g = +-1/sqrt(3)`` (weights 1), each with its own deformation gradient
  ``F_g = sum_a x_a (x) B0_ga`` (reference gradients at the point), velocity
  gradient ``L_g = sum_a v_a (x) B_ga`` (current gradients at the point) with its
  volumetric part replaced by the element's (``tr L_g -> tr L``, so a rate law's
  pressure is the same at every point), taken to the mid-step configuration as
  for the one-point element, Hughes-Winget rotation, stress and material history;
* the mean stress is taken over the element: its deviatoric part is integrated
  at the eight points, its trace (pressure) with the one-point rule, i.e. the
  volume-weighted mean of the points' traces acts with the element's uniform
  gradients ``b``. One volumetric constraint per element: no volumetric locking
  of nearly incompressible laws (MAT_181's pressure already comes from the
  element's volume ratio, which the point volumes sum to exactly);
* nodal forces ``f_a = -sum_g J_g s_g B_ga - V (p_m - q) b_a``, ``s_g`` the
  deviatoric stress of point g, ``J_g`` its Jacobian determinant (the 2-point rule
  integrates the trilinear element's volume exactly, so ``sum_g J_g = V`` and
  ``sum_g J_g B_ga = V b_a``), ``p_m`` the mean of the points' mean stresses,
  ``q`` the bulk viscosity of the element;
* no hourglass forces (the element's only zero-energy modes are rigid motions);
* time step, wave speed and bulk viscosity as for the one-point element, with
  the largest of the points' wave speeds;
* a point whose det J <= 0 counts as a negative volume (the element's volume is
  reported as that det J): the run ends, or erosion deletes the element.

Arrays: e elements, the points of element e are rows ``8 e .. 8 e + 7`` of the
per-point arrays (reference gradients b0g (8e, 8, 3) 1/mm, stress_gp (8e, 6)
GPa, the law's history). The element's stress (e, 6) is the volume mean of its
points' stresses (output: pressure, d3plot). Energies as for the one-point
kernel (work of the element's nodal forces over the step, central difference);
the hourglass energy is zero.
"""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import numpy as np
from numba import njit, prange

from hollowbody.elements import hex8_kinematics, hex8_solid_kernels, time_step
from hollowbody.elements.hex8_kinematics import (
    hex8_max_face_area,
    hughes_winget,
    midpoint_velocity_gradient,
    velocity_gradient,
)
from hollowbody.elements.hex8_solid_kernels import (
    H_Q1,
    H_Q2,
    _bulk_q,
    _kinematics,
    _power,
    _zero,
)
from hollowbody.elements.kernel_cache import source_stamp
from hollowbody.elements.time_step import critical_time_step

_THIRD = 1.0 / 3.0
#: Natural coordinates of the eight nodes (LS-DYNA order), (8, 3).
_XI_NODES = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                      [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=np.float64)


def _shape_derivatives() -> np.ndarray:
    """(8 points, 8 nodes, 3) dN_a / dxi_k at the 2 x 2 x 2 Gauss points."""
    g = 1.0 / np.sqrt(3.0)
    pts = _XI_NODES * g  # one point near each node, same order
    dn = np.empty((8, 8, 3))
    for p in range(8):
        for a in range(8):
            fac = 1.0 + _XI_NODES[a] * pts[p]  # (3,)
            for k in range(3):
                other = [m for m in range(3) if m != k]
                dn[p, a, k] = 0.125 * _XI_NODES[a, k] * fac[other[0]] * fac[other[1]]
    return dn


#: dN_a / dxi_k at the Gauss points, (8, 8, 3); a global constant of the kernels.
DN_GAUSS = _shape_derivatives()


@njit(cache=True, inline="always", fastmath={"contract"})
def _point_gradients(xe, p, bg, jm):
    """Current gradients bg (8, 3) 1/mm of point p from positions xe (8, 3); returns det J (mm^3).

    jm (3, 3) scratch. det J <= 0 leaves bg undefined.
    """
    for i in range(3):
        for k in range(3):
            s = 0.0
            for a in range(8):
                s += xe[a, i] * DN_GAUSS[p, a, k]
            jm[i, k] = s  # dx_i / dxi_k
    c00 = jm[1, 1] * jm[2, 2] - jm[1, 2] * jm[2, 1]
    c01 = jm[1, 2] * jm[2, 0] - jm[1, 0] * jm[2, 2]
    c02 = jm[1, 0] * jm[2, 1] - jm[1, 1] * jm[2, 0]
    det = jm[0, 0] * c00 + jm[0, 1] * c01 + jm[0, 2] * c02
    if det <= 0.0:
        return det
    inv = 1.0 / det
    # (J^-1)[k, i] = cofactor[i, k] / det
    i00 = c00 * inv
    i10 = c01 * inv
    i20 = c02 * inv
    i01 = (jm[0, 2] * jm[2, 1] - jm[0, 1] * jm[2, 2]) * inv
    i11 = (jm[0, 0] * jm[2, 2] - jm[0, 2] * jm[2, 0]) * inv
    i21 = (jm[0, 1] * jm[2, 0] - jm[0, 0] * jm[2, 1]) * inv
    i02 = (jm[0, 1] * jm[1, 2] - jm[0, 2] * jm[1, 1]) * inv
    i12 = (jm[0, 2] * jm[1, 0] - jm[0, 0] * jm[1, 2]) * inv
    i22 = (jm[0, 0] * jm[1, 1] - jm[0, 1] * jm[1, 0]) * inv
    for a in range(8):
        d0, d1, d2 = DN_GAUSS[p, a, 0], DN_GAUSS[p, a, 1], DN_GAUSS[p, a, 2]
        bg[a, 0] = d0 * i00 + d1 * i10 + d2 * i20
        bg[a, 1] = d0 * i01 + d1 * i11 + d2 * i21
        bg[a, 2] = d0 * i02 + d1 * i12 + d2 * i22
    return det


@njit(cache=True)
def _gauss_gradients_loop(conn, x, b0g, jac):
    xe = np.empty((8, 3))
    bg = np.empty((8, 3))
    jm = np.empty((3, 3))
    for e in range(conn.shape[0]):
        n0 = conn[e, 0]
        for a in range(8):
            n = conn[e, a]
            for i in range(3):
                xe[a, i] = x[n, i] - x[n0, i]
        for p in range(8):
            det = _point_gradients(xe, p, bg, jm)
            jac[e, p] = det
            for a in range(8):
                for i in range(3):
                    b0g[8 * e + p, a, i] = bg[a, i] if det > 0.0 else 0.0


def gauss_gradients(conn: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Reference gradients at the Gauss points of a group.

    conn (e, 8) node indices, x (n, 3) mm. Returns b0g (8e, 8, 3) 1/mm (rows
    8e..8e+7 the points of element e; zero where det J <= 0) and the points'
    Jacobian determinants (e, 8) mm^3 (their sum is the element's volume).
    """
    conn = np.ascontiguousarray(conn, dtype=np.int64)
    x = np.ascontiguousarray(x, dtype=np.float64)
    e = conn.shape[0]
    b0g = np.zeros((8 * e, 8, 3))
    jac = np.zeros((e, 8))
    _gauss_gradients_loop(conn, x, b0g, jac)
    return b0g, jac


@njit(cache=True, inline="always", fastmath={"contract"})
def _add_deviatoric(det, s0, s1, s2, s3, s4, s5, bg, fwork, e):
    """fwork[e, a] -= det s b_a, s the trace-free part of (s0..s5) (kN); returns the mean stress."""
    m = (s0 + s1 + s2) * _THIRD
    d0, d1, d2 = s0 - m, s1 - m, s2 - m
    for a in range(8):
        bx, by, bz = bg[a, 0], bg[a, 1], bg[a, 2]
        fwork[e, a, 0] -= det * (d0 * bx + s3 * by + s5 * bz)
        fwork[e, a, 1] -= det * (s3 * bx + d1 * by + s4 * bz)
        fwork[e, a, 2] -= det * (s5 * bx + s4 * by + d2 * bz)
    return m


_KERNELS: dict[str, Callable[..., None]] = {}


def make_hex8_full_kernel(law: ModuleType) -> Callable[..., None]:
    """The fully integrated (ELFORM 2) hexahedron kernel of one solid law module.

    Called as ``kernel(x, v, dt, geom, state, params, history, hg, out)`` like the
    one-point kernel (:func:`hollowbody.elements.hex8_solid_kernels.make_hex8_kernel`)
    with

    * geom = (conn (e, 8) int32, lfac (e,), volume0 (e,) mm^3, b0g (8e, 8, 3) 1/mm
      reference gradients at the points, bounds (nchunk + 1,) int64);
    * state = (alive (e,) bool, stress (e, 6) GPa out (volume mean), stress_gp
      (8e, 6) GPa in/out, volume (e,) mm^3 out (the smallest point det J where it is
      <= 0: an inverted point counts as a negative volume), fwork (e, 8, 3) kN in f^n / out
      f^{n+1}, dt_elem (e,) ms out, c_elem (e,) mm/ms out);
    * params, history: the law's tuples, history arrays with 8e rows;
    * hg (N_HG,) float64: only Q1, Q2 (bulk viscosity) are read;
    * out (nchunk, 5): internal, hourglass (0), dt_min, its index, first element
      with V <= 0 or with a point's det J <= 0 (-1: none).
    """
    key = law.__name__
    kernel = _KERNELS.get(key)
    if kernel is not None:
        return kernel
    stamp = source_stamp(law, hex8_kinematics, hex8_solid_kernels, time_step)

    @njit(cache=True, parallel=True, fastmath={"contract"})
    def hex8_full_kernel(x, v, dt, geom, state, params, history, hg, out):
        if stamp < 0:  # never: the sources' digest only keys the on-disk cache
            return
        conn, lfac, volume0, b0g, bounds = geom
        alive, stress, stress_gp, volume, fwork, dt_elem, c_elem = state
        consts = law.solid_constants(params)
        q1, q2 = hg[H_Q1], hg[H_Q2]
        nchunk = bounds.shape[0] - 1
        for ck in prange(nchunk):
            xe = np.empty((8, 3))
            ve = np.empty((8, 3))
            bt = np.empty((8, 3))
            bgs = np.empty((8, 8, 3))
            dets = np.empty(8)
            lg = np.empty((3, 3))
            lm = np.empty((3, 3))
            rot = np.empty((3, 3))
            lgp = np.empty((3, 3))
            rgp = np.empty((3, 3))
            jm = np.empty((3, 3))
            work = np.empty((3, 3))
            eint = 0.0
            dtmin = np.inf
            imin = -1
            ineg = -1
            for e in range(bounds[ck], bounds[ck + 1]):
                if not alive[e]:
                    _zero(fwork, e)
                    dt_elem[e] = np.inf
                    continue
                vol = _kinematics(e, conn, x, v, dt, xe, ve, bt, lg, lm, rot)
                w_old = _power(ve, fwork, e)
                _zero(fwork, e)
                # an inverted point counts as a negative volume (its det J is reported)
                vmin = vol
                if vol > 0.0:
                    for p in range(8):
                        dets[p] = _point_gradients(xe, p, bgs[p], jm)
                        vmin = min(vmin, dets[p])
                volume[e] = vmin
                if vmin <= 0.0:
                    if ineg < 0:
                        ineg = e
                    eint -= 0.5 * dt * w_old
                    dt_elem[e] = np.inf
                    continue
                trl = lg[0, 0] + lg[1, 1] + lg[2, 2]
                l = vol ** _THIRD
                inv_vol = 1.0 / vol
                pm = 0.0
                cmax = 0.0
                rho = 0.0
                a0 = a1 = a2 = a3 = a4 = a5 = 0.0
                for p in range(8):
                    det = dets[p]
                    bg = bgs[p]
                    velocity_gradient(ve, bg, lgp)
                    # the element's volumetric rate at every point (selective reduction
                    # of the rate too: the points' pressures of a rate law stay equal)
                    dv = (trl - lgp[0, 0] - lgp[1, 1] - lgp[2, 2]) * _THIRD
                    lgp[0, 0] += dv
                    lgp[1, 1] += dv
                    lgp[2, 2] += dv
                    midpoint_velocity_gradient(lgp, dt)
                    hughes_winget(lgp, dt, rgp)
                    r = 8 * e + p
                    n0, n1, n2, n3, n4, n5, rho, modulus, c = law.solid_update(
                        r, dt, vol, volume0[e], l, xe, b0g, lgp, rgp, work, stress_gp, consts,
                        params, history)
                    stress_gp[r, 0] = n0
                    stress_gp[r, 1] = n1
                    stress_gp[r, 2] = n2
                    stress_gp[r, 3] = n3
                    stress_gp[r, 4] = n4
                    stress_gp[r, 5] = n5
                    wgt = det * inv_vol
                    pm += wgt * _add_deviatoric(det, n0, n1, n2, n3, n4, n5, bg, fwork, e)
                    a0 += wgt * n0
                    a1 += wgt * n1
                    a2 += wgt * n2
                    a3 += wgt * n3
                    a4 += wgt * n4
                    a5 += wgt * n5
                    cmax = max(cmax, c)
                # the pressure with the one-point rule (uniform gradients bt)
                trd = lm[0, 0] + lm[1, 1] + lm[2, 2]
                sm = pm - _bulk_q(rho, l, cmax, trd, q1, q2)
                for a in range(8):
                    fwork[e, a, 0] -= vol * sm * bt[a, 0]
                    fwork[e, a, 1] -= vol * sm * bt[a, 1]
                    fwork[e, a, 2] -= vol * sm * bt[a, 2]
                stress[e, 0] = a0
                stress[e, 1] = a1
                stress[e, 2] = a2
                stress[e, 3] = a3
                stress[e, 4] = a4
                stress[e, 5] = a5
                eint += -0.5 * dt * (w_old + _power(ve, fwork, e))
                amax = hex8_max_face_area(xe)
                dte = critical_time_step(lfac[e] * vol / amax, cmax, l, trd, q1, q2)
                dt_elem[e] = dte
                c_elem[e] = cmax
                if dte < dtmin:
                    dtmin = dte
                    imin = e
            out[ck, 0] = eint
            out[ck, 1] = 0.0
            out[ck, 2] = dtmin
            out[ck, 3] = imin
            out[ck, 4] = ineg

    _KERNELS[key] = hex8_full_kernel
    return hex8_full_kernel
