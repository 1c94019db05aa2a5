"""The block test and the calibration on an external engine (``--engine``).

Neither OpenRadioss nor LS-DYNA is installed here, so what is checked is what
does not need one: the deck handed to the engine is the block test's own, the
plan printed by ``--dry-run``, the errors (engine missing, options without an
engine) and the folders and files that
``block_impact`` writes around an engine's run. The real runs are in
``test_real_engines.py`` (skipped with the reason when no engine is found).
"""

from __future__ import annotations

import json
import pickle
from pathlib import Path

import pytest

from hollowbody.calibrate.simulate import BlockSimulator
from hollowbody.cli.main import main
from hollowbody.engines.runner import ExternalEngine
from hollowbody.scenarios.block import BlockConfig, block_impact, build_block_deck


@pytest.fixture
def no_engines(monkeypatch):
    for var in ("OPENRADIOSS_PATH", "LSDYNA"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("PATH", "/nonexistent")


def test_block_dry_run_on_lsdyna_writes_the_block_deck_and_prints_the_mpp_plan(
        tmp_path, capsys, no_engines):
    out = tmp_path / "b"
    assert main(["block", "--engine", "lsdyna", "--np", "2", "--threads", "3", "--dry-run",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "engine: lsdyna" in text and "mpirun -np 2" in text and "i=deck.k" in text
    assert "OMP_NUM_THREADS=3" in text and "not found here" in text
    assert f"work folder: {out / 'lsdyna'}" in text
    # the deck is the block test's, byte for byte what the embedded run reads
    from hollowbody.io.keyword import write_deck

    write_deck(build_block_deck(BlockConfig()), tmp_path / "ref.k")
    assert (out / "deck.k").read_text() == (tmp_path / "ref.k").read_text()
    assert not (out / "lsdyna").exists()  # a dry run writes no engine folder


def test_block_compare_dry_run_writes_both_decks(tmp_path, capsys, no_engines):
    out = tmp_path / "c"
    assert main(["block", "--compare", "--engine", "lsdyna", "--dry-run", "--out",
                 str(out)]) == 0
    assert capsys.readouterr().out.count("engine: lsdyna") == 2
    assert (out / "solid" / "deck.k").is_file() and (out / "hollow" / "deck.k").is_file()
    assert "*SECTION_SHELL" in (out / "hollow" / "deck.k").read_text()


def test_block_on_a_missing_engine_is_exit_2_in_one_line(tmp_path, capsys, no_engines):
    assert main(["block", "--engine", "lsdyna", "--out", str(tmp_path / "m")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("hollowbody block: error: LS-DYNA not found")


def test_block_on_openradioss_writes_its_contacts_natively(tmp_path, capsys, no_engines):
    out = tmp_path / "r"
    assert main(["block", "--engine", "openradioss", "--dry-run", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "-i deck_0000.rad" in text and "TYPE25" in text
    assert (out / "deck.k").is_file() and not (out / "openradioss").exists()


@pytest.mark.parametrize("args, message", [
    (["--np", "2"], "--np is an option of an external engine"),
    (["--engine-path", "/opt/x"], "--engine-path is an option of an external engine"),
    (["--engine", "lsdyna", "--np", "0", "--dry-run"], "--np must be at least 1"),
])
def test_block_engine_options_are_checked(args, message, tmp_path, capsys):
    assert main(["block", *args, "--out", str(tmp_path / "o")]) == 2
    assert message in capsys.readouterr().err


def test_calibrate_looks_for_the_engine_before_running_anything(tmp_path, capsys, no_engines):
    out = tmp_path / "cal"
    assert main(["calibrate", "--tissue", "muscle", "--engine", "openradioss", "--out",
                 str(out)]) == 2
    assert "OpenRadioss not found" in capsys.readouterr().err
    assert not out.exists()


def test_simulator_with_an_engine_describes_it_and_ships_to_workers():
    plain = BlockSimulator.make("muscle")
    assert "engine" not in plain.describe()  # earlier caches stay valid
    eng = ExternalEngine("lsdyna", np=4, threads=2)
    sim = BlockSimulator.make("muscle", engine=eng)
    assert sim.describe()["engine"] == {"name": "lsdyna", "np": 4, "threads": 2, "path": None}
    assert pickle.loads(pickle.dumps(sim)) == sim  # dask ships simulators by pickling
    with pytest.raises(Exception, match="unknown engine"):
        ExternalEngine("abaqus")


def test_block_impact_writes_its_files_around_an_engine_run(tmp_path, monkeypatch):
    """The folders and files of an engine run. The engine's place is taken by
    hollowbody's own run of the deck written into ``<out>/<engine>`` (this checks
    the plumbing, not any engine)."""
    from hollowbody.api import run_deck

    def run_here(self, deck, out, end_time=None, quiet=True):  # noqa: ANN001
        run_deck(deck, out, end_time=end_time, quiet=True, vtk=False, overwrite=True)
        return json.loads((Path(out) / "summary.json").read_text())

    monkeypatch.setattr(ExternalEngine, "run", run_here)
    cfg = BlockConfig(end_time=0.3)
    res = block_impact(cfg, tmp_path, vtk=False, engine=ExternalEngine("lsdyna"))
    assert (tmp_path / "deck.k").is_file() and (tmp_path / "lsdyna" / "glstat.csv").is_file()
    for name in ("force_displacement.csv", "force_displacement.png", "summary.json"):
        assert (tmp_path / name).is_file(), name
    top = json.loads((tmp_path / "summary.json").read_text())
    inner = json.loads((tmp_path / "lsdyna" / "summary.json").read_text())
    assert top == inner and top["impact_outcome"] == "stopped"
    assert res.curve.time.size > 0 and res.curve.time[-1] == pytest.approx(0.3, abs=0.01)
