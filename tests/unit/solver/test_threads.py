"""The thread policy of a run (hollowbody.solver.threads) and its options."""

from __future__ import annotations

import json
import os

import numba
import pytest

from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.io.keyword.writer import write_deck
from hollowbody.solver import threads as th
from hollowbody.solver.explicit import RunOptions, run
from hollowbody.solver.setup import assemble
from hollowbody.testing.decks import box_deck


@pytest.fixture
def small_model():
    return build_model(box_deck(size=(40.0, 40.0, 20.0), h=10.0))


def test_parse_accepts_auto_and_positive_integers():
    assert th.parse("auto") == "auto"
    assert th.parse(" AUTO ") == "auto"
    assert th.parse("3") == 3
    assert th.parse(2) == 2
    for bad in ("0", "-1", "two", 0, 1.5, True):
        with pytest.raises(ValueError, match="positive integer or 'auto'"):
            th.parse(bad)


def test_auto_is_one_thread_below_the_size_where_threads_pay():
    for passive in (True, False):
        assert th.auto_threads(th.AUTO_MIN_WORK - 1, limit=8, idle=8, passive=passive) == 1
        assert th.auto_threads(th.AUTO_MIN_WORK, limit=8, idle=8, passive=passive) == 8
        assert th.auto_threads(10**6, limit=2, idle=8, passive=passive) == 2  # numba's most


def test_auto_spinning_threads_only_on_idle_cores():
    assert th.auto_threads(10**6, limit=8, idle=3, passive=False) == 3
    assert th.auto_threads(10**6, limit=2, idle=1, passive=False) == 1
    assert th.auto_threads(10**6, limit=2, idle=1, passive=True) == 2  # sleeping threads


def test_auto_on_a_large_model_follows_the_wait_policy(monkeypatch):
    monkeypatch.setattr(th, "available_threads", lambda: 2)
    monkeypatch.setattr(th, "idle_cores", lambda: 1)
    monkeypatch.setattr(th, "wait_policy", lambda: "passive")
    assert th.resolve("auto", 10**6) == (2, "auto: 2 available, passive wait")
    monkeypatch.setattr(th, "wait_policy", lambda: "short")
    assert th.resolve("auto", 10**6) == (2, "auto: 2 available, short wait")
    monkeypatch.setattr(th, "wait_policy", lambda: "spin")
    n, why = th.resolve("auto", 10**6)
    assert n == 1 and "spinning" in why


def test_wait_policy_sets_a_short_spin_where_contention_is_watched(monkeypatch):
    monkeypatch.setattr(th, "_threads_started", lambda: False)
    monkeypatch.delenv("OMP_WAIT_POLICY", raising=False)
    monkeypatch.delenv("GOMP_SPINCOUNT", raising=False)
    omp = numba.config.THREADING_LAYER not in ("tbb", "workqueue")
    monkeypatch.setattr(th.contention, "available", lambda: True)
    assert th.wait_policy() == ("short" if omp else "passive")
    assert os.environ["GOMP_SPINCOUNT"] == str(th.SHORT_SPIN)  # set before the threads start
    assert "OMP_WAIT_POLICY" not in os.environ
    monkeypatch.delenv("GOMP_SPINCOUNT")
    monkeypatch.setattr(th.contention, "available", lambda: False)
    assert th.wait_policy() == "passive"
    assert os.environ["OMP_WAIT_POLICY"] == "passive" and "GOMP_SPINCOUNT" not in os.environ


def test_wait_policy_keeps_what_the_environment_sets(monkeypatch):
    monkeypatch.setattr(th, "_threads_started", lambda: False)
    monkeypatch.delenv("GOMP_SPINCOUNT", raising=False)
    monkeypatch.setenv("OMP_WAIT_POLICY", "active")
    omp = numba.config.THREADING_LAYER not in ("tbb", "workqueue")
    assert th.wait_policy() == ("spin" if omp else "passive")
    assert "GOMP_SPINCOUNT" not in os.environ


def test_omp_policy_reads_the_spin_count_before_the_wait_policy():
    assert th.omp_policy({}) == "spin"  # libgomp's default spins long
    assert th.omp_policy({"OMP_WAIT_POLICY": "PASSIVE"}) == "passive"
    assert th.omp_policy({"OMP_WAIT_POLICY": "active"}) == "spin"
    assert th.omp_policy({"GOMP_SPINCOUNT": "20000", "OMP_WAIT_POLICY": "passive"}) == "short"
    assert th.omp_policy({"GOMP_SPINCOUNT": "0"}) == "passive"
    assert th.omp_policy({"GOMP_SPINCOUNT": "20k"}) == "short"
    assert th.omp_policy({"GOMP_SPINCOUNT": "3M"}) == "spin"
    assert th.omp_policy({"GOMP_SPINCOUNT": "infinite"}) == "spin"
    assert th.omp_policy({"GOMP_SPINCOUNT": "lots", "OMP_WAIT_POLICY": "passive"}) == "passive"


def test_contact_kernels_thread_from_fewer_rows_when_threads_spin():
    assert th.per_cycle_min_rows("short") == th.per_cycle_min_rows("spin") == \
        th.PER_CYCLE_MIN_ROWS < th.per_cycle_min_rows("passive")


def test_idle_cores_counts_the_load_of_the_rest_of_the_machine():
    assert th.idle_cores(cores=2, load=0.1) == 2
    assert th.idle_cores(cores=2, load=1.0) == 1
    assert th.idle_cores(cores=2, load=1.6) == 1  # never fewer than one
    assert th.idle_cores(cores=2, load=7.0) == 1
    assert th.idle_cores(cores=8, load=2.4) == 6
    assert th.idle_cores() >= 1


def test_model_work_counts_elements(small_model):
    plan = assemble(small_model)
    assert th.model_work(plan) == 4 * 4 * 2  # 40 x 40 x 20 mm in 10 mm hexahedra


def test_resolve(small_model):
    work = th.model_work(assemble(small_model))
    n, why = th.resolve("auto", work)
    assert n == 1 and "small model" in why
    n, why = th.resolve(None, work)
    assert n == numba.get_num_threads() and why == "as set"
    limit = th.available_threads()
    assert th.resolve(1, work) == (1, "requested")
    n, why = th.resolve(limit + 5, work)
    assert n == limit and "available" in why


def test_using_restores_the_thread_count():
    old = numba.get_num_threads()
    with th.using(1):
        assert numba.get_num_threads() == 1
    assert numba.get_num_threads() == old


def test_auto_runs_a_small_model_on_one_thread_and_records_it(small_model, tmp_path):
    old = numba.get_num_threads()
    res = run(small_model, RunOptions(out_dir=tmp_path, end_time=0.02, vtk=False, quiet=True,
                                      threads="auto"))
    assert res.status == "normal termination"
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["threads"] == 1
    assert "numba threads: 1 (auto: small model" in (tmp_path / "messages.log").read_text()
    assert numba.get_num_threads() == old  # the caller's count is back


def test_cli_threads_option_is_recorded_in_the_summary(tmp_path):
    deck = tmp_path / "box.k"
    write_deck(box_deck(size=(40.0, 40.0, 20.0), h=10.0), deck)
    out = tmp_path / "out"
    assert th.default() is None
    code = cli_main(["run", str(deck), "--out", str(out), "--end-time", "0.02", "--no-vtk",
                     "--quiet", "--threads", "1"])
    assert code == 0
    assert json.loads((out / "summary.json").read_text())["threads"] == 1
    assert th.default() is None  # the command's setting does not outlive it


def test_cli_rejects_a_bad_threads_value(tmp_path, capsys):
    deck = tmp_path / "box.k"
    write_deck(box_deck(size=(40.0, 40.0, 20.0), h=10.0), deck)
    code = cli_main(["run", str(deck), "--out", str(tmp_path / "out"), "--threads", "0"])
    assert code == 2
    assert "positive integer or 'auto'" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
