"""Kernels of the planar rigid wall's velocity constraint (:mod:`hollowbody.solver.rigidwall`).

The wall's slave nodes are often a whole model's nodes, of which a few touch the
wall: these loops find those few without NumPy temporaries of every slave
node. Units: mm, ms.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def behind(x: np.ndarray, v: np.ndarray, nodes: np.ndarray, tail: np.ndarray,
           normal: np.ndarray, dt: float, rows: np.ndarray, gaps: np.ndarray) -> int:
    """The slave nodes whose predicted position x + dt v is behind the wall.

    x, v (n, 3) mm, mm/ms; nodes (k,) int slave nodes; tail (3,) mm a point of the
    wall, normal (3,) its unit normal; dt ms (0: the current positions). Writes
    their positions in ``nodes`` to rows[:m] and their (negative) gaps in mm to
    gaps[:m] (both (k,)); returns m."""
    m = 0
    for j in range(nodes.shape[0]):
        i = nodes[j]
        g = 0.0
        for c in range(3):
            g += (x[i, c] + dt * v[i, c] - tail[c]) * normal[c]
        if g < 0.0:
            rows[m] = j
            gaps[m] = g
            m += 1
    return m


@njit(cache=True)
def moving_in(x: np.ndarray, v: np.ndarray, nodes: np.ndarray, tail: np.ndarray,
              normal: np.ndarray, tol: float, rows: np.ndarray) -> int:
    """The slave nodes on the wall (gap <= tol mm) whose velocity v (n, 3) mm/ms points
    into it; their positions in ``nodes`` to rows[:m]; returns m."""
    m = 0
    for j in range(nodes.shape[0]):
        i = nodes[j]
        g = 0.0
        vn = 0.0
        for c in range(3):
            g += (x[i, c] - tail[c]) * normal[c]
            vn += v[i, c] * normal[c]
        if g <= tol and vn < 0.0:
            rows[m] = j
            m += 1
    return m
