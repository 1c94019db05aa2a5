"""``hollowbody check`` predicts the run's first time step.

``check`` computes the run's set-up and its forces at t = 0 with the run's own
code (:mod:`hollowbody.solver.preflight`), so its time step must equal the
first step of a run of the same deck; the tolerance (1e-12 relative) only
allows for the JSON round trip.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.io.keyword import read_deck
from hollowbody.io.keyword.writer import write_deck
from hollowbody.scenarios.block import BlockConfig, build_block_deck

DECKS = Path(__file__).resolve().parents[2] / "regression" / "decks"
REGRESSION = [DECKS / "hand_check.k", DECKS / "shapes.k", DECKS / "block" / "main.k"]


def _block(tmp_path: Path, structure: str) -> Path:
    path = tmp_path / f"block_{structure}.k"
    write_deck(build_block_deck(BlockConfig(tissue="muscle", structure=structure,
                                            speed_kmh=40)), path)
    return path


def _check_and_run(path: Path, tmp_path: Path, capsys) -> tuple[float, float]:
    code = cli_main(["check", str(path), "--json"])
    s = json.loads(capsys.readouterr().out)
    assert code == 0, s["problems"]
    model = build_model(read_deck(path))
    run = run_model(model, tmp_path / "run", vtk=False, end_time=1e-9)
    return s["time_step"]["run_dt"], run.summary["dt_initial_ms"]


@pytest.mark.parametrize("deck", REGRESSION, ids=lambda p: p.name)
def test_check_predicts_the_first_step_of_regression_decks(deck, tmp_path, capsys):
    predicted, taken = _check_and_run(deck, tmp_path, capsys)
    assert predicted == pytest.approx(taken, rel=1e-12)


@pytest.mark.parametrize("structure", ["solid", "hollow"])
def test_check_predicts_the_first_step_of_the_block_decks(structure, tmp_path, capsys):
    predicted, taken = _check_and_run(_block(tmp_path, structure), tmp_path, capsys)
    assert predicted == pytest.approx(taken, rel=1e-12)


def test_check_rejects_what_the_run_set_up_rejects_with_the_same_message(tmp_path, capsys):
    """A material that solids cannot use passes the reader and the builder and fails the
    run's set-up: check and run both refuse it (exit 2) with the same file:line message
    (check used to say "the deck can run")."""
    text = (DECKS / "hand_check.k").read_text().replace(
        "*MAT_ELASTIC\n         1    1.0e-6      0.21       0.3",
        "*MAT_PLASTIC_KINEMATIC\n         1    1.0e-6      0.21       0.3     0.001", 1)
    path = tmp_path / "bad.k"
    path.write_text(text)
    code = cli_main(["check", str(path), "--json"])
    s = json.loads(capsys.readouterr().out)
    assert code == 2 and not s["can_run"]
    (problem,) = s["problems"]
    assert problem.startswith(f"{path}:29: *MAT_PLASTIC_KINEMATIC:")
    assert "not available for solid elements" in problem
    code = cli_main(["run", str(path), "--out", str(tmp_path / "run"), "--quiet"])
    assert code == 2
    assert problem in capsys.readouterr().err
    assert not (tmp_path / "run").exists()  # nothing written for a deck that cannot run


def test_set_up_warnings_are_log_lines_not_python_warnings(tmp_path, capsys):
    """The MAT_181 stability check of hand_check.k's curve 10 warns: on `run` it is one
    line in messages.log and on the console, not a Python warning with a source path."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a Python warning would fail the run here
        code = cli_main(["run", str(DECKS / "hand_check.k"), "--out", str(tmp_path / "run"),
                         "--quiet", "--no-vtk", "--end-time", "0.01"])
    err = capsys.readouterr().err
    assert code == 0
    assert "UserWarning" not in err and "Baker-Ericksen" in err
    log = (tmp_path / "run" / "messages.log").read_text()
    assert log.count("Baker-Ericksen") == 1
