"""The worked example examples/rigid_bodies/free_flight.k runs (briefly) and checks."""

from __future__ import annotations

import json
from pathlib import Path

from hollowbody.api import run_deck
from hollowbody.cli.main import main as cli_main

EXAMPLE = Path(__file__).resolve().parents[4] / "examples" / "rigid_bodies" / "free_flight.k"


def test_example_checks_and_runs(tmp_path, capsys):
    assert cli_main(["check", str(EXAMPLE), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    bodies = {b["pid"]: b for b in summary["rigid_bodies"]}
    assert bodies[1]["pids"] == [1, 2, 3] and bodies[1]["nodes"] == 26
    assert bodies[100]["kind"] == "nodal" and abs(bodies[100]["mass_kg"] - 0.01) < 1e-15
    res = run_deck(EXAMPLE, tmp_path / "out", end_time=2.0, vtk=False)
    assert res.status == "normal termination"
    assert abs(res.summary["energy_ratio"] - 1.0) < 1e-3
    rows = (tmp_path / "out" / "rbdout.csv").read_text().splitlines()
    assert {r.split(",")[1] for r in rows[1:]} == {"1", "100"}
