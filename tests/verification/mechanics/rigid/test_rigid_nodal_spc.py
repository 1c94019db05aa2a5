"""A nodal rigid body with _SPC keeps its held degrees of freedom at zero under load.

An elastic 10 mm cube whose bottom face is held in y and z by SPC and driven in
x at 1 m/s (prescribed velocity); its top four nodes form a nodal rigid body
with CMO = 1, CON1 = 4 (x and y held), CON2 = 7 (rotations held), launched down
at 2 m/s and sideways at 1 m/s. The sheared, crushed element pushes the body
sideways and tilts it (the gathered x force and moment are not zero), yet its x
and y velocity and its rotation stay exactly zero and its nodes keep their x and
y coordinates (round-off of xc + R r: 1e-12 mm); z moves freely. Without the
_SPC card the same body moves sideways (the constraint is what holds it).
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    BoundarySpcNode,
    BoundarySpcSet,
    ConstrainedNodalRigidBody,
    ConstrainedNodalRigidBodySpc,
    ControlTermination,
    Deck,
    DefineCurve,
    InitialVelocityGeneration,
    MatElastic,
    Part,
    PrescribedMotionSet,
    SectionSolid,
    SetNodeList,
)
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step
from hollowbody.testing.rigid_decks import HEX, assembly_deck


def _deck(spc: bool) -> Deck:
    x = HEX * 10.0
    deck = Deck()
    deck.add_nodes(np.arange(1, 9), x)
    deck.add_solids(np.array([1]), 1, np.arange(1, 9)[None, :])
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=1.0e-6, e=0.01, pr=0.3))
    deck.add(Part(pid=1, secid=1, mid=1))
    deck.add(SetNodeList(sid=1, nodes=[1, 2, 3, 4]))
    deck.add(BoundarySpcSet(nsid=1, dofy=1, dofz=1))
    deck.add(DefineCurve(lcid=1, points=[[0.0, 1.0], [10.0, 1.0]]))
    deck.add(PrescribedMotionSet(nsid=1, dof=1, vad=0, lcid=1))
    deck.add(SetNodeList(sid=2, nodes=[5, 6, 7, 8]))
    if spc:
        deck.add(ConstrainedNodalRigidBodySpc(pid=10, nsid=2, cmo=1, con1=4, con2=7))
    else:
        deck.add(ConstrainedNodalRigidBody(pid=10, nsid=2))
    deck.add(InitialVelocityGeneration(id=2, styp=3, vx=1.0, vz=-2.0))
    deck.add(ControlTermination(endtim=1.0))
    return deck


def _run(spc: bool, cycles: int = 300):
    model = build_model(_deck(spc))
    plan = assemble(model)
    state = init_state(model, plan)
    start(model, plan, state)
    body = plan.bodies[0]
    x0 = state.x[body.nodes].copy()
    worst = {"v": 0.0, "w": 0.0, "xy": 0.0, "fx": 0.0, "mom": 0.0}
    for _ in range(cycles):
        step(model, plan, state, state.dt_next)
        worst["v"] = max(worst["v"], float(np.abs(body.vel[:2]).max()))
        worst["w"] = max(worst["w"], float(np.abs(body.omega).max()))
        worst["xy"] = max(worst["xy"], float(np.abs(state.x[body.nodes][:, :2]
                                                    - x0[:, :2]).max()))
        worst["fx"] = max(worst["fx"], abs(float(body.force[0])))
        worst["mom"] = max(worst["mom"], float(np.abs(body.moment).max()))
    return body, state, x0, worst


def test_held_dofs_stay_zero_under_load():
    body, state, x0, worst = _run(spc=True)
    assert worst["v"] == 0.0 and worst["w"] == 0.0
    assert worst["xy"] < 1e-12
    assert worst["fx"] > 1e-6 and worst["mom"] > 1e-5  # the element pushes and tilts it
    dz = state.x[body.nodes][:, 2] - x0[:, 2]
    assert np.abs(dz).max() > 0.1  # z is free: the body moved (down, then back up)
    assert np.ptp(dz) < 1e-12  # without tilting


def test_without_spc_the_body_moves_sideways():
    _, _, _, worst = _run(spc=False)
    assert worst["v"] > 0.1 and worst["xy"] > 0.01


def test_spc_on_a_node_of_a_rigid_body_holds_the_body():
    """As LS-DYNA converts nodal SPCs on rigid bodies: the SPC's translations hold the
    centre, its rotations the body's rotation (global axes), with a warning."""
    deck = assembly_deck(end=2.0)
    deck.add(BoundarySpcNode(nid=41, dofx=1, dofry=1))
    model = build_model(deck)
    with pytest.warns(UserWarning, match="SPC on 1 node.* of rigid body 100 .* x, ry held"):
        plan = assemble(model)
    state = init_state(model, plan)
    start(model, plan, state)
    body = next(b for b in plan.bodies if b.pid == 100)
    assert body.fixed_trans.tolist() == [True, False, False]
    assert body.fixed_rot.tolist() == [False, True, False]
    x0 = body.xc.copy()
    for _ in range(50):
        step(model, plan, state, state.dt_next)
    assert body.vel[0] == 0.0 and body.omega[1] == 0.0 and body.xc[0] == x0[0]
    assert abs(body.vel[1]) > 0.1 and abs(body.omega[2]) > 0.01  # the others are free
