"""A body spun about the axis of a revolute joint whose inertia has products (its
principal axes are not the joint axis): free, it would wobble (the gyroscopic
moment w x I w is not zero); on the joint it keeps turning about the joint axis.

Body: 1 kg, centre on the axis (0, 5, 0), inertia [[100, 20, 0], [20, 100, 15],
[0, 15, 100]] kg*mm^2, spun at w = 0.05 rad/ms about y (2000 cycles: 4.5 rad).
Checks: the off-axis angular velocity stays below 5e-3 w (at the start, while the
springs pick up the gyroscopic moment: the joint carries no force at t = 0) and
below 1e-4 w after 400 cycles (the start-up wobble is damped by the joint's
dashpots; the springs let the axis tilt by (moment) / (k arm^2) ~ 1e-5 rad); w_y is
kept within 0.1 % (the joint's forces act on the axis and have no moment about
it); the moment the joint puts on the body equals the gyroscopic moment needed to
turn the body's angular momentum with it, |w x I w| = w^2 sqrt(IXY^2 + IYZ^2),
within 2 % (jntforc's moment, about N2 on the axis; the force is ~0 as the centre
is on the axis).
"""

from __future__ import annotations

import numpy as np
import pytest
from joint_decks import Driver, joint_pair

W, IXY, IYZ = 0.05, 20.0, 15.0


def test_revolute_holds_its_axis_against_the_gyroscopic_moment():
    run = Driver(joint_pair("REVOLUTE", w0=(0.0, W, 0.0), products=(IXY, 0.0, IYZ)))
    b = run.body(2)
    off, wy, moment = [], [], []
    for _ in range(2000):
        run.step()
        off.append(np.hypot(b.omega[0], b.omega[2]))
        wy.append(b.omega[1])
        if run.state.cycle > 200:
            _, m = run.joint.joint_resultants(run.state.x)
            moment.append(np.linalg.norm(m[0]))
    assert max(off) < 5e-3 * W
    assert max(off[400:]) < 1e-4 * W
    assert np.allclose(wy, W, rtol=1e-3)
    expected = W ** 2 * np.hypot(IXY, IYZ)
    assert np.mean(moment) == pytest.approx(expected, rel=0.02)
    assert np.abs(np.array(moment) - expected).max() < 0.1 * expected


def test_revolute_takes_out_the_spin_about_other_axes():
    """Body (isotropic inertia 100 kg*mm^2, centre on the axis) started spinning at
    0.05 rad/ms about an axis 30 degrees off the joint axis (in the x-y plane): the
    joint's reactions have no moment about its axis, so the angular momentum about
    it is kept (w_y = w cos 30 deg, within 0.1 %) while the off-axis spin is taken
    out by the penalty springs and dashpots (below 1e-3 w after 800 cycles); the
    energy taken out, I (w sin 30 deg)^2 / 2, goes to the joint's internal energy
    (within 2 %)."""
    th = np.radians(30.0)
    run = Driver(joint_pair("REVOLUTE", w0=(W * np.sin(th), W * np.cos(th), 0.0)))
    b = run.body(2)
    for _ in range(800):
        run.step()
    assert np.hypot(b.omega[0], b.omega[2]) < 1e-3 * W
    assert b.omega[1] == pytest.approx(W * np.cos(th), rel=1e-3)
    assert run.joint.internal_energy == pytest.approx(0.5 * 100.0 * (W * np.sin(th)) ** 2,
                                                      rel=0.02)
