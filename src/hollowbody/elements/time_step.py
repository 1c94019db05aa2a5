"""Critical time step of solid elements (LS-DYNA's rule with bulk viscosity).

``dt_crit = L_e / (Q + sqrt(Q^2 + c^2))`` with ``Q = Q2 c`` always and
``Q = Q2 c + 2 Q1 l |tr D|`` for a compressing element (``tr D < 0``). LS-DYNA
adds Q for compressing elements only and the quadratic term's secant
``Q1 l |tr D|``; here the step is continuous in tr D (in the highest mode tr D
changes sign every cycle, and a step that alternates with it by 6 % pumps that
mode, see tests/verification/solids/test_solid_step_jitter.py), and the
quadratic term enters with its tangent, twice the secant (a damper acting on
the lagged velocity is stable only below 2 / tangent rate; with the secant a
crushed MAT_181 block diverged). ``L_e`` is the
characteristic length (V / A_max for hexahedra and wedges, the smallest
altitude 3 V / A_max for tetrahedra), ``l = V^(1/3)`` the bulk-viscosity
length, ``c`` the material's current dilatational wave speed. The solver
multiplies the minimum by TSSFAC (0.9). Units: mm, ms, mm/ms.

This is an estimate, not a bound: elements with free faces have stiffer
volumetric modes (a lone element 1/sqrt(3) of it for K >> G); the solver
applies the factor of :mod:`hollowbody.elements.solid_step_factor`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hollowbody.elements.hex8_kinematics import characteristic_lengths


@njit(cache=True, inline="always", fastmath={"contract"})
def critical_time_step(length, c, l_visc, trd, q1, q2):
    """Kernel: dt_crit (ms) of one element.

    length: L_e mm; c: wave speed mm/ms; l_visc: V^(1/3) mm; trd: tr D 1/ms
    (mid-step); q1, q2: quadratic and linear bulk-viscosity coefficients.
    """
    qv = q2 * c
    if trd < 0.0:
        qv -= 2.0 * q1 * l_visc * trd
    return length / (qv + math.sqrt(qv * qv + c * c))


def element_time_steps(conn: np.ndarray, x: np.ndarray, c: np.ndarray | float,
                       shape: np.ndarray | None = None) -> np.ndarray:
    """L_e / c (e,) ms: LS-DYNA's critical steps of elements at rest (its Q = 0 at
    tr D = 0; the engine's step at rest is this over ``Q2 + sqrt(1 + Q2^2)``).

    conn: (e, 8) int node indices (canonical, see
    :func:`hollowbody.elements.hex8_kinematics.canonical_connectivity`);
    x: (n, 3) mm; c: wave speed (scalar or (e,)) mm/ms; shape: optional (e,)
    shape codes (tetrahedra use the smallest altitude). Returns L_e / c
    (inf where the element has zero size or c = 0).
    """
    length = characteristic_lengths(conn, x, shape)
    c = np.broadcast_to(np.asarray(c, dtype=np.float64), length.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        dt = np.where(c > 0.0, np.abs(length) / c, np.inf)
    return dt
