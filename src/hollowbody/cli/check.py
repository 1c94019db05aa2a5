"""``hollowbody check DECK.k [--json] [--strict]``: read and validate a deck.

Prints a model summary (counts, parts, masses, extent, critical time steps,
unsupported keywords) without running the deck: the run's set-up and its forces
at t = 0 are computed, so the time step shown is the one the run takes first.
The inventory (nodes, elements by kind, parts, materials and sections by
keyword, unsupported keywords) is printed whenever the deck could be read, also
when it cannot run: a deck whose references do not resolve is counted from its
keyword items (``can_run`` false, the error as the reason). Exit code 0 when
the deck can run, 2 when it cannot (reasons listed) or is malformed (one error
line).
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings

from hollowbody.build import build_model
from hollowbody.io.keyword import UnsupportedKeywordWarning, read_deck
from hollowbody.model.summary import summarize


def register(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser(
        "check", help="read and validate a keyword deck and print a model summary",
        description="Read and validate an LS-DYNA keyword deck without running it and print "
        "a model summary (counts, parts, masses, extent, critical time steps, unsupported "
        "keywords). Exit code 0: the deck can run; 2: it cannot or it is malformed.")
    p.add_argument("deck", help="LS-DYNA keyword file (.k / .key / .dyn)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (default: a readable summary)")
    p.add_argument("--strict", action="store_true",
                   help="an unsupported keyword is an error (default: a warning, listed in "
                        "the summary)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from hollowbody.build.inventory import deck_inventory
    from hollowbody.errors import DeckError

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnsupportedKeywordWarning)  # listed in the summary
        deck = read_deck(args.deck, strict=args.strict)
        try:
            model = build_model(deck)
        except DeckError as exc:
            model, error = None, exc
    if model is None:  # the inventory of what was read, then the error
        summary = deck_inventory(deck)
        summary.update(deck=args.deck, problems=[str(error)], can_run=False, warnings=[],
                       time_step=None)
        if args.json:
            print(json.dumps(summary))
        else:
            print_summary(summary)
        raise error
    summary = summarize(model)
    summary["deck"] = args.deck
    _first_step(model, summary)
    if args.json:
        print(json.dumps(summary))
    else:
        print_summary(summary)
    if summary["problems"]:
        print(f"hollowbody check: {args.deck} cannot run: " + "; ".join(summary["problems"]),
              file=sys.stderr)
        return 2
    return 0


def _first_step(model, summary: dict) -> None:  # noqa: ANN001 - Model
    """The run's own first step and set-up checks (``summary["time_step"]``, problems)."""
    from hollowbody.errors import DeckError
    from hollowbody.solver.preflight import Termination, first_time_step

    summary["time_step"] = {"solid": None, "shell": None, "tssfac": model.controls.tssfac,
                            "run_dt": None}
    if summary["problems"]:
        return  # the set-up would fail on those first
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            summary["time_step"] = first_time_step(model)
        except (DeckError, Termination) as exc:
            summary["problems"].append(str(exc))
            summary["can_run"] = False
    summary["warnings"] = [str(w.message) for w in caught
                           if not issubclass(w.category, UnsupportedKeywordWarning)]


def _fmt_dt(step: dict | None) -> str:
    if not step:
        return "-"
    return f"{step['dt']:.4g} ms (element {step['element']}, part {step['part']})"


def print_summary(s: dict) -> None:
    """Human-readable summary (rich tables)."""
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    con = Console(highlight=False)
    if not con.is_terminal:
        con = Console(highlight=False, width=120)
    con.print(f"[bold]{escape(s['deck'])}[/bold]" + (f"  {escape(s['title'])}" if s["title"]
                                                      else ""))
    e = s["elements"]
    con.print(f"nodes {s['nodes']}; solids: {e['hexahedra']} hexahedra, {e['wedges']} wedges, "
              f"{e['tetrahedra']} tetrahedra" +
              (f", {e['other_solids']} other" if e["other_solids"] else "") +
              f"; shells: {e['shells']} quadrilaterals, {e['triangles']} triangles; "
              f"mass elements {e['mass_elements']}")
    table = Table(title="parts", title_justify="left")
    for col in ("pid", "title", "elements", "section", "material", "mass (kg)"):
        table.add_column(col, justify="right" if col in ("pid", "elements", "mass (kg)")
                         else "left")
    for p in s["parts"]:
        mass = "-" if p["mass_kg"] is None else f"{p['mass_kg']:.6g}"
        table.add_row(str(p["pid"]), escape(p["title"]), str(p["elements"]),
                      escape(p["section"]), escape(p["material"]), mass)
    con.print(table)
    for what in ("materials", "sections"):
        if s.get(what):
            con.print(f"{what}: " + "; ".join(f"{kw} {', '.join(map(str, ids))}"
                                              for kw, ids in s[what].items()), markup=False)
    if s["mass_kg"] is not None:
        con.print(f"total mass {s['mass_kg']:.6g} kg (element masses "
                  f"{s['element_mass_kg']:.6g} kg)")
    bb = s["bounding_box"]
    if bb["min"] is not None:
        lo, hi = bb["min"], bb["max"]
        con.print("bounding box (mm): " + ", ".join(
            f"{a} {lo[k]:.6g} .. {hi[k]:.6g}" for k, a in enumerate("xyz")))
    ts = s["time_step"] or {"solid": None, "shell": None, "run_dt": None}
    if s["time_step"] is not None:
        con.print(f"critical time step: solids {_fmt_dt(ts['solid'])}; "
                  f"shells {_fmt_dt(ts['shell'])}")
    if ts["run_dt"]:
        con.print(f"first time step of the run (TSSFAC {ts['tssfac']:g}) {ts['run_dt']:.4g} ms; "
                  f"end time {s['end_time']:g} ms -> about "
                  f"{int(s['end_time'] / ts['run_dt']) if ts['run_dt'] else 0} cycles")
    if s["unsupported"]:
        con.print(f"unsupported keywords ({len(s['unsupported'])}, ignored):")
        for u in s["unsupported"]:
            con.print(f"  {u['file']}:{u['line']}: *{u['keyword']}", markup=False)
    for w in s.get("warnings", []):
        con.print(f"[yellow]warning:[/yellow] {escape(w)}")
    if s["problems"]:
        con.print("[bold red]cannot run:[/bold red]")
        for reason in s["problems"]:
            con.print(f"  - {reason}", markup=False)
    else:
        con.print("[green]the deck can run[/green]")
