"""``hollowbody validate``: the paper's segment tests, solid and hollow, rated.

Cases: thigh-bending, leg-bending (dynamic three-point bending, 1.5 m/s,
lateral-medial at mid-span), pelvis, abdomen, thorax (Viano 1989 lateral hub
impacts: 23.4 kg, 150 mm) and shoulder (23 kg, 150 mm). Each case is set up
on the open pedestrian model (solid and/or hollow soft tissue) or on the
user's own model (--model DECK with --landmarks FILE, see docs/validation.md),
run, rated with CORA and ISO/TS 18571 against the test data that ship with
hollowbody (Viano 1989) and hollow against solid, and written up:
DIR/<case>/<speed>ms/<model>/ (deck, setup.json, run outputs), DIR/<case>.png,
DIR/report.md, DIR/report.html, DIR/report.json.

Exit code 0 when every run ended normally with quality ok, 1 when one did
not (the report says which and why), 2 for bad input, 130 when interrupted
(the runs so far are reported). A DIR holding an earlier report or case
folder is refused unless --overwrite (which deletes only those) or --resume.

Long validations can be stopped (Ctrl-C) and continued: every run writes a
restart file every --dump-minutes of wall time and one at its end (the newest
kept), and --resume with the same cases continues in DIR: runs that ended are
kept, stopped runs resume from their restart file, runs that ended normally
are continued to a later --end-time, runs not yet started are started.
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from hollowbody.cli.run_engine import add_external_engine_arguments
from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError
from hollowbody.solver.run_lock import LOCK_NAME, check_free

REPORT_FILES = ("report.md", "report.html", "report.json")


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    from hollowbody.validation.cases import ORDER

    p = sub.add_parser("validate", help="the paper's segment tests, rated against cadaver data",
                       description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("cases", nargs="*", metavar="CASE",
                   help=f"one or more of: {', '.join(ORDER)} (default: none; or --all)")
    p.add_argument("--all", action="store_true", help="every case (default: off)")
    p.add_argument("--list", action="store_true", help="list the cases and exit (default: off)")
    p.add_argument("--tissue", choices=("solid", "hollow", "both"), default="both",
                   help="soft tissue of the pedestrian model (default both)")
    p.add_argument("--speed", type=float, default=None,
                   help="impact speed in m/s (default: every speed of the tests)")
    p.add_argument("--model", type=Path, default=None,
                   help="run on your own body model (keyword deck; needs --landmarks; default: the "
                        "open pedestrian)")
    p.add_argument("--landmarks", type=Path, default=None,
                   help="JSON file of your model's landmarks per case (docs/validation.md; "
                        "default: none)")
    p.add_argument("--mesh", type=float, default=30.0,
                   help="pedestrian soft-tissue element size in mm (default 30)")
    p.add_argument("--end-time", type=float, default=None,
                   help="simulated time in ms (default: the length of the test data)")
    p.add_argument("--corridor", type=Path, default=None,
                   help="a corridor CSV to rate against (one case only): polygon (x, y) or "
                        "bounds (x, lower, upper); force-time in ms, kN (default: none)")
    p.add_argument("--threads", default=None,
                   help="solver threads (default: the run's default)")
    add_external_engine_arguments(p)
    p.add_argument("--dry-run", action="store_true",
                   help="write the set-up decks without running them (default: off)")
    p.add_argument("--resume", action="store_true",
                   help="continue the validation in --out: keep the runs that ended, resume "
                        "the stopped ones from their restart files, extend to a later "
                        "--end-time, start the others (default: off)")
    p.add_argument("--dump-minutes", type=float, default=None, metavar="M",
                   help="a restart file every M minutes of wall time per run and one at its "
                        "end, the newest kept (0: only the one a stop writes, all kept; a "
                        "killed run then starts again and an ended one cannot be extended; "
                        "default 10)")
    p.add_argument("--report", action="store_true",
                   help="rate and report the runs already in --out again, run nothing "
                        "(default: off)")
    p.add_argument("--out", type=Path, default=Path("validation"),
                   help="output folder (default: validation)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace an earlier report and case folders in --out (default: refuse)")
    p.set_defaults(func=main)


def _list() -> int:
    from hollowbody.validation.cases import CASES, ORDER

    for name in ORDER:
        c = CASES[name]
        mass = f"{c.impactor_mass:g} kg, " if c.kind == "impact" else "driven, "
        print(f"{name:14s} {c.kind:8s} {', '.join(f'{s:g}' for s in c.speeds)} m/s; "
              f"{mass}{c.impactor_diameter:g} mm; {c.location}; "
              f"data: {c.data or 'none shipped'}")
    return 0


def _prepare(out: Path, cases: list[str], overwrite: bool, model: Path | None) -> None:
    earlier = [out / f for f in REPORT_FILES if (out / f).exists()]
    earlier += [out / c for c in cases if (out / c).exists()]
    if not earlier:
        return
    if not overwrite:
        raise UserInputError(f"{out} holds an earlier validation ({earlier[0].name}); "
                             "choose another --out or pass --overwrite")
    if model is not None:
        m = model.resolve()
        for e in earlier:
            if e.is_dir() and e.resolve() in m.parents:
                raise UserInputError(f"--overwrite would delete {e}, which holds --model "
                                     f"{model}; move the model or choose another --out")
    for e in earlier:  # a run still going on in one of them: delete nothing
        if e.is_dir():
            for lock in sorted(e.rglob(LOCK_NAME)):
                check_free(lock.parent)
    for e in earlier:
        if e.is_dir():
            shutil.rmtree(e)
        else:
            e.unlink()


def main(args: argparse.Namespace) -> int:
    from hollowbody.validation.cases import ORDER, case, speeds_of

    if args.list:
        return _list()
    _check_resume(args)
    if args.report:
        return _report_only(args)
    names = list(ORDER) if args.all else list(dict.fromkeys(args.cases))
    if not names:
        raise UserInputError("give one or more cases or --all (hollowbody validate --list "
                             "shows them)")
    try:
        cases = [case(n) for n in names]
        speeds = {c.name: speeds_of(c, args.speed) for c in cases}
    except ValueError as err:
        raise UserInputError(str(err)) from None
    if (args.model is None) != (args.landmarks is None):
        raise UserInputError("--model and --landmarks go together")
    if args.corridor is not None and len(cases) != 1:
        raise UserInputError("--corridor rates one case: give exactly one CASE")
    if not 10.0 <= args.mesh <= 50.0:
        raise UserInputError(f"--mesh must be between 10 and 50 mm (got {args.mesh:g})")
    if args.np < 1:
        raise UserInputError(f"--np must be at least 1 (got {args.np})")
    if args.end_time is not None and not args.end_time > 0.0:
        raise UserInputError(f"--end-time must be positive (got {args.end_time:g} ms)")
    landmarks = None
    if args.model is not None:
        from hollowbody.validation.landmarks import entry, load_landmarks

        if not args.model.is_file():
            raise UserInputError(f"{args.model}: no such deck (--model)")
        landmarks = load_landmarks(args.landmarks)
        for c in cases:
            entry(landmarks, c.name, args.landmarks)
    corridor = _corridor(args)
    tissues = ("solid", "hollow") if args.tissue == "both" else (args.tissue,)
    if not args.resume:
        _prepare(args.out, names, args.overwrite, args.model)
    return _run(args, cases, speeds, tissues, landmarks, corridor)


def _check_resume(args: argparse.Namespace) -> None:
    """--resume and --dump-minutes against the other options (UserInputError)."""
    from hollowbody.validation.runner import DUMP_MINUTES

    if args.dump_minutes is None:
        args.dump_minutes = DUMP_MINUTES
    elif not args.dump_minutes >= 0.0:
        raise UserInputError(f"--dump-minutes must be >= 0 (got {args.dump_minutes:g})")
    if not args.resume:
        return
    for flag, on in (("--overwrite", args.overwrite), ("--dry-run", args.dry_run),
                     ("--report", args.report)):
        if on:
            raise UserInputError(f"--resume continues the runs in --out; it does not go with "
                                 f"{flag}")
    if args.engine != "hollowbody":
        raise UserInputError(f"--resume needs hollowbody's own engine (restart files); runs on "
                             f"--engine {args.engine} are started again without it")
    if not args.out.is_dir():
        raise UserInputError(f"{args.out}: no such folder to resume (--out)")


def _corridor(args: argparse.Namespace):  # noqa: ANN202 - Corridor | None
    """The --corridor file read, or None; UserInputError naming a missing file."""
    if args.corridor is None:
        return None
    from hollowbody.rating.csvio import read_corridor

    if not args.corridor.is_file():
        raise UserInputError(f"{args.corridor}: no such file (--corridor)")
    return read_corridor(args.corridor, name=args.corridor.name)


def _report_only(args: argparse.Namespace) -> int:
    from hollowbody.report.validation import write_report
    from hollowbody.validation.runner import collect_records

    corridor = _corridor(args)
    records = collect_records(args.out, corridor)
    if not records:
        raise UserInputError(f"{args.out}: no runs of the segment tests found "
                             "(<case>/<speed>ms/<model>/setup.json)")
    paths = write_report(records, args.out, corridor)
    _print(records)
    print(f"report: {paths['markdown']} and {paths['html']}")
    return 0 if all(r.ok for r in records) else 1


def _print(records) -> None:  # noqa: ANN001
    for r in records:
        peak = (f"peak {r.peak_force:.2f} kN at {r.peak_time:.1f} ms"
                if r.peak_force is not None else "no force")
        rated = "; ".join(x.short() for x in r.ratings) or "not rated"
        print(f"{r.case} {r.speed:g} m/s {r.tissue}: {r.status}, quality {r.quality or '-'}, "
              f"{peak}; {rated}")


def _run(args, cases, speeds, tissues, landmarks, corridor) -> int:  # noqa: ANN001
    from hollowbody.report.validation import write_report
    from hollowbody.validation.runner import ValidationInterrupted, run_case

    records = []
    interrupted = False
    try:
        for c in cases:
            lm = landmarks.get(c.name) if landmarks is not None else None
            records += run_case(c, speeds[c.name], tissues, args.out, mesh=args.mesh,
                                end_time=args.end_time, model=args.model, landmarks=lm,
                                landmarks_path=args.landmarks, corridor=corridor,
                                dry_run=args.dry_run, quiet=False, threads=args.threads,
                                engine=args.engine, np_=args.np,
                                engine_path=args.engine_path, resume=args.resume,
                                dump_minutes=args.dump_minutes)
    except ValidationInterrupted as stop:
        interrupted = True
        records += stop.records
    except KeyboardInterrupt:
        interrupted = True
    if interrupted:
        print("interrupted: reporting the runs so far; continue with the same command and "
              "--resume")
    paths = write_report(records, args.out, corridor)
    _print(records)
    print(f"report: {paths['markdown']} and {paths['html']}")
    if interrupted:
        return 130
    if args.dry_run:
        return 0
    return 0 if all(r.ok for r in records) else 1
