"""*LOAD_NODE_SET on an elastic bar, *LOAD_RIGID_BODY and *LOAD_NODE_POINT on a free
rigid body."""

from __future__ import annotations

import numpy as np
import pytest
from loads_decks import Run, add_block, base_deck

from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    BoundarySpcSet,
    DefineCurve,
    LoadNodePoint,
    LoadNodeSet,
    LoadRigidBody,
    MatElastic,
    Part,
    SectionSolid,
    SetNodeList,
)
from hollowbody.mesh import standing_block

E, RHO, H, N = 0.01, 1.0e-6, 5.0, 10  # GPa, kg/mm^3, mm, elements along the bar
F = 1.0e-4  # kN total on the free end


def _bar() -> tuple:
    """A 5 x 5 x 50 mm column of 10 hexes, PR = 0 (one-dimensional), bottom fixed, a
    step force F in +z on its four top nodes (constant curve from t = 0)."""
    deck = base_deck(8.0, g=None)
    x, conn = standing_block((H, H, N * H), H)
    ids = 1 + np.arange(x.shape[0])
    deck.add_nodes(ids, x)
    deck.add_solids(1 + np.arange(conn.shape[0]), 1, ids[conn])
    deck.add(Part(pid=1, secid=1, mid=1, hgid=1))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=RHO, e=E, pr=0.0))
    deck.add(SetNodeList(sid=1, nodes=ids[x[:, 2] == 0.0].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    top = ids[x[:, 2] == N * H]
    deck.add(SetNodeList(sid=2, nodes=top.tolist()))
    deck.add(DefineCurve(lcid=5, points=[[0.0, 1.0], [100.0, 1.0]]))
    deck.add(LoadNodeSet(nsid=2, dof=3, lcid=5, sf=F / top.size))
    return deck, top


def test_step_load_on_a_bar_overshoots_twice_the_static_displacement():
    """Static u = F L / (E A) = 0.02 mm. A step load on an undamped elastic bar: the
    free end moves from 0 to 2u and back with period 4 L / c = 2 ms (c = sqrt(E / rho)
    = 100 mm/ms). Over 4 periods: maximum 2u within 3 % (measured 1.8 % below: the
    ten-element bar's dispersion rounds the front of the reflected step), time mean u
    within 2 % (measured +0.2 %). The external work is F times the end displacement
    to 1e-9 (the trapezoidal work of a constant force is exact). The balance is
    checked with a ramp below: a step excites the mesh's highest modes, whose
    instantaneous kinetic energy the full-step velocity estimate misses by up to a
    few % (as with any load or constraint)."""
    deck, top = _bar()
    run = Run(deck)
    k = [run.index(int(t)) for t in top]
    length = N * H
    u_static = F * length / (E * H * H)
    u_max, u_sum, span = 0.0, 0.0, 0.0

    def every(r: Run) -> None:
        nonlocal u_max, u_sum, span
        u = float(r.state.x[k, 2].mean() - length)
        u_max = max(u_max, u)
        u_sum += u * r.state.dt
        span += r.state.dt

    run.run_to(8.0, every=every)
    assert abs(u_max / (2.0 * u_static) - 1.0) < 0.03, u_max / u_static
    assert abs(u_sum / span / u_static - 1.0) < 0.02, u_sum / span / u_static
    e = run.energies()
    u_end = float(run.state.x[k, 2].mean() - length)
    assert abs(e["external_work"] - F * u_end) < 1e-9 * F * u_static


def test_ramped_load_on_a_bar_static_displacement_and_energy_balance():
    """The same bar loaded by a ramp F t / 4 ms (twice the bar's period), then held:
    the end reaches the static F L / (E A) within 2 % (the residual oscillation of a
    ramp over two periods is small) and strain + kinetic energy balance the external
    work within 5e-4 from t = 2 ms (measured 2.1e-4, 2e-6 once the load is held)."""
    deck, top = _bar()
    curve = next(it for it in deck.iter_items() if isinstance(it, DefineCurve))
    curve.points = np.array([[0.0, 0.0], [4.0, 1.0], [100.0, 1.0]])
    run = Run(deck)
    k = [run.index(int(t)) for t in top]
    length = N * H
    u_static = F * length / (E * H * H)
    worst, u_sum, span = 0.0, 0.0, 0.0

    def every(r: Run) -> None:
        nonlocal worst, u_sum, span
        if r.state.t > 2.0:
            worst = max(worst, abs(r.energies()["energy_ratio"] - 1.0))
        if r.state.t > 4.0:
            u_sum += float(r.state.x[k, 2].mean() - length) * r.state.dt
            span += r.state.dt

    run.run_to(8.0, every=every)
    assert abs(u_sum / span / u_static - 1.0) < 0.02, u_sum / span / u_static
    assert worst < 5e-4, worst


def _free_body(*loads) -> Run:  # noqa: ANN002
    """A free rigid cube (no gravity) of *PART_INERTIA mass 2 g and inertia
    I = M a^2 / 6 = 0.0333 kg mm^2 (a = 10 mm) about each axis through its centre."""
    deck = base_deck(2.0, g=None)
    add_block(deck, pid=2, size=10.0, h=5.0, z0=0.0, rigid=True, e=0.05, inertia_tm=2.0e-3)
    deck.add(DefineCurve(lcid=5, points=[[0.0, 1.0], [100.0, 1.0]]))
    for ld in loads:
        deck.add(ld)
    return Run(deck)


def test_load_rigid_body_force_and_moment():
    """*LOAD_RIGID_BODY DOF 1 (F = 1e-3 kN) and DOF 7 (M = 1e-3 kN mm): a = F / M =
    0.5 mm/ms^2, alpha = M / I = 0.03 rad/ms^2 about the z axis (a principal axis: no
    gyroscopic moment). The central-difference velocities are exact for constant
    loads: v^{n+1/2} = a (t^{n+1} - dt / 2) to round-off (1e-12); the external work
    equals the kinetic energy to 1e-9."""
    mass, inertia = 2.0e-3, 2.0e-3 * 100.0 / 6.0
    run = _free_body(LoadRigidBody(pid=2, dof=1, lcid=5, sf=1.0e-3),
                     LoadRigidBody(pid=2, dof=7, lcid=5, sf=1.0e-3))
    run.run_to(1.0)
    body = run.plan.bodies[0]
    t_half = run.state.t - 0.5 * run.state.dt
    assert abs(body.vel[0] - 1.0e-3 / mass * t_half) < 1e-12
    assert abs(body.omega[2] - 1.0e-3 / inertia * t_half) < 1e-12
    assert np.abs(body.vel[1:]).max() < 1e-15 and np.abs(body.omega[:2]).max() < 1e-15
    e = run.energies()
    assert abs(e["energy_ratio"] - 1.0) < 1e-6, e


def test_load_node_point_on_a_rigid_body_goes_to_the_body():
    """*LOAD_NODE_POINT on a node of a rigid body: a force F in y at the node (5, 0, 5)
    relative to the centre (5 mm off the centre in x) gives a = F / M and the moment
    r x F = 5 F about z: alpha = 5 F / I. A moment DOF 6 on a node (which has no
    rotational degree of freedom of its own) goes to the body: alpha_y = M_y / I."""
    mass, inertia, f = 2.0e-3, 2.0e-3 * 100.0 / 6.0, 1.0e-4
    probe = _free_body()
    x = probe.model.node_x0
    nid = int(probe.model.node_ids[np.flatnonzero((x[:, 0] == 5.0) & (x[:, 1] == 0.0)
                                                  & (x[:, 2] == 5.0))[0]])
    run = _free_body(LoadNodePoint(nid=nid, dof=2, lcid=5, sf=f),
                     LoadNodePoint(nid=nid, dof=6, lcid=5, sf=f))
    run.step()
    body = run.plan.bodies[0]
    dt = run.state.dt
    # first step: v^{1/2} = a dt / 2
    assert abs(body.vel[1] - f / mass * dt / 2) < 1e-15
    assert abs(body.omega[2] - 5.0 * f / inertia * dt / 2) < 1e-15
    assert abs(body.omega[1] - f / inertia * dt / 2) < 1e-15


def test_moment_on_a_solid_node_is_rejected():
    deck, top = _bar()
    deck.add(LoadNodePoint(nid=int(top[0]), dof=5, lcid=5, sf=1.0))
    with pytest.raises(DeckError, match="no rotational degree of freedom"):
        Run(deck)

