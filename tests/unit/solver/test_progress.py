"""What a run says while it runs: progress lines, the compile notice."""

from __future__ import annotations

import io
import json
import logging

import numba
import pytest

from hollowbody.build import build_model
from hollowbody.solver import explicit
from hollowbody.solver.explicit import RunOptions, run
from hollowbody.solver.progress import COMPILE_NOTICE, CompileWatch, Progress, _clock
from hollowbody.testing.decks import box_deck


@pytest.fixture
def model():
    return build_model(box_deck(size=(40.0, 40.0, 20.0), h=10.0))


def _log(out):
    return (out / "messages.log").read_text()


def test_progress_lines_when_stdout_is_not_a_terminal(model, tmp_path, capsys):
    res = run(model, RunOptions(out_dir=tmp_path, end_time=0.02, vtk=False, quiet=False,
                                progress_interval=0.0))
    assert res.status == "normal termination" and res.cycles > 2
    printed = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("progress:")]
    logged = [ln for ln in _log(tmp_path).splitlines() if "progress: t=" in ln]
    assert len(printed) == res.cycles  # interval 0: a line after every cycle
    assert len(logged) == res.cycles
    last = printed[-1]
    assert f"cycle {res.cycles}," in last and "(100%)" in last and "ETA 0s" in last
    assert "t=0.02/0.02 ms" in last and "dt=" in last


def test_quiet_prints_nothing_but_still_logs(model, tmp_path, capsys):
    res = run(model, RunOptions(out_dir=tmp_path, end_time=0.02, vtk=False, quiet=True,
                                progress_interval=0.0))
    assert "progress:" not in capsys.readouterr().out
    assert sum("progress: t=" in ln for ln in _log(tmp_path).splitlines()) == res.cycles


def test_no_progress_line_before_the_interval(model, tmp_path, capsys):
    run(model, RunOptions(out_dir=tmp_path, end_time=0.02, vtk=False, quiet=False,
                          progress_interval=1e9))
    assert "progress:" not in capsys.readouterr().out
    assert "progress: t=" not in _log(tmp_path)


def test_compile_notice_is_logged_when_kernels_compile(model, tmp_path, monkeypatch, capsys):
    original = explicit.start

    def start(model, plan, state):  # a kernel compiled during the first force pass
        @numba.njit
        def fresh(a):
            return a + 1.0
        fresh(1.0)
        original(model, plan, state)

    monkeypatch.setattr(explicit, "start", start)
    res = run(model, RunOptions(out_dir=tmp_path, end_time=0.02, vtk=False, quiet=False))
    log = _log(tmp_path)
    assert f"{COMPILE_NOTICE} ..." in log
    assert f"{COMPILE_NOTICE}: " in log
    assert COMPILE_NOTICE in capsys.readouterr().out
    assert res.summary["compile_seconds"] > 0.0
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["compile_seconds"] > 0.0


def test_no_compile_notice_when_the_kernels_are_ready(model, tmp_path):
    run(model, RunOptions(out_dir=tmp_path, end_time=0.02, vtk=False, quiet=True))
    run(model, RunOptions(out_dir=tmp_path / "again", end_time=0.02, vtk=False, quiet=True))
    assert COMPILE_NOTICE not in _log(tmp_path / "again")
    summary = json.loads((tmp_path / "again" / "summary.json").read_text())
    assert summary["compile_seconds"] == 0.0


def test_compile_watch_counts_outermost_compilations_once():
    @numba.njit
    def inner(a):
        return 2.0 * a

    @numba.njit
    def outer(a):
        return inner(a) + 1.0

    seen = []
    with CompileWatch(on_first=lambda: seen.append(1)) as watch:
        assert outer(1.0) == 3.0
    assert watch.compiled and watch.count == 1 and seen == [1]
    assert watch.seconds > 0.0
    with CompileWatch() as again:
        outer(2.0)  # compiled already
    assert not again.compiled and again.seconds == 0.0


def test_eta_from_the_rate_since_the_loop_began():
    p = Progress(10.0, quiet=True)
    assert p.eta(1.0) is None  # not begun
    p.begin(2.0)
    p._wall0 -= 4.0  # 4 s of wall time for 2 ms
    assert p.eta(4.0) == pytest.approx(12.0, rel=1e-3)  # 6 ms left at 0.5 ms/s
    assert p.eta(2.0) is None  # no progress yet
    assert _clock(12.0) == "12s" and _clock(185.0) == "3m05s" and _clock(3720.0) == "1h02m"


def test_warnings_print_through_the_bar_console(monkeypatch):
    """On a terminal, the run's stderr messages go through rich's console while the
    bar is shown, and back to stderr afterwards."""
    logger = logging.getLogger("hollowbody.test.progress")
    logger.propagate = False
    h = logging.StreamHandler(__import__("sys").__stderr__)
    logger.addHandler(h)
    try:
        with Progress(1.0, tty=True, log=None) as p:
            p._bar.console.file = io.StringIO()
            p.attach(logger)
            assert h.stream is not __import__("sys").__stderr__
            assert h.stream is __import__("sys").stderr  # rich's redirect of stderr
        assert h.stream is __import__("sys").__stderr__
    finally:
        logger.removeHandler(h)


def test_the_bar_ends_at_the_last_cycle():
    with Progress(1.0, tty=True) as p:
        p._bar.console.file = io.StringIO()
        for k in range(1, 51):  # faster than the bar's refresh interval
            p.update(0.02 * k, k, 0.02)
        task = p._bar.tasks[0]
    assert task.completed == pytest.approx(1.0) and task.fields["cycle"] == 50
