"""``hollowbody pedestrian``: generate the open pedestrian model (deck, report, picture).

Writes DIR/pedestrian.k with one include per body region (trunk, head and
neck, each leg, each arm), materials.k and joints.k; DIR/report.json and
DIR/report.md (segment masses, centres of mass and inertias against de
Leva's, element counts, time step, initial penetrations, history nodes);
DIR/pedestrian.png (front view and mid-plane section). Run the deck with
``hollowbody run DIR/pedestrian.k``. See docs/pedestrian.md.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hollowbody.cli.text import plain
from hollowbody.errors import UserInputError


def register(sub: argparse._SubParsersAction) -> None:
    from hollowbody.body.anthropometry import DEFAULT_MASS, DEFAULT_STATURE
    from hollowbody.body.generate import DEFAULT_MESH

    p = sub.add_parser("pedestrian", help="generate the open pedestrian model (solid or hollow)",
                       description=plain(__doc__),
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, required=True, help="output folder")
    p.add_argument("--tissue", choices=("solid", "hollow"), default="solid",
                   help="limb muscle and torso fat as solids or hollow structures "
                        "(default solid)")
    p.add_argument("--posture", choices=("standing", "walking"), default="standing",
                   help="standing, or walking with the struck-side leg forward (default "
                        "standing)")
    p.add_argument("--struck", choices=("l", "r"), default="l",
                   help="struck side for the walking posture: its leg is forward (default l, "
                        "the body's left)")
    p.add_argument("--tone", action=argparse.BooleanOptionalAction, default=True,
                   help="walking: postural tone of hip, knee, shoulder and elbow flexion "
                        "that holds the posture under gravity (default: yes; --no-tone: "
                        "passive joints, as a released cadaver)")
    p.add_argument("--height", type=float, default=DEFAULT_STATURE,
                   help=f"stature in mm (default {DEFAULT_STATURE:g})")
    p.add_argument("--mass", type=float, default=DEFAULT_MASS,
                   help=f"body mass in kg (default {DEFAULT_MASS:g})")
    p.add_argument("--mesh", type=float, default=DEFAULT_MESH,
                   help=f"soft-tissue element size in mm (default {DEFAULT_MESH:g})")
    p.add_argument("--end-time", type=float, default=150.0,
                   help="*CONTROL_TERMINATION end time in ms (default 150)")
    p.add_argument("--picture", action=argparse.BooleanOptionalAction, default=True,
                   help="write pedestrian.png (default: yes)")
    p.add_argument("--overwrite", action="store_true",
                   help="write into a folder that already holds a pedestrian.k (default: "
                        "such a folder is refused)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from hollowbody.body.generate import PedestrianOptions, generate

    opts = PedestrianOptions(tissue=args.tissue, posture=args.posture, height=args.height,
                             mass=args.mass, mesh=args.mesh, end_time=args.end_time,
                             struck=args.struck, picture=args.picture, tone=args.tone)
    try:
        opts.validate()
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    if (args.out / "pedestrian.k").exists() and not args.overwrite:
        raise UserInputError(f"{args.out} already holds a pedestrian.k (use --overwrite)")
    r = generate(args.out, opts)
    m, e, t = r["mass"], r["elements"], r["time_step_ms"]
    print(f"open pedestrian ({opts.tissue}, {opts.posture}): {m['model_kg']:.3f} kg "
          f"(target {m['target_kg']:g} kg), {e['solid']} solids, {e['shell']} shells, first "
          f"step {t['run_dt']:.4g} ms, initial penetrations {r['penetrations']['total']}")
    print(f"  deck {args.out / 'pedestrian.k'}; report {args.out / 'report.md'}"
          + (f"; picture {args.out / 'pedestrian.png'}" if opts.picture else ""))
    return 0
