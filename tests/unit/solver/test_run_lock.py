"""One run at a time in an output folder (hollowbody.solver.run_lock).

A second run in a folder that another process holds is refused before it reads
or writes anything there (an ``--overwrite`` included); the lock file of a
process that was killed is taken over and the log says so; the lock is gone
after the run, however it ended; within one process the lock is re-entrant.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from hollowbody.api import run_model as _run_model
from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.errors import UserInputError
from hollowbody.io.keyword.writer import write_deck
from hollowbody.solver import run_lock
from hollowbody.solver.run_lock import LOCK_NAME, RunLock, check_free
from hollowbody.testing.decks import box_deck

pytestmark = pytest.mark.skipif(run_lock.fcntl is None, reason="folders are locked by flock")

HOLD = ("import sys, time\n"
        "from hollowbody.solver.run_lock import RunLock\n"
        "RunLock(sys.argv[1]).acquire()\n"
        "print('held', flush=True)\n"
        "time.sleep(120)\n")


def run_model(model, out, **kw):
    return _run_model(model, out, threads=1, **kw)


def _model():
    return build_model(box_deck(size=(20.0, 20.0, 10.0), h=10.0))


def _holder(folder):
    """Another process holding ``folder`` (until killed)."""
    p = subprocess.Popen([sys.executable, "-c", HOLD, str(folder)], stdout=subprocess.PIPE,
                         text=True)
    assert p.stdout.readline().strip() == "held"
    return p


@pytest.fixture
def holder():
    procs = []
    yield lambda folder: procs.append(_holder(folder)) or procs[-1]
    for p in procs:
        p.kill()
        p.wait()


def _files(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir()}


def test_a_held_folder_is_left_alone_even_by_overwrite(tmp_path, holder):
    out = tmp_path / "run"
    run_model(_model(), out, end_time=0.05, vtk=False)  # an earlier run's files
    p = holder(out)
    before = _files(out)
    assert json.loads(before[LOCK_NAME])["pid"] == p.pid
    with pytest.raises(UserInputError) as err:
        run_model(_model(), out, end_time=0.05, vtk=False, overwrite=True)
    msg = str(err.value)
    assert str(out) in msg and f"process {p.pid}" in msg
    assert "in use by another hollowbody run" in msg
    assert _files(out) == before  # nothing deleted, nothing written
    with pytest.raises(UserInputError, match="in use"):  # a restart is refused alike
        run_model(_model(), out, end_time=0.1, vtk=False, restart="newest")
    assert _files(out) == before


def test_the_lock_of_a_killed_run_is_taken_over_and_the_lock_goes_after_a_run(tmp_path):
    out = tmp_path / "run"
    res = run_model(_model(), out, end_time=0.05, vtk=False)
    assert res.status == "normal termination"
    assert not (out / LOCK_NAME).exists()
    p = _holder(out)
    p.kill()  # SIGKILL: no clean-up, the file stays
    p.wait()
    assert (out / LOCK_NAME).exists()
    check_free(out)
    res = run_model(_model(), out, end_time=0.05, vtk=False, overwrite=True)
    assert res.status == "normal termination"
    assert not (out / LOCK_NAME).exists()
    assert f"a run lock left by process {p.pid}" in (out / "messages.log").read_text()


def test_a_run_that_ends_in_an_error_gives_the_folder_back(tmp_path):
    model = _model()
    model.controls.dtmin = 10.0  # DTMIN far above the step: error termination at once
    model.controls.erode = 0
    res = run_model(model, tmp_path / "run", end_time=0.05, vtk=False)
    assert res.status != "normal termination"
    assert not (tmp_path / "run" / LOCK_NAME).exists()


def test_reentrant_in_one_process_and_a_file_is_not_a_folder(tmp_path, holder):
    a = tmp_path / "a"
    with RunLock(a) as outer:
        with RunLock(a) as inner:  # a run inside a validation's hold
            assert inner.stale is None
        assert (a / LOCK_NAME).is_file()  # the outer hold keeps it
        check_free(a)  # this process's own lock does not block it
        run_model(_model(), a, end_time=0.05, vtk=False)  # the run inside the hold
        assert outer.stale is None and (a / LOCK_NAME).is_file()
    assert not (a / LOCK_NAME).exists()
    (tmp_path / "f").write_text("x")
    with pytest.raises(UserInputError, match="is a file, not an output folder"):
        RunLock(tmp_path / "f").acquire()
    p = holder(tmp_path / "b")
    with pytest.raises(UserInputError, match=f"process {p.pid}"):
        RunLock(tmp_path / "b").acquire()


def test_the_command_line_refuses_with_exit_code_2(tmp_path, holder, capsys):
    deck = tmp_path / "box.k"
    write_deck(box_deck(size=(20.0, 20.0, 10.0), h=10.0), deck)
    out = tmp_path / "out"
    holder(out)
    code = cli_main(["run", str(deck), "--out", str(out), "--end-time", "0.05", "--quiet",
                     "--no-vtk", "--threads", "1"])
    err = capsys.readouterr().err
    assert code == 2
    assert "in use by another hollowbody run" in err and "Traceback" not in err
    assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]


def test_study_overwrite_leaves_a_held_run_folder_alone(tmp_path, holder):
    from hollowbody.solver.outputs import prepare_runs_dir

    run = tmp_path / "hollow" / "40kmh"
    run.mkdir(parents=True)
    (run / "summary.json").write_text("old")
    (tmp_path / "study.json").write_text("old")
    holder(run)
    with pytest.raises(UserInputError, match="in use"):
        prepare_runs_dir(tmp_path, True, ("study.json",), ("hollow/*",))
    assert (run / "summary.json").read_text() == "old"
    assert (tmp_path / "study.json").read_text() == "old"
