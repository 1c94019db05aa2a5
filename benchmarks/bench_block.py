"""Scenario wall times of the block test and the share of the cycle spent in contact.

    python benchmarks/bench_block.py [--structure solid|hollow] [--tissue muscle]
        [--speed 40] [--mesh 7.5] [--end-time MS] [--out DIR]

Prints cycles, wall time, microseconds per cycle and per element-cycle, and
the fractions of wall time in the element pass and in contact (from the
run's summary.json ``timing_seconds``). Run it twice: the first run of a
fresh install compiles the numba kernels.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path

from hollowbody.scenarios.block import BlockConfig, block_impact


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--structure", default="solid", choices=["solid", "hollow"])
    ap.add_argument("--tissue", default="muscle")
    ap.add_argument("--speed", type=float, default=40.0)
    ap.add_argument("--mesh", type=float, default=7.5)
    ap.add_argument("--end-time", type=float, default=None)
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    out = a.out or Path(tempfile.mkdtemp(prefix="bench_block_"))
    cfg = BlockConfig(tissue=a.tissue, structure=a.structure, speed_kmh=a.speed, mesh=a.mesh,
                      end_time=a.end_time)
    t0 = time.perf_counter()
    res = block_impact(cfg, out, vtk=False, quiet=True)
    wall = time.perf_counter() - t0
    s = json.loads((out / "summary.json").read_text())
    n_el = sum(s["element_counts"].values())
    solids = s["element_counts"]["hexahedra"]
    cyc = max(s["cycles"], 1)
    tm = s["timing_seconds"]
    print(json.dumps({
        "scenario": f"block {a.structure} {a.tissue} {a.speed:g} km/h mesh {a.mesh:g} mm",
        "status": s["status"], "cycles": s["cycles"], "elements": n_el, "solids": solids,
        "wall_run_s": round(s["wall_seconds"], 3), "wall_total_s": round(wall, 3),
        "us_per_cycle": round(1e6 * s["wall_seconds"] / cyc, 1),
        "us_per_element_cycle_in_element_pass": round(1e6 * tm["elements"] / cyc /
                                                       max(solids or n_el, 1), 4),
        "share_elements": round(tm["elements"] / s["wall_seconds"], 3),
        "share_contact": round(tm["contact"] / s["wall_seconds"], 3),
        "contact_s": round(tm["contact"], 2), "elements_s": round(tm["elements"], 2),
        "energy_ratio": round(s["energy_ratio"], 4), "eroded": s["eroded_elements"],
        "impactor": s.get("impact_outcome"),
        "peak_force_kN": round(res.curve.peak_force, 3),
        "max_displacement_mm": round(res.curve.max_displacement, 2),
    }, indent=1))


if __name__ == "__main__":
    main()
