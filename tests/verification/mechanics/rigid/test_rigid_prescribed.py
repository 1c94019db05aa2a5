"""*BOUNDARY_PRESCRIBED_MOTION_RIGID on a nodal rigid body's PID and on a part merged
into another body: the motion drives the whole body.

A prescribed velocity (VAD 0) of 3 m/s in z is imposed exactly on the body's
centre velocity from t = 0 (as on any rigid part); x, y and the rotation stay
free. Tolerance: the velocity is set, so equal to round-off (1e-14).
"""

from __future__ import annotations

import pytest

from hollowbody.build import build_model
from hollowbody.io.keyword import DefineCurve, PrescribedMotionRigid
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step
from hollowbody.testing.rigid_decks import assembly_deck


@pytest.mark.parametrize("pid, body_pid", [(100, 100), (3, 1)])
def test_prescribed_velocity_drives_the_body(pid, body_pid):
    deck = assembly_deck(end=2.0)
    deck.add(DefineCurve(lcid=7, points=[[0.0, 3.0], [100.0, 3.0]]))
    deck.add(PrescribedMotionRigid(pid=pid, dof=3, vad=0, lcid=7))
    model = build_model(deck)
    plan = assemble(model)
    state = init_state(model, plan)
    start(model, plan, state)
    body = next(b for b in plan.bodies if b.pid == body_pid)
    z0 = body.xc[2]
    for _ in range(50):
        step(model, plan, state, state.dt_next)
    assert body.vel[2] == pytest.approx(3.0, rel=1e-14)
    assert body.xc[2] - z0 == pytest.approx(3.0 * state.t, rel=1e-12)
    assert abs(body.omega).max() > 0.01  # the rotation is not held
