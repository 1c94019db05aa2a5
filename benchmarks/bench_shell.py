"""Speed of the Belytschko-Lin-Tsay shell runtime: microseconds per element-cycle.

A flat plate of NX x NY shells (default 250 x 200 = 50 000), NIP = 5 Gauss
points through the thickness, random small velocities and angular
velocities; one "cycle" is one ``ShellGroupRuntime.add_forces`` call (stress
update, hourglass, forces, gather, time step), as the solver's loop makes it.

Cases: *MAT_ELASTIC; *MAT_PIECEWISE_LINEAR_PLASTICITY in its elastic range;
the same with a yield stress so low that every point returns to the yield
surface every cycle (worst case of the Newton iteration). Each case is timed
with 1 and 2 threads (``numba.set_num_threads``); the median over repeats is
reported.

    python benchmarks/bench_shell.py [--nx 250 --ny 200 --cycles 20 --repeats 5]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numba
import numpy as np

from hollowbody.elements.shell_group import ShellGroupRuntime
from hollowbody.model.model import HourglassDef, MaterialDef, SectionDef, ShellGroup


def plate(nx: int, ny: int, size: float = 5.0) -> tuple[np.ndarray, np.ndarray]:
    """Nodes (n,3) mm and quads (e,4) of a flat nx x ny plate of size x size mm shells."""
    xs = np.arange(nx + 1) * size
    ys = np.arange(ny + 1) * size
    gx, gy = np.meshgrid(xs, ys)
    x = np.stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)], axis=1)
    j, i = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    a = (j * (nx + 1) + i).ravel()
    conn = np.stack([a, a + 1, a + nx + 2, a + nx + 1], axis=1).astype(np.int32)
    return x, conn


def make_runtime(kind: str, x: np.ndarray, conn: np.ndarray) -> ShellGroupRuntime:
    e = conn.shape[0]
    group = ShellGroup(pid=1, elem_ids=np.arange(1, e + 1, dtype=np.int64), conn=conn,
                       thickness=np.full((e, 4), 1.5))
    params = {"E": 0.1, "PR": 0.3}
    if kind == "elastic":
        mat = MaterialDef(mid=1, kind="elastic", density=1e-6, params=params)
    else:
        sigy = 1e-9 if kind == "mat024_plastic" else 1.0
        mat = MaterialDef(mid=1, kind="pwl024", density=1e-6,
                          params={**params, "SIGY": sigy, "ETAN": 0.001})
    sec = SectionDef(secid=1, kind="shell", elform=2, params={"NIP": 5.0})
    return ShellGroupRuntime(group, mat, sec, HourglassDef(hgid=0), {}, x)


def time_case(kind: str, x0: np.ndarray, conn: np.ndarray, threads: int, cycles: int,
              repeats: int, seed: int = 0) -> tuple[float, float, float]:
    """Microseconds per element-cycle of ``kind`` with ``threads`` threads.

    Returns (median wall, best wall, median process CPU time over all threads).
    On a machine shared with other work the wall times of 2 threads suffer
    most (one descheduled thread stalls the other); the CPU time shows the
    work done.
    """
    numba.set_num_threads(threads)
    rng = np.random.default_rng(seed)
    n = x0.shape[0]
    rt = make_runtime(kind, x0, conn)
    v = 1e-2 * rng.standard_normal((n, 3))
    w = 1e-3 * rng.standard_normal((n, 3))
    f = np.zeros((n, 3))
    m = np.zeros((n, 3))
    x = x0.copy()
    d, _, _ = rt.add_forces(x, v, 0.0, f, w, m)  # compile / warm up
    dt = 0.5 * d
    wall, cpu = [], []
    scale = 1e6 / (cycles * conn.shape[0])
    for _ in range(repeats):
        t0 = time.perf_counter()
        c0 = time.process_time()
        for _ in range(cycles):
            x += dt * v
            f[:] = 0.0
            m[:] = 0.0
            rt.add_forces(x, v, dt, f, w, m)
        wall.append((time.perf_counter() - t0) * scale)
        cpu.append((time.process_time() - c0) * scale)
    return statistics.median(wall), min(wall), statistics.median(cpu)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nx", type=int, default=250)
    ap.add_argument("--ny", type=int, default=200)
    ap.add_argument("--cycles", type=int, default=20)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    x, conn = plate(args.nx, args.ny)
    max_threads = numba.config.NUMBA_NUM_THREADS
    threads = [t for t in (1, 2) if t <= max_threads]
    print(f"{conn.shape[0]} shells, NIP 5, {args.cycles} cycles x {args.repeats} repeats, "
          f"numba {numba.__version__}; us per element-cycle: wall median / wall best / CPU")
    for kind in ("elastic", "mat024_elastic", "mat024_plastic"):
        res = {t: time_case(kind, x, conn, t, args.cycles, args.repeats) for t in threads}
        line = f"{kind:<15}"
        for t, (med, best, cpu) in res.items():
            line += f" | {t} thread(s): {med:6.3f} / {best:6.3f} / {cpu:6.3f}"
        if len(res) == 2:
            line += f" | speed-up (best wall) {res[1][1] / res[2][1]:.2f}x"
        print(line, flush=True)
    print(f"threading layer: {numba.threading_layer()}")


if __name__ == "__main__":
    main()
