"""The GA with the analytic surrogate recovers known parameters, reproducibly."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.calibrate import (
    CalibrationSettings,
    GASettings,
    SurrogateSimulator,
    calibrate,
    make_space,
)
from hollowbody.calibrate.ga import GeneticSearch, ReplayError

TRUE = {"E": 123.0, "yield": 5.5}
#: Stated tolerance of the recovery (relative), population 12 x 12 generations.
TOLERANCE = 0.05


def _settings(seed: int = 1, population: int = 12, generations: int = 12) -> CalibrationSettings:
    return CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                               GASettings(population, generations, seed))


def _sim() -> SurrogateSimulator:
    return SurrogateSimulator(reference=tuple(TRUE.items()), write_files=False)


def test_ga_recovers_known_parameters(tmp_path):
    res = calibrate(_settings(), tmp_path, _sim())
    assert res.status == "complete"
    for name, value in TRUE.items():
        assert res.best_params[name] == pytest.approx(value, rel=TOLERANCE), res.best_params
    assert res.best_fitness < 0.05
    # every evaluation is recorded with parameters, fitness, status and wall time
    assert len(res.evaluations) == res.runs_here
    e = res.evaluations[0]
    assert set(e) >= {"params", "fitness", "status", "reason", "wall_seconds", "generation"}
    # best so far never gets worse
    best = [h["best"] for h in res.history]
    assert all(b <= a for a, b in zip(best, best[1:]))


def test_same_seed_same_result_other_seed_other_path(tmp_path):
    a = calibrate(_settings(seed=3, generations=3), tmp_path / "a", _sim())
    b = calibrate(_settings(seed=3, generations=3), tmp_path / "b", _sim())
    c = calibrate(_settings(seed=4, generations=3), tmp_path / "c", _sim())
    assert [e["key"] for e in a.evaluations] == [e["key"] for e in b.evaluations]
    assert a.best_params == b.best_params
    assert [e["key"] for e in a.evaluations] != [e["key"] for e in c.evaluations]


def test_replay_detects_a_foreign_checkpoint():
    space = make_space(["E", "yield"])
    s = GeneticSearch(space, GASettings(4, 2, seed=1))
    x = s.ask()
    s.tell(np.ones(len(x)))
    other = GeneticSearch(space, GASettings(4, 2, seed=2))
    with pytest.raises(ReplayError):
        other.replay([{"X": x.tolist(), "F": [1.0] * len(x)}])
