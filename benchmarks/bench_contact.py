"""Contact speed: microseconds per slave node per cycle, 1 and 2 threads.

A rigid plate of 100 x 100 shell segments (200 x 200 mm) and a deformable
block of 70 x 70 x 1 hexahedra (140 x 140 x 4 mm, ~10k surface nodes)
whose bottom face penetrates the plate by 0.1 mm (about half of the slave
nodes in contact), with random velocities and friction, so every cycle runs
the full narrow phase, friction and force scatter. The bucket sort runs every
``contact_sort_interval`` (100) cycles and its cost is included. Printed: mean
wall time, the median (with the sort's share added; robust on a busy machine)
and the process CPU time. Then the contact's kinematic step limit forced to visit
every near pair (``kinematic_step(inf)``; in a run it visits them only when it can
bind), median per slave node per cycle. Last, the bucket sort alone (the contact's
re-sort: segment boxes, grid, candidate lists, distance cut), median of 20, one
and two threads: at large steps (a fast impactor, few cycles per segment) the contact
re-sorts every few cycles and this is most of its cost.

Run:  python benchmarks/bench_contact.py [--cycles 300] [--kind nodes_to_surface]
"""

from __future__ import annotations

import argparse
import time

import numba
import numpy as np

from hollowbody.contact import ContactRuntime
from hollowbody.mesh import block_mesh, plate_mesh
from hollowbody.testing.models import PartSpec, assemble_model, part_contact


def build(kind: str, n_block: int = 70, n_plate: int = 100):
    xp, cp = plate_mesh((n_plate, n_plate), (200.0, 200.0), (-100.0, -100.0, 0.0))
    # offset so that block nodes do not sit exactly on plate vertices
    xb, cb = block_mesh((n_block, n_block, 1), (140.0, 140.0, 4.0), (-69.3, -69.5, 0.4))
    model = assemble_model([
        PartSpec(1, xb, cb, "solid", "rubber181", {"KM": 0.001, "MU": 0.1}),
        PartSpec(2, xp, cp, "shell", "rigid", {"E": 210.0, "PR": 0.3}, 7.8e-6, 1.0)])
    n = model.n_nodes
    mass = np.full(n, 1.0e-5)
    rigid = np.zeros(n, bool)
    rigid[xb.shape[0]:] = True
    cd = part_contact(1, kind, [1], [2], fs=0.3, fd=0.2, dc=0.1, soft=1)
    rt = ContactRuntime(cd, model, mass, rigid)
    return model, rt


def run(kind: str, cycles: int, threads: int
        ) -> tuple[float, float, float, int, int, float]:
    """Per slave node per cycle: (mean wall us, median wall us, mean process CPU us);
    checked nodes; nodes in contact; median wall us of the forced kinematic step
    limit. The median is robust to a busy machine."""
    numba.set_num_threads(threads)
    model, rt = build(kind)
    rt.parallel_min_nodes = 0 if threads > 1 else 1 << 62
    rt.parallel_min_rows = 0 if threads > 1 else 1 << 62
    n = model.n_nodes
    rng = np.random.default_rng(0)
    x = model.node_x0.copy()
    v = rng.normal(0.0, 0.5, size=(n, 3))
    f = np.zeros((n, 3))
    dt = 1.0e-4
    rt.add_forces(x, v, dt, 0, f)  # compile / first sort
    rt.kinematic_step(np.inf)  # compile
    per = np.empty(cycles)
    kin = np.empty(cycles)
    cpu = 0.0
    for cycle in range(1, cycles + 1):
        f[:] = 0.0
        c0 = time.process_time()
        t = time.perf_counter()
        rt.add_forces(x, v, dt, cycle, f)
        per[cycle - 1] = time.perf_counter() - t
        cpu += time.process_time() - c0
        t = time.perf_counter()
        rt.kinematic_step(np.inf)
        kin[cycle - 1] = time.perf_counter() - t
        x += dt * v
    n_slave = sum(p.nodes.shape[0] for p in rt.passes)
    scale = 1e6 / n_slave
    # the median misses the sort (1 cycle in 100): add its share to it
    sorts = per[np.arange(cycles) % rt.sort_interval == rt.sort_interval - 1]
    med = np.median(per) + (sorts.mean() - np.median(per)) / rt.sort_interval
    return (per.mean() * scale, med * scale, cpu / cycles * scale, n_slave, rt.n_active,
            float(np.median(kin)) * scale)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=300)
    ap.add_argument("--kind", default="nodes_to_surface",
                    choices=["nodes_to_surface", "surface_to_surface"])
    args = ap.parse_args()
    avail = numba.config.NUMBA_NUM_THREADS
    print(f"kind={args.kind} cycles={args.cycles} (numba threads available: {avail})")
    for threads in (1, 2):
        if threads > avail:
            break
        us, med, cpu, n_slave, active, kin = run(args.kind, args.cycles, threads)
        print(f"threads={threads}: {us:.3f} us per slave node per cycle "
              f"(median {med:.3f}; CPU {cpu:.3f} summed over threads; {n_slave} checked "
              f"nodes, {active} in contact; {us * n_slave / 1000:.2f} ms per cycle); "
              f"kinematic step limit, every near pair visited: median {kin:.3f}")
    for threads in (1, 2):
        if threads <= avail:
            print(f"bucket sort (threads={threads}): median {sort_ms(args.kind, threads):.3f} "
                  "ms per re-sort")


def sort_ms(kind: str, threads: int = 1, repeats: int = 20) -> float:
    """Median wall ms of one re-sort of the contact (every pass: segment boxes, grid,
    candidate lists, distance cut) on ``threads`` threads (the threaded search from
    two)."""
    numba.set_num_threads(threads)
    model, rt = build(kind)
    rt.parallel_min_nodes = 0 if threads > 1 else 1 << 62
    f = np.zeros((model.n_nodes, 3))
    x = model.node_x0.copy()
    v = np.zeros_like(x)
    rt.add_forces(x, v, 1.0e-4, 0, f)  # the first call sorts (and compiles)
    times = []
    for k in range(repeats):
        t0 = time.perf_counter()
        rt._sort(1.0e-4, k + 1)
        times.append(time.perf_counter() - t0)
    return 1000.0 * float(np.median(times))


if __name__ == "__main__":
    main()
