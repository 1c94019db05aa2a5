"""``hollowbody rate``: objective rating of a candidate curve against a reference.

Example::

    hollowbody rate test.csv simulation.csv --method both --plot rating.png
    hollowbody rate test.csv sim.csv --columns time force --set K_V=5 --json

Both files are comma- or semicolon-separated with a header row; by default
the first column is time [ms] and the second the signal. ``--corridor`` adds
an experimental corridor: two columns (a closed polygon) or three columns
(abscissa, lower, upper); the fraction of the candidate inside it is
reported, it is drawn in the plot and it becomes CORA's inner corridor.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
from typing import Any

from hollowbody.errors import UserInputError

METHODS = ("cora", "iso18571", "both")


def register(subparsers: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``rate`` subcommand."""
    p = subparsers.add_parser(
        "rate", help="rate a curve against a reference (CORA, ISO/TS 18571)",
        description="Objective rating of a CANDIDATE curve (e.g. simulation) against a "
        "REFERENCE curve (e.g. test) with CORA and/or ISO/TS 18571. CSV files with a "
        "header row, comma or semicolon separated; time in ms.")
    p.add_argument("reference", help="reference curve CSV (test)")
    p.add_argument("candidate", help="candidate curve CSV (simulation)")
    p.add_argument("--method", choices=METHODS, default="both",
                   help="rating method (default: both)")
    p.add_argument("--corridor", metavar="FILE",
                   help="corridor CSV: polygon (x, y) or bounds (x, lower, upper) "
                   "(default: none)")
    p.add_argument("--columns", nargs=2, metavar=("TIME", "VALUE"),
                   help="time and value column of both curve files, by name or 1-based "
                   "number (default: 1 2)")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   dest="settings",
                   help="change a parameter, e.g. --set K_V=5, --set iso.eps_p=0.1, "
                   "--set T_MIN=2 (repeatable; prefix cora. or iso. to pick a method; "
                   "default: the methods' standard parameters)")
    p.add_argument("--json", action="store_true",
                   help="print the results as JSON (default: a table)")
    p.add_argument("--plot", metavar="OUT.png",
                   help="save a plot of the curves and the corridor (default: no plot)")
    p.set_defaults(func=run)


def _parse_value(text: str) -> Any:
    low = text.strip().lower()
    if low in ("auto", "automatic", "none"):
        return None
    if low in ("yes", "true"):
        return True
    if low in ("no", "false"):
        return False
    try:
        return float(text)
    except ValueError:
        raise UserInputError(f"--set: {text!r} is not a number") from None


def _parameters(settings: list[str]) -> tuple[Any, Any]:
    """CORA and ISO parameter sets with the ``--set`` changes applied."""
    from hollowbody.rating.cora import CORA_NAMES, CoraParameters
    from hollowbody.rating.iso18571 import IsoParameters

    cora_fields = {f.name for f in dataclasses.fields(CoraParameters)}
    cora_alias = {v.lower(): k for k, v in CORA_NAMES.items()}
    iso_fields = {f.name for f in dataclasses.fields(IsoParameters)}
    cora_changes: dict[str, Any] = {}
    iso_changes: dict[str, Any] = {}
    for item in settings:
        if "=" not in item:
            raise UserInputError(f"--set: expected NAME=VALUE, got {item!r}")
        name, text = (s.strip() for s in item.split("=", 1))
        target, _, key = name.rpartition(".")
        key_l = key.lower()
        value = _parse_value(text)
        hit = False
        if target in ("", "cora"):
            field = cora_alias.get(key_l, key_l if key_l in cora_fields else None)
            if field is not None:
                cora_changes[field] = value
                hit = True
        if target in ("", "iso", "iso18571") and key_l in iso_fields:
            iso_changes[key_l] = value
            hit = True
        if target not in ("", "cora", "iso", "iso18571"):
            raise UserInputError(f"--set: unknown method prefix {target!r} (use cora. or iso.)")
        if not hit:
            raise UserInputError(f"--set: unknown parameter {name!r}")
    for k in ("smooth_points",):
        if k in iso_changes and iso_changes[k] is not None:
            iso_changes[k] = int(iso_changes[k])
    try:
        return CoraParameters(**cora_changes), IsoParameters(**iso_changes)
    except (TypeError, ValueError) as err:
        raise UserInputError(f"--set: {err}") from None


def _read_corridor(path: str) -> Any:
    from hollowbody.rating.csvio import read_corridor

    return read_corridor(path)


def _clean(obj: Any) -> Any:
    """JSON-safe copy: NaN/inf become None, numpy scalars plain numbers."""
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if hasattr(obj, "item") and not isinstance(obj, (str, bytes)):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def _table(report: dict[str, Any]) -> str:
    rows: list[tuple[str, str, str]] = []
    iso = report.get("iso18571")
    if iso:
        rows.append((f"ISO/TS 18571  ({iso['t_start']:.6g}..{iso['t_end']:.6g} ms, "
                     f"{iso['n_samples']} samples)", "", ""))
        rows += [("  corridor", "Z", f"{iso['corridor']:.3f}"),
                 ("  phase", "EP", f"{iso['phase']:.3f}  shift {iso['shift']:+.4g} ms"),
                 ("  magnitude", "EM", f"{iso['magnitude']:.3f}"),
                 ("  slope", "ES", f"{iso['slope']:.3f}"),
                 ("  overall", "R", f"{iso['overall']:.3f}  {iso['grade']}")]
    cora = report.get("cora")
    if cora:
        kind = "user corridor" if cora["user_corridors"] else "a_0/b_0 corridors"
        rows.append((f"CORA  ({cora['t_start']:.6g}..{cora['t_end']:.6g} ms, "
                     f"{cora['n_samples']} samples)", "", ""))
        rows += [("  corridor", "Z", f"{cora['corridor']:.3f}  {kind}"),
                 ("  cross-correlation", "E", f"{cora['cross_correlation']:.3f}"),
                 ("    progression", "V", f"{cora['progression']:.3f}"),
                 ("    size", "G", f"{cora['size']:.3f}"),
                 ("    phase", "P", f"{cora['phase']:.3f}  shift {cora['shift']:+.4g} ms"),
                 ("  total", "R", f"{cora['total']:.3f}")]
    corr = report.get("corridor")
    if corr:
        frac = corr["fraction_inside"]
        text = "n/a (no overlap)" if frac is None else f"{frac:.3f}"
        rows.append(("corridor: fraction inside", "", text))
    w0 = max(len(r[0]) for r in rows if r[1] or r[2])
    lines = [f"reference: {report['reference']}", f"candidate: {report['candidate']}"]
    for name, sym, val in rows:
        lines.append(name if not (sym or val) else f"{name:<{w0}}  {sym:<3} {val}")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    """Rate the candidate against the reference; print a table or JSON."""
    from hollowbody.rating.cora import cora
    from hollowbody.rating.csvio import read_curve
    from hollowbody.rating.iso18571 import iso18571
    from hollowbody.rating.signals import CurveError

    columns = tuple(args.columns) if args.columns else (1, 2)
    cora_p, iso_p = _parameters(args.settings)
    t_ref, y_ref = read_curve(args.reference, columns)
    t_cmp, y_cmp = read_curve(args.candidate, columns)
    corridor = _read_corridor(args.corridor) if args.corridor else None
    report: dict[str, Any] = {"reference": args.reference, "candidate": args.candidate,
                              "columns": list(columns)}
    try:
        if args.method in ("iso18571", "both"):
            report["iso18571"] = iso18571(t_ref, y_ref, t_cmp, y_cmp, iso_p).to_dict()
        if args.method in ("cora", "both"):
            report["cora"] = cora(t_ref, y_ref, t_cmp, y_cmp, cora_p, corridor).to_dict()
    except CurveError as err:
        names = {"reference": args.reference, "candidate": args.candidate,
                 "both": f"{args.reference}, {args.candidate}"}
        raise UserInputError(f"{names.get(err.which or 'both')}: {err}") from None
    if corridor is not None:
        report["corridor"] = {"file": args.corridor,
                              "fraction_inside": corridor.fraction_inside(t_cmp, y_cmp)}
    report = _clean(report)
    if args.plot:
        _plot(args.plot, report, (t_ref, y_ref), (t_cmp, y_cmp), corridor, columns)
        report["plot"] = args.plot
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(_table(report))
        if args.plot:
            print(f"plot: {args.plot}")
    return 0


def _column_names(path: str, columns: tuple[Any, ...]) -> list[str]:
    """Header names of the ``columns`` (names or 1-based numbers) of a CSV file."""
    from hollowbody.rating.csvio import _column_index, read_table

    table = read_table(path)
    return [table.header[_column_index(table, c)] for c in columns]


def _axis_label(names: list[str]) -> str:
    """One axis label from the column names of both files (both when they differ)."""
    unique = list(dict.fromkeys(n for n in names if n))
    return " / ".join(unique) if unique else "value"


def plot_arguments(report: dict[str, Any], ref: Any, cmp: Any, corridor: Any,
                   columns: tuple[Any, ...], corridor_file: str | None = None
                   ) -> dict[str, Any]:
    """Keyword arguments of :func:`hollowbody.rating.plot.corridor_figure` for a rating:
    axis labels from the CSV headers, the file names in the legend, the ratings as
    the note."""
    from pathlib import Path

    ref_names = _column_names(report["reference"], columns)
    cmp_names = _column_names(report["candidate"], columns)
    note = []
    if "iso18571" in report:
        note.append(f"ISO 18571 R = {report['iso18571']['overall']:.3f}")
    if "cora" in report:
        note.append(f"CORA R = {report['cora']['total']:.3f}")
    return {"corridor": corridor, "reference": ref, "response": cmp,
            "reference_label": f"reference: {Path(report['reference']).name}",
            "response_label": f"candidate: {Path(report['candidate']).name}",
            "corridor_label": (f"corridor: {Path(corridor_file).name}" if corridor_file
                               else None),
            "title": "hollowbody rate",
            "xlabel": _axis_label([ref_names[0], cmp_names[0]]),
            "ylabel": _axis_label([ref_names[1], cmp_names[1]]),
            "note": "\n".join(note)}


def _plot(path: str, report: dict[str, Any], ref: Any, cmp: Any, corridor: Any,
          columns: tuple[Any, ...]) -> None:
    from hollowbody.rating.plot import plot_corridor

    kwargs = plot_arguments(report, ref, cmp, corridor, columns,
                            report.get("corridor", {}).get("file"))
    try:
        plot_corridor(path, **kwargs)
    except (OSError, ValueError) as err:
        raise UserInputError(f"{path}: cannot write the plot ({err})") from None
