"""The folder check of the commands that make several runs (``study``, ``bending``):
hollowbody.solver.outputs.prepare_runs_dir."""

from __future__ import annotations

from pathlib import Path

import pytest

from hollowbody.errors import UserInputError
from hollowbody.solver.outputs import prepare_runs_dir

FILES = ("study.json", "study.csv", "fd_*.png")
RUNS = ("solid/*", "hollow/*")


def _run_folder(folder: Path) -> Path:
    folder.mkdir(parents=True)
    for name in ("summary.json", "messages.log", "glstat.csv", "force_displacement.csv",
                 "deck.k", "console.log"):
        (folder / name).write_text("old")
    return folder


def test_a_missing_or_empty_folder_is_accepted(tmp_path):
    prepare_runs_dir(tmp_path / "new", False, FILES, RUNS)
    assert not (tmp_path / "new").exists()  # the command creates it
    prepare_runs_dir(tmp_path, False, FILES, RUNS)


def test_a_file_is_not_an_output_folder(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(UserInputError, match="is a file, not an output folder"):
        prepare_runs_dir(tmp_path / "f", True, FILES, RUNS)


@pytest.mark.parametrize("earlier", ["study.json", "fd_40kmh.png", "run folder"])
def test_an_earlier_run_is_refused_and_nothing_is_touched(tmp_path, earlier):
    if earlier == "run folder":
        _run_folder(tmp_path / "hollow" / "70kmh")
        shown = "hollow/70kmh/"
    else:
        (tmp_path / earlier).write_text("old")
        shown = earlier
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    with pytest.raises(UserInputError) as err:
        prepare_runs_dir(tmp_path, False, FILES, RUNS, ("deck.k",))
    msg = str(err.value)
    assert msg.startswith(f"{tmp_path} holds the outputs of an earlier run (")
    assert shown in msg and "--overwrite" in msg
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before


def test_a_folder_of_other_files_is_not_an_earlier_run(tmp_path):
    (tmp_path / "notes.txt").write_text("mine")
    (tmp_path / "solid" / "40kmh").mkdir(parents=True)
    (tmp_path / "solid" / "40kmh" / "mine.csv").write_text("mine")  # no run's summary/log
    prepare_runs_dir(tmp_path, False, FILES, RUNS)
    assert (tmp_path / "solid" / "40kmh" / "mine.csv").read_text() == "mine"


def test_overwrite_clears_the_earlier_outputs_and_keeps_everything_else(tmp_path):
    run = _run_folder(tmp_path / "solid" / "40kmh")
    (run / "my_notes.txt").write_text("mine")
    (tmp_path / "study.json").write_text("old")
    (tmp_path / "fd_all.png").write_bytes(b"old")
    (tmp_path / "calibration.json").write_text("{}")  # an input inside the folder
    prepare_runs_dir(tmp_path, True, FILES, RUNS, ("deck.k", "console.log"),
                     inputs=(tmp_path / "calibration.json",))
    assert sorted(p.name for p in run.iterdir()) == ["my_notes.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["calibration.json", "solid"]
    prepare_runs_dir(tmp_path, False, FILES, RUNS)  # nothing left of the earlier run


def test_an_input_with_the_name_of_an_output_is_refused_never_deleted(tmp_path):
    (tmp_path / "study.json").write_text("{}")
    with pytest.raises(UserInputError, match="the input file study.json has the name of an "
                                             "output"):
        prepare_runs_dir(tmp_path, True, FILES, RUNS, inputs=(tmp_path / "study.json",))
    assert (tmp_path / "study.json").read_text() == "{}"
    run = _run_folder(tmp_path / "solid" / "40kmh")
    (run / "summary.json").unlink()
    with pytest.raises(UserInputError, match="has the name of an output"):
        prepare_runs_dir(tmp_path, True, (), RUNS, ("deck.k",), inputs=(run / "deck.k",))
    assert (run / "deck.k").read_text() == "old"
