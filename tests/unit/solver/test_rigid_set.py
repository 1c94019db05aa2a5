"""All bodies at once (hollowbody.solver.rigid_set) against one body at a time.

The kernels do the arithmetic of RigidBody's methods in another order (sums in
node order, the 3 x 3 solve by the adjugate, Rodrigues written out), so the two
agree to round-off: 1e-12 relative after 400 cycles of tumbling bodies under
random nodal forces and moments (measured ~1e-14).
"""

import copy

import numpy as np

from hollowbody.model.mass import point_mass_properties
from hollowbody.solver.rigid import RigidBody
from hollowbody.solver.rigid_set import RigidBodySet


def _bodies(rng, n_bodies=5, per=12):
    bodies, offset = [], 0
    x = []
    for k in range(n_bodies):
        x0 = rng.normal(size=(per, 3)) * [20.0, 8.0, 4.0] + [60.0 * k, 0.0, 0.0]
        m = rng.uniform(0.01, 0.2, size=per)
        p = point_mass_properties(x0, m)
        fixed_r = np.array([k == 1, False, False])
        bodies.append(RigidBody(
            pid=k + 1, nodes=np.arange(offset, offset + per), mass=p.mass,
            xc=p.centre.copy(), inertia0=p.inertia, rot=np.eye(3),
            vel=rng.normal(size=3), omega=rng.normal(size=3) * 0.05, local0=x0 - p.centre,
            fixed_trans=np.array([k == 2, False, k == 2]), fixed_rot=fixed_r,
            force=np.zeros(3), moment=np.zeros(3), prescribed_trans=np.zeros(3, bool),
            prescribed_rot=np.array([False, k == 3, False]), xc0=p.centre.copy()))
        bodies[-1].omega[fixed_r] = 0.0
        x.append(x0)
        offset += per
    return bodies, np.concatenate(x)


def test_set_equals_one_body_at_a_time():
    rng = np.random.default_rng(7)
    bodies, x0 = _bodies(rng)
    ref = copy.deepcopy(bodies)
    n = x0.shape[0]
    xa, xb = x0.copy(), x0.copy()
    va, vb = np.zeros((n, 3)), np.zeros((n, 3))
    wb = np.zeros((n, 3))
    rs = RigidBodySet(bodies)
    dt = 0.01
    for _ in range(400):
        f = rng.normal(size=(n, 3)) * 0.01
        mom = rng.normal(size=(n, 3)) * 0.01
        for b in ref:
            b.gather(xa, f, mom)
            b.advance_velocity(dt)
            xr = xa[b.nodes].copy()
            b.advance_position(dt, xa)
            va[b.nodes] = (xa[b.nodes] - xr) / dt
        rs.gather(xb, f, mom)
        rs.advance_velocity(dt)
        x_old = rs.old_positions(xb)
        rs.advance_position(dt, xb, vb, wb, x_old)
    for a, b in zip(ref, bodies):
        for name in ("xc", "rot", "vel", "omega", "force", "moment", "vel_free", "omega_free"):
            got, want = getattr(b, name), getattr(a, name)
            assert np.allclose(got, want, rtol=1e-12, atol=1e-12 * np.abs(want).max()), name
        assert np.array_equal(b.omega[b.fixed_rot], np.zeros(int(b.fixed_rot.sum())))
    assert np.allclose(xb, xa, rtol=0, atol=1e-11 * np.abs(xa).max())
    assert np.allclose(vb, va, rtol=0, atol=1e-9 * np.abs(va).max())
    for b in bodies:
        assert np.array_equal(wb[b.nodes], np.broadcast_to(b.omega, (b.nodes.size, 3)))


def test_body_attributes_are_views_and_rebinding_is_taken_over():
    rng = np.random.default_rng(1)
    bodies, x0 = _bodies(rng, n_bodies=3)
    rs = RigidBodySet(bodies)
    bodies[1].vel[0] = 123.0  # in place: seen by the set
    assert rs.vel[1, 0] == 123.0
    bodies[2].force = np.array([1.0, 2.0, 3.0])  # rebound: taken over at the next phase
    rs.adopt()
    assert np.array_equal(rs.force[2], [1.0, 2.0, 3.0])
    assert bodies[2].force is rs._views[2]["force"]
