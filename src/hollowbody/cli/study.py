"""``hollowbody study``: efficiency and stability of the solid vs the hollow block.

Runs the solid and the hollow block test at each speed (hollow walls from a
calibration's best candidate with --hollow-from, built with the calibration's
cell and run with the hourglass control they were calibrated with unless
--wall-hourglass says otherwise; else
the paper's fit: muscle E 100 MPa / yield 4 MPa, fat 50 / 2 MPa, 1.5 mm walls;
the solid block with the hourglass control of the calibration's solid reference
unless --solid-hourglass says otherwise, else the block's IHQ 6) and writes into DIR:
study.md and study.csv (status and reason, end time, cycles, wall time,
element counts, peak force, maximum displacement; solid/hollow wall-time
ratio where both end normally), fd_<speed>kmh.png (solid vs hollow),
fd_all.png (every curve), study.json and the run folders
(solid/<speed>kmh, hollow/<speed>kmh).

Runs are serial by default so wall times are comparable; --workers N runs N
at a time (each single-threaded).

A DIR holding an earlier study (study.json, study.md, study.csv, fd_*.png or
run folders with a run's outputs) is refused unless --overwrite, which deletes
those files and the run folders' outputs and decks first (never the
--hollow-from file or other files).

Exit codes: 0 the study ran (whatever the runs' status: dying is a result
here), 2 bad input, 130 interrupted.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from hollowbody.cli.calibrate import (
    add_solid_hourglass_options,
    add_wall_hourglass_options,
    solid_hourglass_options,
    wall_hourglass_options,
)
from hollowbody.cli.run import add_threads_argument, with_threads
from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError

#: The study's own files in DIR and its run folders (what --overwrite clears).
STUDY_FILES = ("study.json", "study.md", "study.csv", "fd_*.png")
RUN_DIRS = ("solid/*", "hollow/*")
RUN_FILES = ("deck.k", "console.log")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("study", help="efficiency and stability: solid vs hollow block at "
                       "several speeds", description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tissue", choices=("muscle", "fat"), required=True,
                   help="block tissue (required)")
    p.add_argument("--speeds", default="40,70,100",
                   help="impact speeds in km/h, comma-separated (default 40,70,100)")
    p.add_argument("--hollow-from", type=Path, default=None, metavar="CALIBRATION.json",
                   help="take the hollow walls from a calibration's best candidate "
                        "(default: the paper's fit)")
    p.add_argument("--mesh", type=float, default=7.5,
                   help="solid element edge in mm, also the hollow walls' element size "
                        "(default 7.5)")
    p.add_argument("--end-time", type=float, default=None,
                   help="simulated time in ms (default: the block's)")
    p.add_argument("--vtk", action=argparse.BooleanOptionalAction, default=False,
                   help="write ParaView states of every run (default: no)")
    add_wall_hourglass_options(p, default=None)
    add_solid_hourglass_options(p, study=True)
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=int, default=1,
                   help="runs at a time (default 1: serial, comparable wall times)")
    g.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="address of an existing dask scheduler (default: local processes)")
    p.add_argument("--out", type=Path, required=True, help="output folder (required)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the outputs of an earlier study in --out (default: such a "
                        "folder is refused)")
    add_threads_argument(p)
    p.set_defaults(func=with_threads(main))


def main(args: argparse.Namespace) -> int:
    from hollowbody.calibrate.runner import make_runner
    from hollowbody.calibrate.simulate import BlockSimulator
    from hollowbody.calibrate.space import parse_speeds
    from hollowbody.calibrate.study import (
        hollow_from_calibration,
        run_study,
        solid_control_of_calibration,
        wall_control_of_calibration,
        wall_geometry_of_calibration,
    )
    from hollowbody.report.study import wall_time_ratios, write_study_report
    from hollowbody.solver.outputs import prepare_runs_dir

    speeds = parse_speeds(args.speeds)
    if args.workers is not None and args.workers < 1:
        raise UserInputError(f"--workers must be at least 1 (got {args.workers})")
    if args.end_time is not None and not args.end_time > 0.0:
        raise UserInputError(f"--end-time must be positive (got {args.end_time:g} ms)")
    wall = hollow_from_calibration(args.hollow_from) if args.hollow_from else None
    options = wall_hourglass_options(args)
    if args.hollow_from:
        calibrated = wall_control_of_calibration(args.hollow_from)
        if args.wall_hourglass is None and args.wall_hourglass_qm is None:
            options = calibrated  # the walls run with the control they were calibrated with
        elif options != calibrated:
            print(f"note: the walls of {args.hollow_from} were calibrated with "
                  f"{_control_text(calibrated)}; this study runs them with "
                  f"{_control_text(options)}", file=sys.stderr)
    solid = solid_hourglass_options(args)
    if args.hollow_from:
        calibrated = solid_control_of_calibration(args.hollow_from)
        if args.solid_hourglass is None and solid:  # only a QM given: the calibration's IHQ
            solid["hourglass_ihq"] = calibrated["hourglass_ihq"]
        if not solid:
            solid = calibrated  # the solid block the walls were fitted to
        elif solid != calibrated:
            print(f"note: the walls of {args.hollow_from} were fitted to a solid block with "
                  f"{_solid_text(calibrated)}; this study runs the solid block with "
                  f"{_solid_text(solid)}", file=sys.stderr)
    # the calibrated walls' geometry (cell size) when not the paper's
    geometry = wall_geometry_of_calibration(args.hollow_from) if args.hollow_from else {}
    sim = BlockSimulator.make(args.tissue, mesh=args.mesh, end_time=args.end_time,
                              vtk=args.vtk, options={**options, **solid, **geometry})
    try:
        sim.config("solid", speeds[0])
        sim.config("hollow", speeds[0], wall)
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    prepare_runs_dir(args.out, args.overwrite, STUDY_FILES, RUN_DIRS, RUN_FILES,
                     inputs=(args.hollow_from,) if args.hollow_from else ())
    with make_runner(args.workers, args.scheduler) as runner:
        rows = run_study(sim, speeds, args.out, hollow_params=wall, runner=runner)
    files = write_study_report(rows, args.out)
    for r in rows:
        w = r["wall_seconds"]
        print(f"{r['structure']:6s} {r['speed_kmh']:5g} km/h  {r['status']}"
              f"{': ' + r['reason'] if r['status'] != 'normal termination' else ''}"
              f"  ({'n/a' if w is None else f'{w:.1f} s'})")
    for v, q in wall_time_ratios(rows).items():
        print(f"wall-time ratio solid/hollow at {v:g} km/h: {q:.2f}")
    print(f"table: {files['table_md']}; plots: {args.out / 'fd_all.png'}")
    return 0


def _control_text(options: dict) -> str:
    """'*HOURGLASS IHQ 4 QM 0.1' or 'no wall *HOURGLASS' for a wall-control dict."""
    if not options:
        return "no wall *HOURGLASS (viscous IHQ 1, QH 0.1)"
    return (f"*HOURGLASS IHQ {options['wall_hourglass_ihq']} "
            f"QM {options.get('wall_hourglass_qh', 0.1):g}")


def _solid_text(options: dict) -> str:
    """'*HOURGLASS IHQ 6 QM 1' for a solid-control dict."""
    return f"*HOURGLASS IHQ {options['hourglass_ihq']} QM {options['hourglass_qh']:g}"
