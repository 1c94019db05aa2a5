"""calibrate / study / demo command lines: bad input is one line and exit code 2."""

from __future__ import annotations

import json

import pytest

import hollowbody.cli.main as cli_main
from hollowbody.errors import UserInputError

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
    (["--wall-hourglass", "7"], "--wall-hourglass must be 0-5"),
    (["--wall-hourglass", "4", "--wall-hourglass-qm", "-0.1"], "--wall-hourglass-qm"),
    (["--wall-hourglass-qm", "0.2"], "needs --wall-hourglass"),
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
    (["--wall-hourglass", "6"], "--wall-hourglass must be 0-5"),
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


def _parsed(argv):
    import argparse

    from hollowbody.cli import calibrate as cli_calibrate

    parser = argparse.ArgumentParser()
    cli_calibrate.register(parser.add_subparsers())
    return parser.parse_args(["calibrate", "--tissue", "muscle", "--out", "c", *argv])


def test_calibrate_wall_hourglass_goes_into_the_runs_and_the_cache_key():
    """--wall-hourglass 4: every hollow run's walls get IHQ 4 QM 0.1 (QM as given), and the
    simulator's description (the cache key, calibration.json) records it; default: none."""
    from hollowbody.cli.calibrate import build_settings

    _, plain = build_settings(_parsed([]))
    _, hg4 = build_settings(_parsed(["--wall-hourglass", "4"]))
    _, hg4q = build_settings(_parsed(["--wall-hourglass", "4", "--wall-hourglass-qm", "0.05"]))
    assert plain.config("hollow", 40.0, {"E": 100.0, "yield": 4.0}).wall_hourglass_ihq == 0
    cfg = hg4.config("hollow", 40.0, {"E": 100.0, "yield": 4.0})
    assert (cfg.wall_hourglass_ihq, cfg.wall_hourglass_qh) == (4, 0.1)
    assert hg4q.config("hollow", 40.0, {"E": 100.0, "yield": 4.0}).wall_hourglass_qh == 0.05
    assert hg4.describe()["options"] == {"wall_hourglass_ihq": 4, "wall_hourglass_qh": 0.1}
    assert plain.describe()["options"] == {}
    assert hg4.describe() != plain.describe() != hg4q.describe()


def test_calibrate_solid_hourglass_goes_into_the_reference_and_the_cache_key():
    """--solid-hourglass 4: the solid reference runs with IHQ 4 QM 0.1 (QM as given); the
    description records the solid block's control whether given or the default (IHQ 6, QM
    1), so references and caches of different controls are never mixed up."""
    from hollowbody.cli.calibrate import build_settings

    _, plain = build_settings(_parsed([]))
    _, hg4 = build_settings(_parsed(["--solid-hourglass", "4"]))
    _, hg4q = build_settings(_parsed(["--solid-hourglass", "4", "--solid-hourglass-qm", "0.05"]))
    assert (plain.config("solid", 40.0).hourglass_ihq, plain.config("solid", 40.0).hourglass_qh) \
        == (6, 1.0)
    assert (hg4.config("solid", 40.0).hourglass_ihq, hg4.config("solid", 40.0).hourglass_qh) \
        == (4, 0.1)
    assert hg4q.config("solid", 40.0).hourglass_qh == 0.05
    assert plain.describe()["solid_hourglass"] == [6, 1.0]
    assert hg4.describe()["solid_hourglass"] == [4, 0.1]
    # IHQ 4 QM 0.05 is what calibrations that record nothing were made with: recorded as
    # nothing, so those resume and keep their caches; never also among the options
    assert "solid_hourglass" not in hg4q.describe()
    assert all(d.describe()["options"] == {} for d in (plain, hg4, hg4q))
    descs = [json.dumps(d.describe(), sort_keys=True) for d in (plain, hg4, hg4q)]
    assert len(set(descs)) == 3
    _, explicit6 = build_settings(_parsed(["--solid-hourglass", "6"]))
    assert explicit6.describe() == plain.describe()  # the default given is the default


@pytest.mark.parametrize("argv, why", [
    (["--solid-hourglass", "8"], "--solid-hourglass must be 1-7"),
    (["--solid-hourglass", "0"], "--solid-hourglass must be 1-7"),
    (["--solid-hourglass-qm", "-1"], "--solid-hourglass-qm must be >= 0"),
])
def test_calibrate_refuses_bad_solid_hourglass(argv, why):
    from hollowbody.cli.calibrate import build_settings

    with pytest.raises(UserInputError, match=why):
        build_settings(_parsed(argv))


def _calibration_file(tmp_path, options, solid=None):
    p = tmp_path / "calibration.json"
    sim = {"fixed": {}, "options": options}
    if solid is not None:
        sim["solid_hourglass"] = solid
    p.write_text(json.dumps({"best_parameters": {"E": 120.0, "yield": 9.0}, "simulator": sim}))
    return p


#: the solid block's control of calibrations that do not record it (made before IHQ 6)
LEGACY_SOLID = {"hourglass_ihq": 4, "hourglass_qh": 0.05}


@pytest.mark.parametrize("extra, expected, note", [
    ([], {"wall_hourglass_ihq": 4, "wall_hourglass_qh": 0.1, **LEGACY_SOLID}, False),
    (["--wall-hourglass", "4"], {"wall_hourglass_ihq": 4, "wall_hourglass_qh": 0.1,
                                 **LEGACY_SOLID}, False),
    (["--wall-hourglass", "0"], LEGACY_SOLID, True),
])
def test_study_runs_calibrated_walls_with_their_hourglass_control(tmp_path, capsys,
                                                                   monkeypatch, extra,
                                                                   expected, note):
    """Walls calibrated with IHQ 4 run with IHQ 4 in the study unless --wall-hourglass says
    otherwise, and then the study says that they were calibrated with another control."""
    import hollowbody.calibrate.study as cal_study

    seen = {}

    def fake_run_study(sim, speeds, out, hollow_params=None, runner=None):
        seen["options"] = dict(sim.options)
        seen["wall"] = hollow_params
        return []

    monkeypatch.setattr(cal_study, "run_study", fake_run_study)
    import hollowbody.report.study as report_study

    monkeypatch.setattr(report_study, "write_study_report",
                        lambda rows, out: {"table_md": out / "study.md"})
    cal = _calibration_file(tmp_path, {"wall_hourglass_ihq": 4, "wall_hourglass_qh": 0.1})
    code = cli_main.main(["study", "--tissue", "muscle", "--out", str(tmp_path / "s"),
                          "--hollow-from", str(cal), "--workers", "1", *extra])
    assert code == 0
    assert seen["options"] == expected
    assert seen["wall"]["E"] == 120.0 and seen["wall"]["yield"] == 9.0
    err = capsys.readouterr().err
    assert ("were calibrated with *HOURGLASS IHQ 4 QM 0.1" in err) is note


@pytest.mark.parametrize("recorded, extra, expected, note", [
    ([6, 1.0], [], {"hourglass_ihq": 6, "hourglass_qh": 1.0}, False),
    (None, [], LEGACY_SOLID, False),
    ([6, 1.0], ["--solid-hourglass", "4", "--solid-hourglass-qm", "0.05"], LEGACY_SOLID, True),
    (None, ["--solid-hourglass", "6"], {"hourglass_ihq": 6, "hourglass_qh": 1.0}, True),
    (None, ["--solid-hourglass-qm", "0.1"], {"hourglass_ihq": 4, "hourglass_qh": 0.1}, True),
])
def test_study_runs_the_solid_block_the_walls_were_fitted_to(tmp_path, capsys, monkeypatch,
                                                             recorded, extra, expected, note):
    """The study's solid block takes the hourglass control of the calibration's solid
    reference (recorded in calibration.json; IHQ 4 QM 0.05 for calibrations made before it
    was recorded) unless --solid-hourglass says otherwise, and then says so."""
    import hollowbody.calibrate.study as cal_study
    import hollowbody.report.study as report_study

    seen = {}

    def fake_run_study(sim, speeds, out, hollow_params=None, runner=None):
        seen["solid"] = sim.config("solid", 40.0)
        return []

    monkeypatch.setattr(cal_study, "run_study", fake_run_study)
    monkeypatch.setattr(report_study, "write_study_report",
                        lambda rows, out: {"table_md": out / "study.md"})
    cal = _calibration_file(tmp_path, {}, solid=recorded)
    code = cli_main.main(["study", "--tissue", "muscle", "--out", str(tmp_path / "s"),
                          "--hollow-from", str(cal), "--workers", "1", *extra])
    assert code == 0
    got = {"hourglass_ihq": seen["solid"].hourglass_ihq, "hourglass_qh": seen["solid"].hourglass_qh}
    assert got == expected
    assert ("were fitted to a solid block with" in capsys.readouterr().err) is note


def test_calibrate_cell_goes_into_the_runs_and_the_cache_key():
    """--cell 15: the hollow runs get 15 mm cells with round(15 / mesh) = 2 shells per cell
    edge, the description (cache key, calibration.json) records the cell; the paper's 30
    mm cell is not recorded (calibrations made before the option keep their caches)."""
    from hollowbody.cli.calibrate import build_settings

    _, paper = build_settings(_parsed(["--cell", "30"]))
    _, fine = build_settings(_parsed(["--cell", "15"]))
    cfg = fine.config("hollow", 40.0, {"E": 100.0, "yield": 4.0})
    assert (cfg.cell, cfg.elements_per_edge) == (15.0, 2)
    assert fine.describe()["options"] == {"cell": 15.0}
    assert fine.describe()["elements_per_edge"] == 2
    assert paper.describe() == build_settings(_parsed([]))[1].describe()
    assert paper.config("hollow", 40.0, {"E": 100.0, "yield": 4.0}).cell == 30.0


@pytest.mark.parametrize("cell, words", [("7", "does not divide the block"),
                                         ("0", "must be positive")])
def test_calibrate_refuses_a_bad_cell(tmp_path, capsys, cell, words):
    code = cli_main.main(["calibrate", "--tissue", "muscle", "--cell", cell,
                          "--out", str(tmp_path / "c")])
    assert code == 2
    assert words in capsys.readouterr().err


def test_study_builds_the_calibrated_walls_cells(tmp_path, monkeypatch):
    """Walls calibrated with 15 mm cells are built with 15 mm cells (2 shells per edge at
    the 7.5 mm mesh) in the study."""
    import hollowbody.calibrate.study as cal_study
    import hollowbody.report.study as report_study

    seen = {}

    def fake_run_study(sim, speeds, out, hollow_params=None, runner=None):
        seen["hollow"] = sim.config("hollow", 40.0, hollow_params)
        return []

    monkeypatch.setattr(cal_study, "run_study", fake_run_study)
    monkeypatch.setattr(report_study, "write_study_report",
                        lambda rows, out: {"table_md": out / "study.md"})
    cal = _calibration_file(tmp_path, {"cell": 15.0})
    code = cli_main.main(["study", "--tissue", "muscle", "--out", str(tmp_path / "s"),
                          "--hollow-from", str(cal), "--workers", "1"])
    assert code == 0
    assert (seen["hollow"].cell, seen["hollow"].elements_per_edge) == (15.0, 2)


def test_table1_names_the_walls_cells(tmp_path):
    """Table 1 says which cells the walls were calibrated with: the recorded cell, else
    the paper's 30 mm; the shells per cell edge the simulator had."""
    from hollowbody.report.calibration import table1_row, write_table1

    base = {"tissue": "muscle", "speeds_kmh": [40.0], "parameters": {"E": {}, "yield": {}},
            "best_parameters": {"E": 60.0, "yield": 40.0}, "best_fitness": 0.3}
    fine = {**base, "simulator": {"fixed": {}, "options": {"cell": 15.0},
                                  "elements_per_edge": 2}}
    paper = {**base, "simulator": {"fixed": {}, "options": {}, "elements_per_edge": 4}}
    for data, words in ((fine, "15 mm cells, 2 shells per edge"),
                        (paper, "30 mm cells, 4 shells per edge")):
        write_table1([table1_row(data)], tmp_path / "t.md", tmp_path / "t.csv")
        assert words in (tmp_path / "t.md").read_text()
    assert table1_row(fine)["cell_mm"] == 15.0
