"""Mass, centre and inertia of merged rigid parts, extra nodes and nodal rigid bodies
against hand-computed values.

The bodies are point masses: a one-hexahedron rigid box lumps its mass M equally
on its 8 corners, so about its centre I = M/4 diag(b^2 + c^2, a^2 + c^2, a^2 + b^2)
(a, b, c its edges); *ELEMENT_MASS nodes are point masses. The expected values of
the unions are computed here from the point list directly (sum m, sum m x / M,
sum m (r.r 1 - r r^T)), independently of the parallel-axis sums the code uses.
Everything is summed in double precision over a few dozen terms: the tolerance
is 1e-13 relative (round-off; measured ~1e-16).
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    ConstrainedExtraNodesNode,
    ConstrainedExtraNodesSet,
    ConstrainedNodalRigidBody,
    ConstrainedNodalRigidBodyInertia,
    ConstrainedRigidBodies,
    Part,
    PartInertia,
)
from hollowbody.model.summary import summarize
from hollowbody.solver.setup import assemble
from hollowbody.testing.rigid_decks import BOXES, EXTRA, NRB, assembly_deck, box_nodes

RTOL = 1e-13


def _box_points(pid):
    lo, size, rho, _ = BOXES[pid]
    _, x = box_nodes(pid)
    return x, np.full(8, rho * np.prod(size) / 8.0)


def _points_props(x, m):
    """Hand formula: mass, centre, inertia about the centre of point masses."""
    total = float(np.sum(m))
    c = np.sum(m[:, None] * x, axis=0) / total
    inertia = np.zeros((3, 3))
    for xi, mi in zip(x, m):
        r = xi - c
        inertia += mi * (np.dot(r, r) * np.eye(3) - np.outer(r, r))
    return total, c, inertia


def _body(plan, pid):
    return next(b for b in plan.bodies if b.pid == pid)


def _close(a, b):
    scale = max(np.abs(b).max(), 1e-300)
    assert np.allclose(a, b, rtol=RTOL, atol=RTOL * scale), (a, b)


def test_one_box_matches_the_closed_form():
    plan = assemble(build_model(assembly_deck(merges=False, extra=False, nrb=False)))
    lo, (a, b, c), rho, _ = BOXES[1]
    mass = rho * a * b * c
    body = _body(plan, 1)
    assert body.mass == pytest.approx(mass, rel=RTOL)
    _close(body.xc, np.asarray(lo) + 0.5 * np.array([a, b, c]))
    _close(body.inertia0, mass / 4.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b]))
    assert [bb.pid for bb in plan.bodies] == [1, 2, 3]  # not merged: three bodies


def test_chain_of_merges_with_extra_nodes_and_a_nodal_rigid_body():
    model = build_model(assembly_deck())
    plan = assemble(model)
    assert [b.pid for b in plan.bodies] == [1, 100]  # 1 <- 2 <- 3 is one body
    body = _body(plan, 1)
    assert body.pids == [1, 2, 3] and body.nodes.size == 26
    xs, ms = zip(*[_box_points(p) for p in (1, 2, 3)])
    x = np.concatenate([*xs, [p for p, _, _ in EXTRA.values()]])
    m = np.concatenate([*ms, [w for _, w, _ in EXTRA.values()]])
    mass, centre, inertia = _points_props(x, m)
    assert body.mass == pytest.approx(mass, rel=RTOL)
    _close(body.xc, centre)
    _close(body.inertia0, inertia)
    nrb = _body(plan, 100)
    mass, centre, inertia = _points_props(np.array([p for p, _ in NRB.values()]),
                                          np.array([w for _, w in NRB.values()]))
    assert nrb.mass == pytest.approx(mass, rel=RTOL) and nrb.kind == "nodal"
    _close(nrb.xc, centre)
    _close(nrb.inertia0, inertia)
    # hollowbody check reports the run's own values (one computation)
    rows = {r["pid"]: r for r in summarize(model)["rigid_bodies"]}
    for b in plan.bodies:
        assert rows[b.pid]["mass_kg"] == b.mass
        assert rows[b.pid]["centre_mm"] == b.xc.tolist()
        assert rows[b.pid]["principal_inertia_kg_mm2"] == pytest.approx(
            np.linalg.eigvalsh(b.inertia0), rel=1e-12)
        assert rows[b.pid]["nodes"] == b.nodes.size


GIVEN_XC = np.array([12.0, 4.0, 2.0])
GIVEN_I = np.array([[3.0, 0.2, 0.0], [0.2, 5.0, -0.1], [0.0, -0.1, 6.0]])
GIVEN_M = 0.05


def _with_part_inertia(iflag):
    """Lead part 1 given by *PART_INERTIA; merges and extra nodes on it with ``iflag``."""
    deck = assembly_deck(nrb=False)
    for k, it in enumerate(deck.items):
        if isinstance(it, Part) and it.pid == 1:
            deck.items[k] = PartInertia(pid=1, secid=1, mid=1, title="box 1", xc=GIVEN_XC[0],
                                        yc=GIVEN_XC[1], zc=GIVEN_XC[2], tm=GIVEN_M,
                                        ixx=GIVEN_I[0, 0], ixy=GIVEN_I[0, 1],
                                        ixz=GIVEN_I[0, 2], iyy=GIVEN_I[1, 1],
                                        iyz=GIVEN_I[1, 2], izz=GIVEN_I[2, 2])
        elif isinstance(it, ConstrainedRigidBodies) and it.pidm == 1:
            it.iflag = iflag
        elif isinstance(it, (ConstrainedExtraNodesNode, ConstrainedExtraNodesSet)) and \
                it.pid == 1:
            it.iflag = iflag
    return deck


def test_part_inertia_lead_with_iflag_0_keeps_the_given_values():
    body = _body(assemble(build_model(_with_part_inertia(0))), 1)
    assert body.mass == GIVEN_M
    _close(body.xc, GIVEN_XC)
    _close(body.inertia0, GIVEN_I)


def test_part_inertia_lead_with_iflag_1_adds_what_is_merged():
    body = _body(assemble(build_model(_with_part_inertia(1))), 1)
    # given body + boxes 2, 3 + extra nodes 31 (on part 1, IFLAG 1) and 32 (on part 2)
    xs, ms = zip(*[_box_points(p) for p in (2, 3)])
    x = np.concatenate([*xs, [p for p, _, _ in EXTRA.values()]])
    m = np.concatenate([*ms, [w for _, w, _ in EXTRA.values()]])
    pm, pc, pi = _points_props(x, m)
    mass = GIVEN_M + pm
    centre = (GIVEN_M * GIVEN_XC + pm * pc) / mass
    inertia = np.zeros((3, 3))
    for mk, ck, ik in ((GIVEN_M, GIVEN_XC, GIVEN_I), (pm, pc, pi)):
        d = ck - centre
        inertia += ik + mk * (d @ d * np.eye(3) - np.outer(d, d))
    assert body.mass == pytest.approx(mass, rel=RTOL)
    _close(body.xc, centre)
    _close(body.inertia0, inertia)


def test_nodal_inertia_replaces_the_lumped_masses():
    deck = assembly_deck(extra=False)
    for k, it in enumerate(deck.items):
        if isinstance(it, ConstrainedNodalRigidBody):
            deck.items[k] = ConstrainedNodalRigidBodyInertia(
                pid=100, nsid=100, tm=0.5, nodeid=44, ixx=10.0, ixy=1.0, iyy=20.0, izz=30.0,
                vtx=2.0, vty=0.0, vtz=-1.0, vrx=0.0, vry=0.0, vrz=0.05)
    plan = assemble(build_model(deck))
    nrb = _body(plan, 100)
    assert nrb.mass == 0.5
    _close(nrb.xc, np.asarray(NRB[44][0]))  # NODEID gives the centre
    _close(nrb.inertia0, np.array([[10.0, 1.0, 0.0], [1.0, 20.0, 0.0], [0.0, 0.0, 30.0]]))
    assert nrb.vel.tolist() == [2.0, 0.0, -1.0] and nrb.omega.tolist() == [0.0, 0.0, 0.05]


def test_two_node_body_gets_an_inertia_floor_and_runs():
    """Two point masses have no inertia about their line: the run gives that axis
    1e-6 x the largest moment (warned), and the body tumbles without NaN, its
    nodes 10 mm apart (1e-12 relative)."""
    from hollowbody.io.keyword import SetNodeList
    from hollowbody.solver.state import init_state
    from hollowbody.solver.step import start, step

    deck = assembly_deck(extra=False, nrb=False)
    deck.add_nodes(np.array([51, 52]), np.array([[0.0, 50.0, 0.0], [10.0, 50.0, 0.0]]))
    deck.add_masses(np.array([51, 52]), np.array([51, 52]), 0.001)
    deck.add(SetNodeList(sid=200, nodes=[51, 52]))
    deck.add(ConstrainedNodalRigidBody(pid=200, nsid=200))
    model = build_model(deck)
    with pytest.warns(UserWarning, match="rigid body 200: its nodes lie on a line"):
        plan = assemble(model)
    body = _body(plan, 200)
    largest = 0.002 * 25.0  # 2 x 0.001 kg at 5 mm from the centre
    assert np.linalg.eigvalsh(body.inertia0) == pytest.approx([1e-6 * largest, largest,
                                                                largest], rel=1e-12)
    state = init_state(model, plan)
    start(model, plan, state)
    for _ in range(200):
        step(model, plan, state, state.dt_next)
    x = state.x[body.nodes]
    assert np.all(np.isfinite(x))
    assert np.linalg.norm(x[1] - x[0]) == pytest.approx(10.0, rel=1e-12)
    assert np.abs(body.omega).max() > 0.01  # it tumbles


def test_nodal_inertia_with_principal_moments_about_local_axes():
    """IRCS = 1: principal moments (1, 2, 3) about local axes x' = global y,
    in-plane vector -x (so z' = x' x (-x) = global z, y' = -x): in global axes the
    tensor is diag(2, 1, 3)."""
    deck = assembly_deck(extra=False)
    for k, it in enumerate(deck.items):
        if isinstance(it, ConstrainedNodalRigidBody):
            deck.items[k] = ConstrainedNodalRigidBodyInertia(
                pid=100, nsid=100, tm=0.5, xc=1.0, ircs=1, ixx=1.0, iyy=2.0, izz=3.0,
                ixy=0.7, yl=1.0, xlip=-1.0)
    nrb = _body(assemble(build_model(deck)), 100)
    _close(nrb.inertia0, np.diag([2.0, 1.0, 3.0]))


def test_part_inertia_with_principal_moments_about_local_axes():
    """*PART_INERTIA IRCS = 1, local x = global y, in-plane vector -x: principal
    moments (1, 2, 3) are diag(2, 1, 3) in global axes (as the nodal case)."""
    deck = _with_part_inertia(0)
    for it in deck.items:
        if isinstance(it, PartInertia):
            it.ircs, it.ixx, it.iyy, it.izz, it.ixy, it.yl, it.xlip = 1, 1.0, 2.0, 3.0, 0.7, \
                1.0, -1.0
    body = _body(assemble(build_model(deck)), 1)
    _close(body.inertia0, np.diag([2.0, 1.0, 3.0]))
