"""Calibration evaluations on a SLURM or PBS cluster through dask-jobqueue.

``hollowbody calibrate ... --cluster slurm|pbs`` submits ``--jobs`` batch jobs;
each runs one dask worker that evaluates one candidate at a time with all the
cores the job books (``--cores-per-job``: SLURM ``--cpus-per-task``, PBS
``-l select=1:ncpus=N:mem=M``; the
worker has one thread, and the solver's numba threads and an external
engine's OpenMP threads are set to the job's cores). The calibration's own
process stays where it was started (the dask scheduler); the jobs must reach
it over the network and share its file system (run folders are paths).
``--dry-run`` prints the job script and submits nothing.

dask-jobqueue is an optional extra: ``pip install 'hollowbody[cluster]'``.
The local dask cluster stays the default.
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path

from hollowbody.errors import UserInputError

EXTRA = "pip install 'hollowbody[cluster]' (dask-jobqueue)"
#: Batch systems supported (``--cluster``).
SYSTEMS = ("slurm", "pbs")
#: Memory booked per core when none is given.
GB_PER_CORE = 2


@dataclass(frozen=True)
class JobSpec:
    """The batch jobs of a calibration.

    system: ``slurm`` or ``pbs``; queue: SLURM partition or PBS queue (None: the
    cluster's default); walltime ``HH:MM:SS`` of one
    job; cores_per_job: cores each job books; jobs: number of jobs (dask
    workers); memory: memory per job (dask-jobqueue notation, e.g. ``8GB``;
    None: 2 GB per core); python: the interpreter the jobs run; log_directory:
    folder of the jobs' output files (None: the folder they are submitted from).
    """

    queue: str | None = None
    walltime: str = "01:00:00"
    cores_per_job: int = 1
    jobs: int = 1
    memory: str | None = None
    python: str = sys.executable
    log_directory: str | None = None
    system: str = "slurm"

    def __post_init__(self) -> None:
        if self.system not in SYSTEMS:
            raise UserInputError(f"--cluster must be one of {', '.join(SYSTEMS)} "
                                 f"(got {self.system!r})")
        if not re.fullmatch(r"\d+:[0-5]\d:[0-5]\d", self.walltime):
            raise UserInputError(f"--walltime must be HH:MM:SS (got {self.walltime!r})")
        if self.cores_per_job < 1:
            raise UserInputError(f"--cores-per-job must be at least 1 (got {self.cores_per_job})")
        if self.jobs < 1:
            raise UserInputError(f"--jobs must be at least 1 (got {self.jobs})")

    @property
    def job_memory(self) -> str:
        return self.memory or f"{GB_PER_CORE * self.cores_per_job}GB"

    def prologue(self) -> list[str]:
        """Lines run before the worker: the job's cores for the solver and the engines."""
        n = str(self.cores_per_job)
        return [f"export NUMBA_NUM_THREADS={n}", f"export OMP_NUM_THREADS={n}",
                "export OPENBLAS_NUM_THREADS=1", "export MKL_NUM_THREADS=1"]

    def kwargs(self) -> dict:
        """Arguments of dask-jobqueue's SLURMCluster / SLURMJob (PBSCluster / PBSJob):
        one single-threaded worker per job, booking ``cores_per_job`` cores."""
        kw = dict(cores=1, processes=1, memory=self.job_memory, walltime=self.walltime,
                  job_script_prologue=self.prologue(), python=self.python,
                  job_name="hollowbody-calibrate")
        if self.system == "slurm":
            kw["job_cpu"] = self.cores_per_job
        else:  # PBS Pro / OpenPBS select statement; Torque users give --job-extra instead
            kw["resource_spec"] = (f"select=1:ncpus={self.cores_per_job}:"
                                   f"mem={self.job_memory}")
        if self.queue:
            kw["queue"] = self.queue
        if self.log_directory:
            kw["log_directory"] = self.log_directory
        return kw


def _jobqueue():
    try:
        import dask_jobqueue
    except ImportError:
        raise UserInputError(f"--cluster needs dask-jobqueue: {EXTRA}") from None
    return dask_jobqueue


def job_script(spec: JobSpec, scheduler: str = "tcp://SCHEDULER-ADDRESS:8786") -> str:
    """The batch script each job runs (``scheduler``: the address its worker
    connects to; the calibration's scheduler when it runs)."""
    _jobqueue()
    if spec.system == "slurm":
        from dask_jobqueue.slurm import SLURMJob as Job
    else:
        from dask_jobqueue.pbs import PBSJob as Job
    made: list[Path] = []  # folders of the log directory that do not exist yet
    if spec.log_directory:
        p = Path(spec.log_directory).absolute()
        while not p.exists():
            made.append(p)
            p = p.parent
    job = Job(scheduler=scheduler, name="hollowbody-worker", **spec.kwargs())
    for p in made:  # dask-jobqueue creates the log directory: a script only needs none
        if p.is_dir() and not any(p.iterdir()):
            p.rmdir()
    return job.job_script()


def batch_cluster(spec: JobSpec):  # -> dask_jobqueue.SLURMCluster | PBSCluster
    """A started SLURMCluster or PBSCluster scaled to ``spec.jobs`` jobs."""
    jq = _jobqueue()
    make = jq.SLURMCluster if spec.system == "slurm" else jq.PBSCluster
    cluster = make(**spec.kwargs())
    cluster.scale(jobs=spec.jobs)
    return cluster
