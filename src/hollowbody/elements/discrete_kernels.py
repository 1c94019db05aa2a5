"""Numba kernels of discrete elements (springs and dampers): one loop over a group.

Each element acts along a unit direction ``e``: the current line N1 -> N2, or a
fixed vector (*DEFINE_SD_ORIENTATION IOP 0). Its deflection ``d`` is

- translational, along the line: ``d = L - L0 + OFFSET`` (mm);
- translational, fixed vector: ``d = ((x2 - x1) - (X2 - X1)) . e + OFFSET``;
- torsional (DRO 1): ``d = theta + OFFSET`` (rad) with ``theta`` accumulated from the
  nodal angular velocities, ``theta += dt (w2 - w1) . e``;

and its rate ``d' = (v2 - v1) . e`` (torsional ``(w2 - w1) . e``). The law gives the
force F (kN, tension positive; torsional: moment kN*mm), scaled by S; N1 gets
``+S F e`` and N2 ``-S F e`` (forces into ``f`` or moments into ``mom``). A grounded
element (N2 = -1) ties N1 to its initial position (translational) or to the
ground (torsional: w2 = 0).

Laws (``law`` code): 1 S01 ``F = K d``; 2 S02 ``F = DC d'``; 4 S04 ``F = LCD(d)``;
6 S06 general nonlinear (loading curve LCDL, unloading curve LCDU shifted along
the deflection axis, yield forces TYI / CYI, hardening BETA; see docs/discrete.md).
Curves are interpolated linearly and extrapolated with their end slopes.

Energy: every element's work ``0.5 (F_old + F_new) (d_new - d_old)`` (trapezoidal,
exact for linear springs) summed into ``energy`` (J): stored spring energy plus
the energy a damper or a hysteresis loop dissipates.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: columns of the history array ``hist`` (e, 4)
H_THETA, H_SHIFT, H_YT, H_YC = 0, 1, 2, 3


@njit(cache=True)
def curve_segment(cx: np.ndarray, t: float) -> int:
    """Index k of the segment [cx[k], cx[k+1]] holding t (0 / m-2 beyond the ends);
    bisection, cx (m >= 2,) increasing."""
    m = cx.size
    if t <= cx[0]:
        return 0
    if t >= cx[m - 1]:
        return m - 2
    lo, hi = 0, m - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if cx[mid] <= t:
            lo = mid
        else:
            hi = mid
    return lo


@njit(cache=True)
def curve_value(cx: np.ndarray, cy: np.ndarray, t: float) -> float:
    """y(t) of the piecewise-linear curve (cx, cy), extrapolated with the end slopes."""
    if cx.size == 1:
        return cy[0]
    k = curve_segment(cx, t)
    s = (cy[k + 1] - cy[k]) / (cx[k + 1] - cx[k])
    return cy[k] + s * (t - cx[k])


@njit(cache=True)
def curve_slope_near(cx: np.ndarray, cy: np.ndarray, t: float) -> float:
    """Largest |slope| of the segment of (cx, cy) holding t and of its two neighbours
    (the end segments beyond the ends): the current tangent with a look-ahead."""
    m = cx.size
    if m < 2:
        return 0.0
    k = curve_segment(cx, t)
    best = 0.0
    for j in range(max(k - 1, 0), min(k + 2, m - 1)):
        s = abs((cy[j + 1] - cy[j]) / (cx[j + 1] - cx[j]))
        if s > best:
            best = s
    return best


@njit(cache=True)
def step_limit(k: float, c: float, minv: float) -> float:
    """ms: central-difference limit of a spring k and damper c in parallel between masses
    with 1/m1 + 1/m2 = minv: (2 / omega) (sqrt(1 + xi^2) - xi), omega^2 = k minv,
    xi = c minv / (2 omega); 2 / (c minv) without a spring; inf without either."""
    om2 = k * minv
    cm = c * minv
    if om2 > 0.0:
        om = np.sqrt(om2)
        xi = cm / (2.0 * om)
        return 2.0 / om * (np.sqrt(1.0 + xi * xi) - xi)
    if cm > 0.0:
        return 2.0 / cm
    return np.inf


@njit(cache=True)
def curve_inverse(cx: np.ndarray, cy: np.ndarray, y: float) -> float:
    """t with y(t) = y for a strictly increasing curve (end slopes extrapolated)."""
    return curve_value(cy, cx, y)


@njit(cache=True)
def _general_force(d: float, lx: np.ndarray, ly: np.ndarray, ux: np.ndarray, uy: np.ndarray,
                   beta: float, tyi: float, cyi: float, h: np.ndarray, i: int) -> float:
    """S06: force (kN) at deflection d; updates the shift and yield forces of row i of h."""
    shift = h[i, H_SHIFT]
    trial = curve_value(ux, uy, d - shift)
    load = curve_value(lx, ly, d)
    if beta == 0.0:  # independent yield forces, softening along the curve allowed
        yt, yc = tyi, cyi
    else:
        yt, yc = h[i, H_YT], h[i, H_YC]
    # the loading curve bounds the force on its own side only (tension where it is
    # positive, compression where it is negative); the current yield forces elsewhere
    upper = max(load, yt) if load > 0.0 else yt
    lower = min(load, yc) if load < 0.0 else yc
    if trial > upper:
        force = upper
    elif trial < lower:
        force = lower
    else:
        return trial
    h[i, H_SHIFT] = d - curve_inverse(ux, uy, force)
    if beta == 1.0:  # isotropic: both yield forces grow to the largest force reached
        big = max(abs(force), yt, -yc)
        h[i, H_YT] = big
        h[i, H_YC] = -big
    elif beta != 0.0:  # kinematic: the elastic range [yc, yt] moves with the force
        width = yt - yc
        if trial > upper:
            h[i, H_YT] = force
            h[i, H_YC] = force - width
        else:
            h[i, H_YC] = force
            h[i, H_YT] = force + width
    return force


@njit(cache=True)
def discrete_forces(law: int, torsional: bool, x: np.ndarray, v: np.ndarray, w: np.ndarray,
                    dt: float, n1: np.ndarray, n2: np.ndarray, ground: np.ndarray,
                    fixed: np.ndarray, axis: np.ndarray, length0: np.ndarray,
                    offset: np.ndarray, scale: np.ndarray, alive: np.ndarray,
                    params: np.ndarray, lx: np.ndarray, ly: np.ndarray, ux: np.ndarray,
                    uy: np.ndarray, hist: np.ndarray, force: np.ndarray, defl: np.ndarray,
                    rate: np.ndarray, direction: np.ndarray, energy: np.ndarray,
                    k_other: np.ndarray, c_use: np.ndarray, minv: np.ndarray,
                    dte: np.ndarray, f: np.ndarray, mom: np.ndarray) -> int:
    """Forces of one discrete group; returns the index of the first element that failed
    this call (|d| > FD) or -1.

    x (n,3) mm; v (n,3) mm/ms, w (n,3) rad/ms at t^{n+1/2}; dt ms. Per element (e):
    n1, n2 node indices (n2 = -1 grounded); ground (e,3) mm the ground point (X1)
    or, with a fixed axis, X2 - X1 at t = 0; fixed (e,) bool; axis (e,3) fixed unit
    vectors; length0 (e,) mm; offset (e,) mm or rad; scale (e,) S; alive (e,) bool.
    params: [K or DC, BETA, TYI, CYI, FD]. Curves (lx, ly) loading / LCD, (ux, uy)
    unloading (S06). State (updated): hist (e,4), force (e,) kN or kN*mm scaled,
    defl (e,) mm or rad, rate (e,), direction (e,3) last unit direction, energy (e,)
    J accumulated. Time step: k_other (e,) the stiffness bounds of the other discrete
    elements at the element's nodes, c_use (e,) the damping there (own included),
    minv (e,) 1/m1 + 1/m2 (0 where nothing moves); dte (e,) ms is set to the limit
    with k = k_other + |S| x the law's current tangent (:func:`curve_slope_near`).
    Adds into f (n,3) kN or mom (n,3) kN*mm. No allocation.
    """
    e_count = n1.size
    failed = -1
    fd = params[4]
    for i in range(e_count):
        if not alive[i]:
            continue
        a = n1[i]
        b = n2[i]
        # direction
        if fixed[i]:
            ex, ey, ez = axis[i, 0], axis[i, 1], axis[i, 2]
            length = 0.0
        else:
            if b >= 0:
                rx = x[b, 0] - x[a, 0]
                ry = x[b, 1] - x[a, 1]
                rz = x[b, 2] - x[a, 2]
            else:
                rx = ground[i, 0] - x[a, 0]
                ry = ground[i, 1] - x[a, 1]
                rz = ground[i, 2] - x[a, 2]
            length = np.sqrt(rx * rx + ry * ry + rz * rz)
            if length > 1e-12:
                ex, ey, ez = rx / length, ry / length, rz / length
            else:  # passing through zero length: keep the last direction
                ex, ey, ez = direction[i, 0], direction[i, 1], direction[i, 2]
        direction[i, 0], direction[i, 1], direction[i, 2] = ex, ey, ez
        # rate and deflection
        if torsional:
            r = -(w[a, 0] * ex + w[a, 1] * ey + w[a, 2] * ez)
            if b >= 0:
                r += w[b, 0] * ex + w[b, 1] * ey + w[b, 2] * ez
            hist[i, H_THETA] += dt * r
            d = hist[i, H_THETA] + offset[i]
        else:
            r = -(v[a, 0] * ex + v[a, 1] * ey + v[a, 2] * ez)
            if b >= 0:
                r += v[b, 0] * ex + v[b, 1] * ey + v[b, 2] * ez
            if fixed[i]:
                if b >= 0:
                    ux_, uy_, uz_ = x[b, 0] - x[a, 0], x[b, 1] - x[a, 1], x[b, 2] - x[a, 2]
                else:
                    ux_, uy_, uz_ = -x[a, 0], -x[a, 1], -x[a, 2]
                d = ((ux_ - ground[i, 0]) * ex + (uy_ - ground[i, 1]) * ey
                     + (uz_ - ground[i, 2]) * ez + offset[i])
            else:
                d = length - length0[i] + offset[i]
        # law and its current tangent
        if law == 1:
            fl = params[0] * d
            kt = params[0]
        elif law == 2:
            fl = params[0] * r
            kt = 0.0
        elif law == 4:
            fl = curve_value(lx, ly, d)
            kt = curve_slope_near(lx, ly, d)
        else:
            fl = _general_force(d, lx, ly, ux, uy, params[1], params[2], params[3], hist, i)
            kt = max(curve_slope_near(lx, ly, d),
                     curve_slope_near(ux, uy, d - hist[i, H_SHIFT]))
        dte[i] = step_limit(k_other[i] + abs(scale[i]) * kt, c_use[i], minv[i])
        fs = scale[i] * fl
        if fd > 0.0 and abs(d) > fd:  # failure deflection: the element is deleted
            fs = 0.0
            alive[i] = False
            if failed < 0:
                failed = i
        energy[i] += 0.5 * (force[i] + fs) * (d - defl[i])
        force[i] = fs
        defl[i] = d
        rate[i] = r
        if fs == 0.0:
            continue
        gx, gy, gz = fs * ex, fs * ey, fs * ez
        out = mom if torsional else f
        out[a, 0] += gx
        out[a, 1] += gy
        out[a, 2] += gz
        if b >= 0:
            out[b, 0] -= gx
            out[b, 1] -= gy
            out[b, 2] -= gz
    return failed
