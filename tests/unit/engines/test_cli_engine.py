"""``hollowbody run --engine ... [--dry-run]`` from the command line.

Neither OpenRadioss nor LS-DYNA is run here: --dry-run prints the plan, and
without it an engine that is not installed is a one-line error with exit code
2 (the PATH and the engine variables are emptied for these tests so that an
installed engine does not change their outcome).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from hollowbody.cli.main import main

EXAMPLE = Path(__file__).parents[3] / "examples" / "loads" / "block_drop.k"


@pytest.fixture
def no_engines(monkeypatch):
    for var in ("OPENRADIOSS_PATH", "LSDYNA"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("PATH", "/nonexistent")


@pytest.mark.parametrize("engine", ["openradioss", "lsdyna"])
def test_missing_engine_is_exit_2_without_traceback_and_nothing_written(
        engine, tmp_path, capsys, no_engines):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--engine", engine, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("hollowbody run: error: ")
    assert ("OpenRadioss not found" if engine == "openradioss" else "LS-DYNA not found") in err[0]
    assert "Traceback" not in err[0]
    assert not out.exists()


def test_dry_run_openradioss_prints_the_plan_and_writes_nothing(tmp_path, capsys, no_engines):
    out = tmp_path / "out"
    code = main(["run", str(EXAMPLE), "--engine", "openradioss", "--np", "4", "--threads", "2",
                 "--out", str(out), "--dry-run"])
    assert code == 0
    text = capsys.readouterr().out
    assert "starter_" in text and "-i block_drop_0000.rad -np 4" in text
    assert "mpirun -np 4" in text and "engine_" in text and "_ompi" in text
    assert "-i block_drop_0001.rad" in text and "env OMP_NUM_THREADS=2" in text
    assert f"cd {out}" in text and "not found here" in text
    assert "/RUN/block_drop/1" in text and "/ANIM/DT" in text
    assert not out.exists()


def test_dry_run_lsdyna_smp_and_mpp(tmp_path, capsys, no_engines):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--engine", "lsdyna", "--threads", "4", "--out",
                 str(out), "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert "i=block_drop.k ncpu=4 memory=" in text and "memory from the model size" in text
    assert main(["run", str(EXAMPLE), "--engine", "lsdyna", "--np", "8", "--memory", "300m,40m",
                 "--out", str(out), "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert "mpirun -np 8" in text and "i=block_drop.k memory=300m memory2=40m" in text
    assert not out.exists()


def test_dry_run_of_the_embedded_engine(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--out", str(out), "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("engine: hollowbody") and str(EXAMPLE) in text
    assert not out.exists()


@pytest.mark.parametrize("args, message", [
    (["--np", "0"], "--np must be at least 1"),
    (["--threads", "0"], "threads must be a positive integer"),
    (["--memory", "lots"], "--memory"),
    (["--restart"], "--restart is an option of hollowbody's own engine"),
    (["--erode"], "--erode is an option of hollowbody's own engine"),
])
def test_bad_engine_options_are_exit_2(args, message, tmp_path, capsys, no_engines):
    code = main(["run", str(EXAMPLE), "--engine", "lsdyna", "--out", str(tmp_path / "o"),
                 "--dry-run", *args])
    assert code == 2
    assert message in capsys.readouterr().err


def test_end_time_reaches_both_engines(tmp_path, capsys, no_engines):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE), "--engine", "openradioss", "--end-time", "2.5",
                 "--out", str(out), "--dry-run"]) == 0
    text = capsys.readouterr().out.splitlines()
    i = text.index("  /RUN/block_drop/1")
    assert float(text[i + 1]) == 2.5
    assert main(["run", str(EXAMPLE), "--engine", "lsdyna", "--end-time", "2.5",
                 "--out", str(out), "--dry-run"]) == 0
    assert "ENDTIM set to 2.5 ms" in capsys.readouterr().out


def test_the_decks_the_engines_read_are_written_into_the_run_folder(tmp_path, no_engines):
    from hollowbody.engines.runner import plan_run
    from hollowbody.io.keyword import ControlTermination, read_deck

    out = tmp_path / "ls"
    prep = plan_run("lsdyna", EXAMPLE, out, end_time=3.0, dry_run=True, write=True)
    deck = read_deck(out / "block_drop.k")
    assert [c.endtim for c in deck.of_type(ControlTermination)] == [3.0]
    assert prep.end_time_ms == 3.0 and prep.found is False
    out = tmp_path / "or"
    prep = plan_run("openradioss", EXAMPLE, out, dry_run=True, write=True)
    assert (out / "block_drop.k").is_file() and prep.engine_file[0] == "block_drop_0001.rad"
    assert prep.plan.deck == out / "block_drop_0000.rad"
    assert "/INCLUDE_LS-DYNA\nblock_drop.k\n" in prep.plan.deck.read_text()
    with pytest.raises(Exception, match="overwritten"):
        plan_run("lsdyna", out / "block_drop.k", out, dry_run=True)
