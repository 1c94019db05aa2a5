"""The open pedestrian stands on a rigid floor under gravity (coarse mesh, a few ms).

Checks (``hollowbody run`` on the generated deck): normal termination with the
run's quality ok; the energy balance closes (|ratio - 1| < 1 %: the joint
stiffnesses, the floor and gravity all enter it); the feet stay on the floor
(their rigid bodies move less than 0.5 mm vertically, the floor carries a
positive normal force) and no joint centre drifts apart (history nodes of the
knees follow the body: under 0.5 mm). The long standing run (150 ms, default
mesh) is reported in docs/pedestrian.md, not run here; the hollow variant's short run
takes minutes (its wall shells set a step several times smaller) and is marked slow.
"""

from __future__ import annotations

import csv
import json

import pytest

from hollowbody.body.generate import PedestrianOptions, generate
from hollowbody.body.settling import foot_parts, settling_summary, settling_table
from hollowbody.cli.main import main


@pytest.mark.parametrize("tissue", ["solid", pytest.param("hollow", marks=pytest.mark.slow)])
def test_standing_under_gravity(tmp_path, tissue: str) -> None:
    r = generate(tmp_path, PedestrianOptions(mesh=50.0, end_time=3.0, picture=False,
                                             tissue=tissue))
    out = _run_and_check_standing(tmp_path)
    hist = r["history_nodes"]
    nodes = [row for row in csv.DictReader((out / "nodout.csv").open())
             if int(row["node"]) in (hist["knee_l"], hist["knee_r"])]
    assert max(abs(float(row["uz [mm]"])) for row in nodes) < 0.5


def test_walking_with_tone_under_gravity(tmp_path) -> None:
    """The walking posture with its postural tone (coarse mesh, 3 ms): runs to normal
    termination with quality ok and a closed energy balance (1 %), the feet stay on
    the floor (0.5 mm) and the floor carries the body. Whether the tone holds the
    posture for 150 ms is a long run (docs/pedestrian.md, Figures)."""
    r = generate(tmp_path, PedestrianOptions(mesh=50.0, end_time=3.0, picture=False,
                                             posture="walking"))
    assert r["postural_tone_Nm_per_rad"]["knee_r"][1] > 100.0
    _run_and_check_standing(tmp_path)


def _run_and_check_standing(folder):
    """Run the generated deck in ``folder``; it ends normally with quality ok, a closed
    energy balance (1 %), the feet on the floor (0.5 mm) and the floor carrying the
    body. Returns the run's folder."""
    out = folder / "run"
    assert main(["run", str(folder / "pedestrian.k"), "--out", str(out), "--quiet",
                 "--no-vtk"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "normal termination"
    assert s["quality"] == "ok", s["quality_reasons"]
    assert abs(s["energy_ratio"] - 1.0) < 0.01
    feet = set(foot_parts(folder / "pedestrian.k").values())
    rows = [row for row in csv.DictReader((out / "rbdout.csv").open())
            if int(row["part"]) in feet]
    assert rows and max(abs(float(row["uz [mm]"])) for row in rows) < 0.5
    wall = list(csv.DictReader((out / "rwforc.csv").open()))
    assert float(wall[-1]["normal [kN]"]) > 0.0
    _check_settling_report(folder, out, rows, float(wall[-1]["normal [kN]"]))
    return out


def _check_settling_report(folder, out, feet_rows, floor_end: float) -> None:
    """The settling report reads the same run: its feet and floor figures are those
    read here from the raw histories, the weight is the model's mass times g, and
    its head drop is the head history node's."""
    s = settling_summary(folder, out)
    report = json.loads((folder / "report.json").read_text())
    assert s["status"] == "normal termination" and s["quality"] == "ok"
    assert s["weight_kN"] == pytest.approx(report["mass"]["model_kg"] * 9.81e-3, rel=1e-12)
    assert s["floor_normal_end_kN"] == pytest.approx(floor_end, rel=1e-12)
    assert max(f["uz_largest_mm"] for f in s["feet"].values()) == pytest.approx(
        max(abs(float(r["uz [mm]"])) for r in feet_rows), rel=1e-12)
    assert len(s["feet"]) == 2
    head = [float(r["uz [mm]"]) for r in csv.DictReader((out / "nodout.csv").open())
            if int(r["node"]) == report["history_nodes"]["head_cg"]]
    assert s["landmarks"]["head_cg"]["uz_end_mm"] == pytest.approx(head[-1], rel=1e-12)
    assert s["landmarks"]["head_cg"]["uz_lowest_mm"] == pytest.approx(min(head), rel=1e-12)
    assert s["kinetic_largest_J"] >= s["kinetic_end_J"] >= 0.0
    # glstat.csv holds the ratio to 9 significant digits, summary.json in full
    assert abs(s["energy_ratio_worst"] - 1.0) >= abs(s["energy_ratio"] - 1.0) - 1e-8
    assert settling_table({"run": s}).count("\n") == 3
