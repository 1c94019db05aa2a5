"""``hollowbody check DECK.k [--json] [--strict]``: read and validate a deck.

Prints a model summary (counts, parts, masses, extent, critical time steps,
unsupported keywords) without running the deck: the run's set-up and its forces
at t = 0 are computed, so the time step shown is the one the run takes first.
The inventory (keyword blocks per keyword, nodes, elements by kind, parts,
materials and sections by keyword, unsupported keywords) is always printed, also
when the deck cannot run: a deck whose references do not resolve is counted from
its keyword items, a malformed deck (a card that does not read, a missing include
file) from what was read before the error (``can_run`` false, the error with its
file and line as the reason). The summary also gives the numba threads a run
would use (``--threads N|auto``, the same policy as ``run``,
:mod:`hollowbody.solver.threads`). Exit code 0 when the deck can run, 2 when it
cannot (reasons listed) or is malformed (one error line).
"""

from __future__ import annotations

import argparse
import json
import sys
import warnings

from hollowbody.build import build_model
from hollowbody.cli.run import add_threads_argument, with_threads
from hollowbody.io.keyword import UnsupportedKeywordWarning, read_deck_partial
from hollowbody.model.summary import summarize


def register(subparsers: argparse._SubParsersAction) -> None:
    p = subparsers.add_parser(
        "check", help="read and validate a keyword deck and print a model summary",
        description="Read and validate an LS-DYNA keyword deck without running it and print "
        "a model summary (counts, parts, masses, extent, critical time steps, unsupported "
        "keywords, the numba threads a run would use). Exit code 0: the deck can run; 2: it "
        "cannot or it is malformed.")
    p.add_argument("deck", help="LS-DYNA keyword file (.k / .key / .dyn)")
    p.add_argument("--json", action="store_true",
                   help="print one JSON object (default: a readable summary)")
    p.add_argument("--strict", action="store_true",
                   help="an unsupported keyword is an error (default: a warning, listed in "
                        "the summary)")
    add_threads_argument(p)
    p.set_defaults(func=with_threads(run))


def run(args: argparse.Namespace) -> int:
    from hollowbody.build.inventory import deck_inventory
    from hollowbody.errors import DeckError

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnsupportedKeywordWarning)  # listed in the summary
        read = read_deck_partial(args.deck, strict=args.strict)
        model, error = None, read.error
        if error is None:
            try:
                model = build_model(read.deck)
            except DeckError as exc:
                error = exc
    if model is None:  # the inventory of what was read, then the error
        summary = deck_inventory(read.deck, "not read" if read.error else "not defined")
        summary.update(deck=args.deck, keywords=read.keywords, problems=[str(error)],
                       can_run=False, warnings=[], time_step=None, threads=None,
                       rigid_bodies=[])
        _print(summary, args.json)
        raise error
    summary = summarize(model)
    summary.update(deck=args.deck, keywords=read.keywords)
    _first_step(model, summary)
    _print(summary, args.json)
    if summary["problems"]:
        print(f"hollowbody check: {args.deck} cannot run: " + "; ".join(summary["problems"]),
              file=sys.stderr)
        return 2
    return 0


def _print(summary: dict, as_json: bool) -> None:
    if as_json:
        print(json.dumps(summary))
    else:
        print_summary(summary)


def _first_step(model, summary: dict) -> None:  # noqa: ANN001 - Model
    """The run's own first step, threads and set-up checks (``summary["time_step"]``,
    ``summary["threads"]``, problems)."""
    from hollowbody.errors import DeckError
    from hollowbody.solver.preflight import Termination, first_time_step

    summary["time_step"] = {"solid": None, "shell": None, "tssfac": model.controls.tssfac,
                            "run_dt": None}
    summary["threads"] = None
    if summary["problems"]:
        return  # the set-up would fail on those first
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            summary["time_step"] = first_time_step(model)
            summary["threads"] = summary["time_step"].pop("threads")
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
              f"; shells: {e['shells']} quadrilaterals, {e['triangles']} triangles; " +
              (f"beams: {e['beams']}; " if e.get("beams") else "") +
              f"mass elements {e['mass_elements']}")
    if s.get("discrete"):
        con.print("discrete elements: " + "; ".join(f"{n} {law}" for law, n in
                                                     s["discrete"].items()), markup=False)
    table = Table(title="parts", title_justify="left")
    for col in ("pid", "title", "elements", "section", "material", "mass (kg)"):
        table.add_column(col, justify="right" if col in ("pid", "elements", "mass (kg)")
                         else "left")
    for p in s["parts"]:
        mass = "-" if p["mass_kg"] is None else f"{p['mass_kg']:.6g}"
        table.add_row(str(p["pid"]), escape(p["title"]), str(p["elements"]),
                      escape(p["section"]), escape(p["material"]), mass)
    con.print(table)
    if s.get("rigid_bodies"):
        con.print(_rigid_table(s["rigid_bodies"]))
    for what in ("materials", "sections"):
        if s.get(what):
            con.print(f"{what}: " + "; ".join(f"{kw} {', '.join(map(str, ids))}"
                                              for kw, ids in s[what].items()), markup=False)
    if s.get("keywords"):
        con.print("keywords read: " + ", ".join(f"*{kw} {n}" for kw, n in
                                                s["keywords"].items()), markup=False)
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
                  f"shells {_fmt_dt(ts['shell'])}" +
                  (f"; beams {_fmt_dt(ts['beam'])}" if ts.get("beam") else "") +
                  (f"; discrete {_fmt_dt(ts['discrete'])}" if ts.get("discrete") else ""))
    if ts["run_dt"]:
        con.print(f"first time step of the run (TSSFAC {ts['tssfac']:g}) {ts['run_dt']:.4g} ms; "
                  f"end time {s['end_time']:g} ms -> about "
                  f"{int(s['end_time'] / ts['run_dt']) if ts['run_dt'] else 0} cycles")
    if s.get("threads"):
        con.print(f"numba threads: {s['threads']['count']} ({s['threads']['reason']})",
                  markup=False)
    for j in s.get("joints", []):
        con.print(f"joint {j['jid']}: {j['type']}, nodes {', '.join(map(str, j['nodes']))}, "
                  f"rigid parts {j['parts'][0]} / {j['parts'][1]}", markup=False)
    for ld in s.get("loads", []):
        what = f"DOF {ld['dof']}" if "dof" in ld else ld["target"]
        con.print(f"load *{ld['kind']}: curve {ld['curve']} x {ld['sf']:g}, {what}"
                  + (f", {ld['target']}" if "dof" in ld else ""))
    for w in s.get("rigid_walls", []):
        con.print(f"rigid wall {w['rwid']}: through {_vec(w['point'])} mm, normal "
                  f"{_vec(w['normal'])}, {w['nodes']} slave nodes, friction {w['fric']:g}")
    for js in s.get("joint_stiffness", []):
        con.print(f"joint stiffness {js['jsid']}: {js['type']}, parts {js['parts'][0]} / "
                  f"{js['parts'][1]}, coordinate systems {js['cid'][0]} / {js['cid'][1]}",
                  markup=False)
    if s["unsupported"]:
        con.print(f"unsupported keywords ({len(s['unsupported'])}, ignored):")
        for u in s["unsupported"]:
            con.print(f"  {u['file']}:{u['line']}: *{u['keyword']}", markup=False,
                      soft_wrap=True)
    for w in s.get("warnings", []):
        con.print(f"[yellow]warning:[/yellow] {escape(w)}")
    if s["problems"]:
        con.print("[bold red]cannot run:[/bold red]")
        for reason in s["problems"]:
            con.print(f"  - {reason}", markup=False, soft_wrap=True)  # one line: file:line
    else:
        con.print("[green]the deck can run[/green]")


def _rigid_table(rows: list[dict]):  # noqa: ANN202 - rich Table
    """The rigid bodies: pid, parts, nodes, mass, centre, principal inertias."""
    from rich.markup import escape
    from rich.table import Table

    table = Table(title="rigid bodies", title_justify="left")
    for col in ("pid", "made of", "nodes", "mass (kg)", "centre (mm)",
                "principal inertias (kg*mm^2)"):
        table.add_column(col, justify="right" if col in ("pid", "nodes", "mass (kg)")
                         else "left")
    for r in rows:
        made = ("nodal rigid body" if r["kind"] == "nodal" else
                "part" + ("s " if len(r["pids"]) > 1 else " ") + ", ".join(map(str, r["pids"])))
        table.add_row(str(r["pid"]), escape(made), str(r["nodes"]), f"{r['mass_kg']:.6g}",
                      ", ".join(f"{c:.5g}" for c in r["centre_mm"]),
                      ", ".join(f"{c:.5g}" for c in r["principal_inertia_kg_mm2"]))
    return table


def _vec(v: list[float]) -> str:
    return "(" + ", ".join(f"{x:g}" for x in v) + ")"
