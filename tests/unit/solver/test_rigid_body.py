"""Rigid-body integration (hollowbody.solver.rigid): conservation laws."""

import numpy as np
import pytest

from hollowbody.model.mass import point_mass_properties
from hollowbody.solver.rigid import RigidBody, _rotation


def _body(vel, omega):
    rng = np.random.default_rng(3)
    x0 = rng.normal(size=(40, 3)) * [30.0, 12.0, 5.0]
    m = rng.uniform(0.01, 0.2, size=40)
    p = point_mass_properties(x0, m)
    return RigidBody(pid=1, nodes=np.arange(40), mass=p.mass, xc=p.centre.copy(),
                     inertia0=p.inertia, rot=np.eye(3), vel=np.array(vel, float),
                     omega=np.array(omega, float), local0=x0 - p.centre,
                     fixed_trans=np.zeros(3, bool), fixed_rot=np.zeros(3, bool),
                     force=np.zeros(3), moment=np.zeros(3),
                     prescribed_trans=np.zeros(3, bool), prescribed_rot=np.zeros(3, bool),
                     xc0=p.centre.copy()), x0


def test_rotation_matrix_is_orthonormal():
    r = _rotation(np.array([0.3, -1.2, 0.7]))
    assert np.allclose(r @ r.T, np.eye(3), atol=1e-14)
    assert np.linalg.det(r) == pytest.approx(1.0)


def test_free_body_keeps_linear_and_angular_momentum():
    """Torque-free tumbling about a non-principal axis: momentum exact, L within 1e-3.

    The gyroscopic term is integrated explicitly (first order), so L drifts
    by O(dt); with dt * |w| ~ 1e-3 rad per step over ~3 rad of rotation the
    measured drift is 4e-4 (L) and 3e-4 (energy); 1e-3 bounds it with margin
    and halving dt halves it.
    """
    body, x0 = _body([1.0, -2.0, 0.5], [0.02, 0.05, -0.03])
    x = x0.copy()
    p0 = body.mass * body.vel.copy()
    l0 = body.inertia() @ body.omega
    e0 = body.kinetic_energy()
    dt = 0.015
    for _ in range(3000):
        body.gather(x, np.zeros_like(x))
        body.advance_velocity(dt)
        body.advance_position(dt, x)
    assert np.allclose(body.mass * body.vel, p0, rtol=0, atol=1e-14)
    l1 = body.inertia() @ body.omega
    assert np.linalg.norm(l1 - l0) / np.linalg.norm(l0) < 1e-3
    assert body.kinetic_energy() == pytest.approx(e0, rel=1e-3)
    # nodes stay rigidly attached: pairwise distances unchanged
    d0 = np.linalg.norm(x0[0] - x0[1:], axis=1)
    d1 = np.linalg.norm(x[0] - x[1:], axis=1)
    assert np.allclose(d0, d1, rtol=1e-12)


def test_constant_force_gives_uniform_acceleration():
    body, x0 = _body([0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    x = x0.copy()
    f = np.zeros_like(x)
    f[:, 2] = -0.1 / x.shape[0]  # total -0.1 kN through the centre on average
    f[:, 2] -= 0.0
    dt, n = 0.01, 200
    body.fixed_rot[:] = True
    for _ in range(n):
        body.gather(x, f)
        body.advance_velocity(dt)
        body.advance_position(dt, x)
    a = -0.1 / body.mass
    assert body.vel[2] == pytest.approx(a * dt * n, rel=1e-12)
    # central difference: displacement exact for constant acceleration with v at half steps
    assert body.xc[2] - body.xc0[2] == pytest.approx(a * dt * dt * n * (n + 1) / 2, rel=1e-12)
