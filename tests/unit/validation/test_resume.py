"""``hollowbody validate --resume``: a stopped validation continues where it stopped.

What a resumed validation does with each run folder (keep, resume, start) is
checked on folders made by hand; the whole path on the coarsest pedestrian:
a run stopped by Ctrl-C stops the validation (exit 130, the stopped run in the
report, a restart file in its folder); ``--resume`` continues it to its end
(the histories continue without a repeated or missing row), then extends it to
a later ``--end-time`` from the restart file written at its end, then keeps it.
"""

from __future__ import annotations

import json
import signal

import numpy as np
import pytest

from hollowbody import __version__
from hollowbody.cli.main import main
from hollowbody.solver import explicit
from hollowbody.solver import restart as rs
from hollowbody.validation.resume import KEEP, RESUME, START, resume_action, update_end_time


def _folder(tmp_path, summary=None, dump=None, end=40.0):
    f = tmp_path / "thorax" / "4.4ms" / "hollow"
    f.mkdir(parents=True)
    (f / "deck.k").write_text("*KEYWORD\n*END\n")
    setup = {"case": "thorax", "speed": 4.4, "tissue": "hollow", "end_time": end,
             "impactor_pid": 1, "impactor_mass": 23.4, "contact_id": 1,
             "direction": [0, -1, 0], "impact_point": [0, 0, 0]}
    (f / "setup.json").write_text(json.dumps(setup))
    if summary is not None:
        (f / "summary.json").write_text(json.dumps(summary))
    if dump is not None:
        head = {"format": rs.FORMAT, "version": __version__, "time_ms": dump, "cycle": 7}
        head.update({} if dump >= 0 else {"version": "0.0.1", "time_ms": -dump})
        (f / "d3dump01").write_bytes(rs.MAGIC + json.dumps(head).encode() + b"\n")
    return f


@pytest.mark.parametrize("summary, dump, asked, action, words", [
    (None, None, None, START, "run from the start"),
    ({"status": "error termination", "end_time_ms": 12.5}, 12.0, None, KEEP, "error"),
    ({"status": "normal termination", "end_time_ms": 40.0}, 40.0, None, KEEP, "kept"),
    ({"status": "normal termination", "end_time_ms": 40.0}, 40.0, 60.0, RESUME,
     "resumed from d3dump01 (t=40 ms) to 60 ms"),
    ({"status": "normal termination", "end_time_ms": 40.0}, None, 60.0, START,
     "without a restart file"),
    ({"status": "user interrupt", "end_time_ms": 17.3}, 17.3, None, RESUME, "stopped"),
    (None, 9.0, None, RESUME, "resumed from d3dump01 (t=9 ms) to 40 ms"),  # killed
    ({"status": "user interrupt", "end_time_ms": 17.3}, None, None, START, "from the start"),
    ({"status": "user interrupt", "end_time_ms": 35.0}, 35.0, 30.0, KEEP,
     "at or past the end time asked for (30 ms)"),
    ({"status": "user interrupt", "end_time_ms": 17.3}, -17.3, None, START,
     "written by hollowbody 0.0.1"),
])
def test_what_a_resumed_validation_does_with_a_run(tmp_path, summary, dump, asked, action,
                                                  words):
    f = _folder(tmp_path, summary, dump)
    got, why = resume_action(f, asked)
    assert got == action and words in why, why


def test_no_setup_is_started_and_end_time_is_updated(tmp_path):
    assert resume_action(tmp_path / "nothing")[0] == START
    f = _folder(tmp_path)
    assert update_end_time(f, 55.0).end_time == 55.0
    assert json.loads((f / "setup.json").read_text())["end_time"] == 55.0
    assert update_end_time(f, None).end_time == 55.0


@pytest.mark.parametrize("extra, message", [
    (["--overwrite"], "does not go with --overwrite"),
    (["--dry-run"], "does not go with --dry-run"),
    (["--engine", "lsdyna"], "needs hollowbody's own engine"),
    (["--dump-minutes", "-1"], "--dump-minutes must be >= 0"),
])
def test_resume_refusals(tmp_path, capsys, extra, message):
    assert main(["validate", "thorax", "--resume", "--out", str(tmp_path), *extra]) == 2
    assert message in capsys.readouterr().err


def test_resume_needs_the_folder(tmp_path, capsys):
    assert main(["validate", "thorax", "--resume", "--out", str(tmp_path / "none")]) == 2
    assert "no such folder to resume" in capsys.readouterr().err


def _rows(folder, name="rcforc.csv"):
    return np.loadtxt(folder / name, delimiter=",", skiprows=1, ndmin=2)


def test_stop_resume_extend_keep(tmp_path, capsys, monkeypatch):
    """Coarsest pedestrian, thorax 4.4 m/s, solid: stopped at cycle 400 of 1,293."""
    out = tmp_path / "val"

    def command(end: str) -> list[str]:
        return ["validate", "thorax", "--speed", "4.4", "--tissue", "solid", "--mesh", "50",
                "--end-time", end, "--threads", "1", "--out", str(out)]

    argv = command("2.5")
    original = explicit.step

    def step(model, plan, state, dt):
        original(model, plan, state, dt)
        if state.cycle == 400:
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(explicit, "step", step)
    assert main(argv) == 130
    printed = capsys.readouterr().out
    assert "--resume" in printed and "thorax 4.4 m/s solid: user interrupt" in printed
    run = out / "thorax" / "4.4ms" / "solid"
    first = json.loads((run / "summary.json").read_text())
    assert first["status"] == "user interrupt" and first["cycles"] == 400
    assert [p.name for p in rs.dump_files(run)] == ["d3dump01"]
    assert json.loads((out / "report.json").read_text())[0]["status"] == "user interrupt"
    monkeypatch.undo()
    assert json.loads((run / "setup.json").read_text())["mesh"] == 50.0

    # another mesh than the runs in the folder: refused, nothing touched
    capsys.readouterr()
    other = [*argv, "--resume"]
    other[other.index("--mesh") + 1] = "40"
    assert main(other) == 2
    assert "--mesh 40 differs from the run in" in capsys.readouterr().err
    assert json.loads((run / "summary.json").read_text()) == first

    # resumed: ends normally at 2.5 ms; one restart file kept (the one of its end)
    code = main([*argv, "--resume"])
    s = json.loads((run / "summary.json").read_text())
    assert s["status"] == "normal termination" and s["end_time_ms"] == pytest.approx(2.5)
    assert s["resumed_from"]["cycle"] == 400
    assert code == (0 if s["quality"] == "ok" else 1)
    assert [p.name for p in rs.dump_files(run)] == ["d3dump02"]
    t = _rows(run)[:, 0]
    assert np.all(np.diff(t) > 0.0) and t[-1] == pytest.approx(2.5)
    assert "resumed 1x" in (out / "report.md").read_text()

    # extended from the restart file of its end
    capsys.readouterr()
    main([*command("3"), "--resume"])
    assert "ended normally at t=2.5 ms: resumed from d3dump02" in capsys.readouterr().out
    s = json.loads((run / "summary.json").read_text())
    assert s["end_time_ms"] == pytest.approx(3.0) and len(s["resumed"]) == 2
    assert json.loads((run / "setup.json").read_text())["end_time"] == 3.0
    t2 = _rows(run)[:, 0]
    assert np.all(np.diff(t2) > 0.0) and np.array_equal(t2[:t.size], t)

    # nothing left to do: kept, rated and reported again
    assert [f["file"] for f in s["restart_files"]] == ["d3dump03"]
    assert [p.name for p in rs.dump_files(run)] == ["d3dump03"]
    main([*command("3"), "--resume"])
    assert "ended normally at t=3 ms: kept" in capsys.readouterr().out
    assert json.loads((run / "summary.json").read_text()) == s


def test_a_run_still_going_on_in_its_folder_is_left_alone(tmp_path, capsys):
    """A second ``validate`` on a folder that another process holds (a run still
    going on there): refused with exit 2 before anything of that run is touched."""
    import subprocess
    import sys

    from hollowbody.solver import run_lock

    if run_lock.fcntl is None:
        pytest.skip("folders are locked by flock")
    f = _folder(tmp_path, summary={"status": "user interrupt", "end_time_ms": 17.3}, dump=17.3)
    hold = ("import sys, time\nfrom hollowbody.solver.run_lock import RunLock\n"
            "RunLock(sys.argv[1]).acquire()\nprint('held', flush=True)\ntime.sleep(120)\n")
    live = subprocess.Popen([sys.executable, "-c", hold, str(f)], stdout=subprocess.PIPE,
                            text=True)
    try:
        assert live.stdout.readline().strip() == "held"
        before = {p.name: p.read_bytes() for p in f.iterdir()}
        for extra in (["--resume"], ["--overwrite"]):
            code = main(["validate", "thorax", "--speed", "4.4", "--tissue", "hollow",
                         "--out", str(tmp_path), *extra])
            assert code == 2
            assert "in use by another hollowbody run" in capsys.readouterr().err
            assert {p.name: p.read_bytes() for p in f.iterdir()} == before
    finally:
        live.kill()
        live.wait()
