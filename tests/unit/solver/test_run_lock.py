"""One run at a time in an output folder (hollowbody.solver.run_lock).

A second run in a folder where a run is still going on is refused before it
reads or writes anything there (an ``--overwrite`` included); a lock left by a
process that no longer exists is taken over and the log says so; the lock is
gone after the run, however it ended.
"""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys

import pytest

from hollowbody.api import run_model as _run_model
from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.errors import UserInputError
from hollowbody.io.keyword.writer import write_deck
from hollowbody.solver.run_lock import LOCK_NAME, RunLock, _start_ticks, check_free
from hollowbody.testing.decks import box_deck


def run_model(model, out, **kw):
    return _run_model(model, out, threads=1, **kw)


def _model():
    return build_model(box_deck(size=(20.0, 20.0, 10.0), h=10.0))


@pytest.fixture
def other_process():
    """A live process of this machine that is not this one."""
    p = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
    yield p
    p.kill()
    p.wait()


def _lock(folder, pid, host=None, ticks="auto"):
    folder.mkdir(parents=True, exist_ok=True)
    info = {"pid": pid, "host": host or socket.gethostname(), "started": "2026-12-03 10:00:00"}
    info["ticks"] = _start_ticks(pid) if ticks == "auto" else ticks
    (folder / LOCK_NAME).write_text(json.dumps(info))


def _files(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir()}


@pytest.mark.skipif(os.name == "nt", reason="process checks by signal 0")
def test_a_live_run_keeps_its_folder_even_from_overwrite(tmp_path, other_process):
    out = tmp_path / "run"
    run_model(_model(), out, end_time=0.05, vtk=False)  # an earlier run's files
    _lock(out, other_process.pid)
    before = _files(out)
    with pytest.raises(UserInputError) as err:
        run_model(_model(), out, end_time=0.05, vtk=False, overwrite=True)
    msg = str(err.value)
    assert str(out) in msg and f"process {other_process.pid}" in msg
    assert "in use by another hollowbody run" in msg
    assert _files(out) == before  # nothing deleted, nothing written
    with pytest.raises(UserInputError, match="in use"):  # a restart is refused alike
        run_model(_model(), out, end_time=0.1, vtk=False, restart="newest")


def test_the_lock_is_gone_after_a_run_and_an_earlier_lock_of_a_dead_process_is_taken(
        tmp_path):
    out = tmp_path / "run"
    res = run_model(_model(), out, end_time=0.05, vtk=False)
    assert res.status == "normal termination"
    assert not (out / LOCK_NAME).exists()
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    _lock(out, dead.pid, ticks=None)
    res = run_model(_model(), out, end_time=0.05, vtk=False, overwrite=True)
    assert res.status == "normal termination"
    assert not (out / LOCK_NAME).exists()
    log = (out / "messages.log").read_text()
    assert f"a stale run lock (process {dead.pid}" in log


@pytest.mark.skipif(not os.path.exists("/proc/self/stat"), reason="Linux process start times")
def test_a_reused_process_id_is_not_the_run_that_locked(tmp_path, other_process):
    """The pid lives, but a process started at another time: the lock is stale."""
    out = tmp_path / "run"
    _lock(out, other_process.pid, ticks=(_start_ticks(other_process.pid) or 0) + 12345)
    check_free(out)
    assert run_model(_model(), out, end_time=0.05, vtk=False).status == "normal termination"


def test_a_lock_of_another_machine_is_refused_and_says_which_file_to_delete(tmp_path):
    out = tmp_path / "run"
    _lock(out, 4242, host="another-machine.invalid", ticks=None)
    with pytest.raises(UserInputError) as err:
        run_model(_model(), out, end_time=0.05, vtk=False)
    msg = str(err.value)
    assert "another-machine.invalid" in msg and str(out / LOCK_NAME) in msg


def test_a_run_that_ends_in_an_error_gives_the_folder_back(tmp_path):
    deck = box_deck(size=(20.0, 20.0, 10.0), h=10.0)
    model = build_model(deck)
    model.controls.dtmin = 10.0  # DTMIN far above the step: error termination at once
    model.controls.erode = False
    res = run_model(model, tmp_path / "run", end_time=0.05, vtk=False)
    assert res.status != "normal termination"
    assert not (tmp_path / "run" / LOCK_NAME).exists()


def test_the_holder_takes_it_again_and_a_file_is_not_a_folder(tmp_path):
    with RunLock(tmp_path / "a") as lock:
        assert (tmp_path / "a" / LOCK_NAME).is_file()
        check_free(tmp_path / "a")  # this process's own lock does not block it
        assert lock.stale is None
    assert not (tmp_path / "a" / LOCK_NAME).exists()
    (tmp_path / "f").write_text("x")
    with pytest.raises(UserInputError, match="is a file, not an output folder"):
        RunLock(tmp_path / "f").acquire()


@pytest.mark.skipif(os.name == "nt", reason="process checks by signal 0")
def test_the_command_line_refuses_with_exit_code_2(tmp_path, other_process, capsys):
    deck = tmp_path / "box.k"
    write_deck(box_deck(size=(20.0, 20.0, 10.0), h=10.0), deck)
    out = tmp_path / "out"
    _lock(out, other_process.pid)
    code = cli_main(["run", str(deck), "--out", str(out), "--end-time", "0.05", "--quiet",
                     "--no-vtk", "--threads", "1"])
    err = capsys.readouterr().err
    assert code == 2
    assert "in use by another hollowbody run" in err and "Traceback" not in err
    assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]
