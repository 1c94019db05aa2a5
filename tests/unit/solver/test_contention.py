"""The contention guard (hollowbody.solver.contention): a threaded run whose threads
keep waiting for cores goes on with one thread, and says so."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time

import pytest

from hollowbody.solver import contention as ct
from hollowbody.solver import threads as th


class Clock:
    def __init__(self) -> None:
        self.t = 0.0
        self.delay = 0.0

    def wall(self) -> float:
        return self.t

    def waited(self) -> float:
        return self.delay

    def advance(self, seconds: float, waiting_share: float, threads: int = 2) -> None:
        self.t += seconds
        self.delay += seconds * waiting_share * threads


def guard(clock: Clock, threads: int = 2) -> tuple[ct.ContentionGuard, list]:
    calls: list[int] = []
    g = ct.ContentionGuard(threads, set_threads=calls.append, delay=clock.waited,
                           clock=clock.wall)
    return g, calls


def test_an_idle_machine_keeps_the_threads():
    c = Clock()
    g, calls = guard(c)
    for _ in range(20):
        c.advance(0.3, 0.02)
        assert g.check() is None
    assert calls == [] and g.active and g.current == 2
    assert g.shares and all(s == pytest.approx(0.02) for s in g.shares)


def test_a_busy_machine_drops_to_one_thread_after_windows_in_a_row():
    c = Clock()
    g, calls = guard(c)
    c.advance(ct.WINDOW_SECONDS, 0.4)
    assert g.check() is None  # one contended window is not enough
    c.advance(ct.WINDOW_SECONDS, 0.02)
    assert g.check() is None  # a quiet one resets the count
    got = None
    for _ in range(ct.WINDOWS):
        c.advance(ct.WINDOW_SECONDS, 0.4)
        got = g.check()
    assert got == (1, pytest.approx(0.4)) and calls == [1] and g.current == 1
    c.advance(0.5 * ct.RETRY_SECONDS, 0.0, threads=1)
    assert g.check() is None and calls == [1]  # no try before RETRY_SECONDS


def busy_then_try(c: Clock, g: ct.ContentionGuard) -> None:
    for _ in range(ct.WINDOWS):
        c.advance(ct.WINDOW_SECONDS, 0.4)
        g.check()
    assert g.current == 1


def test_the_threads_come_back_when_the_cores_are_free_again():
    c = Clock()
    g, calls = guard(c)
    busy_then_try(c, g)
    c.advance(ct.RETRY_SECONDS, 0.0, threads=1)
    assert g.check() is None and calls == [1, 2] and g.current == 2  # the try starts
    c.advance(ct.WINDOW_SECONDS, 0.02)
    assert g.check() == (2, pytest.approx(0.02))  # kept: said once
    assert g.current == 2 and calls == [1, 2]
    c.advance(10 * ct.WINDOW_SECONDS, 0.02)
    assert g.check() is None and calls == [1, 2]


def test_a_failed_try_goes_back_to_one_thread_and_waits_twice_as_long():
    c = Clock()
    g, calls = guard(c)
    busy_then_try(c, g)
    wait = ct.RETRY_SECONDS
    for k in range(6):
        c.advance(0.9 * wait, 0.0, threads=1)
        assert g.check() is None and g.current == 1  # not yet
        c.advance(0.1 * wait, 0.0, threads=1)
        assert g.check() is None and g.current == 2  # a try
        c.advance(ct.WINDOW_SECONDS, 0.4)
        assert g.check() is None and g.current == 1  # still busy: silently back
        assert g.failed_tries == k + 1
        wait = min(2.0 * wait, ct.RETRY_MAX_SECONDS)
    assert wait == ct.RETRY_MAX_SECONDS  # the waits grew to the cap
    assert calls == [1] + [2, 1] * 6


def test_share_is_per_thread_and_per_wall_second():
    c = Clock()
    g, _ = guard(c, threads=4)
    c.advance(2.0, 0.1, threads=4)
    g.check()
    assert g.shares[-1] == pytest.approx(0.1)


def test_no_guard_for_one_thread_or_without_the_kernel_report():
    c = Clock()
    g, calls = guard(c, threads=1)
    c.advance(5.0, 0.9, threads=1)
    assert not g.active and g.check() is None and calls == []
    g = ct.ContentionGuard(2, set_threads=calls.append, delay=lambda: math.nan,
                           clock=c.wall)
    assert not g.active and g.check() is None


@pytest.mark.skipif(not ct.available(), reason="the kernel does not report run delays")
def test_run_delay_counts_time_waiting_for_a_core():
    """Real measurement: with every core of the process busy with another process,
    a thread of ours that computes for 0.5 s waits for a core part of the time: about
    1 / (cores + 1) of it under a fair scheduler (a third on two cores); at least
    0.03 s is asked (the scheduler may favour the waker; a busier machine only adds)."""
    cores = len(os.sched_getaffinity(0))
    busy = [subprocess.Popen([sys.executable, "-c", "import time\nt=time.time()\n"
                              "while time.time() - t < 1.5: pass"]) for _ in range(cores)]
    try:
        time.sleep(0.3)  # the children are running
        d0 = ct.run_delay()
        stop = time.perf_counter() + 0.5
        while time.perf_counter() < stop:
            pass
        waited = ct.run_delay() - d0
    finally:
        for p in busy:
            p.kill()
            p.wait()
    assert waited >= 0.03


def test_a_dropped_run_says_so_in_the_summary(tmp_path, monkeypatch):
    from hollowbody.build import build_model
    from hollowbody.solver.explicit import RunOptions, run
    from hollowbody.testing.decks import box_deck

    c = Clock()

    class Busy(ct.ContentionGuard):
        def __init__(self, threads: int) -> None:
            super().__init__(threads, set_threads=lambda n: None, delay=c.waited,
                             clock=self._tick)

        def _tick(self) -> float:  # every cycle a contended window
            c.advance(ct.WINDOW_SECONDS, 0.5)
            return c.wall()

    import hollowbody.solver.explicit as ex

    monkeypatch.setattr(ex, "ContentionGuard", Busy)
    monkeypatch.setattr(th, "wait_policy", lambda: "short")
    model = build_model(box_deck(size=(40.0, 40.0, 20.0), h=10.0))
    res = run(model, RunOptions(out_dir=tmp_path / "run", end_time=0.05, threads=2,
                                quiet=True, vtk=False))
    s = json.loads((tmp_path / "run" / "summary.json").read_text())
    (d,) = s["thread_changes"]  # dropped; no try within the run's wall time
    assert d["threads"] == 1 and d["waiting_share"] == pytest.approx(0.5)
    assert 0.0 < d["time_ms"] <= 0.05 and d["cycle"] >= ct.WINDOWS
    log = (tmp_path / "run" / "messages.log").read_text()
    assert "threads: 2 -> 1" in log and "waited 50 %" in log
    assert res.status == "normal termination"
