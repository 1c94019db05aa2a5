"""One hexahedron element loop for every solid constitutive law.

:func:`make_hex8_kernel` builds, for one law module (see
:mod:`hollowbody.materials.solid_laws`), the kernel that runs per element
(``prange`` over chunks of elements, so every chunk allocates its small scratch
arrays once and reduces its own energies and minimum time step, race-free):

1. gather nodal positions (relative to node N1, for round-off) and velocities;
2. exact volume and uniform gradients b (hex8_kinematics); ``L_end = sum v (x) b``,
   mid-step ``L_mid = (I - dt/2 L_end)^-1 L_end``, ``D = sym(L_mid)``,
   Hughes-Winget rotation ``Q`` from ``W = skew(L_mid)``;
3. the law's stress update ``law.solid_update`` (stress at t^{n+1}, density,
   hourglass modulus and wave speed);
4. bulk viscosity ``q = rho l (Q1 l trD^2 - Q2 c trD)`` for trD < 0 (LS-DYNA; l = V^(1/3));
5. nodal forces ``f_a = -V (sigma - q I) b_a`` written to the element's own slots of
   ``fwork`` (e, 8, 3), plus the hourglass forces (hourglass: FB viscous and
   stiffness forms; hourglass_assumed_strain: IHQ 6);
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

The law is chosen at compile time: the kernel is a closure over the law
*module*, so numba resolves ``law.solid_update`` as a constant and inlines it;
one kernel is compiled per law and cached on disk (the cache key of a closure
holds its captured values: the module reference, stable between processes,
and a digest of the law's and the helpers' sources, see kernel_cache, so an
edit of either compiles the kernel anew).
"""

from __future__ import annotations

from collections.abc import Callable
from types import ModuleType

import numpy as np
from numba import njit, prange

from hollowbody.elements import hex8_kinematics, hourglass, hourglass_assumed_strain, time_step
from hollowbody.elements.hex8_kinematics import (
    hex8_max_face_area,
    hex8_volume_derivatives,
    hughes_winget,
    midpoint_velocity_gradient,
    velocity_gradient,
)
from hollowbody.elements.hourglass import (
    hourglass_add_forces,
    hourglass_hx,
    hourglass_rates,
    hourglass_stiffness,
    hourglass_viscous,
)
from hollowbody.elements.hourglass_assumed_strain import (
    assumed_strain_hourglass,
    assumed_strain_total,
    element_frame,
)
from hollowbody.elements.kernel_cache import source_stamp
from hollowbody.elements.time_step import critical_time_step

#: Indices into the hourglass/bulk-viscosity parameter vector ``hg``: IHQ, QH, Q1, Q2,
#: and the small-strain shear and bulk moduli (GPa) of the law (IHQ 6).
H_IHQ, H_QH, H_Q1, H_Q2, H_G, H_K = range(6)
N_HG = 6

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
               hgstate, hgdisp, hgmod, fwork, elastic, fr, qw, ax0, ax1, ax2, vol0):
    """Adds hourglass forces to fwork[e]; returns the hourglass work increment (J).

    elastic = (G0, K) GPa, the law's small-strain shear and bulk moduli (IHQ 6: the
    shear modulus used is ``max(G0, 3/4 (modulus - K))``, the law's current tangent
    implied by its modulus ``K + 4G/3``); fr (3, 3), qw (4, 3) scratch; hgdisp
    (e, 4, 3) mm hourglass displacements (IHQ 7 only); hgmod (e,) GPa the shear
    modulus of the last call (IHQ 6/7, passive rule); ax0..ax2 mm, vol0 mm^3 the
    element's reference half-lengths and volume (the stiffness is that of the
    initial shape, in the current frame).
    """
    hourglass_hx(xe, hx)
    hourglass_rates(ve, lg, hx, qd)
    if ihq >= 6:
        g0, bulk = elastic
        g = max(g0, 0.75 * (modulus - bulk))
        nu = (3.0 * bulk - 2.0 * g) / (6.0 * bulk + 2.0 * g)
        element_frame(xe, fr)
        if ihq == 7:
            w = assumed_strain_total(qh, 2.0 * g * (1.0 + nu), nu, g, bulk, vol0, dt, rot, fr,
                                     ax0, ax1, ax2, qd, hgstate, hgdisp, hgmod, e, qf, qw)
        else:
            w = assumed_strain_hourglass(qh, 2.0 * g * (1.0 + nu), nu, g, bulk, vol0, dt, rot,
                                         fr, ax0, ax1, ax2, qd, hgstate, hgmod, e, qf)
    elif ihq >= 4:
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


_KERNELS: dict[str, Callable[..., None]] = {}


def make_hex8_kernel(law: ModuleType) -> Callable[..., None]:
    """The hexahedron kernel of one solid law module (built once per law, then reused).

    ``law`` provides ``solid_constants`` and ``solid_update`` (see
    :mod:`hollowbody.materials.solid_laws`).
    The returned kernel is called as ``kernel(x, v, dt, geom, state, params,
    history, hg, out)`` with

    * x, v (n, 3) float64: positions (mm) at t^{n+1}, velocities (mm/ms) at
      t^{n+1/2}; dt ms;
    * geom = (conn (e, 8) int32, lfac (e,) length factor (1, or 3 for
      tetrahedra), volume0 (e,) mm^3, b0 (e, 8, 3) 1/mm reference uniform
      gradients, bounds (nchunk + 1,) int64 element ranges of the chunks, axes0
      (e, 3) mm reference half-lengths for IHQ 6/7);
    * state = (alive (e,) bool, stress (e, 6) GPa in/out, volume (e,) mm^3 in
      (previous) / out (current), hgstate (e, 4, 3) kN generalised hourglass
      forces of the last call, hgdisp (e, 4, 3) mm hourglass displacements (IHQ 7;
      any (k, 4, 3) array otherwise), hgmod (e,) GPa shear modulus of the hourglass
      stiffness at the last call (IHQ 6/7; any (k,) array otherwise), fwork (e, 8, 3)
      kN element forces (in: f^n,
      out: f^{n+1}), dt_elem (e,) ms out, c_elem (e,) mm/ms out);
    * params, history: the law's parameter and history tuples;
    * hg (N_HG,) float64: IHQ (6 / 7: assumed strain, incremental / total;
      4 and 5: FB stiffness; else viscous), QH, Q1, Q2, small-strain shear and
      bulk moduli G0, K (GPa) of the law; out (nchunk, 5) float64 (module docstring).
    """
    key = law.__name__
    kernel = _KERNELS.get(key)
    if kernel is not None:
        return kernel
    stamp = source_stamp(law, hex8_kinematics, hourglass, hourglass_assumed_strain, time_step)

    @njit(cache=True, parallel=True, fastmath={"contract"})
    def hex8_kernel(x, v, dt, geom, state, params, history, hg, out):
        if stamp < 0:  # never: the sources' digest only keys the on-disk cache
            return
        conn, lfac, volume0, b0, bounds, axes0 = geom
        alive, stress, volume, hgstate, hgdisp, hgmod, fwork, dt_elem, c_elem = state
        consts = law.solid_constants(params)
        ihq = int(hg[H_IHQ])
        qh, q1, q2 = hg[H_QH], hg[H_Q1], hg[H_Q2]
        elastic = (hg[H_G], hg[H_K])
        nchunk = bounds.shape[0] - 1
        for ck in prange(nchunk):
            xe = np.empty((8, 3))
            ve = np.empty((8, 3))
            bt = np.empty((8, 3))
            lg = np.empty((3, 3))
            lm = np.empty((3, 3))
            rot = np.empty((3, 3))
            work = np.empty((3, 3))
            hx = np.empty((4, 3))
            qd = np.empty((4, 3))
            qf = np.empty((4, 3))
            fr = np.empty((3, 3))
            qw = np.empty((4, 3))
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
                l = vol ** _THIRD
                n0, n1, n2, n3, n4, n5, rho, modulus, c = law.solid_update(
                    e, dt, vol, volume0[e], l, xe, b0, lm, rot, work, stress, consts, params,
                    history)
                stress[e, 0] = n0
                stress[e, 1] = n1
                stress[e, 2] = n2
                stress[e, 3] = n3
                stress[e, 4] = n4
                stress[e, 5] = n5
                trd = lm[0, 0] + lm[1, 1] + lm[2, 2]
                qb = _bulk_q(rho, l, c, trd, q1, q2)
                _stress_forces(vol, n0 - qb, n1 - qb, n2 - qb, n3, n4, n5, bt, fwork, e)
                dhg = 0.0
                if qh > 0.0:
                    dhg = _hourglass(e, ihq, qh, rho, modulus, c, vol, l, dt, xe, ve, bt, lg,
                                     rot, hx, qd, qf, hgstate, hgdisp, hgmod, fwork, elastic,
                                     fr, qw,
                                     axes0[e, 0], axes0[e, 1], axes0[e, 2], volume0[e])
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

    _KERNELS[key] = hex8_kernel
    return hex8_kernel
