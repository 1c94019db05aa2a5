"""A candidate whose runs end normally but are suspect fails its evaluation:
penalised, recorded with the verdict, counted as failed and never the best."""

from __future__ import annotations

import json

from hollowbody.calibrate import (
    CalibrationSettings,
    FitnessSettings,
    GASettings,
    SurrogateSimulator,
    calibrate,
    make_space,
)
from hollowbody.calibrate.cache import EvaluationCache
from hollowbody.calibrate.study import StudyTask, run_study_task
from hollowbody.report.study import study_markdown, wall_time_ratios

REASON = {"indicator": "energy_ratio", "level": "suspect", "value": 10.05,
          "message": "energy ratio 10.1"}


def _settings() -> CalibrationSettings:
    return CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                               GASettings(population=8, generations=2),
                               FitnessSettings(penalty=10.0))


class SuspectAt(SurrogateSimulator):
    """The surrogate, with a suspect verdict for the candidates of ``keys``."""

    def __init__(self, keys: set[tuple[float, float]] = frozenset(), **kw) -> None:
        super().__init__(**kw)
        self.keys = set(keys)

    def hollow(self, params, speed_kmh, run_dir):
        out = super().hollow(params, speed_kmh, run_dir)
        if (params["E"], params["yield"]) in self.keys:
            out.summary.update({"quality": "suspect", "quality_reasons": [REASON]})
        return out


def test_a_suspect_candidate_is_never_the_best(tmp_path):
    clean = calibrate(_settings(), tmp_path / "clean", SuspectAt(write_files=False))
    best = (clean.best_params["E"], clean.best_params["yield"])
    res = calibrate(_settings(), tmp_path / "flagged", SuspectAt({best}, write_files=False))
    flagged = [e for e in res.evaluations
               if (e["params"]["E"], e["params"]["yield"]) == best]
    assert flagged, "the same seed evaluates the clean run's best again"
    for e in flagged:
        assert e["status"] == "suspect run"
        assert e["fitness"] == 10.0  # penalty x 1 speed
        assert e["reason"] == "40 km/h: SUSPECT: energy ratio 10.1"
        assert e["runs"][0]["quality"] == "suspect"
    assert (res.best_params["E"], res.best_params["yield"]) != best
    assert res.best_fitness > clean.best_fitness
    data = json.loads((tmp_path / "flagged" / "calibration.json").read_text())
    assert sum(h["suspect"] for h in data["generations"]) >= 1
    assert all(h["failed"] >= h["suspect"] for h in data["generations"])
    # a suspect evaluation is a finished, repeatable result: cached
    cache = EvaluationCache(tmp_path / "flagged" / "evaluations.jsonl")
    assert len(cache.records(data["context"])) == len(res.evaluations)


def test_study_rows_and_table_flag_a_suspect_run(tmp_path):
    sim = SuspectAt({(100.0, 4.0)}, write_files=False)
    rows = [run_study_task(StudyTask(sim, st, 40.0, {"E": 100.0, "yield": 4.0},
                                     str(tmp_path / st))) for st in ("solid", "hollow")]
    rows[0]["wall_seconds"] = rows[1]["wall_seconds"] = 1.0
    hollow = rows[1]
    # the surrogate's summaries carry no energies: no verdict for the solid row
    assert rows[0]["quality"] is None
    assert hollow["quality"] == "suspect" and hollow["quality_reasons"] == "energy ratio 10.1"
    md = study_markdown(rows)
    assert "**SUSPECT**: energy ratio 10.1" in md
    assert wall_time_ratios(rows) == {}  # a suspect run is left out of the ratios
    rows[1]["quality"] = "ok"
    assert wall_time_ratios(rows) == {40.0: 1.0}
