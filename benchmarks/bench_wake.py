"""What a threaded kernel costs to start: numba's OpenMP threads, passive or spinning.

Every threaded (``prange``) kernel wakes the worker threads, runs, and waits for
them. While the workers spin between kernels this costs a few microseconds; once
they sleep (``OMP_WAIT_POLICY=passive``, which hollowbody's runs set, see
docs/solver.md) each kernel pays a wake-up, which on a virtual machine can be a
hundred microseconds. That fixes how much work a kernel must have before running
it threaded pays (the contact's and elements' serial sizes).

The script times a trivial two-thread kernel after a serial gap of 0 to 3,000 us
(the serial work between two threaded kernels of a cycle), in one fresh process
per wait policy (the policy is read when OpenMP starts). Printed: median and 90th
percentile wall time per kernel call, microseconds.

Run:  python benchmarks/bench_wake.py [--calls 300]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys

POLICIES = {
    "passive (hollowbody's runs)": {"OMP_WAIT_POLICY": "passive"},
    "spinning (OpenMP default)": {},
    "short spin (GOMP_SPINCOUNT=10000)": {"OMP_WAIT_POLICY": "active",
                                          "GOMP_SPINCOUNT": "10000"},
}
GAPS_US = (0, 50, 200, 1000, 3000)


def measure(calls: int) -> dict[str, list[float]]:
    """In this process: {gap: [median, p90]} us of a trivial two-thread kernel."""
    import time

    import numba
    import numpy as np
    from numba import njit, prange

    @njit(parallel=True)
    def touch(a):  # pragma: no cover - jit
        for i in prange(a.shape[0]):
            a[i] += 1.0

    def serial_gap(us: float) -> None:
        """Keep the main thread busy for ``us`` microseconds (serial work)."""
        end = time.perf_counter() + 1e-6 * us
        while time.perf_counter() < end:
            pass

    a = np.zeros(2)
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    touch(a)
    serial_gap(1.0)
    out = {}
    for gap in GAPS_US:
        t = np.empty(calls)
        for k in range(calls):
            serial_gap(float(gap))
            t0 = time.perf_counter()
            touch(a)
            t[k] = time.perf_counter() - t0
        out[str(gap)] = [1e6 * float(np.median(t)), 1e6 * float(np.percentile(t, 90))]
    out["threads"] = [float(numba.get_num_threads())] * 2
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--calls", type=int, default=300)
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        print(json.dumps(measure(args.calls)))
        return
    print(f"trivial threaded kernel after a serial gap; {args.calls} calls per gap; "
          "us per call: median / 90th percentile")
    print("policy".ljust(36) + "".join(f"gap {g} us".rjust(18) for g in GAPS_US))
    for name, env in POLICIES.items():
        full = {k: v for k, v in os.environ.items()
                if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
        full.update(env)
        res = subprocess.run([sys.executable, __file__, "--child", "--calls", str(args.calls)],
                             env=full, capture_output=True, text=True, check=True)
        r = json.loads(res.stdout.strip().splitlines()[-1])
        if r["threads"][0] < 2:
            print(f"{name}: only one numba thread available; nothing to measure")
            continue
        print(name.ljust(36) + "".join(f"{r[str(g)][0]:8.1f} / {r[str(g)][1]:6.1f}"
                                       for g in GAPS_US))


if __name__ == "__main__":
    main()
