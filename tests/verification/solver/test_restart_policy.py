"""Restart files by wall time, only the newest kept, one at a normal end.

A long run writes a restart file every few minutes of wall time and keeps the
newest; one that ends normally can write one more and be continued later to
a later end time. The resumed runs are checked as in test_restart.py: on one
thread a run resumed from a dump written during the run is the uninterrupted
run to the last printed digit. A run continued past its end differs from the
one-leg run only by the one step that was cut to land on the first end time,
which shifts the later steps by less than one step: its energies agree with
the one-leg run's within their largest change over one step.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from solver_decks import cube_and_plate

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.io.keyword.writer import write_deck
from hollowbody.solver.dump_policy import DumpPolicy
from hollowbody.solver.restart import dump_files, read_dump, read_header

pytestmark = pytest.mark.usefixtures("one_thread")

HISTORIES = ("glstat.csv", "rcforc.csv", "nodout.csv")


def _deck():
    return cube_and_plate(e=0.1, speed=3.0, end=1.5, friction=0.2)


def _run(out, **kw):
    return run_model(build_model(_deck()), out, vtk=False, **kw)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("one_leg")
    res = _run(out)
    assert res.status == "normal termination" and res.cycles > 100
    return out, res


def _glstat(folder):
    """Columns time, kinetic, internal of glstat.csv."""
    a = np.loadtxt(folder / "glstat.csv", delimiter=",", skiprows=1)
    return {"time": a[:, 0], "kinetic": a[:, 3], "internal": a[:, 4]}


def test_keep_newest_dumps_only_and_resume_equals_the_uninterrupted(tmp_path, reference):
    ref_out, ref = reference
    res = _run(tmp_path, dump_cycles=20, keep_dumps=2)
    written = (ref.cycles - 1) // 20
    names = [p.name for p in dump_files(tmp_path)]
    assert names == [f"d3dump{written - 1:02d}", f"d3dump{written:02d}"]
    assert [f["file"] for f in res.summary["restart_files"]] == names
    log = (tmp_path / "messages.log").read_text()
    assert log.count("restart file d3dump") == written
    assert "d3dump01 deleted" in log
    # the newest kept one resumes to the same run
    res2 = _run(tmp_path, restart="newest", dump_cycles=0)
    assert res2.cycles == ref.cycles
    for name in HISTORIES:
        assert (tmp_path / name).read_text() == (ref_out / name).read_text(), name


def test_dumps_by_wall_time(tmp_path, reference):
    _, ref = reference
    # an interval far below one cycle's wall time: a dump after every cycle but the last
    res = _run(tmp_path, dump_minutes=1e-9, keep_dumps=1)
    log = (tmp_path / "messages.log").read_text()
    assert log.count("restart file d3dump") == ref.cycles - 1
    files = dump_files(tmp_path)
    assert len(files) == 1 and read_header(files[0])["cycle"] == ref.cycles - 1
    assert res.summary["restart_files"] == [{"file": files[0].name,
                                             "time_ms": pytest.approx(read_header(files[0])
                                                                      ["time_ms"]),
                                             "cycle": ref.cycles - 1}]


def test_interval_of_hours_writes_none(tmp_path):
    _run(tmp_path, dump_minutes=600.0)
    assert dump_files(tmp_path) == []


def test_dump_at_normal_end_continues_to_a_later_end_time(tmp_path, reference):
    ref_out, ref = reference
    first = _run(tmp_path, end_time=0.75, dump_at_end=True)
    assert first.status == "normal termination"
    files = dump_files(tmp_path)
    assert len(files) == 1
    head = read_header(files[0])
    assert head["time_ms"] == pytest.approx(0.75, rel=1e-12) and head["cycle"] == first.cycles
    before = read_dump(files[0], build_model(_deck()))[1]["wall_seconds"]
    assert 0.0 < before <= first.summary["wall_seconds_total"]
    second = _run(tmp_path, end_time=1.5, restart="newest")
    assert second.status == "normal termination"
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["resumed_from"]["time_ms"] == pytest.approx(0.75, rel=1e-12)
    # the first process's wall time up to its restart file is carried over
    assert s["wall_seconds_total"] >= before + s["wall_seconds"] - 1e-3
    g, r = _glstat(tmp_path), _glstat(ref_out)
    t = g["time"]
    assert np.all(np.diff(t) > 0.0)  # no row written twice, none out of order
    assert t[0] == 0.0 and t[-1] == pytest.approx(1.5, rel=1e-12)
    # the one cut step shifts the later steps against the one-leg run by less than a
    # step: the curves agree within their largest change over one step
    dt = np.max(np.diff(r["time"]))
    for name in ("kinetic", "internal"):
        a = np.interp(r["time"], t, g[name])
        rate = np.max(np.abs(np.diff(r[name]) / np.diff(r["time"])))
        assert np.max(np.abs(a - r[name])) <= rate * dt, name
    assert abs(second.cycles - ref.cycles) <= 1


def test_a_last_step_cut_to_the_end_time_is_not_the_smallest_step(tmp_path, reference):
    """The step cut short to land on the end time is not a stability step: the
    run's dt_min (and so its verdict's time-step drop) must not count it. Continued
    from its end dump by a millionth of a step, the run takes one step of that
    length; its dt_min stays the smallest stable step of the run (before: that
    millionth, and a time-step warning on a sound run)."""
    first = _run(tmp_path, end_time=0.75, dump_at_end=True)
    stable = first.summary["dt_min_ms"]
    assert 0.3 * first.summary["dt_initial_ms"] < stable <= first.summary["dt_initial_ms"]
    tiny = 1e-6 * stable
    second = _run(tmp_path, end_time=0.75 + tiny, restart="newest")
    assert second.status == "normal termination" and second.cycles == first.cycles + 1
    assert second.summary["end_time_ms"] == pytest.approx(0.75 + tiny, rel=1e-15)
    assert second.summary["dt_min_ms"] == stable
    assert second.summary["quality"] == "ok", second.summary["quality_reasons"]


def test_kept_files_only_are_listed_after_a_resume(tmp_path):
    _run(tmp_path, end_time=0.5, dump_at_end=True, keep_dumps=1)
    res = _run(tmp_path, end_time=1.0, restart="newest", dump_at_end=True, keep_dumps=1)
    names = [p.name for p in dump_files(tmp_path)]
    assert names == ["d3dump02"]
    assert [f["file"] for f in res.summary["restart_files"]] == names
    res = _run(tmp_path, end_time=1.5, restart="newest", dump_at_end=True, keep_dumps=1)
    assert [f["file"] for f in res.summary["restart_files"]] == ["d3dump03"]


def test_dump_policy_checks_its_numbers():
    for kw in ({"cycles": -1}, {"minutes": -0.5}, {"minutes": float("nan")}, {"keep": -2}):
        with pytest.raises(ValueError):
            DumpPolicy(**kw)


@pytest.mark.parametrize("flag", [["--keep-dumps", "-1"], ["--dump-minutes", "-3"]])
def test_bad_dump_options_are_one_line_and_exit_2(tmp_path, capsys, flag):
    deck = tmp_path / "deck.k"
    write_deck(_deck(), deck)
    out = tmp_path / "out"
    code = cli_main(["run", str(deck), "--out", str(out), "--quiet", *flag])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and "must be >= 0" in err, err
    assert not out.exists()


def test_a_stop_in_the_last_cycle_ends_normally_and_is_reported(tmp_path, monkeypatch,
                                                                reference):
    """Ctrl-C during the last cycle: the run ends as it would have (normal, its restart
    file at the end written), and the caller learns that a stop was asked for."""
    import signal

    from hollowbody.solver import explicit

    _, ref = reference
    original = explicit.step

    def step(model, plan, state, dt):
        original(model, plan, state, dt)
        if state.cycle == ref.cycles:
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(explicit, "step", step)
    res = _run(tmp_path, dump_at_end=True)
    assert res.status == "normal termination" and res.cycles == ref.cycles
    assert res.stop_requested == "Ctrl-C"
    assert len(dump_files(tmp_path)) == 1
    monkeypatch.undo()
    assert _run(tmp_path / "again").stop_requested is None
