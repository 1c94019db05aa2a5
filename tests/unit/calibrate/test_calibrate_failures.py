"""Failed candidates are penalised and recorded; broken set-ups stop with a clear error."""

from __future__ import annotations

import json

import pytest

from hollowbody.calibrate import (
    CalibrationError,
    CalibrationSettings,
    FitnessSettings,
    GASettings,
    SurrogateSimulator,
    calibrate,
    make_space,
)
from hollowbody.calibrate.cache import EvaluationCache
from hollowbody.calibrate.reference import ReferenceRunError


def _settings(**ga) -> CalibrationSettings:
    return CalibrationSettings("muscle", (40.0, 70.0), make_space(["E", "yield"]),
                               GASettings(**{"population": 8, "generations": 2, **ga}),
                               FitnessSettings(penalty=10.0))


def test_error_termination_is_penalised_and_recorded(tmp_path):
    sim = SurrogateSimulator(fail_above=(("E", 200.0),), write_files=False)
    res = calibrate(_settings(), tmp_path, sim)
    failed = [e for e in res.evaluations if e["status"] == "error termination"]
    assert failed, "the bounds 10..400 MPa must produce some E above 200 MPa"
    for e in failed:
        assert e["params"]["E"] > 200.0
        assert e["fitness"] == 20.0  # penalty x 2 speeds
        assert "negative volume" in e["reason"] and e["reason"].startswith("40 km/h")
    assert res.best_params["E"] <= 200.0
    data = json.loads((tmp_path / "calibration.json").read_text())
    assert any(e["status"] == "error termination" for e in data["evaluations"])
    # error terminations are finished results: cached
    cache = EvaluationCache(tmp_path / "evaluations.jsonl")
    assert len(cache.records(data["context"])) == len(res.evaluations)


class Exploding(SurrogateSimulator):
    """Raises for large yield stresses (a Python error, not a solver death)."""

    def hollow(self, params, speed_kmh, run_dir):
        if params["yield"] > 10.0:
            raise RuntimeError("boom")
        return super().hollow(params, speed_kmh, run_dir)


def test_exceptions_are_recorded_but_not_cached(tmp_path):
    res = calibrate(_settings(), tmp_path, Exploding(write_files=False))
    broken = [e for e in res.evaluations if e["status"] == "exception"]
    assert broken and all("RuntimeError: boom" in e["reason"] for e in broken)
    cache = EvaluationCache(tmp_path / "evaluations.jsonl")
    assert len(cache) == len(res.evaluations) - len(broken)


class AlwaysBroken(SurrogateSimulator):
    def hollow(self, params, speed_kmh, run_dir):
        raise ValueError("hollow block not available")


def test_a_generation_of_exceptions_stops_the_calibration(tmp_path):
    with pytest.raises(CalibrationError, match="hollow block not available"):
        calibrate(_settings(), tmp_path, AlwaysBroken(write_files=False))


class DeadReference(SurrogateSimulator):
    def solid(self, speed_kmh, run_dir):
        out = super().solid(speed_kmh, run_dir)
        if speed_kmh > 50:
            out.status, out.reason = "error termination", "negative volume in element 7"
        return out


def test_failed_reference_stops_with_its_reason(tmp_path):
    with pytest.raises(ReferenceRunError, match="70 km/h.*negative volume"):
        calibrate(_settings(), tmp_path, DeadReference())


def test_reference_is_reused_when_complete(tmp_path):
    calibrate(_settings(generations=1), tmp_path, SurrogateSimulator(write_files=False))
    stamp = (tmp_path / "reference" / "40kmh" / "reference.json").stat().st_mtime_ns
    calibrate(_settings(generations=1), tmp_path, SurrogateSimulator(write_files=False))
    assert (tmp_path / "reference" / "40kmh" / "reference.json").stat().st_mtime_ns == stamp
    # another simulator (other reference material): run again
    calibrate(_settings(generations=1), tmp_path,
              SurrogateSimulator(reference=(("E", 90.0), ("yield", 4.0)), write_files=False))
    assert (tmp_path / "reference" / "40kmh" / "reference.json").stat().st_mtime_ns != stamp
