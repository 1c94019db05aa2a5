"""Axial crushing of thin-walled tubes against the closed-form mean crush forces.

Full-size cases of :mod:`hollowbody.scenarios.crush` (square tubes C/t 20-50,
circular tubes D/t 30 and 50, aluminium and steel, with and without the
trigger, 2-4 elements per closed-form half fold), run one after the other on
one thread, until the wall-time budget is spent (the remaining cases are
listed as not run). Prints one table row per case as it ends:

    case, C/t or D/t, mesh, analytical range [kN], mean force [kN], ratio to
    the range's upper end, half-fold length ours / closed form [mm],
    hourglass / internal, contact energy share, energy ratio, cycles, first and
    smallest time step [ms], wall time [s]

and writes ``results.json`` (one object per case) into ``--out``.

    NUMBA_NUM_THREADS=1 python benchmarks/bench_crush.py [--budget 1500] [--out DIR]
        [--only NAME-SUBSTRING ...] [--speed 10] [--tangent-drilling] [--drilling F]

``--tangent-drilling`` runs the cases with the shells' opt-in tangent drilling
spring (``Model.controls.shell_tangent_drilling``, docs/shells.md; no deck card,
so the deck is read into a model, the control set, and the model run); the
cases' run folders and rows then carry the suffix ``-tdrill``. ``--drilling F``
sets the shells' drilling stiffness factor (``Model.controls.shell_drilling``,
likewise no deck card; suffix ``-drillF``).

See docs/crush.md.
"""

from __future__ import annotations

import argparse
import json
import math
import tempfile
import time
from dataclasses import asdict, replace
from pathlib import Path

from hollowbody.scenarios.crush import CrushCase, CrushResult, run_crush
from hollowbody.scenarios.crush_theory import circular_half_fold, square_half_fold


def _length(shape: str, size: float, t: float, folds: float) -> float:
    """Tube length (mm): ``folds`` closed-form half-fold lengths, rounded to 10 mm."""
    h = square_half_fold(size, t) if shape == "square" else circular_half_fold(size, t)
    return 10.0 * math.ceil(folds * h / 10.0)


def cases(speed: float = 10.0) -> list[CrushCase]:
    """The benchmark's cases, most informative first (the budget cuts the tail); ``speed``
    mm/ms (the last two cases run at half of it)."""
    out = []

    def sq(t: float, **kw) -> CrushCase:
        kw.setdefault("speed", speed)
        return CrushCase(shape="square", size=50.0, t=t, length=_length("square", 50.0, t, 8.0),
                         **kw)

    def circ(t: float, **kw) -> CrushCase:
        kw.setdefault("per_half_fold", 2.0)
        kw.setdefault("speed", speed)
        return CrushCase(shape="circular", size=60.0, t=t,
                         length=_length("circular", 60.0, t, 10.0), **kw)

    out.append(sq(1.5))                              # C/t 33, aluminium, trigger, 3 / H
    out.append(sq(2.5))                              # C/t 20
    out.append(sq(1.0))                              # C/t 50
    out.append(circ(2.0))                            # D/t 30
    out.append(sq(1.5, material="steel"))
    out.append(sq(1.5, trigger=0.0))
    out.append(sq(1.5, per_half_fold=2.0))
    out.append(circ(1.2))                            # D/t 50
    out.append(circ(2.0, material="steel"))
    out.append(sq(1.5, per_half_fold=4.0))
    out.append(sq(2.5, per_half_fold=4.0))           # mesh convergence at C/t 20 and 50
    out.append(sq(1.0, per_half_fold=4.0))
    out.append(sq(1.5, material="steel", per_half_fold=4.0))
    out.append(sq(1.5, speed=0.5 * speed))           # inertia: half the speed
    out.append(sq(1.5, material="steel", speed=0.5 * speed))
    return out


HEADER = ("| case | C/t, D/t | mesh | analytical [kN] | ours [kN] | ratio | H ours / cf [mm] "
          "| HG/IE | contact | E ratio | cycles | dt0 / dt_min [us] | wall [s] |")


def row(r: CrushResult, suffix: str = "") -> str:
    """One markdown table row of a finished case (``suffix`` appended to its name)."""
    c, s, ref = r.case, r.setup, r.reference
    mesh = (f"{s.per_side}/side x {s.nz}" if c.shape == "square" else f"{s.around} x {s.nz}")
    mesh += f" ({c.per_half_fold:g}/H, {s.elem:.1f} mm)"
    return (f"| {c.name}{suffix} | {c.slenderness:.0f} | {mesh} | {ref.low:.1f}-{ref.high:.1f} "
            f"| {r.mean_force:.1f} | {r.ratio:.2f} | {r.half_fold:.1f} / {ref.half_fold:.1f} "
            f"| {r.hourglass_share:.1%} | {r.contact_share:.1%} | {r.energy_ratio:.3f} "
            f"| {r.cycles} | {1e3 * r.dt0:.3f} / {1e3 * r.dt_min:.3f} | {r.wall_seconds:.0f} |")


def record(r: CrushResult, suffix: str = "") -> dict:
    """JSON-able summary of a case (``suffix`` appended to its name)."""
    return {"case": asdict(r.case), "name": r.case.name + suffix, "status": r.status,
            "tangent_drilling": "-tdrill" in suffix,
            "mesh": asdict(r.setup), "forms_kN": r.reference.forms,
            "half_fold_closed_form": r.reference.half_fold, "window_mm": list(r.window),
            "mean_force_kN": r.mean_force, "ratio_to_high": r.ratio,
            "half_fold_ours": r.half_fold, "peaks_mm": r.peaks.tolist(),
            "hourglass_over_internal": r.hourglass_share, "contact_share": r.contact_share,
            "energy_ratio": r.energy_ratio, "plate_work_J": r.plate_work,
            "energy_sum_J": r.energy_sum, "cycles": r.cycles, "dt0_ms": r.dt0,
            "dt_min_ms": r.dt_min, "wall_s": r.wall_seconds}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--budget", type=float, default=1500.0,
                    help="wall seconds; no case is started once they are spent")
    ap.add_argument("--out", default=None, help="folder for the runs (default: a temporary one)")
    ap.add_argument("--only", nargs="*", default=None, help="run cases whose name has one of these")
    ap.add_argument("--speed", type=float, default=10.0, help="plate speed, mm/ms")
    ap.add_argument("--tangent-drilling", action="store_true",
                    help="shells with the opt-in tangent drilling spring (docs/shells.md)")
    ap.add_argument("--drilling", type=float, default=None,
                    help="shell drilling stiffness factor (default: the solver's, docs/shells.md)")
    a = ap.parse_args()
    out = Path(a.out) if a.out else Path(tempfile.mkdtemp(prefix="bench_crush_"))
    todo = cases(a.speed)
    if a.only:
        todo = [c for c in todo if any(s in c.name for s in a.only)]
    print(HEADER)
    print("|" + "---|" * 13, flush=True)
    t0 = time.perf_counter()
    results, skipped = [], []
    suffix = "-tdrill" if a.tangent_drilling else ""
    if a.drilling is not None:
        suffix += f"-drill{a.drilling:g}"
    for c in todo:
        if time.perf_counter() - t0 > a.budget:
            skipped.append(c.name)
            continue
        r = run_crush(replace(c), out / (c.name + suffix), threads=1,
                      tangent_drilling=a.tangent_drilling, drilling=a.drilling)
        results.append(record(r, suffix))
        print(row(r, suffix) + ("" if r.status == "normal termination" else f" {r.status}"),
              flush=True)
        (out / "results.json").write_text(json.dumps(results, indent=1))
    for name in skipped:
        print(f"not run (budget): {name}")
    print(f"total wall {time.perf_counter() - t0:.0f} s; runs in {out}")


if __name__ == "__main__":
    main()
