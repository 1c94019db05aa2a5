"""The dask path: a LocalCluster of 2 worker processes gives the serial result."""

from __future__ import annotations

from hollowbody.calibrate import (
    CalibrationSettings,
    DaskRunner,
    GASettings,
    SurrogateSimulator,
    calibrate,
    make_space,
)
from hollowbody.calibrate.runner import WORKER_ENV, make_runner


def _settings() -> CalibrationSettings:
    return CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]),
                               GASettings(population=6, generations=2, seed=2))


def _worker_env(_task: object) -> dict:
    import os

    return {k: os.environ.get(k) for k in WORKER_ENV}


def _die_once(marker: str) -> str:
    """Kill the worker process the first time (a lost worker), succeed the second."""
    import os
    from pathlib import Path

    if not Path(marker).exists():
        Path(marker).write_text("died")
        os._exit(1)
    return "done"


def _note_pid(folder: str) -> None:
    import os
    from pathlib import Path

    (Path(folder) / f"{os.getpid()}.pid").write_text("warm")


def test_local_cluster_of_two_processes_matches_serial(tmp_path):
    sim = SurrogateSimulator(fail_above=(("E", 300.0),), write_files=False)
    serial = calibrate(_settings(), tmp_path / "serial", sim)
    runner = DaskRunner(workers=2, processes=True, retries=1)
    try:
        assert runner.workers == 2
        env = [r for _, r, _ in runner.run(_worker_env, [None])][0]
        assert env["NUMBA_NUM_THREADS"] == "1"
        par = calibrate(_settings(), tmp_path / "dask", sim, runner=runner)
        # broadcast (kernel warm-up) reaches every worker process
        runner.broadcast(_note_pid, str(tmp_path))
        assert len(list(tmp_path.glob("*.pid"))) == 2
        # an evaluation lost with its worker runs again on another one
        lost = list(runner.run(_die_once, [str(tmp_path / "marker")]))
        assert lost == [(0, "done", None)]
    finally:
        runner.close()
    assert runner.client.status == "closed"
    assert runner.cluster.status.name == "closed"
    assert [e["key"] for e in par.evaluations] == [e["key"] for e in serial.evaluations]
    assert [e["fitness"] for e in par.evaluations] == [e["fitness"] for e in serial.evaluations]
    assert par.best_params == serial.best_params


def test_make_runner_in_process_for_one_worker():
    r = make_runner(workers=1)
    assert r.workers == 1 and "serial" in r.description
    r.close()
