"""The segment tests' cost: set-up time, step, cycles and wall time per simulated ms.

For each case (default: one speed of every case) and tissue (solid, hollow),
builds the set-up on the open pedestrian model, runs ``--ms`` milliseconds past
the impactor's first contact and prints one row:

    case, tissue, set-up [s], elements (hexahedra, shells), first step [us],
    cycles, wall [s], wall per simulated ms [s/ms], us per element-cycle,
    projected wall time of the full case [s]

and the solid/hollow ratio of the wall per simulated ms. Writes
``results.json`` into ``--out``. Quote medians of repeated runs in one sitting
(the machine is shared).

    python benchmarks/bench_validate.py [--cases thorax pelvis ...] [--ms 5]
        [--mesh 30] [--tissues solid hollow] [--out DIR]

See docs/validation.md.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

from hollowbody.api import run_deck
from hollowbody.validation.cases import CASES, ORDER, end_time_of
from hollowbody.validation.runner import build_setup, write_setup


def bench(case: str, tissue: str, ms: float, mesh: float, out: Path) -> dict:
    c = CASES[case]
    speed = c.speeds[0]
    t0 = time.perf_counter()
    s = build_setup(c, speed, tissue, mesh)
    setup_s = time.perf_counter() - t0
    folder = out / case / tissue
    deck = write_setup(s, folder)
    end = s.contact_time + ms
    r = run_deck(deck, folder, end_time=end, quiet=True, vtk=False, overwrite=True)
    summ = json.loads((folder / "summary.json").read_text())
    counts = summ["element_counts"]
    n_el = counts.get("hexahedra", 0) + counts.get("shells", 0) + counts.get("beams", 0)
    wall = summ["wall_seconds"]
    cyc = max(summ["cycles"], 1)
    return {"case": case, "speed": speed, "tissue": tissue, "setup_s": setup_s,
            "hexahedra": counts.get("hexahedra", 0), "shells": counts.get("shells", 0),
            "dt_us": 1e3 * summ["dt_initial_ms"], "cycles": cyc, "wall_s": wall,
            "wall_per_ms": wall / end, "us_per_element_cycle": 1e6 * wall / (cyc * n_el),
            "projected_s": wall / end * end_time_of(c, speed), "status": r.status,
            "quality": summ.get("quality")}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", nargs="*", default=list(ORDER))
    ap.add_argument("--tissues", nargs="*", default=["solid", "hollow"])
    ap.add_argument("--ms", type=float, default=5.0, help="simulated ms past contact")
    ap.add_argument("--mesh", type=float, default=30.0)
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    out = a.out or Path(tempfile.mkdtemp(prefix="bench_validate_"))
    rows = []
    print("case            tissue  setup[s] hexa   shells  dt[us] cycles  wall[s] "
          "s/ms   us/el-cyc projected[s]")
    for case in a.cases:
        for tissue in a.tissues:
            r = bench(case, tissue, a.ms, a.mesh, out)
            rows.append(r)
            print(f"{case:15s} {tissue:7s} {r['setup_s']:7.1f} {r['hexahedra']:6d} "
                  f"{r['shells']:7d} {r['dt_us']:6.2f} {r['cycles']:6d} {r['wall_s']:8.1f} "
                  f"{r['wall_per_ms']:6.2f} {r['us_per_element_cycle']:8.3f} "
                  f"{r['projected_s']:10.0f}  {r['status']}, {r['quality']}", flush=True)
        w = {r["tissue"]: r["wall_per_ms"] for r in rows if r["case"] == case}
        if "solid" in w and "hollow" in w:
            print(f"{case}: wall per simulated ms solid / hollow = "
                  f"{w['solid'] / w['hollow']:.2f}")
    (out / "results.json").write_text(json.dumps(rows, indent=1) + "\n")
    print(f"results: {out / 'results.json'}")


if __name__ == "__main__":
    main()
