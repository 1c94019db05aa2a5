"""The worked examples of examples/joints run (briefly) through ``hollowbody run``:
normal termination, a balanced energy, jntforc.csv written with the joints (and the
elbow's joint stiffness angles) and no joint separated by more than 0.5 mm."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from hollowbody.cli.main import main

EXAMPLES = Path(__file__).resolve().parents[4] / "examples" / "joints"


@pytest.mark.parametrize("name, joints", [("pendulum.k", {1}), ("double_pendulum.k", {1, 2})])
def test_example_runs(tmp_path, name, joints):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLES / name), "--out", str(out), "--end-time", "100"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "normal termination"
    assert abs(s["energy_ratio"] - 1.0) < 0.01
    rows = list(csv.DictReader((out / "jntforc.csv").open()))
    assert {int(r["joint"]) for r in rows} == joints
    assert np.isfinite([float(r["f [kN]"]) for r in rows]).all()
    if name == "double_pendulum.k":
        theta = [float(r["angle2 [rad]"]) for r in rows if r["joint"] == "2"]
        assert max(abs(t) for t in theta) > 0.05  # the forearm bends at the elbow
    assert main(["check", str(EXAMPLES / name)]) == 0
