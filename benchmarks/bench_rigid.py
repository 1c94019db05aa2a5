"""Rigid-body cost: microseconds per body per cycle of the real cycle (``solver.step``).

A model of N free-flying rigid boxes (each a *MAT_RIGID part of 2 x 2 x 2
hexahedra, 27 nodes, spinning about a non-principal axis), nothing deformable,
so a cycle is the rigid-body work (resultants, velocity and rotation update,
node placement) plus the cycle's fixed overhead. Printed: N, cycles, the median
and mean wall time per cycle and per body-cycle (us), the marginal cost of a
body (N bodies against 1), and for comparison the rigid-body work done one body
at a time with RigidBody's own methods (the cycle before ``solver.rigid_set``).

Run:  python benchmarks/bench_rigid.py [--bodies 30] [--cycles 2000]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    ControlTermination,
    Deck,
    InitialVelocityGeneration,
    MatRigid,
    Part,
    SectionSolid,
)
from hollowbody.mesh import block_mesh
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step


def rigid_boxes(n_bodies: int, per_side: int = 2) -> Deck:
    """N rigid boxes 20 x 10 x 5 mm in a row along x, each spinning and moving."""
    deck = Deck()
    deck.title = f"{n_bodies} rigid boxes"
    deck.add(SectionSolid(secid=1))
    deck.add(MatRigid(mid=1, ro=7.8e-6, e=210.0, pr=0.3))
    nid, eid = 1, 1
    for k in range(n_bodies):
        x, c = block_mesh((per_side, per_side, per_side), (20.0, 10.0, 5.0),
                          (40.0 * k, 0.0, 0.0))
        ids = nid + np.arange(x.shape[0])
        deck.add_nodes(ids, x)
        deck.add_solids(eid + np.arange(c.shape[0]), k + 1, ids[c])
        nid += x.shape[0]
        eid += c.shape[0]
        deck.add(Part(pid=k + 1, secid=1, mid=1, title=f"box {k + 1}"))
        deck.add(InitialVelocityGeneration(id=k + 1, styp=2, omega=0.05, vx=1.0, vy=-0.5,
                                           xc=40.0 * k + 10.0, yc=5.0, zc=2.5,
                                           nx=1.0, ny=1.0, nz=0.3))
    deck.add(ControlTermination(endtim=1.0))
    return deck


def per_cycle(n_bodies: int, cycles: int) -> tuple[float, float]:
    """(median, mean) wall seconds of one cycle of N bodies."""
    model = build_model(rigid_boxes(n_bodies))
    plan = assemble(model)
    state = init_state(model, plan)
    start(model, plan, state)
    dt = state.dt_next
    for _ in range(20):  # warm-up (compilation)
        step(model, plan, state, dt)
    times = np.empty(cycles)
    for k in range(cycles):
        t0 = time.perf_counter()
        step(model, plan, state, dt)
        times[k] = time.perf_counter() - t0
    return float(np.median(times)), float(times.mean())


def per_body_python(n_bodies: int, cycles: int) -> float:
    """Median wall seconds of the rigid-body work of one cycle done one body at a time
    with RigidBody's own methods (how the cycle did it before solver.rigid_set)."""
    model = build_model(rigid_boxes(n_bodies))
    plan = assemble(model)
    state = init_state(model, plan)
    start(model, plan, state)
    dt, x, v, f, mom = state.dt_next, state.x, state.v, state.f, state.mom
    times = np.empty(cycles)
    for k in range(cycles):
        t0 = time.perf_counter()
        for body in plan.bodies:
            body.advance_velocity(dt)
        x_old = [x[b.nodes].copy() for b in plan.bodies]
        for body, xr in zip(plan.bodies, x_old):
            body.advance_position(dt, x)
            v[body.nodes] = (x[body.nodes] - xr) / dt
        for body in plan.bodies:
            body.gather(x, f, mom)
        times[k] = time.perf_counter() - t0
    return float(np.median(times))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bodies", type=int, default=30)
    ap.add_argument("--cycles", type=int, default=2000)
    args = ap.parse_args()
    one_med, one_mean = per_cycle(1, args.cycles)
    med, mean = per_cycle(args.bodies, args.cycles)
    print(f"bodies {args.bodies}, cycles {args.cycles}")
    print(f"cycle: median {med * 1e6:.1f} us, mean {mean * 1e6:.1f} us "
          f"(1 body: median {one_med * 1e6:.1f} us)")
    print(f"per body-cycle: median {med * 1e6 / args.bodies:.2f} us, "
          f"mean {mean * 1e6 / args.bodies:.2f} us; "
          f"marginal (N vs 1 body) {(med - one_med) * 1e6 / (args.bodies - 1):.2f} us")
    py = per_body_python(args.bodies, min(args.cycles, 500))
    print(f"rigid-body work one body at a time (RigidBody methods): median "
          f"{py * 1e6 / args.bodies:.2f} us per body-cycle")


if __name__ == "__main__":
    main()
