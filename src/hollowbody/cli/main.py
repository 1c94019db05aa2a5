"""The ``hollowbody`` command: one module per subcommand in this package.

Each subcommand module exposes ``register(subparsers)`` which adds its parser
and sets ``func`` (a callable taking the parsed namespace and returning an
exit code).
"""

from __future__ import annotations

import argparse
import importlib
import sys

from hollowbody.errors import UserInputError

#: Subcommand modules (in hollowbody.cli), in help order. A module that is
#: missing is skipped, so capabilities can land one by one.
SUBCOMMANDS = ("check", "run", "block", "hollowize", "bending", "calibrate", "study", "demo",
               "rate")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hollowbody",
        description="Explicit FE impact solver with LS-DYNA keyword decks and hollow "
        "soft-tissue structures. Units: mm, ms, kg, kN, GPa.",
    )
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


def main(argv: list[str] | None = None) -> int:
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
