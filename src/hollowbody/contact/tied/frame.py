"""The tie frame of a segment point: the axes a kept offset is stored in.

At natural coordinates (u, v) of a segment (see :mod:`hollowbody.contact.geometry`):
e1 = g1 / |g1|, n = g1 x g2 / |g1 x g2|, e2 = n x e1, with g1 = dx/du,
g2 = dx/dv. The frame turns with the segment, so an offset stored in it
follows any rigid motion exactly.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hollowbody.contact.geometry import tangents


@njit(cache=True)
def tie_frame(xs: np.ndarray, u: float, v: float, tri: bool, g: np.ndarray,
              e: np.ndarray) -> bool:
    """Orthonormal tie frame e (3, 3) rows e1, e2, n at (u, v) of segment corners xs
    (4, 3) mm; False if degenerate. g: (2, 3) work array (tangents on return)."""
    tangents(xs, u, v, tri, g)
    n0 = g[0, 1] * g[1, 2] - g[0, 2] * g[1, 1]
    n1 = g[0, 2] * g[1, 0] - g[0, 0] * g[1, 2]
    n2 = g[0, 0] * g[1, 1] - g[0, 1] * g[1, 0]
    nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    l1 = np.sqrt(g[0, 0] ** 2 + g[0, 1] ** 2 + g[0, 2] ** 2)
    if nn <= 0.0 or l1 <= 0.0:
        return False
    for k in range(3):
        e[0, k] = g[0, k] / l1
    e[2, 0] = n0 / nn
    e[2, 1] = n1 / nn
    e[2, 2] = n2 / nn
    e[1, 0] = e[2, 1] * e[0, 2] - e[2, 2] * e[0, 1]
    e[1, 1] = e[2, 2] * e[0, 0] - e[2, 0] * e[0, 2]
    e[1, 2] = e[2, 0] * e[0, 1] - e[2, 1] * e[0, 0]
    return True
