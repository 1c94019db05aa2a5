"""Kinematics of the Belytschko-Lin-Tsay shell (one in-plane point, co-rotational frame).

Reference: Belytschko, Lin & Tsay, CMAME 42 (1984) 225-251; LS-DYNA Theory
Manual, "Belytschko-Tsay shell". All functions are ``@njit``, take and return
tuples of floats (no arrays are allocated) and are inlined into the element
kernels.

Co-rotational frame of an element with nodes x1..x4 (triangles: x4 = x3):

* ``e3`` = normalised cross product of the diagonals ``r31 x r42``;
* ``e1`` = bisector of the diagonal directions ``r31/|r31| - r42/|r42|`` (in
  the plane normal to e3). This is the *invariant* choice (independent of
  which node is N1, and for a square it rotates with the material: pure shear
  does not turn it), rather than LS-DYNA's default side 1-2;
* ``e2 = e3 x e1``.

Local in-plane coordinates ``(xh_I, yh_I)`` are the projections of
``x_I - centre`` (centre = mean of the 4 node positions); the area is
``A = |r31 x r42| / 2`` (exact for a flat quadrilateral, the projected area of a
warped one). With ``xh_IJ = xh_I - xh_J`` the one-point derivative operator is::

    B1 = [yh_24, yh_31, yh_42, yh_13] / (2A),   B2 = [xh_42, xh_13, xh_24, xh_31] / (2A)

Mindlin kinematics (velocity of a fibre point at height z):
``v(z) = v + z * theta x e3`` gives in the local frame (theta: nodal angular
velocity)::

    d_xx = B1 vx + z B1 thy            d_yy = B2 vy - z B2 thx
    g_xy = B2 vx + B1 vy + z (B2 thy - B1 thx)
    g_xz = B1 vz + (1/4) sum thy       g_yz = B2 vz - (1/4) sum thx

(g: engineering shear rates; sums over the 4 nodes). Drilling rotations
(theta about e3) do not enter. :func:`rotate_to_global` turns a local tensor
(s_zz = 0) into global Voigt components with the frame.
"""

from __future__ import annotations

import math

from numba import njit

from hollowbody.materials.plane_stress_plasticity import FASTMATH

_TINY = 1.0e-300


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def cross3(a, b):
    """Cross product of two 3-tuples."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def dot3(a, b) -> float:
    """Dot product of two 3-tuples."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def bt_geometry(p0, p1, p2, p3):
    """Co-rotational frame, local coordinates and area of a shell.

    p0..p3: node positions (3-tuples, mm; p3 == p2 for a triangle).
    Returns ``(e1, e2, e3, xl, yl, zl, area)``: unit vectors (3-tuples), local
    coordinates (4-tuples, mm, relative to the node mean; zl is the warping,
    of the form a * (1, -1, 1, -1)) and the area (mm^2).
    """
    r31 = (p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2])
    r42 = (p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2])
    n = cross3(r31, r42)
    nn = math.sqrt(dot3(n, n))
    area = 0.5 * nn
    inv = 1.0 / max(nn, _TINY)
    e3 = (n[0] * inv, n[1] * inv, n[2] * inv)
    l31 = 1.0 / max(math.sqrt(dot3(r31, r31)), _TINY)
    l42 = 1.0 / max(math.sqrt(dot3(r42, r42)), _TINY)
    s = (r31[0] * l31 - r42[0] * l42, r31[1] * l31 - r42[1] * l42,
         r31[2] * l31 - r42[2] * l42)
    sn = dot3(s, e3)  # zero up to round-off; remove it anyway
    s = (s[0] - sn * e3[0], s[1] - sn * e3[1], s[2] - sn * e3[2])
    inv = 1.0 / max(math.sqrt(dot3(s, s)), _TINY)
    e1 = (s[0] * inv, s[1] * inv, s[2] * inv)
    e2 = cross3(e3, e1)
    c = (0.25 * (p0[0] + p1[0] + p2[0] + p3[0]), 0.25 * (p0[1] + p1[1] + p2[1] + p3[1]),
         0.25 * (p0[2] + p1[2] + p2[2] + p3[2]))
    d0 = (p0[0] - c[0], p0[1] - c[1], p0[2] - c[2])
    d1 = (p1[0] - c[0], p1[1] - c[1], p1[2] - c[2])
    d2 = (p2[0] - c[0], p2[1] - c[1], p2[2] - c[2])
    d3 = (p3[0] - c[0], p3[1] - c[1], p3[2] - c[2])
    xl = (dot3(d0, e1), dot3(d1, e1), dot3(d2, e1), dot3(d3, e1))
    yl = (dot3(d0, e2), dot3(d1, e2), dot3(d2, e2), dot3(d3, e2))
    zl = (dot3(d0, e3), dot3(d1, e3), dot3(d2, e3), dot3(d3, e3))
    return e1, e2, e3, xl, yl, zl, area


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def bt_bmatrix(xl, yl, area):
    """One-point derivative operator ``(B1, B2)`` (4-tuples, 1/mm) of local coordinates."""
    f = 0.5 / max(area, _TINY)
    b1 = ((yl[1] - yl[3]) * f, (yl[2] - yl[0]) * f, (yl[3] - yl[1]) * f, (yl[0] - yl[2]) * f)
    b2 = ((xl[3] - xl[1]) * f, (xl[0] - xl[2]) * f, (xl[1] - xl[3]) * f, (xl[2] - xl[0]) * f)
    return b1, b2


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def bt_hourglass_vector(xl, yl, b1, b2):
    """Belytschko-Tsay hourglass shape vector gamma = h - (h.xl) B1 - (h.yl) B2 (4-tuple).

    h = (1, -1, 1, -1); gamma is orthogonal to every linear field on the element.
    """
    hx = xl[0] - xl[1] + xl[2] - xl[3]
    hy = yl[0] - yl[1] + yl[2] - yl[3]
    return (1.0 - hx * b1[0] - hy * b2[0], -1.0 - hx * b1[1] - hy * b2[1],
            1.0 - hx * b1[2] - hy * b2[2], -1.0 - hx * b1[3] - hy * b2[3])


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def characteristic_length(xl, yl, area, triangle: bool) -> float:
    """LS-DYNA's shell length (ISDO = 0): A / longest side (quads), 2A / longest side (tris)."""
    l01 = (xl[1] - xl[0]) ** 2 + (yl[1] - yl[0]) ** 2
    l12 = (xl[2] - xl[1]) ** 2 + (yl[2] - yl[1]) ** 2
    l23 = (xl[3] - xl[2]) ** 2 + (yl[3] - yl[2]) ** 2
    l30 = (xl[0] - xl[3]) ** 2 + (yl[0] - yl[3]) ** 2
    lmax = math.sqrt(max(max(l01, l12), max(l23, l30)))
    if triangle:
        return 2.0 * area / max(lmax, _TINY)
    return area / max(lmax, _TINY)


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def bt_strain_rates(b1, b2, vx, vy, vz, tx, ty):
    """Mid-surface strain rates of the one-point BT shell.

    b1, b2: B operator (4-tuples); vx, vy, vz, tx, ty: local nodal velocities
    (mm/ms) and angular velocities about e1, e2 (rad/ms), 4-tuples.
    Returns ``(dxx, dyy, gxy, kxx, kyy, kxy, gxz, gyz)``: membrane rates (1/ms,
    engineering shear), curvature rates (1/(mm ms), engineering twist) and
    transverse shear rates (1/ms); the in-plane rate at height z is d + z k.
    """
    dxx = b1[0] * vx[0] + b1[1] * vx[1] + b1[2] * vx[2] + b1[3] * vx[3]
    dyy = b2[0] * vy[0] + b2[1] * vy[1] + b2[2] * vy[2] + b2[3] * vy[3]
    gxy = (b2[0] * vx[0] + b2[1] * vx[1] + b2[2] * vx[2] + b2[3] * vx[3]
           + b1[0] * vy[0] + b1[1] * vy[1] + b1[2] * vy[2] + b1[3] * vy[3])
    kxx = b1[0] * ty[0] + b1[1] * ty[1] + b1[2] * ty[2] + b1[3] * ty[3]
    kyy = -(b2[0] * tx[0] + b2[1] * tx[1] + b2[2] * tx[2] + b2[3] * tx[3])
    kxy = (b2[0] * ty[0] + b2[1] * ty[1] + b2[2] * ty[2] + b2[3] * ty[3]
           - b1[0] * tx[0] - b1[1] * tx[1] - b1[2] * tx[2] - b1[3] * tx[3])
    gxz = (b1[0] * vz[0] + b1[1] * vz[1] + b1[2] * vz[2] + b1[3] * vz[3]
           + 0.25 * (ty[0] + ty[1] + ty[2] + ty[3]))
    gyz = (b2[0] * vz[0] + b2[1] * vz[1] + b2[2] * vz[2] + b2[3] * vz[3]
           - 0.25 * (tx[0] + tx[1] + tx[2] + tx[3]))
    return dxx, dyy, gxy, kxx, kyy, kxy, gxz, gyz


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def rotate_to_global(e1, e2, e3, sxx, syy, sxy, sxz, syz):
    """Global Voigt (xx yy zz xy yz zx) of a local tensor with s_zz = 0; R = [e1 e2 e3]."""
    out0 = 0.0
    out1 = 0.0
    out2 = 0.0
    out3 = 0.0
    out4 = 0.0
    out5 = 0.0
    # s_g[p, q] = u_p . S u_q with u_p = (e1[p], e2[p], e3[p])
    for p in range(3):
        a0 = e1[p]
        a1 = e2[p]
        a2 = e3[p]
        t0 = sxx * a0 + sxy * a1 + sxz * a2
        t1 = sxy * a0 + syy * a1 + syz * a2
        t2 = sxz * a0 + syz * a1
        q = (p + 1) % 3
        diag = t0 * a0 + t1 * a1 + t2 * a2
        off = t0 * e1[q] + t1 * e2[q] + t2 * e3[q]
        if p == 0:
            out0 = diag
            out3 = off
        elif p == 1:
            out1 = diag
            out4 = off
        else:
            out2 = diag
            out5 = off
    return out0, out1, out2, out3, out4, out5
