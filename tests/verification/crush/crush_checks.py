"""Checks shared by the crush runs of this folder."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hollowbody.scenarios.crush import CrushResult


def assert_balanced_run(r: CrushResult, out: Path) -> None:
    """Normal termination; the energy ratio within 0.98-1.02 at every output once the
    plate has done 1 % of its work (before, the energies are below 2 J and the ratio
    is that of numbers near zero) and within 1 % at the end."""
    assert r.status == "normal termination"
    gl = np.genfromtxt(out / "glstat.csv", delimiter=",", names=True)
    ratio = gl["energy_ratio"][gl["external_work_J"] >= 0.01 * gl["external_work_J"][-1]]
    assert ratio.size > 100
    assert ratio.min() > 0.98 and ratio.max() < 1.02
    assert abs(ratio[-1] - 1.0) < 0.01
