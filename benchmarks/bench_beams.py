"""Speed of the beam runtime: microseconds per beam-cycle (ELFORM 1 and 2).

A straight chain of N beams (default 10 000) along x, 10 mm each, 5 x 5 mm
steel section, orientation node above; random small velocities and angular
velocities; one "cycle" is one ``BeamGroupRuntime.add_forces`` call (triad
update, co-rotational frame, section law, nodal forces and moments, step),
as the solver's loop makes it (single thread: the beam kernel is serial).

Cases: ELFORM 2 (resultant, elastic); ELFORM 1 with 2 x 2 Gauss points,
*MAT_ELASTIC; ELFORM 1 2 x 2 with *MAT_PLASTIC_KINEMATIC and a yield stress
so low that every point returns every cycle; ELFORM 1 with a 4 x 4 rule
(QR 5), elastic. Median over repeats.

    python benchmarks/bench_beams.py [--n 10000 --cycles 50 --repeats 5]
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np

from hollowbody.elements.beam_group import BeamGroupRuntime
from hollowbody.model.beams import BeamGroup
from hollowbody.model.model import MaterialDef, SectionDef


def chain(n: int, length: float = 10.0) -> tuple[np.ndarray, BeamGroup]:
    """Nodes (n + 2, 3) mm (the last one the orientation node) and the group."""
    x = np.zeros((n + 2, 3))
    x[: n + 1, 0] = np.arange(n + 1) * length
    x[n + 1] = (0.0, 10.0, 0.0)
    conn = np.stack([np.arange(n), np.arange(1, n + 1), np.full(n, n + 1)], axis=1)
    return x, BeamGroup(pid=1, elem_ids=np.arange(1, n + 1, dtype=np.int64),
                        conn=conn.astype(np.int32))


def make_runtime(case: str, x: np.ndarray, group: BeamGroup) -> BeamGroupRuntime:
    base = {"E": 200.0, "PR": 0.3}
    if case.endswith("plastic"):
        mat = MaterialDef(1, "plastic003", 7.85e-6, {**base, "SIGY": 1e-9, "ETAN": 0.1,
                                                     "BETA": 1.0})
    else:
        mat = MaterialDef(1, "elastic", 7.85e-6, base)
    if case.startswith("elform2"):
        sec = SectionDef(1, "beam", 2, {"A": 25.0, "ISS": 52.08, "ITT": 52.08, "J": 88.0,
                                        "SA": 20.8, "SHRF": 1.0, "NSM": 0.0})
    else:
        qr = 5.0 if "4x4" in case else 2.0
        sec = SectionDef(1, "beam", 1, {"TS1": 5.0, "TS2": 5.0, "TT1": 5.0, "TT2": 5.0,
                                        "QR": qr, "CST": 0.0, "SHRF": 5 / 6, "NSM": 0.0})
    return BeamGroupRuntime(group, mat, sec, {}, x)


def time_case(case: str, n: int, cycles: int, repeats: int, seed: int = 0) -> float:
    """Median microseconds per beam-cycle of ``case``."""
    x0, group = chain(n)
    rng = np.random.default_rng(seed)
    rt = make_runtime(case, x0, group)
    v = 1e-2 * rng.standard_normal(x0.shape)
    w = 1e-4 * rng.standard_normal(x0.shape)
    f = np.zeros_like(x0)
    mom = np.zeros_like(x0)
    dt = 1e-4
    x = x0.copy()
    rt.add_forces(x, v, dt, f, w, mom)  # compile / warm up
    walls = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(cycles):
            x += dt * v
            f[:] = 0.0
            mom[:] = 0.0
            rt.add_forces(x, v, dt, f, w, mom)
        walls.append(time.perf_counter() - t0)
    return 1e6 * statistics.median(walls) / (cycles * n)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--n", type=int, default=10000)
    ap.add_argument("--cycles", type=int, default=50)
    ap.add_argument("--repeats", type=int, default=5)
    a = ap.parse_args()
    out = {"beams": a.n}
    for case in ("elform2_elastic", "elform1_2x2_elastic", "elform1_2x2_plastic",
                 "elform1_4x4_elastic"):
        out[f"us_per_beam_cycle_{case}"] = round(time_case(case, a.n, a.cycles, a.repeats), 4)
    try:  # Linux: the machine's load while timing
        with open("/proc/loadavg") as fh:
            out["loadavg"] = fh.read().split()[:3]
    except OSError:
        pass
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
