"""calibrate / study / demo command lines: bad input is one line and exit code 2."""

from __future__ import annotations

import json

import pytest

import hollowbody.cli.main as cli_main

COMMANDS = ("calibrate", "study", "demo")


@pytest.fixture(autouse=True)
def _subcommands(monkeypatch):
    """Register the subcommands whether or not cli/main.py lists them yet."""
    extra = tuple(c for c in COMMANDS if c not in cli_main.SUBCOMMANDS)
    monkeypatch.setattr(cli_main, "SUBCOMMANDS", cli_main.SUBCOMMANDS + extra)


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "Traceback" not in err[0]
    return err[0]


@pytest.mark.parametrize("args, words", [
    (["--params", "E,nu"], "unknown parameter 'nu'"),
    (["--bounds", "E=10-300"], "NAME=LO:HI"),
    (["--bounds", "E=300:10"], "LO < HI"),
    (["--bounds", "E=10:10"], "LO < HI"),
    (["--bounds", "thickness=1:2"], "not calibrated"),
    (["--params", "E,yield", "--fix", "yield=3"], "cannot also be fixed"),
    (["--fix", "thickness"], "NAME=VALUE"),
    (["--speeds", "40,fast"], "--speeds"),
    (["--population", "1"], "--population"),
    (["--generations", "0"], "--generations"),
    (["--workers", "0"], "--workers"),
    (["--mesh", "7"], "does not divide"),
    (["--end-time", "-1"], "--end-time"),
    (["--resume"], "no checkpoint"),
])
def test_calibrate_bad_inputs(tmp_path, capsys, args, words):
    code = cli_main.main(["calibrate", "--tissue", "muscle", "--out", str(tmp_path / "c"),
                          "--quiet", *args])
    assert code == 2
    assert words in _one_line_error(capsys)
    assert not (tmp_path / "c" / "reference").exists()  # nothing ran


def test_calibrate_resume_with_other_settings(tmp_path, capsys):
    from hollowbody.calibrate import CalibrationSettings, GASettings, calibrate, make_space
    from hollowbody.calibrate.surrogate import SurrogateSimulator

    calibrate(CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                                  GASettings(4, 1)), tmp_path, SurrogateSimulator())
    code = cli_main.main(["calibrate", "--tissue", "muscle", "--out", str(tmp_path),
                          "--quiet", "--resume", "--workers", "1"])
    assert code == 2
    assert "settings differ" in _one_line_error(capsys)


@pytest.mark.parametrize("args, words", [
    (["--speeds", "0"], "positive"),
    (["--hollow-from", "missing.json"], "no such calibration file"),
    (["--workers", "0"], "--workers"),
    (["--mesh", "7"], "does not divide"),
])
def test_study_bad_inputs(tmp_path, capsys, monkeypatch, args, words):
    monkeypatch.chdir(tmp_path)
    code = cli_main.main(["study", "--tissue", "fat", "--out", str(tmp_path / "s"), *args])
    assert code == 2
    assert words in _one_line_error(capsys)


def test_study_hollow_from_a_calibration_without_best(tmp_path, capsys):
    p = tmp_path / "calibration.json"
    p.write_text(json.dumps({"best_parameters": None}))
    code = cli_main.main(["study", "--tissue", "fat", "--out", str(tmp_path / "s"),
                          "--hollow-from", str(p)])
    assert code == 2
    assert "no valid best candidate" in _one_line_error(capsys)


def test_demo_bad_workers(tmp_path, capsys):
    code = cli_main.main(["demo", "--out", str(tmp_path), "--workers", "0"])
    assert code == 2
    assert "--workers" in _one_line_error(capsys)


def test_help_lists_the_options(capsys):
    with pytest.raises(SystemExit):
        cli_main.main(["calibrate", "--help"])
    out = capsys.readouterr().out
    for opt in ("--speeds", "--params", "--bounds", "--population", "--generations", "--seed",
                "--workers", "--scheduler", "--resume", "--mesh", "--end-time", "--out"):
        assert opt in out
