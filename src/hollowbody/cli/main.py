"""The ``hollowbody`` command: one module per subcommand in this package.

Each subcommand module exposes ``register(subparsers)`` which adds its parser
and sets ``func`` (a callable taking the parsed namespace and returning an
exit code).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

import hollowbody
from hollowbody.errors import UserInputError

#: Subcommand modules (in hollowbody.cli), in help order. A module that is
#: missing is skipped, so capabilities can land one by one.
SUBCOMMANDS = ("check", "run", "block", "hollowize", "bending", "calibrate", "study", "demo",
               "rate", "pedestrian", "validate")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hollowbody",
        description="Explicit FE impact solver with LS-DYNA keyword decks and hollow "
        "soft-tissue structures. Units: mm, ms, kg, kN, GPa.",
        epilog="Run 'hollowbody COMMAND --help' for the options of a command.",
    )
    parser.add_argument("--version", action="version",
                        version=f"hollowbody {hollowbody.__version__}",
                        help="print the version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in SUBCOMMANDS:
        try:
            module = importlib.import_module(f"hollowbody.cli.{name}")
        except ModuleNotFoundError as exc:  # capability not built yet
            if exc.name == f"hollowbody.cli.{name}":
                continue
            raise
        module.register(sub)
    return parser


def _silence_stdout() -> None:
    """Point stdout at the null device, so that flushing it at exit cannot fail again
    after its reader went away."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # stdout without a file descriptor (captured)
        pass


def main(argv: list[str] | None = None) -> int:
    """Run the command line ``argv`` (default: ``sys.argv[1:]``); returns the exit code.

    A reader that closes the output early (``hollowbody rate ... --json | head``)
    ends the command quietly with exit code 0.
    """
    try:
        code = _dispatch(argv)
        sys.stdout.flush()
    except BrokenPipeError:
        _silence_stdout()
        return 0
    return code


def _dispatch(argv: list[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        code = args.func(args)
    except UserInputError as err:
        print(f"hollowbody {args.command}: error: {err}", file=sys.stderr)
        return err.exit_code
    except KeyboardInterrupt:
        print(f"hollowbody {args.command}: interrupted", file=sys.stderr)
        return 130
    return int(code or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
