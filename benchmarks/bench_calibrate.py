"""Calibration throughput (evaluations per minute, 1 and 2 workers) and the demo's wall time.

    python benchmarks/bench_calibrate.py [--evaluations 8] [--mesh 30] [--end-time 6]
        [--workers 1,2] [--synthetic] [--cost 1.0] [--skip-demo]

Evaluator: the real hollow block test (coarse mesh, short end time) when the
hollow block is available, else (or with --synthetic) the analytic surrogate
burning ``--cost`` seconds of CPU per evaluation; the output says which.
With 1 worker evaluations run in this process, with N > 1 on a LocalCluster of
N single-threaded worker processes (``--workers`` lists the counts measured;
the cluster's start-up time is printed apart and not counted in the rate).
Then ``hollowbody demo --quick`` is timed (in this process; the first run of a
fresh install also compiles the numba kernels, so run the script twice).
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path


def hollow_available(tmp: Path) -> bool:
    from hollowbody.scenarios.block import BlockConfig, block_impact

    try:
        block_impact(BlockConfig(structure="hollow", mesh=30.0, elements_per_edge=1,
                                 end_time=0.05), tmp / "probe", vtk=False, quiet=True)
    except ValueError:
        return False
    return True


def throughput(sim, workers: int, evaluations: int, tmp: Path) -> tuple[float, float, str]:
    """(cluster start-up s, evaluations per minute, runner description)."""
    from hollowbody.calibrate import CalibrationSettings, GASettings, calibrate, make_space
    from hollowbody.calibrate.runner import make_runner

    t0 = time.perf_counter()
    with make_runner(workers) as runner:
        startup = time.perf_counter() - t0
        settings = CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                                       GASettings(population=evaluations, generations=1,
                                                  seed=workers))
        # the solid reference is run (and timed) apart: only candidate evaluations count
        from hollowbody.calibrate.reference import ensure_references

        ensure_references(sim, (40.0,), tmp / "reference", runner)
        if hasattr(sim, "warm_up"):  # compile the kernels in every worker first
            runner.broadcast(_warm_up, sim)
        t1 = time.perf_counter()
        res = calibrate(settings, tmp, sim, runner=runner)
        wall = time.perf_counter() - t1
        desc = runner.description
    return startup, 60.0 * res.runs_here / wall, desc


def _warm_up(sim) -> None:
    sim.warm_up()


def time_demo(tmp: Path) -> tuple[float, int]:
    import hollowbody.cli.main as cli

    if "demo" not in cli.SUBCOMMANDS:
        cli.SUBCOMMANDS = cli.SUBCOMMANDS + ("demo",)
    t0 = time.perf_counter()
    code = cli.main(["demo", "--quick", "--quiet", "--out", str(tmp / "demo")])
    return time.perf_counter() - t0, code


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--evaluations", type=int, default=8, help="evaluations per measurement")
    ap.add_argument("--mesh", type=float, default=30.0, help="block mesh (mm) of real runs")
    ap.add_argument("--end-time", type=float, default=6.0, help="end time (ms) of real runs")
    ap.add_argument("--synthetic", action="store_true", help="use the surrogate evaluator")
    ap.add_argument("--cost", type=float, default=1.0,
                    help="CPU seconds per synthetic evaluation (default 1)")
    ap.add_argument("--workers", default="1,2",
                    help="worker counts to measure, comma-separated (default 1,2)")
    ap.add_argument("--skip-demo", action="store_true")
    a = ap.parse_args()
    try:
        counts = sorted({int(w) for w in a.workers.split(",") if w.strip()})
    except ValueError:
        ap.error(f"--workers: comma-separated integers expected (got {a.workers!r})")
    if not counts or counts[0] < 1:
        ap.error("--workers: at least one count, each >= 1")

    from hollowbody.calibrate import BlockSimulator, SurrogateSimulator

    tmp = Path(tempfile.mkdtemp(prefix="bench_calibrate_"))
    real = not a.synthetic and hollow_available(tmp)
    if real:
        sim = BlockSimulator.make("muscle", mesh=a.mesh, end_time=a.end_time)
        print(f"evaluator: real hollow block test, mesh {a.mesh:g} mm, end time "
              f"{a.end_time:g} ms, 1 speed (40 km/h)")
    else:
        sim = SurrogateSimulator(cost_seconds=a.cost)
        why = "requested" if a.synthetic else "the hollow block is not available yet"
        print(f"evaluator: SYNTHETIC (analytic surrogate burning {a.cost:g} s CPU per "
              f"evaluation; {why})")
    rates = {}
    for workers in counts:
        startup, rate, desc = throughput(sim, workers, a.evaluations, tmp / f"w{workers}")
        rates[workers] = rate
        print(f"{workers} worker{'s' if workers > 1 else ''} ({desc}): {rate:.1f} "
              f"evaluations/min over {a.evaluations} evaluations; start-up {startup:.1f} s")
    if 1 in rates and 2 in rates:
        print(f"speed-up 2 vs 1 worker: {rates[2] / rates[1]:.2f}")
    if not a.skip_demo:
        wall, code = time_demo(tmp)
        print(f"hollowbody demo --quick: {wall:.0f} s wall (exit code {code})")
    print(f"scratch folder: {tmp}")


if __name__ == "__main__":
    main()
