"""Small tensor kernels in Voigt order (xx, yy, zz, xy, yz, zx), for the stress updates.

Pure scalar functions, inlined into the element loops (no allocation).
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, inline="always", fastmath={"contract"})
def rotate_sym(q, s0, s1, s2, s3, s4, s5):
    """Kernel: Q S Q^T for a symmetric S in Voigt order (xx, yy, zz, xy, yz, zx).

    Returns the six rotated components as a tuple (same unit as S).
    """
    # T = Q S
    t00 = q[0, 0] * s0 + q[0, 1] * s3 + q[0, 2] * s5
    t01 = q[0, 0] * s3 + q[0, 1] * s1 + q[0, 2] * s4
    t02 = q[0, 0] * s5 + q[0, 1] * s4 + q[0, 2] * s2
    t10 = q[1, 0] * s0 + q[1, 1] * s3 + q[1, 2] * s5
    t11 = q[1, 0] * s3 + q[1, 1] * s1 + q[1, 2] * s4
    t12 = q[1, 0] * s5 + q[1, 1] * s4 + q[1, 2] * s2
    t20 = q[2, 0] * s0 + q[2, 1] * s3 + q[2, 2] * s5
    t21 = q[2, 0] * s3 + q[2, 1] * s1 + q[2, 2] * s4
    t22 = q[2, 0] * s5 + q[2, 1] * s4 + q[2, 2] * s2
    r0 = t00 * q[0, 0] + t01 * q[0, 1] + t02 * q[0, 2]
    r1 = t10 * q[1, 0] + t11 * q[1, 1] + t12 * q[1, 2]
    r2 = t20 * q[2, 0] + t21 * q[2, 1] + t22 * q[2, 2]
    r3 = t00 * q[1, 0] + t01 * q[1, 1] + t02 * q[1, 2]
    r4 = t10 * q[2, 0] + t11 * q[2, 1] + t12 * q[2, 2]
    r5 = t00 * q[2, 0] + t01 * q[2, 1] + t02 * q[2, 2]
    return r0, r1, r2, r3, r4, r5
