"""``hollowbody run DECK.k --out DIR``: run a keyword deck with the explicit solver.

Exit codes: 0 normal termination, 2 bad input (nothing run), 3 error
termination (negative volume, DTMIN, non-finite numbers; outputs kept),
130 user interrupt (outputs kept). With ``--restart`` the run resumes from
the newest restart file (``d3dumpNN``) of the output folder, or the one given.
An output folder holding an earlier run is refused unless ``--overwrite``, which
deletes that run's outputs first (histories, states, log, summary, restart
files; never the deck or its includes).
``--threads auto`` (the default) runs small models on one thread and larger
ones on every core (see :mod:`hollowbody.solver.threads`); ``--threads N`` on
at most N.

``--engine openradioss|lsdyna`` runs the deck on an installed external engine
instead (docs/engines.md): ``--np`` MPI ranks of ``--threads`` threads each
(auto: 1), found through ``--engine-path``, OPENRADIOSS_PATH / LSDYNA or the
PATH; its results are read back into the same glstat.csv and summary.json.
``--dry-run`` prints what would run (programs, arguments, environment,
folder) and runs nothing.
"""

from __future__ import annotations

import argparse
import functools
from collections.abc import Callable
from pathlib import Path

from hollowbody.cli.text import plain

EXIT_ERROR_TERMINATION = 3
EXIT_INTERRUPT = 130


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("run", help="run a keyword deck with the explicit solver",
                       description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("deck", type=Path, help="LS-DYNA keyword deck (.k, .key, .dyn)")
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: <deck name>_out next to the deck)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the outputs of an earlier run in --out (default: such a "
                        "folder is refused)")
    p.add_argument("--end-time", type=float, default=None,
                   help="end time in ms (default: the deck's *CONTROL_TERMINATION ENDTIM)")
    p.add_argument("--erode", action="store_true", default=None,
                   help="delete solids that reach negative volume instead of stopping "
                        "(default: the deck's *CONTROL_TIMESTEP ERODE)")
    p.add_argument("--vtk", action=argparse.BooleanOptionalAction, default=True,
                   help="write ParaView states (default: --vtk)")
    p.add_argument("--d3plot", action=argparse.BooleanOptionalAction, default=None,
                   help="write the states as a d3plot for LS-PrePost (needs the optional "
                        "extra: pip install 'hollowbody[d3plot]'); default: when the deck "
                        "has *DATABASE_BINARY_D3PLOT and lasso-python is installed")
    p.add_argument("--strict", action="store_true",
                   help="unknown keywords are errors (default: warnings)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress display (default: progress shown)")
    p.add_argument("--restart", nargs="?", const="newest", default=None, metavar="FILE",
                   help="resume from a restart file; without FILE the newest d3dumpNN of --out "
                        "(default: a new run)")
    p.add_argument("--dump-cycles", type=int, default=None, metavar="N",
                   help="write a restart file every N cycles (overrides "
                        "*DATABASE_BINARY_D3DUMP; 0 = none; default: the deck's)")
    p.add_argument("--dump-minutes", type=float, default=None, metavar="M",
                   help="write a restart file every M minutes of wall time too (default: "
                        "not by time)")
    p.add_argument("--keep-dumps", type=int, default=None, metavar="K",
                   help="keep only the newest K restart files of --out (default: all)")
    p.add_argument("--dump-at-end", action="store_true",
                   help="write a restart file when the run ends normally too, so that it can "
                        "be continued to a later --end-time with --restart (default: off)")
    p.add_argument("--quality", action="append", default=None, metavar="KEY=VALUE",
                   help="a limit of the run's quality verdict, e.g. hourglass_warn=0.15 "
                        "(repeatable; default: the limits in docs/solver.md)")
    add_threads_argument(p)
    add_engine_arguments(p)
    p.set_defaults(func=with_threads(main))


def add_engine_arguments(p: argparse.ArgumentParser) -> None:
    """``--engine``, ``--np``, ``--engine-path``, ``--memory``, ``--dry-run``."""
    from hollowbody.cli.run_engine import add_external_engine_arguments

    add_external_engine_arguments(p)
    p.add_argument("--memory", default=None, metavar="WORDS[,WORDS2]",
                   help="LS-DYNA memory= (and MPP memory2=) in words, e.g. 400m,80m (default: "
                        "from the model size)")
    p.add_argument("--dry-run", action="store_true",
                   help="print what would run and run nothing (default: run)")


def add_threads_argument(p: argparse.ArgumentParser) -> None:
    """The ``--threads N|auto`` option of the commands that run the solver."""
    p.add_argument("--threads", default="auto", metavar="N|auto",
                   help="numba threads of the solver: at most N, or auto (default: one "
                        "thread for small models, else every core)")


def with_threads(func: Callable[[argparse.Namespace], int]) -> Callable[[argparse.Namespace], int]:
    """``func`` (a command's main) with ``--threads`` as the setting of every run it
    makes, restored afterwards (UserInputError when it is neither a positive integer
    nor auto)."""
    @functools.wraps(func)
    def main(args: argparse.Namespace) -> int:
        from hollowbody.errors import UserInputError
        from hollowbody.solver import threads

        old = threads.default()
        try:
            threads.set_default(getattr(args, "threads", "auto"))
        except ValueError as exc:
            raise UserInputError(str(exc)) from None
        try:
            return func(args)
        finally:
            threads.set_default(old)
    return main


def exit_code(status: str) -> int:
    """Process exit code of a run's termination status."""
    if status == "normal termination":
        return 0
    if status == "user interrupt":
        return EXIT_INTERRUPT
    return EXIT_ERROR_TERMINATION


def main(args: argparse.Namespace) -> int:
    if getattr(args, "engine", "hollowbody") != "hollowbody":
        from hollowbody.cli.run_engine import main as run_engine

        return run_engine(args)
    if getattr(args, "dry_run", False):
        from hollowbody.cli.run_engine import describe_embedded

        print(describe_embedded(args))
        return 0
    from hollowbody.api import run_deck
    from hollowbody.errors import UserInputError
    from hollowbody.solver.verdict import Thresholds, headline

    try:
        thresholds = Thresholds.parse(args.quality)
    except ValueError as exc:
        raise UserInputError(f"--quality: {exc}") from None
    out = args.out or args.deck.with_name(args.deck.stem + "_out")
    result = run_deck(args.deck, out, end_time=args.end_time, erode=args.erode,
                      vtk=args.vtk, d3plot=args.d3plot, quiet=args.quiet, strict=args.strict,
                      restart=args.restart, dump_cycles=args.dump_cycles,
                      dump_minutes=args.dump_minutes or 0.0, keep_dumps=args.keep_dumps or 0,
                      dump_at_end=args.dump_at_end,
                      overwrite=args.overwrite, quality=thresholds)
    print(f"{result.status}: {result.reason}")
    print(f"  {result.cycles} cycles, end time {result.end_time_ms:.6g} ms, wall "
          f"{result.summary.get('wall_seconds', 0.0):.2f} s, energy ratio "
          f"{_fmt(result.summary.get('energy_ratio'))}; outputs in {out}")
    quality = result.summary.get("quality", "ok")
    print(f"{result.status} - {headline(quality, result.summary.get('quality_reasons', []))}")
    return exit_code(result.status)


def _fmt(v: float | None) -> str:
    return "n/a" if v is None else f"{v:.4f}"
