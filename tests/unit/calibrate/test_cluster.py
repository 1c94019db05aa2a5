"""``hollowbody calibrate --cluster slurm``: the SLURM job script (dask-jobqueue) and
tasks run in a real SLURM job when SLURM is installed (skipped otherwise, with the
reason; ``tests/cluster/single_node_slurm.sh`` starts a one-node SLURM from the
distribution's packages and runs these tests against it)."""

from __future__ import annotations

import operator
import shutil

import pytest

from hollowbody.calibrate.cluster import JobSpec
from hollowbody.cli.main import main
from hollowbody.errors import UserInputError

jobqueue = pytest.importorskip("dask_jobqueue", reason="dask-jobqueue (extra 'cluster') is "
                               "not installed")


def test_job_script_books_the_cores_and_runs_one_single_threaded_worker():
    from hollowbody.calibrate.cluster import job_script

    spec = JobSpec(queue="short", walltime="02:30:00", cores_per_job=4, jobs=3,
                   python="/opt/py/bin/python")
    text = job_script(spec, scheduler="tcp://10.0.0.1:8786")
    lines = text.splitlines()
    assert lines[0] == "#!/usr/bin/env bash"
    for directive in ("#SBATCH -J hollowbody-calibrate", "#SBATCH -p short", "#SBATCH -n 1",
                      "#SBATCH --cpus-per-task=4", "#SBATCH --mem=8G", "#SBATCH -t 02:30:00"):
        assert directive in lines
    assert "export NUMBA_NUM_THREADS=4" in lines and "export OMP_NUM_THREADS=4" in lines
    worker = next(line for line in lines if "dask_worker" in line)
    assert worker.startswith("/opt/py/bin/python -m distributed.cli.dask_worker "
                             "tcp://10.0.0.1:8786")
    assert "--nthreads 1" in worker
    # the jobs' output files go to the log folder
    logs = job_script(JobSpec(log_directory="/data/cal/slurm")).splitlines()
    assert "#SBATCH -o /data/cal/slurm/hollowbody-calibrate-%J.out" in logs
    # no queue given: no partition line
    assert not any(line.startswith("#SBATCH -p")
                   for line in job_script(JobSpec()).splitlines())


def test_pbs_job_script_selects_the_cores_and_memory_of_one_chunk():
    from hollowbody.calibrate.cluster import job_script

    spec = JobSpec(system="pbs", queue="workq", walltime="03:00:00", cores_per_job=8,
                   python="/opt/py/bin/python", log_directory="/data/cal/pbs")
    lines = job_script(spec, scheduler="tcp://10.0.0.1:8786").splitlines()
    for directive in ("#PBS -N hollowbody-calibrate", "#PBS -q workq",
                      "#PBS -l select=1:ncpus=8:mem=16GB", "#PBS -l walltime=03:00:00"):
        assert directive in lines, directive
    assert not any(line.startswith("#SBATCH") for line in lines)
    assert "export NUMBA_NUM_THREADS=8" in lines and "export OMP_NUM_THREADS=8" in lines
    worker = next(line for line in lines if "dask_worker" in line)
    assert worker.startswith("/opt/py/bin/python -m distributed.cli.dask_worker "
                             "tcp://10.0.0.1:8786") and "--nthreads 1" in worker


def test_cli_pbs_dry_run(tmp_path, capsys):
    out = tmp_path / "cal"
    assert main(["calibrate", "--tissue", "fat", "--out", str(out), "--cluster", "pbs",
                 "--cores-per-job", "2", "--jobs", "3", "--dry-run"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("# 3 PBS job(s) of 2 core(s), 4GB, 01:00:00")
    assert "#PBS -l select=1:ncpus=2:mem=4GB" in text
    assert not out.exists()


@pytest.mark.parametrize("kwargs, message", [
    ({"walltime": "2h"}, "HH:MM:SS"), ({"cores_per_job": 0}, "--cores-per-job"),
    ({"jobs": 0}, "--jobs"), ({"system": "lsf"}, "--cluster must be one of")])
def test_bad_job_options(kwargs, message):
    with pytest.raises(UserInputError, match=message):
        JobSpec(**kwargs)


def test_cli_dry_run_prints_the_script_and_runs_nothing(tmp_path, capsys):
    out = tmp_path / "cal"
    code = main(["calibrate", "--tissue", "muscle", "--out", str(out), "--cluster", "slurm",
                 "--queue", "q1", "--walltime", "00:10:00", "--cores-per-job", "2",
                 "--jobs", "5", "--dry-run"])
    assert code == 0
    text = capsys.readouterr().out
    assert text.startswith("# 5 SLURM job(s) of 2 core(s), 4GB, 00:10:00")
    assert "#SBATCH -p q1" in text and "#SBATCH --cpus-per-task=2" in text
    assert not out.exists()


@pytest.mark.parametrize("args, message", [
    (["--dry-run"], "give --cluster"),
    (["--cluster", "slurm", "--workers", "2", "--dry-run"], "cannot be combined"),
    (["--cluster", "slurm", "--walltime", "1:00", "--dry-run"], "HH:MM:SS"),
])
def test_cli_bad_cluster_options_are_exit_2(args, message, tmp_path, capsys):
    assert main(["calibrate", "--tissue", "muscle", "--out", str(tmp_path / "c"), *args]) == 2
    assert message in capsys.readouterr().err


def _slurm_unavailable() -> str | None:
    """Why no SLURM can run jobs here (None: a partition has an idle or mixed node)."""
    import subprocess

    if shutil.which("sbatch") is None or shutil.which("sinfo") is None:
        return "no SLURM here (sbatch / sinfo not on the PATH)"
    try:
        res = subprocess.run(["sinfo", "-h", "-o", "%T"], capture_output=True, text=True,
                             timeout=10)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"SLURM does not answer (sinfo: {exc})"
    states = res.stdout.split()
    if res.returncode != 0 or not any(s.rstrip("*") in ("idle", "mixed") for s in states):
        said = res.stdout.strip() or res.stderr.strip()
        return f"no SLURM node free to run a job (sinfo: {said})"
    return None


def test_tasks_run_on_a_real_slurm(tmp_path):
    why = _slurm_unavailable()
    if why:
        pytest.skip(why)
    from hollowbody.calibrate.runner import make_runner

    spec = JobSpec(walltime="00:05:00", cores_per_job=1, jobs=1,
                     log_directory=str(tmp_path / "slurm"))
    with make_runner(batch=spec) as runner:
        results = sorted(r for _, r, err in runner.run(operator.neg, [1, 2, 3]) if err is None)
    assert results == [-3, -2, -1]
