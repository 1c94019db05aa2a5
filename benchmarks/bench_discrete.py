"""Speed of the discrete element groups (springs and dampers).

10 000 springs (pairs of nodes 10 mm apart along x, random small motion) for each
law: S01 linear spring, S02 damper, S04 nonlinear spring (a 15-point curve), S06
general nonlinear spring (loading and unloading curves, isotropic hardening),
translational and torsional. Times ``DiscreteGroupRuntime.add_forces`` (the
kernel over the group plus the per-call Python work: N calls after warm-up,
median and best of repeats) and prints microseconds per spring-cycle.

Usage: python benchmarks/bench_discrete.py [--springs 10000] [--calls 200] [--repeats 7]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from hollowbody.elements.discrete_group import DiscreteGroupRuntime
from hollowbody.model.discrete import DiscreteGroup
from hollowbody.model.model import Curve, MaterialDef

STRAIN = np.linspace(-5.0, 5.0, 15)


class _Model:
    """What a discrete runtime reads of a Model: materials and curves."""

    def __init__(self, kind: str) -> None:
        params = {"spring_elastic": {"K": 1.0}, "damper_viscous": {"DC": 0.1},
                  "spring_nonlinear": {"LCD": 1, "LCR": 0},
                  "spring_general": {"LCDL": 1, "LCDU": 2, "BETA": 1.0, "TYI": 0.0,
                                     "CYI": 0.0}}[kind]
        self.materials = {1: MaterialDef(1, kind, 0.0, params)}
        self.curves = {1: Curve(1, STRAIN, STRAIN * (1.0 + 0.1 * STRAIN ** 2)),
                       2: Curve(2, np.array([-1.0, 1.0]), np.array([-50.0, 50.0]))}


def make_runtime(kind: str, n: int, torsional: bool) -> tuple[DiscreteGroupRuntime, tuple]:
    rng = np.random.default_rng(1)
    x0 = np.zeros((2 * n, 3))
    x0[0::2, 1] = np.arange(n) * 20.0
    x0[1::2] = x0[0::2] + [10.0, 0.0, 0.0]
    group = DiscreteGroup(
        pid=1, kind=kind, mid=1, torsional=torsional,
        elem_ids=np.arange(1, n + 1, dtype=np.int64), n1=np.arange(0, 2 * n, 2),
        n2=np.arange(1, 2 * n, 2), scale=np.ones(n), offset=np.zeros(n),
        print_flag=np.zeros(n, np.int64), fixed_axis=np.zeros(n, bool), axis=np.zeros((n, 3)))
    rt = DiscreteGroupRuntime(group, _Model(kind), x0)
    minv = np.full(2 * n, 1.0)
    rt.bind(np.full(2 * n, 1.0), np.full(2 * n, 0.1), minv, np.full(2 * n, -1))
    x = x0 + rng.normal(scale=0.5, size=x0.shape)
    v = rng.normal(scale=1.0, size=x0.shape)
    w = rng.normal(scale=0.1, size=x0.shape)
    return rt, (x, v, w, np.zeros_like(x0), np.zeros_like(x0))


def time_calls(fn, calls: int, repeats: int) -> tuple[float, float]:
    """Median and best seconds per call over ``repeats`` blocks of ``calls`` calls."""
    fn()
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        samples.append((time.perf_counter() - t0) / calls)
    return statistics.median(samples), min(samples)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--springs", type=int, default=10_000)
    ap.add_argument("--calls", type=int, default=200)
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args()
    n = args.springs
    print(f"{n} springs, {args.calls} calls x {args.repeats} repeats")
    print(f"{'law':<42} {'median us/spring-cycle':>22} {'best':>8}")
    for kind in ("spring_elastic", "damper_viscous", "spring_nonlinear", "spring_general"):
        for torsional in (False, True):
            rt, (x, v, w, f, mom) = make_runtime(kind, n, torsional)

            def call(rt=rt, x=x, v=v, w=w, f=f, mom=mom) -> None:
                rt.add_forces(x, v, 1e-3, f, w, mom)

            med, best = time_calls(call, args.calls, args.repeats)
            label = rt.law_name() + (" (torsional)" if torsional else "")
            print(f"{label:<42} {1e6 * med / n:>22.4f} {1e6 * best / n:>8.4f}")


if __name__ == "__main__":
    main()
