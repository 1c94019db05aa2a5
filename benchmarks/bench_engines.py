"""The block test on hollowbody's engine and on OpenRadioss: the cross-engine table.

Runs (or reads, with ``--table-only``) the solid and the hollow muscle block at
40 km/h, one engine after the other on one thread (``--threads 1``, OpenRadioss
``--np 1``), each in ``OUT/<structure>-<engine>/``, and prints one row per run:

    structure, engine, status, peak force CFC 600 (as the block reports) and
    CFC 180 [kN], maximum impactor displacement [mm], energy ratio at the end,
    cycles, first time step [ms], wall time [s]

then writes ``results.json`` and ``force_displacement_engines.png`` (the
force-displacement curves of every run, CFC 600) into OUT; ``--png`` copies the
plot elsewhere (docs/). OpenRadioss is found through OPENRADIOSS_PATH or the
PATH (docs/engines.md); without it only hollowbody's rows are made.

    NUMBA_NUM_THREADS=1 python benchmarks/bench_engines.py --out DIR
        [--engines hollowbody openradioss] [--structures solid hollow] [--speed 40]
        [--table-only] [--png docs/engines_block_fd.png]
"""

from __future__ import annotations

import argparse
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

from hollowbody.curves.cfc import cfc_filter
from hollowbody.io.results.history import read_history


def _row(folder: Path, structure: str, engine: str) -> dict:
    """The table row of one finished run folder (the block's output folder)."""
    s = json.loads((folder / "summary.json").read_text())
    run = folder / "openradioss" if engine == "openradioss" else folder
    fd = np.loadtxt(folder / "force_displacement.csv", delimiter=",", skiprows=1, ndmin=2)
    row = {"structure": structure, "engine": engine, "status": s.get("status"),
           "cycles": s.get("cycles"), "wall_s": s.get("wall_seconds"),
           "energy_ratio": s.get("energy_ratio"), "peak_cfc600_kN": math.nan,
           "peak_cfc180_kN": math.nan, "max_disp_mm": math.nan, "dt0_ms": math.nan}
    if fd.shape[0] > 3:
        t, d, f = fd[:, 0], fd[:, 1], fd[:, 2]
        row["peak_cfc600_kN"] = float(np.max(cfc_filter(t, f, 600.0)))
        row["peak_cfc180_kN"] = float(np.max(cfc_filter(t, f, 180.0)))
        row["max_disp_mm"] = float(np.max(d))
    g = run / "glstat.csv"
    if g.is_file():
        gl = read_history(g)
        dts = gl["dt [ms]"][gl["dt [ms]"] > 0.0]
        if dts.size:
            row["dt0_ms"] = float(dts[0])
        ratio = gl["energy_ratio"][np.isfinite(gl["energy_ratio"])]
        if ratio.size:  # the run's glstat.csv, the same for every engine
            row["energy_ratio"] = float(ratio[-1])
    return row


def _fmt(v: object, spec: str) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    return format(v, spec)


def _plot(rows: list[dict], out: Path, png: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for r in rows:
        folder = out / f"{r['structure']}-{r['engine']}"
        fd = np.loadtxt(folder / "force_displacement.csv", delimiter=",", skiprows=1, ndmin=2)
        if fd.shape[0] < 4:
            continue
        f = cfc_filter(fd[:, 0], fd[:, 2], 600.0)
        ax.plot(fd[:, 1], f, "-" if r["engine"] == "hollowbody" else "--",
                label=f"{r['structure']}, {r['engine']}")
    ax.set_xlim(left=-5.0)  # the rebound beyond the start point is left out
    ax.set_xlabel("impactor displacement [mm]")
    ax.set_ylabel("contact force, CFC 600 [kN]")
    ax.set_title("muscle block, 40 km/h: hollowbody and OpenRadioss")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--engines", nargs="+", default=["hollowbody", "openradioss"])
    ap.add_argument("--structures", nargs="+", default=["solid", "hollow"])
    ap.add_argument("--speed", type=float, default=40.0)
    ap.add_argument("--table-only", action="store_true",
                    help="read the run folders in OUT, run nothing")
    ap.add_argument("--png", type=Path, default=None)
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    for structure in args.structures:
        for engine in args.engines:
            folder = args.out / f"{structure}-{engine}"
            if not args.table_only:
                cmd = [sys.executable, "-m", "hollowbody", "block", "--tissue", "muscle",
                       "--structure", structure, "--speed", f"{args.speed:g}", "--threads",
                       "1", "--no-vtk", "--quiet", "--overwrite", "--out", str(folder)]
                if engine != "hollowbody":
                    cmd += ["--engine", engine, "--np", "1"]
                subprocess.run(cmd, check=False)
            if not (folder / "summary.json").is_file():
                print(f"{structure} {engine}: no run in {folder}")
                continue
            r = _row(folder, structure, engine)
            rows.append(r)
            print(f"{structure:6s} {engine:11s} {str(r['status'])[:20]:20s} "
                  f"peak {_fmt(r['peak_cfc600_kN'], '.2f')} / {_fmt(r['peak_cfc180_kN'], '.2f')}"
                  f" kN  max disp {_fmt(r['max_disp_mm'], '.1f')} mm  ratio "
                  f"{_fmt(r['energy_ratio'], '.4f')}  cycles {r['cycles']}  dt0 "
                  f"{_fmt(r['dt0_ms'], '.3e')} ms  wall {_fmt(r['wall_s'], '.1f')} s",
                  flush=True)
    (args.out / "results.json").write_text(json.dumps(rows, indent=2))
    if rows:
        png = args.out / "force_displacement_engines.png"
        _plot(rows, args.out, png)
        if args.png is not None:
            shutil.copy(png, args.png)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
