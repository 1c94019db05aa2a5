"""``hollowbody demo``: the paper's section 2.1 end to end in a few minutes.

Solid reference block (skeletal muscle, 40 km/h), a small genetic-algorithm
calibration of the hollow walls' Young's modulus and yield stress, the
solid-vs-hollow overlay (the paper's Fig. 2), a Table 1-like table and the
efficiency and stability study at 40, 70 and 100 km/h, all in one folder with
index.md and index.html. Default budget: 15 mm mesh, 12 ms, population 6 x 3
generations on 2 worker processes; --quick: the same mesh, 6 ms, 4 x 2 (a
smoke test of the pipeline). See docs/calibrate.md.

Exit codes: 0 done, 2 bad input, 3 the calibration could not run, 130
interrupted.
"""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("demo", help="the paper's section 2.1 end to end (small budget)",
                       description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, default=Path("hollowbody_demo"),
                   help="output folder (default hollowbody_demo)")
    p.add_argument("--quick", action="store_true",
                   help="an even smaller budget (pipeline smoke test; default: the default "
                        "budget)")
    p.add_argument("--tissue", choices=("muscle", "fat"), default="muscle",
                   help="tissue of the block (default muscle)")
    p.add_argument("--workers", type=int, default=2,
                   help="local worker processes (default 2; 1: run in this process)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress display (default: progress shown)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    import sys

    from hollowbody.calibrate.driver import CalibrationError
    from hollowbody.calibrate.progress import make_progress
    from hollowbody.calibrate.reference import ReferenceRunError
    from hollowbody.report.demo import BUDGETS, run_demo

    if args.workers < 1:
        raise UserInputError(f"--workers must be at least 1 (got {args.workers})")
    budget = replace(BUDGETS["quick" if args.quick else "default"], tissue=args.tissue,
                     workers=args.workers)
    progress = make_progress(args.quiet)
    if not args.quiet:
        progress.message(f"hollowbody demo ({budget.name} budget) into {args.out}")
    try:
        res = run_demo(args.out, budget, progress=progress)
    except (ReferenceRunError, CalibrationError) as exc:
        print(f"hollowbody demo: {exc}", file=sys.stderr)
        return 3
    for name, sec in res.timings.items():
        print(f"  {name}: {sec:.0f} s")
    print(f"open {args.out / 'index.html'} (or index.md)")
    return 0
