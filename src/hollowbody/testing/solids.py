"""Helpers for tests of the solid element groups: stiffness by finite differences and a
smooth free-vibration velocity field. Units: mm, ms, kN."""

from __future__ import annotations

import math

import numpy as np

from hollowbody.elements.solid_group import SolidGroupRuntime


def forces_from_rest(rt: SolidGroupRuntime, x0: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Nodal forces (n, 3) kN after one step of displacement u (n, 3) mm from rest, dt = 1 ms
    (the group's stresses, hourglass state and previous forces cleared first)."""
    rt.stress[:] = 0.0
    rt.stress_gp[:] = 0.0
    rt._hgstate[:] = 0.0
    rt._hgdisp[:] = 0.0
    rt._fwork[:] = 0.0
    f = np.zeros_like(x0)
    rt.add_forces(x0 + u, u.copy(), 1.0, f)
    return f


def stiffness(rt: SolidGroupRuntime, x0: np.ndarray, eps: float = 1e-7) -> np.ndarray:
    """K (3n, 3n) kN/mm by columns, ``f = -K u``, symmetrised. One call from rest per
    column with displacement eps (mm): exact up to the geometric non-linearity, O(eps)
    relative to the element size."""
    n = x0.size
    k = np.zeros((n, n))
    for j in range(n):
        u = np.zeros(n)
        u[j] = eps
        k[:, j] = -forces_from_rest(rt, x0, u.reshape(-1, 3)).ravel() / eps
    return 0.5 * (k + k.T)


def initial_velocity(x: np.ndarray) -> np.ndarray:
    """Smooth, non-rigid velocity field (n, 3) mm/ms of a box-shaped mesh x (n, 3): bending
    + torsion + breathing."""
    lx = x.max(axis=0)
    s = np.sin(math.pi * x[:, 2] / lx[2])
    v = np.zeros_like(x)
    v[:, 0] = 0.02 * s + 0.01 * (x[:, 1] - lx[1] / 2) * x[:, 2] / lx[2]
    v[:, 1] = -0.01 * (x[:, 0] - lx[0] / 2) * x[:, 2] / lx[2]
    v[:, 2] = 0.01 * (x[:, 2] / lx[2] - 0.5)
    return v


def energy_history(run, rt, cycles: int) -> tuple[np.ndarray, float, float]:  # noqa: ANN001
    """Advance ``run`` (an EngineRun) ``cycles`` cycles; returns the total mechanical energy
    KE + internal + hourglass of group ``rt`` per cycle (cycles,) J, and the largest
    internal and hourglass energies reached (J)."""
    total = np.empty(cycles)
    ie_max = hg_max = 0.0
    for k in range(cycles):
        v = run.step()
        total[k] = run.kinetic(v) + rt.internal_energy + rt.hourglass_energy
        ie_max = max(ie_max, rt.internal_energy)
        hg_max = max(hg_max, rt.hourglass_energy)
    return total, ie_max, hg_max


def rot_axis(axis: np.ndarray, theta: float) -> np.ndarray:
    """(3, 3) rotation by theta (rad) about ``axis`` (Rodrigues)."""
    a = axis / np.linalg.norm(axis)
    k = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + math.sin(theta) * k + (1.0 - math.cos(theta)) * k @ k
