"""Calibration report: readable convergence axis, eroded shells of the best hollow run."""

from __future__ import annotations

import json
from pathlib import Path

from hollowbody.calibrate import (
    CalibrationSettings,
    FitnessSettings,
    GASettings,
    SurrogateSimulator,
    calibrate,
    make_space,
)
from hollowbody.report.calibration import best_eroded, use_log_scale, write_report


def test_log_scale_only_over_a_decade():
    assert not use_log_scale([0.48, 0.39, 0.46])  # narrow range: linear axis
    assert use_log_scale([0.5, 0.04])
    assert not use_log_scale([])
    assert not use_log_scale([None, float("nan"), 0.0, -1.0])
    assert use_log_scale([None, 2.0, float("nan"), 0.1])


def _calibrated(tmp_path: Path) -> dict:
    settings = CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                                   GASettings(population=4, generations=1),
                                   FitnessSettings())
    calibrate(settings, tmp_path, SurrogateSimulator())
    return json.loads((tmp_path / "calibration.json").read_text())


def test_best_eroded_reads_the_best_runs_summary(tmp_path):
    data = _calibrated(tmp_path)
    assert best_eroded(data, tmp_path) == {}  # the surrogate reports no erosion
    run = Path(data["best_run_dirs"][0])
    summary = json.loads((run / "summary.json").read_text())
    (run / "summary.json").write_text(json.dumps({**summary, "eroded_elements": 14}))
    assert best_eroded(data, tmp_path) == {40.0: 14}
    files = write_report(tmp_path)
    assert files["overlay"].stat().st_size > 1000
    assert files["convergence"].stat().st_size > 1000


def test_best_eroded_survives_a_missing_or_broken_summary(tmp_path):
    data = _calibrated(tmp_path)
    run = Path(data["best_run_dirs"][0])
    (run / "summary.json").write_text("{not json")
    assert best_eroded(data, tmp_path) == {}
    (run / "summary.json").unlink()
    assert best_eroded(data, tmp_path) == {}


def test_calibration_records_its_wall_time(tmp_path):
    data = _calibrated(tmp_path)
    assert data["elapsed_seconds"] > 0.0 and data["runs_here"] == len(data["evaluations"])
    again = _calibrated(tmp_path)  # everything from the cache
    assert again["runs_here"] == 0 and again["elapsed_seconds"] > 0.0
