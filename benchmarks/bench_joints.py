"""Cost of joints: 20 rigid bodies on 19 joints beside a 20,000-element model.

Three models stepped with the real cycle (``solver.step.step``), after warm-up:

- A: a free elastic block of 25 x 25 x 32 hexahedra (20,000 elements) with a small
  random velocity field;
- B: A plus a chain of 20 rigid cubes (*MAT_RIGID, *PART_INERTIA) away from it;
- C: B plus 19 revolute joints between neighbouring cubes, each with a
  *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED (curves, damping, stops).

Prints the median and best microseconds per cycle of each (blocks of the three
interleaved, so that the load of a shared machine hits them alike), the joint
term's own time per cycle and per joint-cycle (``JointTerm.add_forces``, timed
alone on the same states), the rigid bodies' own per-cycle work (``solver.rigid``,
timed alone), and the ratios (C - A) / A (bodies and joints) and (C - B) / A (the
joints alone).

Usage: python benchmarks/bench_joints.py [--cycles 200] [--repeats 5] [--threads N]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numba
import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    ConstrainedJoint,
    ControlTermination,
    Deck,
    DefineCoordinateSystem,
    DefineCurve,
    JointStiffnessGeneralized,
    MatElastic,
    MatRigid,
    Part,
    PartInertia,
    SectionSolid,
)
from hollowbody.mesh import block_mesh
from hollowbody.solver.joints import JointTerm
from hollowbody.solver.rigid_set import rigid_set
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step

N_BODIES = 20
UNIT = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1],
                 [0, 1, 1]], float)


def make_deck(bodies: bool, joints: bool) -> Deck:
    deck = Deck()
    x0, conn = block_mesh((25, 25, 32), (250.0, 250.0, 320.0))
    ids = np.arange(1, x0.shape[0] + 1)
    deck.add_nodes(ids, x0)
    deck.add_solids(np.arange(1, conn.shape[0] + 1), 1, ids[conn])
    deck.add(Part(pid=1, secid=1, mid=1, title="block"))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=1e-6, e=0.01, pr=0.45))
    deck.add(ControlTermination(endtim=1.0e3))
    if bodies:
        rng = np.random.default_rng(1)
        for k in range(N_BODIES):
            pid = 10 + k
            nid = 100001 + 8 * k + np.arange(8)
            corner = np.array([400.0 + 10.0 * k, 0.0, 0.0])
            deck.add_nodes(nid, corner + 10.0 * UNIT)
            deck.add_solids(np.array([100001 + k]), pid, nid[None, :])
            deck.add(MatRigid(mid=pid, ro=1e-6, e=210.0, pr=0.3))
            deck.add(PartInertia(pid=pid, secid=1, mid=pid, title=f"segment {k}",
                                 xc=corner[0] + 5.0, yc=5.0, zc=5.0, tm=1.0, ixx=50.0,
                                 iyy=50.0, izz=50.0, vrx=0.01 * rng.standard_normal(),
                                 vry=0.01 * rng.standard_normal()))
        if joints:
            deck.add(DefineCoordinateSystem(cid=1, xl=1.0, yp=1.0))
            q = np.linspace(-2.0, 2.0, 21)
            deck.add(DefineCurve(lcid=1, points=np.column_stack([q, q + q ** 3]).tolist()))
            deck.add(DefineCurve(lcid=2, points=[[-10.0, -1.0], [10.0, 1.0]]))
            for k in range(N_BODIES - 1):
                a, b = 100001 + 8 * k, 100001 + 8 * (k + 1)
                # cube k's face x = x_k + 10 (local nodes 1, 2) meets cube k+1's face
                # x = x_{k+1} (local nodes 0, 3): a hinge along y
                deck.add(ConstrainedJoint(kind="REVOLUTE", n1=a + 1, n2=b, n3=a + 2, n4=b + 3))
                deck.add(JointStiffnessGeneralized(jsid=k + 1, pida=10 + k, pidb=11 + k,
                                                   cida=1, jid=k + 1, lcidph=1, lcidt=1,
                                                   lcidps=1, dlcidt=2, est=10.0, nsat=30.0,
                                                   psat=30.0))
    return deck


def prepare(deck: Deck) -> tuple[object, object, object]:
    """Model, plan and state of ``deck``, stepped past the warm-up (compilation)."""
    model = build_model(deck)
    plan = assemble(model)
    state = init_state(model, plan)
    rng = np.random.default_rng(0)
    state.v[plan.deformable] += 0.1 * rng.standard_normal((int(plan.deformable.sum()), 3))
    start(model, plan, state)
    for _ in range(20):
        step(model, plan, state, state.dt_next)
    return model, plan, state


def time_block(run: tuple, cycles: int) -> float:
    """Seconds per cycle over ``cycles`` cycles."""
    model, plan, state = run
    t0 = time.perf_counter()
    for _ in range(cycles):
        step(model, plan, state, state.dt_next)
    return (time.perf_counter() - t0) / cycles


def time_bodies(plan, state, calls: int, repeats: int) -> float:  # noqa: ANN001
    """Best seconds per cycle of the rigid bodies' own per-cycle work as the step does
    it (gather, velocity and position update of every body at once:
    :class:`hollowbody.solver.rigid_set.RigidBodySet`), timed alone."""
    rs = rigid_set(plan)
    x, v, f, mom = state.x.copy(), state.v.copy(), state.f.copy(), state.mom.copy()
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            rs.gather(x, f, mom)
            rs.advance_velocity(0.0)
            rs.advance_position(0.0, x, v, None, rs.old_positions(x))
        best = min(best, (time.perf_counter() - t0) / calls)
    return best


def time_joint_term(plan, state, calls: int, repeats: int) -> tuple[float, float]:  # noqa: ANN001
    term = next(t for t in plan.terms if isinstance(t, JointTerm))
    f, mom = state.f.copy(), state.mom.copy()
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            term.add_forces(state, state.dt)
        samples.append((time.perf_counter() - t0) / calls)
    state.f[:], state.mom[:] = f, mom
    return statistics.median(samples), min(samples)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--threads", type=int, default=None)
    args = ap.parse_args()
    if args.threads:
        numba.set_num_threads(args.threads)
    print(f"numba threads {numba.get_num_threads()}; {args.repeats} blocks of "
          f"{args.cycles} cycles (us per cycle: median / best)")
    labels = {"A": "A block (20,000 hexahedra)", "B": "B + 20 rigid bodies",
              "C": "C + 19 revolute joints with stiffness"}
    runs = {"A": prepare(make_deck(False, False)), "B": prepare(make_deck(True, False)),
            "C": prepare(make_deck(True, True))}
    samples: dict[str, list[float]] = {k: [] for k in runs}
    for _ in range(args.repeats):  # interleaved: load changes hit all three alike
        for k, run in runs.items():
            samples[k].append(time_block(run, args.cycles))
    res = {k: (statistics.median(v), min(v)) for k, v in samples.items()}
    for k, (med, best) in res.items():
        print(f"{labels[k]:42s} {med * 1e6:9.1f} / {best * 1e6:9.1f}")
    _, plan, state = runs["C"]
    rb = time_bodies(plan, state, 200, args.repeats)
    print(f"rigid bodies' own work (20 bodies): {rb * 1e6:.1f} us per cycle, "
          f"{rb * 1e6 / N_BODIES:.2f} us per body-cycle")
    jm, jb = time_joint_term(plan, state, 2000, args.repeats)
    n = N_BODIES - 1
    print(f"joint term (19 joints, 38 pairs, 19 stiffnesses): {jm * 1e6:.1f} / {jb * 1e6:.1f} "
          f"us per cycle; {jm * 1e6 / n:.2f} / {jb * 1e6 / n:.2f} us per joint-cycle")
    a, b, c = (res[k][1] for k in "ABC")
    print(f"(C - A) / A = {100 * (c - a) / a:.1f} % (bodies and joints, best blocks); "
          f"(C - B) / A = {100 * (c - b) / a:.1f} % (joints alone)")
    print(f"timed alone: joint term / A = {100 * jb / a:.2f} %; (joint term + rigid bodies' "
          f"work) / A = {100 * (jb + rb) / a:.1f} %")


if __name__ == "__main__":
    main()
