"""``hollowbody hollowize DECK.k --out NEW.k``: replace solid soft tissue by hollow shells.

Every selected solid part (default: all parts with MAT_181 simplified
rubber) becomes a hollow structure: its boundary surface as shells on the
original nodes plus a cubic grid of shell walls clipped to its volume, with
a plastic-kinematic material (MAT_003) and its mass, centre of mass and
inertia kept. The rest of the deck is unchanged; include files that change
are written next to NEW.k with the suffix ``_hollow``, the others are
referenced where they are. A report (Markdown and JSON) lists what was
converted and the mass properties before and after. Units: mm, MPa.
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("hollowize", help="convert solid soft-tissue parts into hollow shell "
                       "structures", description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("deck", type=Path, help="LS-DYNA keyword deck to convert (not modified)")
    p.add_argument("--out", type=Path, required=True, help="converted deck to write (required)")
    sel = p.add_mutually_exclusive_group()
    sel.add_argument("--parts", type=_id_list, default=None,
                     help="part ids, e.g. 3,7,12 (default: by material type)")
    sel.add_argument("--part-set", type=int, default=None,
                     help="a *SET_PART id (default: by material type)")
    sel.add_argument("--material-type", type=int, default=None,
                     help="every solid part with this LS-DYNA material type (default 181)")
    p.add_argument("--cell", type=float, default=None,
                   help="cell edge in mm (default: the calibration's, else 30)")
    p.add_argument("--thickness", type=float, default=None,
                   help="wall thickness in mm (default: the calibration's, else 1.5)")
    p.add_argument("--elements-per-edge", type=int, default=None,
                   help="shell elements along a cell edge (default: the calibration's, "
                        "else 4)")
    mat = p.add_mutually_exclusive_group()
    mat.add_argument("--material", type=_pair, default=None, metavar="E,YIELD",
                     help="wall Young's modulus and yield stress in MPa (default: the paper's "
                     "fit, muscle 100,4 for KM >= 0.1 GPa, fat 50,2 otherwise)")
    mat.add_argument("--calibration", type=Path, default=None,
                     help="calibration.json (best E and yield in MPa; its etan, thickness, "
                     "cell and shells per cell edge too when present; default: none)")
    p.add_argument("--wall-hourglass", type=int, default=0, metavar="IHQ",
                   help="hourglass control of the walls: 0 none (the deck's default), 4 "
                        "stiffness form, as the block test's --wall-hourglass (default 0)")
    p.add_argument("--wall-hourglass-qm", type=float, default=0.1,
                   help="QM of --wall-hourglass (default 0.1)")
    p.add_argument("--etan", type=float, default=0.0,
                   help="wall tangent modulus in MPa (default: the calibration's, else 0)")
    p.add_argument("--grid-axes", choices=("global", "principal"), default="global",
                   help="grid along the global axes or the part's principal axes "
                        "(default global)")
    p.add_argument("--mass-mode", choices=("density", "nodal"), default="density",
                   help="mass in the walls' density (point masses only as a correction) or "
                   "walls at tissue density plus point masses (default density)")
    p.add_argument("--self-contact", action=argparse.BooleanOptionalAction, default=True,
                   help="add a single-surface contact on each converted part (default: yes)")
    p.add_argument("--report", type=Path, default=None,
                   help="report file (Markdown; JSON next to it; default NEW_report.md)")
    p.set_defaults(func=run)


def _id_list(text: str) -> list[int]:
    try:
        ids = [int(t) for t in text.replace(" ", "").split(",") if t]
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a list of part ids: {text!r}") from None
    if not ids:
        raise argparse.ArgumentTypeError("no part id given")
    return ids


def _pair(text: str) -> tuple[float, float]:
    try:
        e, y = (float(t) for t in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected E,YIELD in MPa, got {text!r}") from None
    return e, y


def run(args: argparse.Namespace) -> int:
    from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
    from hollowbody.hollow.output import input_files, write_converted
    from hollowbody.io.keyword import UnsupportedKeywordWarning, read_deck

    deck_path: Path = args.deck
    out: Path = args.out
    if not deck_path.is_file():
        raise UserInputError(f"deck '{deck_path}' does not exist")
    if out.resolve() == deck_path.resolve():
        raise UserInputError(f"--out {out} is the input deck; choose another name")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnsupportedKeywordWarning)
        deck = read_deck(deck_path)
    inputs = input_files(deck)
    if out.resolve() in inputs:
        raise UserInputError(f"--out {out} is a file of the input deck; choose another name")
    options = HollowOptions(cell=30.0 if args.cell is None else args.cell,
                            thickness=1.5 if args.thickness is None else args.thickness,
                            thickness_from_calibration=args.thickness is None,
                            geometry_from_calibration=(args.cell is None
                                                       and args.elements_per_edge is None),
                            elements_per_edge=(4 if args.elements_per_edge is None
                                               else args.elements_per_edge),
                            material=args.material,
                            calibration=args.calibration, etan=args.etan,
                            wall_hourglass_ihq=args.wall_hourglass,
                            wall_hourglass_qm=args.wall_hourglass_qm,
                            grid_axes=args.grid_axes, mass_mode=args.mass_mode,
                            self_contact=args.self_contact)
    selection = Selection(parts=args.parts, part_set=args.part_set,
                          material_type=args.material_type)
    new, report = hollowize(deck, selection, options)
    files = write_converted(new, out, report.changed_decks, inputs)
    md = args.report or out.with_name(out.stem + "_report.md")
    report.files = [str(f) for f in files]
    report.write_markdown(md)
    report.write_json(md.with_suffix(".json"))
    for p in report.parts:
        e = p.errors
        print(f"part {p.pid}: {sum(p.solids_removed.values())} solids -> {p.shells_added} "
              f"shells; mass {100 * e['mass_rel']:+.3f} %, centre {e['centre_mm']:.3f} mm, "
              f"inertia {max(abs(v) for v in e['inertia_rel']) * 100:.2f} %; smallest shell "
              f"dt {p.smallest_shell['dt_ms']:.3g} ms")
    for w in report.warnings:
        print(f"warning: {w}")
    print(f"wrote {', '.join(str(f) for f in files)}; report {md}")
    return 0
