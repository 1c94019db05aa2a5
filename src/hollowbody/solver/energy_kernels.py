"""Kernels of the energies a run writes (glstat, matsum, the run monitors).

One pass over the nodes instead of a chain of NumPy temporaries: outputs of
the block tests are due every few cycles, where the NumPy form of these sums
cost a quarter of a small model's wall time. Units: mm, ms, kg; energies J
(kg mm^2/ms^2 = J).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def full_step_velocity(v_half: np.ndarray, f: np.ndarray, inv_m: np.ndarray, half: float,
                       fixed: np.ndarray, any_fixed: bool, out: np.ndarray) -> None:
    """out (n, 3) mm/ms = v^{n+1/2} + half * f * inv_m, with the SPC'd degrees of
    freedom (``fixed`` (n, 3) bool, read when ``any_fixed``) at zero.

    v_half (n, 3) mm/ms; f (n, 3) kN; inv_m (n,) 1/kg; half: dt^n / 2 ms."""
    n = v_half.shape[0]
    for i in range(n):
        s = half * inv_m[i]
        for k in range(3):
            out[i, k] = 0.0 if any_fixed and fixed[i, k] else v_half[i, k] + s * f[i, k]


@njit(cache=True)
def translational_energy(v: np.ndarray, mass: np.ndarray, nodes: np.ndarray) -> float:
    """Sum of m |v|^2 / 2 (J) over ``nodes`` (k,) int of v (n, 3) mm/ms, mass (n,) kg."""
    s = 0.0
    for j in range(nodes.shape[0]):
        i = nodes[j]
        s += mass[i] * (v[i, 0] * v[i, 0] + v[i, 1] * v[i, 1] + v[i, 2] * v[i, 2])
    return 0.5 * s


@njit(cache=True)
def share_energy(v: np.ndarray, nodes: np.ndarray, mass: np.ndarray) -> float:
    """Sum of m_j |v_{nodes[j]}|^2 / 2 (J): a part's share ``mass`` (k,) kg of its
    ``nodes`` (k,) int."""
    s = 0.0
    for j in range(nodes.shape[0]):
        i = nodes[j]
        s += mass[j] * (v[i, 0] * v[i, 0] + v[i, 1] * v[i, 1] + v[i, 2] * v[i, 2])
    return 0.5 * s


@njit(cache=True)
def rotational_energy(w_half: np.ndarray, mom: np.ndarray, inv_i: np.ndarray, half: float,
                      fixed_rot: np.ndarray, inertia: np.ndarray, nodes: np.ndarray) -> float:
    """Sum of I |w|^2 / 2 (J) over ``nodes`` with the full-step rotational velocity
    w = w^{n+1/2} + half * mom * inv_i (rad/ms), SPC'd rotations at zero.

    w_half (n, 3) rad/ms; mom (n, 3) kN mm; inv_i (n,) 1/(kg mm^2); fixed_rot (n, 3)
    bool; inertia (n,) kg mm^2."""
    s = 0.0
    for j in range(nodes.shape[0]):
        i = nodes[j]
        a = half * inv_i[i]
        e = 0.0
        for k in range(3):
            if not fixed_rot[i, k]:
                w = w_half[i, k] + a * mom[i, k]
                e += w * w
        s += inertia[i] * e
    return 0.5 * s
