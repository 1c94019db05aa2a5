"""Study table and plots, and the demo's folder, with the analytic surrogate."""

from __future__ import annotations

import json

from hollowbody.calibrate import SerialRunner, SurrogateSimulator
from hollowbody.calibrate.study import run_study
from hollowbody.report.demo import BUDGETS, run_demo
from hollowbody.report.study import wall_time_ratios, write_study_report


class DiesFast(SurrogateSimulator):
    """The solid dies above 80 km/h, as the paper's solid tissue does at high energy."""

    def solid(self, speed_kmh, run_dir):
        out = super().solid(speed_kmh, run_dir)
        if speed_kmh > 80:
            out.status, out.reason = "error termination", "negative volume in solid 12"
        return out


def test_study_table_and_plots(tmp_path):
    rows = run_study(DiesFast(), (40.0, 100.0), tmp_path, hollow_params={"E": 90.0})
    assert [(r["structure"], r["speed_kmh"]) for r in rows] == [
        ("solid", 40.0), ("hollow", 40.0), ("solid", 100.0), ("hollow", 100.0)]
    dead = rows[2]
    assert dead["status"] == "error termination" and "negative volume" in dead["reason"]
    for r in rows:
        assert r["peak_force_kN"] > 0 and r["max_displacement_mm"] > 0
        assert r["cycles"] > 0 and r["wall_seconds"] is not None
    assert set(wall_time_ratios(rows)) == {40.0}
    files = write_study_report(rows, tmp_path)
    md = files["table_md"].read_text()
    assert "error termination" in md and "negative volume" in md and "wall-time ratio" in md
    csv_lines = files["table_csv"].read_text().splitlines()
    assert len(csv_lines) == 5 and csv_lines[0].startswith("structure,speed_kmh,status")
    for name in ("fd_40kmh", "fd_100kmh", "fd_all"):
        assert files[name].stat().st_size > 1000
    assert json.loads((tmp_path / "study.json").read_text())["rows"][0]["structure"] == "solid"


def test_demo_folder_is_complete(tmp_path):
    res = run_demo(tmp_path, BUDGETS["quick"], simulator=SurrogateSimulator(),
                   runner=SerialRunner())
    assert res.best_wall is not None and set(res.best_wall) == {"E", "yield", "etan",
                                                                "thickness"}
    for name in ("index.md", "index.html", "table1.md", "table1.csv", "demo.json",
                 "calibration/overlay.png", "calibration/convergence.png",
                 "calibration/calibration.json", "study/study.md", "study/fd_all.png"):
        assert (tmp_path / name).exists(), name
    md = (tmp_path / "index.md").read_text()
    html = (tmp_path / "index.html").read_text()
    for link in ("calibration/overlay.png", "calibration/convergence.png", "study/fd_all.png",
                 "table1.csv"):
        assert link in md and link in html
    assert "<table>" in html and "Young's modulus" in html
    assert len(res.study_rows) == 6


def test_study_rates_each_hollow_curve_against_the_solid_one(tmp_path):
    """fitness_vs_solid: 0 for walls that reproduce the solid curve (the surrogate's
    reference parameters), the calibration's own fitness for other walls (the same
    curve_distance with the study's filter), None for solid rows and where the solid
    run died; in the table and the CSV."""
    from hollowbody.calibrate.fitness import FitnessSettings, curve_distance
    from hollowbody.calibrate.study import load_curves

    sim = DiesFast()
    exact = run_study(sim, (40.0,), tmp_path / "exact", hollow_params=dict(sim.reference))
    write_study_report(exact, tmp_path / "exact")
    assert exact[1]["fitness_vs_solid"] < 1e-9
    assert exact[0]["fitness_vs_solid"] is None
    rows = run_study(sim, (40.0, 100.0), tmp_path / "off", hollow_params={"E": 150.0})
    files = write_study_report(rows, tmp_path / "off")
    curves = load_curves(rows)
    expected = curve_distance(curves[("solid", 40.0)], curves[("hollow", 40.0)],
                              FitnessSettings(cfc=180.0))
    assert rows[1]["fitness_vs_solid"] == expected > 0.01
    assert rows[3]["fitness_vs_solid"] is None  # the solid run at 100 km/h died
    assert "fitness vs solid" in files["table_md"].read_text()
    assert files["table_csv"].read_text().splitlines()[0].split(",")[-2] == "fitness_vs_solid"
