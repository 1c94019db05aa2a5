"""Speed of the solid element groups (one-point hexahedron + material).

A 40 x 40 x 32 block (51 200 elements, 7.5 mm cubes) with *MAT_ELASTIC and with
MAT_181 (the DESIGN muscle curve), a small random velocity field; times
``SolidGroupRuntime.add_forces`` (N calls after warm-up, median of repeats)
with 1 and 2 numba threads and prints microseconds per element-cycle (median
and best block), plus
the split between the element kernel and the two force-assembly variants
(serial scatter, parallel node gather).

The hourglass forms are compared on MAT_181 (IHQ 1, 4, 6, 7) and MAT_ELASTIC
(IHQ 4, 6), and the fully integrated element (ELFORM 2, no hourglass control) on
both; ``--cases`` picks some of them by label.

Usage: python benchmarks/bench_solid.py [--calls 50] [--repeats 9] [--threads 1 2]
       [--cases "hex + MAT_181, IHQ=4" "hex + MAT_181, IHQ=6"]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numba
import numpy as np

from hollowbody.elements.assembly import scatter_add
from hollowbody.elements.solid_group import SolidGroupRuntime
from hollowbody.mesh import block_mesh
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, SolidGroup

MUSCLE_STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                          0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                       0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])


def make_runtime(kind: str, ihq: int = 1,
                 elform: int = 1) -> tuple[SolidGroupRuntime, np.ndarray]:
    x0, conn = block_mesh((40, 40, 32), (300.0, 300.0, 240.0))
    group = SolidGroup(1, np.arange(1, conn.shape[0] + 1, dtype=np.int64), conn)
    curves = {}
    if kind == "elastic":
        mat = MaterialDef(1, "elastic", 1e-6, {"E": 0.01, "PR": 0.45})
    else:
        mat = MaterialDef(2, "rubber181", 1e-6, {"KM": 1.0, "MU": 0.1, "G": 0.0, "SIGF": 0.0,
                                                 "SGL": 1.0, "SW": 1.0, "ST": 1.0, "LCID": 1})
        curves = {1: Curve(1, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}
    rt = SolidGroupRuntime(group, mat, HourglassDef(0, ihq=ihq), curves, x0, elform=elform)
    return rt, x0


def time_calls(fn, calls: int, repeats: int) -> tuple[float, float]:
    """Median and best seconds per call over ``repeats`` blocks of ``calls`` calls.

    On a shared machine the best block is the better estimate of the code's
    speed (other processes only ever slow it down); both are printed.
    """
    fn()
    samples = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        samples.append((time.perf_counter() - t0) / calls)
    return statistics.median(samples), min(samples)


def bench(kind: str, ihq: int, threads: int, calls: int, repeats: int,
          elform: int = 1) -> dict[str, float]:
    numba.set_num_threads(threads)
    rt, x0 = make_runtime(kind, ihq, elform)
    rng = np.random.default_rng(0)
    v = rng.normal(scale=0.1, size=x0.shape)
    dt = 1e-4
    x = x0 + dt * v
    f = np.zeros_like(x0)
    rt.add_forces(x0.copy(), np.zeros_like(x0), 0.0, f)
    n = rt.n_elem

    def full() -> None:
        x[:] += dt * v  # the mesh keeps moving (eigen-solver warm starts see real changes)
        rt.add_forces(x, v, dt, f)

    t_full, t_best = time_calls(full, calls, repeats)

    def scatter() -> None:
        scatter_add(rt.connectivity_used(), rt._fwork, f)

    def gather() -> None:
        rt._gather.add(rt._fwork, f)

    t_scatter = time_calls(scatter, calls, repeats)[0]
    t_gather = time_calls(gather, calls, repeats)[0] if rt._gather is not None else float("nan")
    used = t_gather if (rt._gather is not None and threads > 1) else t_scatter
    us = 1e6 / n
    return {"full": t_full * us, "best": t_best * us, "kernel": (t_full - used) * us,
            "scatter": t_scatter * us, "gather": t_gather * us}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--calls", type=int, default=50)
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--cases", nargs="+", default=None, help="case labels (default: all)")
    args = ap.parse_args()
    threads = [t for t in args.threads if t <= numba.config.NUMBA_NUM_THREADS]
    print(f"51 200 elements, {args.calls} calls x {args.repeats} repeats (median); "
          "microseconds per element-cycle")
    print(f"{'case':28s} {'thr':>3s} {'median':>7s} {'best':>7s} {'kernel':>7s} "
          f"{'scatter':>8s} {'gather':>7s}")
    results: dict[tuple[str, int], dict[str, float]] = {}
    cases = [("elastic", 1, "hex + MAT_ELASTIC, IHQ=1"),
             ("elastic", 4, "hex + MAT_ELASTIC, IHQ=4"),
             ("elastic", 6, "hex + MAT_ELASTIC, IHQ=6"),
             ("rubber181", 1, "hex + MAT_181, IHQ=1"),
             ("rubber181", 4, "hex + MAT_181, IHQ=4"),
             ("rubber181", 6, "hex + MAT_181, IHQ=6"),
             ("rubber181", 7, "hex + MAT_181, IHQ=7"),
             ("elastic", 0, "hex + MAT_ELASTIC, ELFORM 2"),
             ("rubber181", 0, "hex + MAT_181, ELFORM 2")]
    if args.cases:
        unknown = set(args.cases) - {c[2] for c in cases}
        if unknown:
            raise SystemExit(f"unknown cases: {sorted(unknown)}")
        cases = [c for c in cases if c[2] in args.cases]
    for kind, ihq, label in cases:
        for t in threads:
            r = bench(kind, max(ihq, 1), t, args.calls, args.repeats, 2 if ihq == 0 else 1)
            results[(label, t)] = r
            print(f"{label:28s} {t:3d} {r['full']:7.3f} {r['best']:7.3f} {r['kernel']:7.3f} "
                  f"{r['scatter']:8.3f} {r['gather']:7.3f}")
    if 1 in threads and 2 in threads:
        for label in dict.fromkeys(k[0] for k in results):
            s = results[(label, 1)]["full"] / results[(label, 2)]["full"]
            sb = results[(label, 1)]["best"] / results[(label, 2)]["best"]
            print(f"speed-up 2 threads, {label}: {s:.2f}x (median), {sb:.2f}x (best)")


if __name__ == "__main__":
    main()
