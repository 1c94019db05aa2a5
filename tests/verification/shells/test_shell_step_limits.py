"""The shell time step (LS-DYNA ISDO = 0) against the exact limit of free shell meshes.

Rule: ``dt = L_s / c``, ``L_s = A / longest side``, ``c = sqrt(E / (rho (1 - nu^2)))``
(``ShellGroupRuntime.dt_elem``, unscaled). Exact: ``2 / omega_max``, omega_max^2 the
largest eigenvalue of M^-1 K over translations and rotations (lumped masses and the
runtime's rotational inertias; K assembled column by column from central finite
differences of the group's own force routine about the flat stress-free mesh, with
its default hourglass control and drilling stiffness). Elastic steel, nu 0.3, two
integration points, 10 mm elements, free edges.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from shell_driver import ShellDriver, elastic, plate_mesh, section


def mesh(name: str) -> tuple[np.ndarray, np.ndarray]:
    if name == "square":
        return plate_mesh(40.0, 40.0, 4, 4)
    if name == "rectangle":
        return plate_mesh(40.0, 20.0, 4, 4)  # 10 x 5 mm elements
    if name == "strip":
        return plate_mesh(40.0, 10.0, 4, 1)
    if name == "distorted":
        x, c = plate_mesh(40.0, 40.0, 4, 4)
        inner = (x[:, 0] > 0) & (x[:, 0] < 40) & (x[:, 1] > 0) & (x[:, 1] < 40)
        x = x.copy()
        x[inner, :2] += np.random.default_rng(3).uniform(-2.5, 2.5, (int(inner.sum()), 2))
        return x, c
    return plate_mesh(10.0, 10.0, 1, 1)  # "lone"


def driver(name: str, thickness: float = 1.0) -> ShellDriver:
    x, c = mesh(name)
    return ShellDriver(x, c, elastic(), section(nip=2), thickness=thickness)


def omega_max(d: ShellDriver) -> float:
    """Largest circular frequency (1/ms) of the driver's free mesh."""
    rt = d.rt
    saved = {k: getattr(rt, k) for k in rt.STATE_FIELDS}
    saved = {k: (np.copy(v) if isinstance(v, np.ndarray) else v) for k, v in saved.items()}
    x0 = d.x.copy()
    n = x0.shape[0]
    k_mat = np.zeros((6 * n, 6 * n))
    dq = 1e-7
    for j in range(6 * n):
        for sign in (1.0, -1.0):
            for name, value in saved.items():  # every column from the stress-free state
                if isinstance(value, np.ndarray):
                    getattr(rt, name)[...] = value
                elif isinstance(value, list):
                    setattr(rt, name, list(value))
                else:
                    setattr(rt, name, value)
            q = np.zeros((n, 6))
            q.flat[j] = sign * dq
            u, w = np.ascontiguousarray(q[:, :3]), np.ascontiguousarray(q[:, 3:])
            f, m = np.zeros((n, 3)), np.zeros((n, 3))
            # rates q over dt = 1 ms: the increment is q
            rt.add_forces(np.ascontiguousarray(x0 + u), u, 1.0, f, w, m)
            k_mat[:, j] -= sign * np.concatenate([f, m], axis=1).ravel() / (2.0 * dq)
    mass = np.concatenate([np.repeat(d.m[:, None], 3, axis=1),
                           np.repeat(d.inertia[:, None], 3, axis=1)], axis=1).ravel()
    a = 0.5 * (k_mat + k_mat.T) / np.sqrt(np.outer(mass, mass))
    return math.sqrt(np.linalg.eigvalsh(a).max())


def test_rule_is_lsdyna_isdo0():
    """dt_elem = (A / longest side) / sqrt(E / (rho (1 - nu^2))), to round-off."""
    d = driver("rectangle")
    c = math.sqrt(210.0 / (7.85e-6 * (1.0 - 0.3 ** 2)))
    np.testing.assert_allclose(d.rt.dt_elem, 50.0 / 10.0 / c, rtol=1e-12)


@pytest.mark.parametrize("name,low,high", [
    # regular meshes: the rule is the exact limit (measured 0.994, 0.999, 0.963)
    ("square", 0.98, 1.01), ("rectangle", 0.98, 1.01), ("strip", 0.95, 1.0),
    # distorted interior nodes (+-2.5 mm): conservative (measured 1.51)
    ("distorted", 1.3, 1.7),
])
@pytest.mark.parametrize("thickness", [1.0, 3.0])
def test_exact_limit_over_rule(name, low, high, thickness):
    """(2 / omega_max) / min dt_elem within the stated band; the finite-difference
    omega_max is good to ~1e-5, so the bands are the measured values +-1.5 % (regular)
    and +-0.2 (distorted, random nodes). With TSSFAC 0.9 every mesh here is stable."""
    d = driver(name, thickness)
    ratio = 2.0 / omega_max(d) / float(d.rt.dt_elem.min())
    assert low < ratio < high


def test_lone_square_breathing_mode():
    """A lone free square's in-plane breathing mode is sqrt(1 + nu) above 2 / dt:
    exact / rule = 1 / sqrt(1.3) = 0.877, so at TSSFAC 0.9 omega dt / 2 = 1.026 (the
    lone element is unstable, as with LS-DYNA's rule; in a mesh the rule holds)."""
    d = driver("lone")
    ratio = 2.0 / omega_max(d) / float(d.rt.dt_elem.min())
    assert ratio == pytest.approx(1.0 / math.sqrt(1.3), rel=1e-3)


@pytest.mark.parametrize("name", ["square", "rectangle", "distorted"])
def test_free_mesh_with_random_velocities_stays_stable(name):
    """5,000 cycles at TSSFAC 0.9 from random plus node-alternating velocities and
    random rotation rates: the half-step kinetic energy of the last 10 % stays below
    that of the first 10 % (measured 0.06-0.11: the viscous hourglass control damps
    the hourglass content; at TSSFAC 1.0 the square and rectangular meshes blow up
    within 42 and 937 cycles, the distorted one stays stable) and the energy (kinetic
    + internal + hourglass) after the first 10 % varies by less than 10 % (measured
    1.5-8 %: the half-step estimate of the high modes' kinetic energy is inexact near
    the limit)."""
    d = driver(name)
    rng = np.random.default_rng(1)
    n = d.x.shape[0]
    amp = 0.01
    d.v = rng.normal(scale=amp, size=(n, 3)) + amp * (-1.0) ** np.arange(n)[:, None]
    d.w = rng.normal(scale=amp / 10.0, size=(n, 3))
    e0 = d.kinetic_energy()
    ke, tot = np.zeros(5000), np.zeros(5000)
    for i in range(5000):
        d.step()
        ke[i] = d.kinetic_energy()
        tot[i] = (ke[i] + d.rt.internal_energy + d.rt.hourglass_energy) / e0
    q = 500
    assert np.all(np.isfinite(tot))
    assert ke[-q:].max() < ke[:q].max()
    assert tot[q:].max() - tot[q:].min() < 0.1
