"""``hollowbody calibrate``: fit the hollow block's walls to the solid tissue (paper 2.1).

Runs the solid block once per speed (cached in DIR/reference/<speed>kmh), then
a genetic algorithm over the hollow walls' parameters; each candidate runs the
hollow block at every speed and scores the least-squares distance between
its force-displacement curve and the solid one (loading and unloading,
normalised by the reference's peak force and maximum displacement; summed
over speeds). Evaluations run in parallel on a local dask cluster (default:
one worker per CPU), on an existing one (--scheduler) or as SLURM jobs
(--cluster slurm|pbs; --dry-run prints the job script), and each run on
hollowbody's own engine or an installed OpenRadioss or LS-DYNA (--engine,
docs/engines.md). Every evaluation is
cached in DIR/evaluations.jsonl and the GA checkpointed after each
generation: --resume continues a stopped calibration without running
anything twice.

Parameters (default bounds): {bounds}. Outputs in DIR: calibration.json, convergence.png,
overlay.png, best_hollow/deck.k, table1.md, table1.csv.

Exit codes: 0 done, 2 bad input, 3 the calibration could not run (solid
reference failed, every candidate raised), 130 interrupted (checkpoint kept).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from hollowbody.calibrate.simulate import CELL_MM
from hollowbody.cli.run import add_threads_argument, with_threads
from hollowbody.cli.run_engine import add_external_engine_arguments, external_engine
from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError


def _default_bounds(sep: str = "..") -> str:
    """The calibrated parameters' default bounds, e.g. ``E 10..400 MPa, ...``."""
    from hollowbody.calibrate.space import PARAMETERS

    return ", ".join(f"{name} {lo:g}{sep}{hi:g} {unit}"
                     for name, (unit, lo, hi, _) in PARAMETERS.items())

EXIT_FAILED = 3


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("calibrate", help="fit the hollow structure to the solid tissue (GA)",
                       description=plain(__doc__.format(bounds=_default_bounds())),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tissue", choices=("muscle", "fat"), required=True,
                   help="tissue to calibrate (required)")
    p.add_argument("--speeds", default="40",
                   help="impact speeds in km/h, comma-separated (default 40)")
    p.add_argument("--params", default="E,yield",
                   help="calibrated parameters, comma-separated, from E, yield, etan, "
                        "thickness (default E,yield)")
    p.add_argument("--bounds", nargs="+", action="extend", default=[], metavar="NAME=LO:HI",
                   help="bounds of a calibrated parameter, e.g. E=20:300 yield=1:10 "
                        f"(default: {_default_bounds(':')})")
    p.add_argument("--fix", nargs="+", action="extend", default=[], metavar="NAME=VALUE",
                   help="value of a parameter that is not calibrated, e.g. thickness=1.2 "
                        "(default: etan 0 MPa, thickness 1.5 mm)")
    add_ga_options(p)
    add_runner_options(p)
    add_cluster_options(p)
    p.add_argument("--resume", action="store_true",
                   help="continue the calibration checkpointed in --out (default: start anew)")
    p.add_argument("--mesh", type=float, default=7.5,
                   help="solid element edge in mm, also the hollow walls' element size "
                        "(round(cell/mesh) per cell edge); must divide 180 and 90 (default 7.5)")
    p.add_argument("--cell", type=float, default=CELL_MM,
                   help="the hollow walls' cell size in mm; must divide 180 and 90 "
                        f"(default {CELL_MM:g}, the paper's)")
    p.add_argument("--end-time", type=float, default=None,
                   help="simulated time in ms (default: the block's, long enough to rebound)")
    p.add_argument("--cfc", type=float, default=180.0,
                   help="SAE J211 filter class of the contact force in the fitness "
                        "(default 180; 0: no filter)")
    add_wall_hourglass_options(p)
    add_solid_hourglass_options(p)
    p.add_argument("--quiet", action="store_true",
                   help="no progress display (default: progress shown)")
    p.add_argument("--out", type=Path, required=True, help="output folder (required)")
    add_threads_argument(p)
    add_external_engine_arguments(p)
    p.set_defaults(func=with_threads(main))


def add_ga_options(p: argparse.ArgumentParser, population: int = 16,
                   generations: int = 20) -> None:
    p.add_argument("--population", type=int, default=population,
                   help=f"GA population size (default {population})")
    p.add_argument("--generations", type=int, default=generations,
                   help=f"GA generations including the initial one (default {generations})")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")


def add_wall_hourglass_options(p: argparse.ArgumentParser, default: int | None = 0) -> None:
    """``--wall-hourglass IHQ`` and ``--wall-hourglass-qm QM`` (the hollow walls' control)."""
    p.add_argument("--wall-hourglass", type=int, default=default, metavar="IHQ",
                   help="hourglass control of the hollow walls: 0 none (LS-DYNA's default, "
                        "viscous IHQ 1 QH 0.1), 1-5 that *HOURGLASS IHQ, e.g. 4 the "
                        "stiffness form (default "
                        + ("0" if default == 0 else "the calibration's, else 0") + ")")
    p.add_argument("--wall-hourglass-qm", type=float, default=None, metavar="QM",
                   help="QM of --wall-hourglass (default 0.1)")


def add_solid_hourglass_options(p: argparse.ArgumentParser, study: bool = False) -> None:
    """``--solid-hourglass IHQ`` and ``--solid-hourglass-qm QM`` (the solid block's control)."""
    p.add_argument("--solid-hourglass", type=int, default=None, metavar="IHQ",
                   help="*HOURGLASS IHQ (1-7) of the solid block's one-point hexahedra "
                        "(default " + ("the calibration's, else " if study else "")
                        + "6, the assumed-strain stiffness form; 4 with QM 0.05, the "
                        "default before, about doubles the block's force)")
    p.add_argument("--solid-hourglass-qm", type=float, default=None, metavar="QM",
                   help="QM of --solid-hourglass (default 1 for IHQ 6 and 7, else 0.1"
                        + ("; alone: with the calibration's IHQ" if study else "") + ")")


def solid_hourglass_options(args: argparse.Namespace) -> dict:
    """BlockConfig fields of --solid-hourglass / --solid-hourglass-qm ({} when neither is
    given); UserInputError for an IHQ outside 1-7 or a negative QM."""
    from hollowbody.scenarios.block import SOLID_HOURGLASS, SOLID_HOURGLASS_TYPES

    ihq, qm = args.solid_hourglass, args.solid_hourglass_qm
    if ihq is None and qm is None:
        return {}
    ihq = SOLID_HOURGLASS[0] if ihq is None else ihq
    if ihq not in SOLID_HOURGLASS_TYPES:
        raise UserInputError(f"--solid-hourglass must be 1-7 (got {ihq})")
    if qm is not None and qm < 0.0:
        raise UserInputError(f"--solid-hourglass-qm must be >= 0 (got {qm:g})")
    if qm is None:
        qm = 1.0 if ihq in (6, 7) else 0.1
    return {"hourglass_ihq": int(ihq), "hourglass_qh": float(qm)}


def wall_hourglass_options(args: argparse.Namespace) -> dict:
    """BlockConfig fields of --wall-hourglass / --wall-hourglass-qm ({} when neither is
    given or IHQ is 0); UserInputError for an IHQ outside 0-5 or a negative QM."""
    ihq = args.wall_hourglass
    qm = args.wall_hourglass_qm
    if ihq is not None and ihq not in (0, 1, 2, 3, 4, 5):
        raise UserInputError(f"--wall-hourglass must be 0-5 (got {ihq})")
    if qm is not None and qm < 0.0:
        raise UserInputError(f"--wall-hourglass-qm must be >= 0 (got {qm:g})")
    if qm is not None and not ihq:
        raise UserInputError("--wall-hourglass-qm needs --wall-hourglass 1-5")
    if not ihq:
        return {}
    return {"wall_hourglass_ihq": int(ihq), "wall_hourglass_qh": 0.1 if qm is None else qm}


def add_runner_options(p: argparse.ArgumentParser) -> None:
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=int, default=None,
                   help="local worker processes (default: one per CPU; 1: run in this process)")
    g.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="address of an existing dask scheduler, e.g. tcp://host:8786 "
                        "(workers need hollowbody and this file system; default: a local "
                        "cluster)")


def add_cluster_options(p: argparse.ArgumentParser) -> None:
    """``--cluster slurm|pbs`` and its job options, ``--dry-run``."""
    g = p.add_argument_group("cluster (optional extra: pip install 'hollowbody[cluster]')")
    g.add_argument("--cluster", choices=("slurm", "pbs"), default=None,
                   help="run the evaluations as SLURM or PBS jobs through dask-jobqueue "
                        "(default: a local dask cluster)")
    g.add_argument("--queue", default=None,
                   help="SLURM partition or PBS queue (default: the cluster's)")
    g.add_argument("--walltime", default="01:00:00", metavar="HH:MM:SS",
                   help="wall time of one job (default 01:00:00)")
    g.add_argument("--cores-per-job", type=int, default=1, metavar="N",
                   help="cores each job books; its evaluation runs on all of them (default 1)")
    g.add_argument("--jobs", type=int, default=1, metavar="N",
                   help="batch jobs, each evaluating one candidate at a time (default 1)")
    g.add_argument("--job-memory", default=None, metavar="SIZE",
                   help="memory per job, e.g. 8GB (default: 2 GB per core)")
    g.add_argument("--dry-run", action="store_true",
                   help="with --cluster: print the job script and submit nothing (default: submit)")


def job_spec(args: argparse.Namespace):
    """The JobSpec of the parsed options (None without --cluster)."""
    from hollowbody.calibrate.cluster import JobSpec

    if getattr(args, "cluster", None) is None:
        if getattr(args, "dry_run", False):
            raise UserInputError("--dry-run prints the job script of --cluster slurm|pbs; "
                                 "give --cluster")
        return None
    if args.workers is not None or args.scheduler is not None:
        raise UserInputError("--cluster cannot be combined with --workers or --scheduler")
    return JobSpec(queue=args.queue, walltime=args.walltime,
                   cores_per_job=args.cores_per_job, jobs=args.jobs, memory=args.job_memory,
                   log_directory=str(args.out / args.cluster), system=args.cluster)


def parse_fixed(items: list[str], calibrated: list[str]) -> dict[str, float]:
    """``['thickness=1.2']`` -> {'thickness': 1.2}; UserInputError on bad input."""
    from hollowbody.calibrate.space import PARAMETERS

    out: dict[str, float] = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep:
            raise UserInputError(f"bad --fix {item!r}: expected NAME=VALUE, e.g. thickness=1.2")
        if name not in PARAMETERS:
            raise UserInputError(f"unknown parameter {name!r} in --fix; choose from "
                                 f"{', '.join(PARAMETERS)}")
        if name in calibrated:
            raise UserInputError(f"{name} is calibrated; it cannot also be fixed")
        try:
            v = float(value)
        except ValueError:
            raise UserInputError(f"bad --fix {item!r}: VALUE must be a number") from None
        if not math.isfinite(v) or v < 0.0 or (name != "etan" and v == 0.0):
            raise UserInputError(f"bad --fix {item!r}: VALUE must be positive")
        out[name] = v
    return out


def check_positive(name: str, value: float | int | None, minimum: float = 1) -> None:
    if value is not None and value < minimum:
        raise UserInputError(f"{name} must be at least {minimum:g} (got {value})")


def build_settings(args: argparse.Namespace):
    """(CalibrationSettings, BlockSimulator) from the parsed options (UserInputError)."""
    from hollowbody.calibrate import CalibrationSettings, FitnessSettings, GASettings
    from hollowbody.calibrate.simulate import BlockSimulator
    from hollowbody.calibrate.space import make_space, parse_bounds, parse_names, parse_speeds

    speeds = parse_speeds(args.speeds)
    names = parse_names(args.params)
    space = make_space(names, parse_bounds(args.bounds))
    fixed = parse_fixed(args.fix, names)
    check_positive("--population", args.population, 2)
    check_positive("--generations", args.generations, 1)
    check_positive("--workers", args.workers, 1)
    if args.end_time is not None and not args.end_time > 0.0:
        raise UserInputError(f"--end-time must be positive (got {args.end_time:g} ms)")
    if args.cfc < 0.0:
        raise UserInputError(f"--cfc must be >= 0 (got {args.cfc:g})")
    # the engine is looked for here unless the evaluations run on a cluster's nodes
    engine = external_engine(args, find=getattr(args, "cluster", None) is None)
    if not args.cell > 0.0:
        raise UserInputError(f"--cell must be positive (got {args.cell:g} mm)")
    # the paper's cell is not recorded (calibrations made before --cell keep their caches)
    geometry = {} if args.cell == CELL_MM else {"cell": float(args.cell)}
    sim = BlockSimulator.make(args.tissue, mesh=args.mesh, end_time=args.end_time, fixed=fixed,
                              options={**wall_hourglass_options(args),
                                       **solid_hourglass_options(args), **geometry},
                              engine=engine)
    try:  # the block's own checks (mesh divides the block, ...)
        sim.config("solid", speeds[0])
        sim.config("hollow", speeds[0], space.rounded(space.lower))
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    ga = GASettings(population=args.population, generations=args.generations, seed=args.seed)
    fitness = FitnessSettings(cfc=args.cfc or None)
    return CalibrationSettings(args.tissue, speeds, space, ga, fitness), sim


def main(args: argparse.Namespace) -> int:
    from hollowbody.calibrate.driver import CHECKPOINT, CalibrationError, calibrate
    from hollowbody.calibrate.progress import make_progress
    from hollowbody.calibrate.reference import ReferenceRunError
    from hollowbody.calibrate.runner import make_runner
    from hollowbody.calibrate.wall import WALL_UNITS, effective_wall
    from hollowbody.report.calibration import write_report

    settings, sim = build_settings(args)
    batch = job_spec(args)
    if batch is not None and args.dry_run:
        from hollowbody.calibrate.cluster import job_script

        print(f"# {batch.jobs} {batch.system.upper()} job(s) of {batch.cores_per_job} "
              f"core(s), {batch.job_memory}, {batch.walltime}; each runs one dask worker that "
              "evaluates one candidate at a time")
        print(job_script(batch))
        return 0
    out: Path = args.out
    if args.resume and not (out / CHECKPOINT).exists():
        raise UserInputError(f"--resume: no checkpoint in {out} (nothing to resume)")
    progress = make_progress(args.quiet)
    try:
        with make_runner(args.workers, args.scheduler, batch=batch) as runner:
            if not args.quiet:
                progress.message(f"calibrating the hollow {settings.tissue} block: "
                                 f"{', '.join(settings.space.names)} at "
                                 f"{', '.join(f'{s:g}' for s in settings.speeds)} km/h; "
                                 f"evaluations on {runner.description}")
            result = calibrate(settings, out, sim, runner=runner, resume=args.resume,
                               progress=progress)
    except (ReferenceRunError, CalibrationError) as exc:
        import sys

        print(f"hollowbody calibrate: {exc}", file=sys.stderr)
        return EXIT_FAILED
    files = write_report(out)
    wall = effective_wall(result.data)
    if wall is None:
        print(f"no candidate ended normally with a sound run (error terminations and "
              f"suspect runs count as failed); see {out / 'calibration.json'}")
        return EXIT_FAILED
    print("best: " + ", ".join(f"{k} {v:g} {WALL_UNITS[k]}" for k, v in wall.items())
          + f"; fitness {result.best_fitness:.4g} ({len(result.evaluations)} evaluations, "
          f"{result.runs_here} run now, {result.data.get('elapsed_seconds', 0.0):.0f} s wall)")
    print(f"outputs in {out}: " + ", ".join(p.name for p in files.values()))
    return 0
