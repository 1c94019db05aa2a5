"""The open pedestrian standing under gravity: solid and hollow, standing and walking.

    python benchmarks/bench_pedestrian.py --out DIR [--tissue solid hollow]
        [--posture standing walking] [--end-time 150] [--mesh 30] [--threads 1]

For each combination, generates the model (``hollowbody pedestrian``) in
DIR/<tissue>-<posture>, runs it (``hollowbody run``, one thread by default)
unless DIR/<tissue>-<posture>/run already holds a finished run, and writes
DIR/settling.md (the settling table: status, quality, energy ratio, cycles,
wall time, head and sacrum drop, feet, floor force over the body weight,
kinetic energy), DIR/settling.json and DIR/settling.png (head and sacrum
sinking and kinetic energy against time). The default runs take hours on two
cores for the hollow variant (docs/pedestrian.md, Figures).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from hollowbody.body.generate import PedestrianOptions, generate
from hollowbody.body.settling import plot_settling, settling_summary, settling_table
from hollowbody.cli.main import main as cli


def run_case(folder: Path, tissue: str, posture: str, end_time: float, mesh: float,
             threads: int) -> dict:
    """Generate (if missing) and run (if not finished) one model; its settling summary."""
    if not (folder / "pedestrian.k").exists():
        generate(folder, PedestrianOptions(tissue=tissue, posture=posture, mesh=mesh,
                                           end_time=end_time, picture=False))
    run = folder / "run"
    if not (run / "summary.json").exists():
        cli(["run", str(folder / "pedestrian.k"), "--out", str(run), "--overwrite",
             "--threads", str(threads), "--no-vtk"])
    return settling_summary(folder, run)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--tissue", nargs="+", default=["solid", "hollow"])
    ap.add_argument("--posture", nargs="+", default=["standing", "walking"])
    ap.add_argument("--end-time", type=float, default=150.0)
    ap.add_argument("--mesh", type=float, default=30.0)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    runs = {}
    for tissue in a.tissue:
        for posture in a.posture:
            label = f"{tissue}-{posture}"
            runs[label] = run_case(a.out / label, tissue, posture, a.end_time, a.mesh,
                                   a.threads)
    table = settling_table(runs)
    (a.out / "settling.md").write_text(table)
    (a.out / "settling.json").write_text(json.dumps(
        {k: {kk: vv for kk, vv in v.items() if kk != "curves"} for k, v in runs.items()},
        indent=2))
    plot_settling(runs, a.out / "settling.png")
    print(table)


if __name__ == "__main__":
    main()
