"""``hollowbody run DECK --engine openradioss|lsdyna``: the deck on an external engine.

Exit codes as ``hollowbody run``: 0 normal termination, 2 bad input or the
engine not found (nothing run), 3 error termination (outputs kept).
``--dry-run`` prints the plan and exits 0, whether the engine is installed or
not (then the executables are shown by name and a note says so).
"""

from __future__ import annotations

import argparse
import shlex
import sys
from pathlib import Path

from hollowbody.errors import UserInputError


def engine_threads(value: str | None) -> int:
    """``--threads`` of an external engine: N, or auto (1 per MPI rank)."""
    if value in (None, "auto"):
        return 1
    try:
        n = int(value)
    except ValueError:
        raise UserInputError(f"--threads must be a positive integer or auto (got {value!r})") \
            from None
    if n < 1:
        raise UserInputError(f"--threads must be at least 1 (got {n})")
    return n


def add_external_engine_arguments(p: argparse.ArgumentParser) -> None:
    """``--engine``, ``--np``, ``--engine-path`` of a command that runs decks it writes
    (block, calibrate, validate); threads per MPI rank are its ``--threads``."""
    e = p.add_argument_group("engine (docs/engines.md)")
    e.add_argument("--engine", choices=("hollowbody", "openradioss", "lsdyna"),
                   default="hollowbody",
                   help="the engine that runs the decks (default: hollowbody, this program)")
    e.add_argument("--np", type=int, default=1, metavar="N",
                   help="MPI ranks of an external engine (default 1)")
    e.add_argument("--engine-path", default=None, metavar="PATH",
                   help="the external engine's executable or folder (default: found on the "
                        "PATH or from OPENRADIOSS_PATH / LSDYNA)")


def external_engine(args: argparse.Namespace, find: bool = False):  # -> ExternalEngine | None
    """The external engine of ``--engine`` (None: hollowbody's own); ``find``: look for
    it now (EngineNotFound, exit code 2, before anything is run)."""
    if args.engine == "hollowbody":
        for flag, given in (("--np", args.np != 1), ("--engine-path", args.engine_path)):
            if given:
                raise UserInputError(f"{flag} is an option of an external engine; give "
                                     "--engine openradioss or --engine lsdyna")
        return None
    from hollowbody.engines.discovery import find_lsdyna, find_openradioss
    from hollowbody.engines.runner import ExternalEngine

    if args.np < 1:
        raise UserInputError(f"--np must be at least 1 (got {args.np})")
    engine = ExternalEngine(args.engine, np=args.np,
                            threads=engine_threads(getattr(args, "threads", None)),
                            path=args.engine_path)
    if find:
        if engine.name == "openradioss":
            find_openradioss(engine.path)
        else:
            find_lsdyna(engine.path, mpp=True if engine.np > 1 else None)
    return engine


def _memory(value: str | None) -> tuple[int, int] | None:
    """``400m,80m`` -> (400e6, 80e6) words; one value sets both."""
    if not value:
        return None
    out = []
    for part in value.split(","):
        part = part.strip().lower()
        scale = 1_000_000 if part.endswith("m") else 1
        try:
            n = int(float(part.rstrip("m")) * scale)
        except ValueError:
            raise UserInputError(f"--memory: expected WORDS[,WORDS2] such as 400m,80m "
                                 f"(got {value!r})") from None
        if n <= 0:
            raise UserInputError(f"--memory must be positive (got {value!r})")
        out.append(n)
    if len(out) > 2:
        raise UserInputError(f"--memory: at most two values (got {value!r})")
    return out[0], out[-1]


def _out(args: argparse.Namespace) -> Path:
    return args.out or args.deck.with_name(args.deck.stem + "_out")


def describe_embedded(args: argparse.Namespace) -> str:
    """What ``hollowbody run`` without --engine would do (its --dry-run)."""
    argv = [sys.executable, "-m", "hollowbody.cli.main", "run", str(args.deck),
            "--out", str(_out(args)), "--threads", str(args.threads)]
    return "\n".join(["engine: hollowbody (this program, in this process)",
                      f"deck: {args.deck}", f"work folder: {_out(args)}", "[hollowbody]",
                      f"  cd {shlex.quote(str(Path.cwd()))}", f"  {shlex.join(argv)}"])


def main(args: argparse.Namespace) -> int:
    from hollowbody.cli.run import exit_code
    from hollowbody.engines.runner import execute, plan_run
    from hollowbody.solver.outputs import prepare_out_dir
    from hollowbody.solver.run_lock import RunLock

    for flag, value in (("--restart", args.restart), ("--dump-cycles", args.dump_cycles),
                        ("--dump-minutes", args.dump_minutes),
                        ("--keep-dumps", args.keep_dumps),
                        ("--dump-at-end", args.dump_at_end or None),
                        ("--erode", args.erode), ("--quality", args.quality)):
        if value is not None:
            raise UserInputError(f"{flag} is an option of hollowbody's own engine; not "
                                 f"supported with --engine {args.engine}")
    out = _out(args)
    np_ = int(args.np)
    threads = engine_threads(args.threads)
    memory = _memory(args.memory)
    if args.dry_run:
        prep = plan_run(args.engine, args.deck, out, np_=np_, threads=threads,
                        engine_path=args.engine_path, dry_run=True, memory=memory,
                        write=False, end_time=args.end_time)
        print(prep.describe())
        return 0
    prepare_out_dir(out, args.overwrite, (args.deck,))  # refuses a held folder
    prep = plan_run(args.engine, args.deck, out, np_=np_, threads=threads,
                    engine_path=args.engine_path, dry_run=False, memory=memory,
                    write=True, end_time=args.end_time)  # nothing written without the engine
    with RunLock(out):
        summary = execute(prep, quiet=args.quiet)
    print(f"{summary['status']}: {summary['reason']}")
    print(f"  {args.engine} {summary.get('engine_version') or ''}".rstrip()
          + f", {summary.get('cycles')} cycles, end time {summary.get('end_time_ms')} ms, "
          f"wall {summary['wall_seconds']:.2f} s; outputs in {out}")
    return exit_code(summary["status"])
