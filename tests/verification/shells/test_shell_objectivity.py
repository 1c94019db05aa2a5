"""Objectivity: rigid rotations neither create nor alter stress (co-rotational frame)."""

import math

import numpy as np
import pytest
from shell_driver import ShellDriver, patch_mesh, section

from hollowbody.model.model import MaterialDef

E, NU, RHO = 210.0, 0.3, 7.85e-6


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    k = axis / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def voigt_to_tensor(s):
    return np.array([[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]])


@pytest.mark.parametrize("prestress", [False, True])
def test_large_rigid_rotation(prestress):
    x0, conn, _ = patch_mesh(scale=100.0)
    x0[:, 2] = 0.3 * np.sin(x0[:, 0] / 7.0) * np.cos(x0[:, 1] / 5.0)  # warped elements
    mat = MaterialDef(mid=1, kind="pwl024", density=RHO,
                      params={"E": E, "PR": NU, "SIGY": 0.2, "ETAN": 1.0})
    d = ShellDriver(x0, conn, mat, section(5), thickness=0.5)
    mask = np.ones((8, 3), dtype=bool)
    dt = 1e-4
    d.dt_fixed = dt
    if prestress:  # stretch and bend (into plasticity), then hold
        grad = np.array([[4e-3, 1e-3, 0.0], [1e-3, -2e-3, 0.0], [0.0, 0.0, 0.0]])
        d.prescribed = (mask, lambda _t: x0 @ grad.T)
        d.prescribed_w = (mask, lambda _t: np.tile([0.02, -0.03, 0.0], (8, 1)))
        d.run(1.0)
        assert d.rt.plastic_strain.max() > 0.0
    s_before = d.rt.stress.copy()
    sig_before = d.rt.sig.copy()
    ep_before = d.rt.plastic_strain.copy()
    ie_before = d.rt.internal_energy
    # rigid rotation by 100 degrees about a skew axis in 500 steps: chord velocities
    axis = np.array([1.0, -2.0, 0.5])
    n_steps = 500
    total = math.radians(100.0)
    r_step = rotation(axis, total / n_steps)
    # the angular velocity that matches the chord velocities of a finite step (Cayley)
    omega = axis / np.linalg.norm(axis) * 2.0 * math.tan(0.5 * total / n_steps) / dt
    d.prescribed = None
    d.prescribed_w = None
    d.fix_v[:] = False
    for _ in range(n_steps):
        c = d.x.mean(axis=0)
        x_new = c + (d.x - c) @ r_step.T
        d.v[:] = (x_new - d.x) / dt
        d.w[:] = omega
        d.x[:] = x_new
        d.t += dt
        d.f[:] = 0.0
        d.mom[:] = 0.0
        d.rt.add_forces(d.x, d.v, dt, d.f, d.w, d.mom)
    r = rotation(axis, total)
    scale = max(np.abs(s_before).max(), 1e-3)
    for e in range(conn.shape[0]):
        expected = r @ voigt_to_tensor(s_before[e]) @ r.T
        got = voigt_to_tensor(d.rt.stress[e])
        assert got == pytest.approx(expected, abs=1e-6 * scale)
    assert d.rt.sig == pytest.approx(sig_before, abs=1e-6 * scale)
    assert d.rt.plastic_strain == pytest.approx(ep_before, abs=1e-12)
    assert d.rt.internal_energy == pytest.approx(ie_before, abs=1e-9 + 1e-6 * ie_before)
