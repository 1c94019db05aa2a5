"""``hollowbody block``: the paper's block impact test (section 2.1).

Builds the block test (docs/block.md), writes ``DIR/deck.k`` (the same
run, repeatable in LS-DYNA or OpenRadioss), runs it and writes
``DIR/force_displacement.csv`` and ``DIR/force_displacement.png`` next to the
run's histories, ParaView states and ``summary.json``.

``--engine openradioss|lsdyna`` runs ``deck.k`` on an installed external engine
instead, in ``DIR/<engine>/`` (``--np`` MPI ranks of ``--threads`` threads each,
found through ``--engine-path``, OPENRADIOSS_PATH / LSDYNA or the PATH;
docs/engines.md); its histories are converted and the same curve files and
plot are written to DIR. ``--dry-run`` writes the deck and prints what would
run.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hollowbody.cli.calibrate import (
    add_solid_hourglass_options,
    add_wall_hourglass_options,
    solid_hourglass_options,
)
from hollowbody.cli.run import add_threads_argument, with_threads
from hollowbody.cli.run_engine import add_external_engine_arguments, external_engine
from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("block", help="the paper's block impact test (solid or hollow)",
                       description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--tissue", choices=("muscle", "fat"), default="muscle",
                   help="block tissue (default muscle)")
    p.add_argument("--structure", choices=("solid", "hollow"), default="solid",
                   help="solid hexahedra or hollow shell walls (default solid)")
    p.add_argument("--speed", type=float, default=40.0, help="impact speed in km/h (default 40)")
    p.add_argument("--mesh", type=float, default=7.5,
                   help="solid element edge in mm; must divide 180 and 90 (default 7.5)")
    p.add_argument("--impactor", choices=("cylinder", "sphere"), default="cylinder",
                   help="rigid impactor shape (default cylinder)")
    p.add_argument("--edge-radius", type=float, default=5.0,
                   help="rounding radius of the cylinder's face edge in mm (default 5)")
    p.add_argument("--end-time", type=float, default=None,
                   help="simulated time in ms (default: long enough for the rebound)")
    p.add_argument("--elform", type=int, choices=(1, 2), default=1,
                   help="solid block element: 1 one-point with hourglass control "
                        "(default; --solid-hourglass), 2 fully integrated, no hourglass modes "
                        "(about 4x slower per cycle)")
    add_solid_hourglass_options(p)
    p.add_argument("--friction", type=float, default=0.2,
                   help="impactor-tissue friction coefficient (default 0.2)")
    p.add_argument("--erode", action=argparse.BooleanOptionalAction, default=None,
                   help="delete collapsed elements (solids: negative volume; shells: area "
                        "below 1 %%) instead of stopping (default: on for hollow, off for "
                        "solid)")
    p.add_argument("--dtmin", type=float, default=None,
                   help="DTMIN, fraction of the initial step: with erosion, elements whose "
                        "step falls below it are deleted, else the run stops (default 0.05 "
                        "for hollow, off for solid)")
    p.add_argument("--mass-scaling", type=float, default=0.0, metavar="DT",
                   help="selective mass scaling: elements whose step falls below DT ms get "
                        "mass (DT2MS = -DT; default 0 = off; e.g. 0.002 for the hollow "
                        "block); the added mass is reported")
    p.add_argument("--thickness-update", action="store_true",
                   help="shell thickness follows the membrane strain (ISTUPD 1; default: "
                        "constant thickness)")
    p.add_argument("--vtk", action=argparse.BooleanOptionalAction, default=True,
                   help="write ParaView states (default: yes)")
    p.add_argument("--quiet", action="store_true",
                   help="no progress display (default: progress shown)")
    add_threads_argument(p)
    g = p.add_argument_group("hollow structure (--structure hollow)")
    g.add_argument("--E", dest="hollow_E", type=float, default=None,
                   help="wall Young's modulus in MPa (default: paper's fit, muscle 100, fat 50)")
    g.add_argument("--yield", dest="hollow_yield", type=float, default=None,
                   help="wall yield stress in MPa (default: paper's fit, muscle 4, fat 2)")
    g.add_argument("--etan", type=float, default=0.0,
                   help="wall tangent modulus in MPa (default 0)")
    g.add_argument("--thickness", type=float, default=1.5,
                   help="wall thickness in mm (default 1.5)")
    g.add_argument("--cell", type=float, default=30.0, help="cell size in mm (default 30)")
    g.add_argument("--elements-per-edge", type=int, default=4,
                   help="shell elements along a cell edge (default 4)")
    g.add_argument("--imperfection", type=float, default=None,
                   help="amplitude in mm of the walls' buckling-mode offsets (default 0.1 x "
                        "thickness; 0 gives flat walls)")
    add_wall_hourglass_options(g)
    g.add_argument("--mass-preserving", action=argparse.BooleanOptionalAction, default=True,
                   help="walls carry the solid block's mass; --no-mass-preserving keeps the "
                        "tissue density instead (default: mass preserving)")
    add_external_engine_arguments(p)
    p.add_argument("--dry-run", action="store_true",
                   help="write the deck and print what would run, run nothing (default: run)")
    p.add_argument("--compare", action="store_true",
                   help="run solid and hollow at this speed and overlay their curves "
                        "(default: one run)")
    p.add_argument("--out", type=Path, default=None,
                   help="output folder (default: block_<structure>_<tissue>_<speed>kmh)")
    p.add_argument("--overwrite", action="store_true",
                   help="replace the outputs of an earlier run in --out (default: such a "
                        "folder is refused)")
    p.set_defaults(func=with_threads(main))


def main(args: argparse.Namespace) -> int:
    from hollowbody.cli.run import exit_code
    from hollowbody.scenarios.block import BlockConfig, block_impact

    if args.speed <= 0.0:
        raise UserInputError(f"--speed must be positive (got {args.speed:g} km/h)")
    structure = "compare" if args.compare else args.structure
    out = args.out or Path(f"block_{structure}_{args.tissue}_{args.speed:g}kmh")
    try:
        cfg = BlockConfig(tissue=args.tissue, structure=args.structure, speed_kmh=args.speed,
                          mesh=args.mesh, impactor=args.impactor, edge_radius=args.edge_radius,
                          end_time=args.end_time, friction=args.friction, erode=args.erode,
                          elform=args.elform, hollow_E=args.hollow_E,
                          hollow_yield=args.hollow_yield,
                          hollow_etan=args.etan, thickness=args.thickness, cell=args.cell,
                          elements_per_edge=args.elements_per_edge,
                          imperfection=args.imperfection,
                          mass_preserving=args.mass_preserving,
                          wall_hourglass_ihq=args.wall_hourglass,
                          wall_hourglass_qh=(0.1 if args.wall_hourglass_qm is None
                                             else args.wall_hourglass_qm),
                          mass_scaling=args.mass_scaling, dtmin=args.dtmin,
                          thickness_update=args.thickness_update,
                          **solid_hourglass_options(args))
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    from hollowbody.solver.outputs import prepare_out_dir

    engine = external_engine(args)
    folders = (out / "solid", out / "hollow") if args.compare else (out,)
    for folder in folders:
        prepare_out_dir(folder, args.overwrite)  # before the deck is written
    if args.dry_run:
        return _dry_run(cfg, folders, engine)
    if args.compare:
        return _compare(cfg, out, args, engine)
    res = block_impact(cfg, out, vtk=args.vtk, quiet=args.quiet, engine=engine)
    s = res.summary
    print(f"{s['status']}: {s['reason']}")
    before = (s.get("energies_before_error_J") or {}).get("energy_ratio")
    print(f"  peak force {res.curve.peak_force:.3f} kN, max impactor displacement "
          f"{res.curve.max_displacement:.2f} mm, energy ratio "
          f"{_ratio(s.get('energy_ratio'))}"
          + (f" ({before:.4f} before the failing cycle)" if before is not None else "")
          + f", {s['cycles']} cycles, wall {s['wall_seconds']:.1f} s")
    outcome = s.get("impact_outcome")
    if outcome == "through the base":
        print(f"  WARNING: the impactor went {res.curve.max_displacement:.1f} mm, through the "
              "block's fixed base: the curve after it reached the base is not valid")
    elif outcome == "reached the base":
        print("  note: the impactor crushed the block onto its fixed base (the force peak is "
              "the base's)")
    elif outcome == "ended before it stopped":
        print(f"  note: the run ended with the impactor still pressing in at "
              f"{res.curve.max_displacement:.1f} mm: the block did not stop it within the run")
    print(f"  outputs in {out} (deck.k, force_displacement.csv/.png, summary.json, states.pvd)")
    return exit_code(s["status"])


def _ratio(r: float | None) -> str:
    """An energy ratio as printed: four decimals, or three digits when it blew up."""
    r = float("nan") if r is None else float(r)
    return f"{r:.4f}" if abs(r) < 1e4 else f"{r:.3g}"


def _variant(cfg, structure: str):  # noqa: ANN001, ANN202 - BlockConfig
    """The solid or hollow block of ``cfg`` (the element formulation is the solid's)."""
    from dataclasses import replace

    return replace(cfg, structure=structure, elform=cfg.elform if structure == "solid" else 1)


def _dry_run(cfg, folders: tuple[Path, ...], engine) -> int:  # noqa: ANN001
    """Write each run's deck and print the plan of its run."""

    from hollowbody.scenarios.block import write_block_deck

    for folder in folders:
        c = _variant(cfg, folder.name) if len(folders) > 1 else cfg
        folder.mkdir(parents=True, exist_ok=True)
        deck = write_block_deck(c, folder)
        if engine is None:
            print(f"engine: hollowbody (this program, in this process)\ndeck: {deck}\n"
                  f"work folder: {folder}")
        else:
            print(engine.plan(deck, folder / engine.name, dry_run=True).describe())
    return 0


def _compare(cfg, out: Path, args: argparse.Namespace, engine=None) -> int:  # noqa: ANN001
    """Solid and hollow at the same speed, curves overlaid in ``out/compare.png``."""

    from hollowbody.cli.run import exit_code
    from hollowbody.curves.plot import plot
    from hollowbody.scenarios.block import block_impact

    results = {}
    for structure in ("solid", "hollow"):
        c = _variant(cfg, structure)
        results[structure] = block_impact(c, out / structure, vtk=args.vtk,
                                          quiet=args.quiet, engine=engine)
    plot([r.curve for r in results.values()], out / "compare.png",
         title=f"block test, {cfg.tissue}, {cfg.speed_kmh:g} km/h: solid vs hollow")
    for name, r in results.items():
        s = r.summary
        print(f"{name:6s} {s['status']}: peak {r.curve.peak_force:.3f} kN, max displacement "
              f"{r.curve.max_displacement:.2f} mm, {s['cycles']} cycles, wall "
              f"{s['wall_seconds']:.1f} s")
    ws, wh = (results[k].summary["wall_seconds"] for k in ("solid", "hollow"))
    if all(r.summary["status"] == "normal termination" for r in results.values()) and wh > 0:
        print(f"wall-time ratio solid/hollow: {ws / wh:.2f}")
    print(f"overlay: {out / 'compare.png'}")
    return max(exit_code(r.summary["status"]) for r in results.values())
