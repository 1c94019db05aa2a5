"""``hollowbody bending``: the limb segment's dynamic three-point bending, solid vs hollow.

Builds the limb segment (bone shell tube, muscle hexahedra, skin shells), its
hollowized version (muscle converted to walls tied to the boundary), and the
paper's three-point bending test of each (rigid cylinder at mid-span,
lateral-medial, 1.5 m/s; bone ends simply supported). Writes
``DIR/<structure>/deck.k`` with the run's outputs, ``DIR/bending.csv`` and
``DIR/bending.png`` (force- and moment-deflection side by side, wall times in
the legend). Units: mm, ms, kN.

A DIR holding an earlier run (bending.csv, bending.png or a structure folder
with a run's outputs) is refused unless --overwrite, which deletes those files
and the runs' outputs and decks first (other files are kept).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError

#: The command's own files in DIR (with the structure folders: what --overwrite clears).
BENDING_FILES = ("bending.csv", "bending.png")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("bending", help="limb three-point bending, solid vs hollow",
                       description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--segment", choices=("thigh", "leg"), default="thigh",
                   help="limb segment (default thigh)")
    p.add_argument("--end-time", type=float, default=20.0,
                   help="simulated time in ms (default 20: 30 mm of deflection)")
    p.add_argument("--structures", default="solid,hollow",
                   help="comma-separated: solid, hollow (default both)")
    p.add_argument("--self-contact", action=argparse.BooleanOptionalAction, default=False,
                   help="give the hollow muscle its self-contact (default: no; see "
                        "docs/hollowize.md: it pushes tied wall edges apart)")
    p.add_argument("--dtmin", type=float, default=0.1,
                   help="DTMIN as a fraction of the initial time step (default 0.1; 0 = off)")
    p.add_argument("--erode", action=argparse.BooleanOptionalAction, default=True,
                   help="delete the elements whose step falls below DTMIN (crushed wall "
                        "slivers under the impactor); --no-erode ends the run instead "
                        "(default: erode)")
    p.add_argument("--vtk", action=argparse.BooleanOptionalAction, default=False,
                   help="write ParaView states (default: no)")
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: bending_<segment>)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the outputs of an earlier run in --out (default: such a "
                        "folder is refused)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from hollowbody.cli.run import exit_code
    from hollowbody.hollow.convert import HollowOptions
    from hollowbody.scenarios.limb import run_three_point_bending
    from hollowbody.solver.outputs import prepare_runs_dir

    structures = tuple(s.strip() for s in args.structures.split(",") if s.strip())
    if not structures or set(structures) - {"solid", "hollow"}:
        raise UserInputError(f"--structures must list solid and/or hollow (got "
                             f"{args.structures!r})")
    if not 0.0 <= args.dtmin < 1.0:
        raise UserInputError(f"--dtmin must be in [0, 1) (got {args.dtmin:g})")
    if args.end_time <= 0.0:
        raise UserInputError(f"--end-time must be positive (got {args.end_time:g} ms)")
    out = args.out or Path(f"bending_{args.segment}")
    prepare_runs_dir(out, args.overwrite, BENDING_FILES, ("solid", "hollow"), ("deck.k",))
    runs = run_three_point_bending(out, args.segment, end_time=args.end_time,
                                   structures=structures,
                                   hollow_options=HollowOptions(self_contact=args.self_contact),
                                   quiet=False, vtk=args.vtk, dtmin=args.dtmin,
                                   erode=args.erode)
    codes = []
    for name, r in runs.items():
        if r.status.startswith(("skipped", "failed")):
            print(f"{name:6s} {r.status}")
            codes.append(3)
            continue
        peak = float(r.force.max()) if r.force.size else float("nan")
        defl = float(r.deflection.max()) if r.deflection.size else float("nan")
        print(f"{name:6s} {r.status}: peak force {peak:.3f} kN, max deflection {defl:.2f} mm, "
              f"energy ratio {r.energy_ratio:.4f}, {r.cycles} cycles, wall "
              f"{r.wall_seconds:.1f} s")
        codes.append(exit_code(r.status))
    print(f"plot: {out / 'bending.png'}")
    return max(codes)
