"""Benchmark: rate a pair of 10 000-sample curves with ISO/TS 18571 and CORA.

Run as ``python benchmarks/bench_rating.py [--repeats N] [--samples N]``; prints
the median wall time per rating over N repeats (after one warm-up call that
compiles or loads the numba kernels) and the time of the main kernels.
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from hollowbody.rating.cora import CoraParameters, cora
from hollowbody.rating.iso18571 import IsoParameters, iso18571, magnitude_error, phase_shift


def curves(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A test-like pulse and a shifted, scaled, noisy candidate, sampled at 10 kHz."""
    t = np.arange(n) * 0.1  # ms
    span = t[-1]
    ref = np.exp(-(((t - 0.4 * span) / (0.08 * span)) ** 2)) * (1.0 + 0.1 * np.sin(t / 7.0))
    rng = np.random.default_rng(18571)
    cmp = 1.1 * np.exp(-(((t - 0.42 * span) / (0.085 * span)) ** 2))
    cmp += 0.01 * rng.standard_normal(n)
    return t, ref, cmp


def median_ms(fn, repeats: int) -> float:
    fn()  # warm-up: numba compilation or cache load
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--samples", type=int, default=10_000)
    args = parser.parse_args()
    t, ref, cmp = curves(args.samples)
    iso_p = IsoParameters()
    cora_p = CoraParameters(t_min=float(t[0]), t_max=float(t[-1]))  # whole curve
    cases = {
        "ISO/TS 18571 (all scores)": lambda: iso18571(t, ref, t, cmp, iso_p),
        "CORA (whole curve)": lambda: cora(t, ref, t, cmp, cora_p),
        "CORA (automatic interval)": lambda: cora(t, ref, t, cmp),
        "  kernel: Pearson cross-correlation, +/-20 %": lambda: phase_shift(ref, cmp, 0.2),
        "  kernel: DTW, Sakoe-Chiba band 10 %": lambda: magnitude_error(ref, cmp, 0.1),
    }
    print(f"{args.samples} samples per curve, median of {args.repeats} repeats")
    for name, fn in cases.items():
        print(f"{name:<46s} {median_ms(fn, args.repeats):9.1f} ms")


if __name__ == "__main__":
    main()
