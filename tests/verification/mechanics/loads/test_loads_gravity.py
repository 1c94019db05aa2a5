"""*LOAD_BODY_Z: free fall of a deformable block and of a rigid body.

The central-difference scheme integrates a constant acceleration exactly, for any
sequence of steps: v^{n+1/2} = -g (t^n + dt^n / 2) and x^{n+1} - x^n = dt^n v^{n+1/2}
= -g ((t^{n+1})^2 - (t^n)^2) / 2, so z(t) = z0 - g t^2 / 2 holds to round-off at every
cycle. Tolerance 1e-9 mm on a 2 mm fall over ~500 cycles (round-off is ~1e-13 mm).
The external work of gravity (trapezoidal force times the step's displacement) is
then exactly M g (z0 - z) and the kinetic energy 0.5 M v^2 balances it to round-off
(relative 1e-9).
"""

from __future__ import annotations

import numpy as np
from loads_decks import G, Run, add_block, base_deck

from hollowbody.io.keyword import DefineCurve, LoadBodyParts, SetPartList

END = 20.0  # ms: a 1.96 mm fall


def _deck(**kw):
    deck = base_deck(END, **kw)
    add_block(deck, pid=1, size=10.0, h=5.0, z0=100.0)
    # a rigid cube whose *PART_INERTIA mass (3 g) is not its elements' (1 g):
    # gravity must act on the body's mass at its centre of mass
    add_block(deck, pid=2, size=10.0, h=5.0, z0=100.0, x0=50.0, first_node=1001,
              first_elem=1001, rigid=True, e=210.0, inertia_tm=3.0e-3)
    return deck


def test_free_fall_deformable_and_rigid():
    run = Run(_deck())
    z0 = run.state.x[:, 2].copy()
    worst = 0.0

    def check(r):
        nonlocal worst
        t = r.state.t
        worst = max(worst, float(np.abs(r.state.x[:, 2] - (z0 - 0.5 * G * t * t)).max()))

    run.run_to(END, every=check)
    assert run.state.cycle > 300
    assert worst < 1e-9, worst
    body = run.plan.bodies[0]
    t = run.state.t
    # rigid centre and mid-step velocity v^{n+1/2} = -g (t^{n+1} - dt / 2) exact
    assert abs(body.xc[2] - (105.0 - 0.5 * G * t * t)) < 1e-9
    assert abs(body.vel[2] + G * (t - 0.5 * run.state.dt)) < 1e-12
    # weight of the body: its *PART_INERTIA mass
    assert abs(body.force[2] + 3.0e-3 * G) < 1e-15
    e = run.energies()
    mass = run.plan.node_mass[run.plan.deformable].sum() + body.mass
    drop = 0.5 * G * t * t
    assert abs(e["external_work"] - mass * G * drop) < 1e-9 * mass * G * drop
    assert abs(e["kinetic"] - e["external_work"]) < 1e-9 * e["external_work"]
    assert abs(e["energy_ratio"] - 1.0) < 1e-9


def test_time_varying_gravity_work():
    """A ramp a(t) = g t / T: z(t) = z0 - g t^3 / (6 T) (the scheme is second order,
    error O(dt^2): 1e-3 relative); energy balance to 1e-5: the trapezoidal work of a
    force linear in time is second order, its error ~ (dt / T)^2 = (0.045 / 20)^2
    = 5e-6 (measured 1.8e-6)."""
    deck = _deck(g=None)
    deck.add(DefineCurve(lcid=1, points=[[0.0, 0.0], [END, 1.0]]))
    from hollowbody.io.keyword import LoadBody
    deck.add(LoadBody(axis="Z", lcid=1, sf=G))
    run = Run(deck)
    run.run_to(END)
    t = run.state.t
    z = run.state.x[0, 2]
    exact = 100.0 - G * t ** 3 / (6.0 * END)
    assert abs(z - exact) < 1e-3 * (100.0 - exact)
    e = run.energies()
    assert abs(e["energy_ratio"] - 1.0) < 1e-5, e


def test_load_body_parts_only_listed_parts():
    """*LOAD_BODY_PARTS with part 2 only: the rigid body falls, the block stays."""
    deck = _deck()
    deck.add(SetPartList(sid=7, parts=[2]))
    deck.add(LoadBodyParts(psid=7))
    run = Run(deck)
    run.run_to(5.0)
    t = run.state.t
    block = run.plan.deformable
    assert np.abs(run.state.x[block, 2] - run.model.node_x0[block, 2]).max() == 0.0
    assert abs(run.plan.bodies[0].xc[2] - (105.0 - 0.5 * G * t * t)) < 1e-9


def test_gravity_along_x_is_opposite_to_the_base_acceleration():
    """*LOAD_BODY_X with a positive value: the body force points to -x."""
    deck = _deck(g=None)
    deck.add(DefineCurve(lcid=1, points=[[0.0, 1.0], [END, 1.0]]))
    from hollowbody.io.keyword import LoadBody
    deck.add(LoadBody(axis="X", lcid=1, sf=2.0 * G))
    run = Run(deck)
    run.run_to(2.0)
    t = run.state.t
    dx = run.state.x[:, 0] - run.model.node_x0[:, 0]
    assert np.allclose(dx, -G * t * t, rtol=0, atol=1e-10)
