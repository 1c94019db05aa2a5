"""The worked example examples/loads/block_drop.k runs (briefly) from the command line."""

from __future__ import annotations

import json
from pathlib import Path

from hollowbody.cli.main import main

EXAMPLE = Path(__file__).resolve().parents[4] / "examples" / "loads" / "block_drop.k"


def test_block_drop_example_runs(tmp_path):
    """Up to 5 ms (before the impact at 31.9 ms): both blocks fall freely, the rigid
    one by g t^2 / 2 = 0.1226 mm (rbdout, to 1e-6 mm), the energy ratio is 1."""
    assert EXAMPLE.exists()
    assert main(["run", str(EXAMPLE), "--out", str(tmp_path), "--end-time", "5"]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["status"] == "normal termination"
    assert abs(s["energy_ratio"] - 1.0) < 1e-6
    last = (tmp_path / "rbdout.csv").read_text().splitlines()[-1].split(",")
    assert abs(float(last[4]) + 0.5 * 9.81e-3 * 25.0) < 1e-6
    assert (tmp_path / "rwforc.csv").exists()
