"""Thread scaling of the block test: one thread against two, per wait policy.

    python benchmarks/bench_threads.py [--structure hollow] [--speeds 40 70 100]
        [--repeats 3] [--waits short passive] [-- block options...]

Each run is a fresh ``hollowbody block`` process (the OpenMP wait policy is read
when numba starts its threads): ``short`` leaves the policy to hollowbody (threads
spin ~0.5 ms before they sleep, contact kernels threaded from 256 active rows),
``passive`` sets ``OMP_WAIT_POLICY=passive`` (threads sleep at once). Runs of one
speed alternate between the settings so that a change of the machine's load hits
them alike. Prints per speed and setting the median wall time, element and contact
seconds (``timing_seconds`` of summary.json), the contact share, and the speed-ups
of two threads over one. Options after ``--`` go to ``hollowbody block`` (e.g. the
walls' ``--E 60.19 --yield 47.58 --etan 44.64 --wall-hourglass 4``). Run once
before measuring: the first run of a fresh install compiles the kernels.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path


def one_run(out: Path, structure: str, speed: float, threads: int, wait: str,
            extra: list[str]) -> dict:
    env = dict(os.environ)
    env.pop("OMP_WAIT_POLICY", None)
    env.pop("GOMP_SPINCOUNT", None)
    if wait == "passive":
        env["OMP_WAIT_POLICY"] = "passive"
    cmd = [sys.executable, "-m", "hollowbody", "block", "--structure", structure,
           "--speed", f"{speed:g}", "--threads", str(threads), "--no-vtk", "--quiet",
           "--overwrite", "--out", str(out), *extra]
    subprocess.run(cmd, env=env, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)  # the runs' warnings: in their summaries
    s = json.loads((out / "summary.json").read_text())
    t = s["timing_seconds"]
    return {"wall": s["wall_seconds"], "elements": t["elements"], "contact": t["contact"],
            "cycles": s["cycles"], "dropped": "thread_changes" in s}


def main() -> None:
    argv = sys.argv[1:]
    extra: list[str] = []
    if "--" in argv:
        i = argv.index("--")
        argv, extra = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--structure", default="hollow", choices=["solid", "hollow"])
    ap.add_argument("--speeds", type=float, nargs="+", default=[40.0, 70.0, 100.0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--waits", nargs="+", default=["short", "passive"],
                    choices=["short", "passive"])
    a = ap.parse_args(argv)
    settings = [(1, "short")] + [(2, w) for w in a.waits]
    print(f"{a.structure} block, {a.repeats} runs per setting (median); load average "
          f"{os.getloadavg()[0]:.2f} at start")
    print(f"{'km/h':>5} {'threads':>7} {'wait':>8} {'cycles':>6} {'wall s':>7} "
          f"{'elem s':>7} {'contact s':>9} {'contact %':>9}")
    with tempfile.TemporaryDirectory(prefix="bench_threads_") as tmp:
        for speed in a.speeds:
            runs: dict[tuple[int, str], list[dict]] = {k: [] for k in settings}
            for _ in range(a.repeats):
                for k in settings:
                    runs[k].append(one_run(Path(tmp) / "run", a.structure, speed, k[0], k[1],
                                           extra))
            med = {k: {f: statistics.median(r[f] for r in v)
                       for f in ("wall", "elements", "contact")} for k, v in runs.items()}
            for k in settings:
                m = med[k]
                drop = " (dropped to 1 thread)" if any(r["dropped"] for r in runs[k]) else ""
                print(f"{speed:5g} {k[0]:7d} {k[1] if k[0] > 1 else '-':>8} "
                      f"{runs[k][0]['cycles']:6d} {m['wall']:7.2f} {m['elements']:7.2f} "
                      f"{m['contact']:9.2f} {100 * m['contact'] / m['wall']:8.0f} %{drop}")
            one = med[(1, "short")]
            for w in a.waits:
                two = med[(2, w)]
                print(f"      2 threads ({w}) over 1: wall {one['wall'] / two['wall']:.2f}x, "
                      f"elements {one['elements'] / two['elements']:.2f}x, contact "
                      f"{one['contact'] / max(two['contact'], 1e-9):.2f}x")


if __name__ == "__main__":
    main()
