"""Cost of gravity and of the planar rigid wall: microseconds per node-cycle.

A deformable block of NX x NX x NZ hexahedra (default 40 x 40 x 10, 18 491 nodes)
standing on z = 0 and a rigid plate of NX x NX hexahedra (one layer) beside it,
with *LOAD_BODY_Z and a *RIGIDWALL_PLANAR floor (every node a slave). One "cycle"
is one call of the term's per-cycle methods on the run's State, as the solver's
loop makes it:

- gravity: ``BodyLoadTerm.add_forces`` (m g on every deformable node, its work)
  and ``after_gather`` (the rigid body): per deformable node;
- rigid wall, deformable nodes: ``constrain`` with every slave node moving into the
  wall (worst case: every node is stopped, friction 0.3), per slave node; and with
  the block at rest above the wall (the test only), per slave node;
- rigid wall, rigid-body nodes: ``add_forces`` with the plate pressed into the wall
  (every node in contact, penalty and friction), per rigid slave node.

The median over repeats is reported. One thread (the terms are numpy, not numba).

    python benchmarks/bench_loads.py [--nx 40 --nz 10 --cycles 50 --repeats 5]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    ControlTermination,
    Deck,
    DefineCurve,
    LoadBody,
    MatElastic,
    MatRigid,
    Part,
    RigidwallPlanar,
    SectionSolid,
)
from hollowbody.mesh import standing_block
from hollowbody.solver.loads import BodyLoadTerm
from hollowbody.solver.rigidwall import RigidWallTerm
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state


def model(nx: int, nz: int):  # noqa: ANN201
    deck = Deck()
    x, c = standing_block((float(nx), float(nx), float(nz)), 1.0)
    ids = 1 + np.arange(x.shape[0])
    deck.add_nodes(ids, x)
    deck.add_solids(1 + np.arange(c.shape[0]), 1, ids[c])
    xr, cr = standing_block((float(nx), float(nx), 1.0), 1.0)
    xr = xr + np.array([2.0 * nx, 0.0, 0.0])
    idr = 1 + ids.size + np.arange(xr.shape[0])
    deck.add_nodes(idr, xr)
    deck.add_solids(1 + c.shape[0] + np.arange(cr.shape[0]), 2, idr[cr])
    deck.add(Part(pid=1, secid=1, mid=1))
    deck.add(Part(pid=2, secid=1, mid=2))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=1.0e-6, e=0.01, pr=0.3))
    deck.add(MatRigid(mid=2, ro=7.85e-6, e=0.01, pr=0.3))
    deck.add(DefineCurve(lcid=1, points=[[0.0, 1.0], [1.0, 1.0]]))
    deck.add(LoadBody(axis="Z", lcid=1, sf=9.81e-3))
    deck.add(RigidwallPlanar(xt=0.0, yt=0.0, zt=0.0, xh=0.0, yh=0.0, zh=1.0, fric=0.3))
    deck.add(ControlTermination(endtim=1.0))
    m = build_model(deck)
    plan = assemble(m)
    return m, plan, init_state(m, plan)


def timed(fn, prepare, cycles: int, repeats: int) -> float:  # noqa: ANN001
    """Median seconds per call of ``fn`` (``prepare`` runs untimed before each call)."""
    runs = []
    for _ in range(repeats):
        total = 0.0
        for _ in range(cycles):
            prepare()
            t0 = time.perf_counter()
            fn()
            total += time.perf_counter() - t0
        runs.append(total / cycles)
    return statistics.median(runs)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nx", type=int, default=40)
    ap.add_argument("--nz", type=int, default=10)
    ap.add_argument("--cycles", type=int, default=50)
    ap.add_argument("--repeats", type=int, default=5)
    a = ap.parse_args()
    m, plan, state = model(a.nx, a.nz)
    dt = 1.0e-3
    state.cycle = 10
    gravity = next(t for t in plan.terms if isinstance(t, BodyLoadTerm))
    wall = next(t for t in plan.terms if isinstance(t, RigidWallTerm))
    n_def = gravity.nodes.size
    rng = np.random.default_rng(0)
    v0 = rng.normal(scale=0.1, size=state.v.shape)

    def gravity_cycle() -> None:
        gravity.add_forces(state, dt)
        gravity.after_gather(state, plan.bodies, dt)

    s = timed(gravity_cycle, lambda: None, a.cycles, a.repeats)
    print(f"gravity: {n_def} deformable nodes + {len(plan.bodies)} rigid body: "
          f"{1e6 * s / n_def:.4f} us per node-cycle ({1e3 * s:.3f} ms per cycle)")

    into = v0.copy()
    into[:, 2] = -10.0  # every node would pass the wall in this step
    n_wall = wall.nodes.size

    def reset_into() -> None:
        state.v[:] = into

    s = timed(lambda: wall.constrain(state, dt), reset_into, a.cycles, a.repeats)
    print(f"rigid wall, deformable nodes all stopped (friction 0.3): {n_wall} slave nodes: "
          f"{1e6 * s / n_wall:.4f} us per slave-node-cycle")
    state.v[:] = 0.0
    s = timed(lambda: wall.constrain(state, dt), lambda: None, a.cycles, a.repeats)
    print(f"rigid wall, deformable nodes at rest above it: "
          f"{1e6 * s / n_wall:.4f} us per slave-node-cycle")

    body = plan.bodies[0]
    n_rigid = wall.rigid_nodes[0].size
    wall.k[:] = 0.1 * body.mass / (n_rigid * dt * dt)
    pressed = state.x.copy()
    pressed[body.nodes, 2] -= 1.0e-3

    def press() -> None:
        state.x[:] = pressed
        state.v[body.nodes] = v0[body.nodes]

    s = timed(lambda: wall.add_forces(state, dt), press, a.cycles, a.repeats)
    print(f"rigid wall, rigid-body nodes all in contact (penalty, friction): {n_rigid} "
          f"slave nodes: {1e6 * s / n_rigid:.4f} us per slave-node-cycle")


if __name__ == "__main__":
    main()
