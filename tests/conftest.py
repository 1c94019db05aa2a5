"""Test-suite-wide settings.

The suite runs in several processes (pytest-xdist) on as many cores, each with
numba's default thread count: threads that spin while they wait would take the
cores from the other processes (hollowbody.solver.threads), so unless the
environment says otherwise the test processes' threads sleep while they wait.
"""

from __future__ import annotations

import os

if "OMP_WAIT_POLICY" not in os.environ and "GOMP_SPINCOUNT" not in os.environ:
    os.environ["OMP_WAIT_POLICY"] = "passive"
