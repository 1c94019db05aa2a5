"""Eigen-decomposition of a symmetric 3x3 matrix for element kernels.

Cyclic Jacobi rotations written with scalars: no allocation, no LAPACK, robust
for repeated eigenvalues (the case of every undeformed element). Each rotation
zeroes one off-diagonal entry; convergence is quadratic, so a few sweeps reach
machine precision. A warm start (the previous eigenvectors of the element)
usually needs one sweep.
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True, inline="always", fastmath={"contract"})
def _rotation(app, aqq, apq):
    """Jacobi rotation (t, c, s) that zeroes apq (t = tan of the angle).

    Small angles (|apq| < 1e-3 |aqq - app|, the usual case with a warm start)
    use the series t = r (1 - r^2), r = apq / (aqq - app), accurate to r^5, and
    c = 1 - t^2/2 + 3 t^4/8: no square roots.
    """
    d = aqq - app
    if abs(apq) < 1e-3 * abs(d):
        r = apq / d
        t = r * (1.0 - r * r)
        t2 = t * t
        c = 1.0 - t2 * (0.5 - 0.375 * t2)
        return t, c, t * c
    th = d / (2.0 * apq)
    t = 1.0 / (abs(th) + math.sqrt(th * th + 1.0))
    if th < 0.0:
        t = -t
    c = 1.0 / math.sqrt(t * t + 1.0)
    return t, c, t * c


@njit(cache=True, fastmath={"contract"})
def jacobi_eig3(a0, a1, a2, a3, a4, a5, vec, tol=1e-14, max_sweeps=12):
    """Kernel: eigenvalues and eigenvectors of the symmetric matrix A.

    a0..a5: A in Voigt order (xx, yy, zz, xy, yz, zx). vec (3, 3) float64:
    on entry an orthogonal start basis (identity, or the previous
    eigenvectors as columns); on return the eigenvectors as columns. The
    start basis is applied first (A <- V^T A V). Returns (l0, l1, l2), the
    eigenvalues belonging to the columns of vec (unsorted). Stops when every
    off-diagonal entry is below ``tol`` times the largest diagonal magnitude.
    """
    # B = V^T A V
    v00, v01, v02 = vec[0, 0], vec[0, 1], vec[0, 2]
    v10, v11, v12 = vec[1, 0], vec[1, 1], vec[1, 2]
    v20, v21, v22 = vec[2, 0], vec[2, 1], vec[2, 2]
    # A V columns
    c00 = a0 * v00 + a3 * v10 + a5 * v20
    c10 = a3 * v00 + a1 * v10 + a4 * v20
    c20 = a5 * v00 + a4 * v10 + a2 * v20
    c01 = a0 * v01 + a3 * v11 + a5 * v21
    c11 = a3 * v01 + a1 * v11 + a4 * v21
    c21 = a5 * v01 + a4 * v11 + a2 * v21
    c02 = a0 * v02 + a3 * v12 + a5 * v22
    c12 = a3 * v02 + a1 * v12 + a4 * v22
    c22 = a5 * v02 + a4 * v12 + a2 * v22
    b00 = v00 * c00 + v10 * c10 + v20 * c20
    b11 = v01 * c01 + v11 * c11 + v21 * c21
    b22 = v02 * c02 + v12 * c12 + v22 * c22
    b01 = v00 * c01 + v10 * c11 + v20 * c21
    b12 = v01 * c02 + v11 * c12 + v21 * c22
    b02 = v00 * c02 + v10 * c12 + v20 * c22
    for _ in range(max_sweeps):
        scale = max(abs(b00), abs(b11), abs(b22))
        thr = tol * scale
        if abs(b01) <= thr and abs(b12) <= thr and abs(b02) <= thr:
            break
        # pivot (0, 1)
        if abs(b01) > thr:
            t, c, s = _rotation(b00, b11, b01)
            b00 -= t * b01
            b11 += t * b01
            b01 = 0.0
            r0 = c * b02 - s * b12
            r1 = s * b02 + c * b12
            b02, b12 = r0, r1
            r0 = c * v00 - s * v01
            v01 = s * v00 + c * v01
            v00 = r0
            r0 = c * v10 - s * v11
            v11 = s * v10 + c * v11
            v10 = r0
            r0 = c * v20 - s * v21
            v21 = s * v20 + c * v21
            v20 = r0
        # pivot (0, 2)
        if abs(b02) > thr:
            t, c, s = _rotation(b00, b22, b02)
            b00 -= t * b02
            b22 += t * b02
            b02 = 0.0
            r0 = c * b01 - s * b12
            r1 = s * b01 + c * b12
            b01, b12 = r0, r1
            r0 = c * v00 - s * v02
            v02 = s * v00 + c * v02
            v00 = r0
            r0 = c * v10 - s * v12
            v12 = s * v10 + c * v12
            v10 = r0
            r0 = c * v20 - s * v22
            v22 = s * v20 + c * v22
            v20 = r0
        # pivot (1, 2)
        if abs(b12) > thr:
            t, c, s = _rotation(b11, b22, b12)
            b11 -= t * b12
            b22 += t * b12
            b12 = 0.0
            r0 = c * b01 - s * b02
            r1 = s * b01 + c * b02
            b01, b02 = r0, r1
            r0 = c * v01 - s * v02
            v02 = s * v01 + c * v02
            v01 = r0
            r0 = c * v11 - s * v12
            v12 = s * v11 + c * v12
            v11 = r0
            r0 = c * v21 - s * v22
            v22 = s * v21 + c * v22
            v21 = r0
    vec[0, 0], vec[0, 1], vec[0, 2] = v00, v01, v02
    vec[1, 0], vec[1, 1], vec[1, 2] = v10, v11, v12
    vec[2, 0], vec[2, 1], vec[2, 2] = v20, v21, v22
    return b00, b11, b22
