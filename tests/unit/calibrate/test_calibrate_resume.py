"""Cache and checkpoint: a resumed calibration runs nothing twice."""

from __future__ import annotations

import json

import pytest

from hollowbody.calibrate import (
    CalibrationSettings,
    GASettings,
    SurrogateSimulator,
    calibrate,
    make_space,
)
from hollowbody.calibrate.evaluation import evaluate_candidate
from hollowbody.errors import UserInputError

SIM = SurrogateSimulator(write_files=False)


def _settings(generations: int = 4, seed: int = 5) -> CalibrationSettings:
    return CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                               GASettings(population=6, generations=generations, seed=seed))


class Counting:
    """Evaluator that counts its calls and can simulate a kill after ``stop_after`` calls."""

    def __init__(self, stop_after: int | None = None) -> None:
        self.calls = 0
        self.stop_after = stop_after

    def __call__(self, task):
        if self.stop_after is not None and self.calls >= self.stop_after:
            raise KeyboardInterrupt
        self.calls += 1
        return evaluate_candidate(task)


def test_resume_after_interruption_runs_nothing_twice(tmp_path):
    full = Counting()
    ref = calibrate(_settings(), tmp_path / "full", SIM, evaluate=full)

    first = Counting(stop_after=9)  # dies in the middle of generation 2
    with pytest.raises(KeyboardInterrupt):
        calibrate(_settings(), tmp_path / "cut", SIM, evaluate=first)
    data = json.loads((tmp_path / "cut" / "calibration.json").read_text())
    assert data["status"] == "interrupted"
    second = Counting()
    res = calibrate(_settings(), tmp_path / "cut", SIM, evaluate=second, resume=True)
    assert first.calls + second.calls == full.calls
    assert [e["key"] for e in res.evaluations] == [e["key"] for e in ref.evaluations]
    assert res.best_params == ref.best_params
    assert res.best_fitness == ref.best_fitness


def test_resume_of_a_finished_calibration_runs_nothing(tmp_path):
    calibrate(_settings(), tmp_path, SIM)
    again = Counting()
    res = calibrate(_settings(), tmp_path, SIM, evaluate=again, resume=True)
    assert again.calls == 0
    assert res.status == "complete"


def test_more_generations_continue_the_run(tmp_path):
    full = Counting()
    ref = calibrate(_settings(generations=5), tmp_path / "a", SIM, evaluate=full)
    short, more = Counting(), Counting()
    calibrate(_settings(generations=3), tmp_path / "b", SIM, evaluate=short)
    res = calibrate(_settings(generations=5), tmp_path / "b", SIM, evaluate=more, resume=True)
    assert short.calls + more.calls == full.calls
    assert res.best_params == ref.best_params


def test_a_new_run_in_the_same_folder_reuses_the_cache(tmp_path):
    calibrate(_settings(), tmp_path, SIM)
    again = Counting()
    calibrate(_settings(), tmp_path, SIM, evaluate=again)  # no resume: cache hits only
    assert again.calls == 0


def test_torn_cache_line_is_ignored(tmp_path):
    calibrate(_settings(generations=1), tmp_path, SIM)
    with open(tmp_path / "evaluations.jsonl", "a") as fh:
        fh.write('{"key": "E=1')  # killed while writing
    again = Counting()
    calibrate(_settings(generations=2), tmp_path, SIM, evaluate=again, resume=True)
    assert again.calls > 0  # generation 2 ran, and its records went on new lines
    lines = (tmp_path / "evaluations.jsonl").read_text().splitlines()
    assert sum(1 for ln in lines if ln.startswith('{"key": "E=1')) == 1


def test_resume_with_other_settings_is_refused(tmp_path):
    calibrate(_settings(generations=1), tmp_path, SIM)
    with pytest.raises(UserInputError, match="seed"):
        calibrate(_settings(generations=1, seed=6), tmp_path, SIM, resume=True)


def test_resume_without_checkpoint_is_refused(tmp_path):
    with pytest.raises(UserInputError, match="no checkpoint"):
        calibrate(_settings(), tmp_path, SIM, resume=True)
