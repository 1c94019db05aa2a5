"""Where evaluations run: in this process, or on dask.distributed workers.

Both runners have the same interface::

    with make_runner(workers=4) as runner:
        for index, result, error in runner.run(fn, tasks):
            ...

``run`` yields ``(index into tasks, fn(task), None)`` as evaluations finish
(in any order), or ``(index, None, exception)`` when the infrastructure failed
(a worker lost more often than the retries allow). ``fn`` and the tasks must
be picklable for :class:`DaskRunner` (module-level functions, dataclasses).

- :class:`SerialRunner` — one evaluation after the other in this process
  (``--workers 1``); the solver's own threads use every core.
- :class:`DaskRunner` — a ``LocalCluster`` of N single-threaded worker
  processes started here (no set-up; ``NUMBA_NUM_THREADS=1`` and the BLAS
  thread counts set to 1 in the workers so N runs share N cores), or an
  existing cluster (``scheduler="tcp://host:8786"``). Tasks are submitted with
  ``retries`` so an evaluation lost with its worker runs again elsewhere.
  The workers of an existing cluster need hollowbody installed and, when runs
  write files, the same file system as this process (run folders are paths).
"""

from __future__ import annotations

import logging
import os
import uuid
from collections.abc import Callable, Iterator, Sequence
from typing import Any

from hollowbody.errors import UserInputError

#: Environment of LocalCluster workers: one thread per run.
WORKER_ENV = {"NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
              "MKL_NUM_THREADS": "1"}

Result = tuple[int, Any, BaseException | None]


class SerialRunner:
    """Evaluate tasks one after the other in this process."""

    workers = 1
    description = "this process (serial)"

    def run(self, fn: Callable[[Any], Any], tasks: Sequence[Any]) -> Iterator[Result]:
        for i, task in enumerate(tasks):
            try:
                res = fn(task)
            except Exception as exc:  # fn should not raise; report it as an infrastructure error
                yield i, None, exc
                continue
            yield i, res, None

    def broadcast(self, fn: Callable[[Any], Any], arg: Any) -> None:
        """Call ``fn(arg)`` once in every worker (here: this process)."""
        fn(arg)

    def close(self) -> None:
        pass

    def __enter__(self) -> SerialRunner:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class DaskRunner:
    """Evaluate tasks on dask.distributed workers (a LocalCluster or a scheduler address).

    workers: number of LocalCluster worker processes (ignored with
    ``scheduler``); retries: resubmissions of a task that failed or lost its
    worker; processes: False runs the LocalCluster workers as threads (tests).
    """

    def __init__(self, workers: int | None = None, scheduler: str | None = None,
                 retries: int = 2, processes: bool = True, cluster: Any = None,
                 description: str = "") -> None:
        from dask.distributed import Client, LocalCluster

        self.retries = int(retries)
        self.cluster = None
        if cluster is not None:  # a started cluster (SLURM jobs), closed with this runner
            self.cluster = cluster
            self.client = Client(cluster)
            self.description = description or f"dask cluster {type(cluster).__name__}"
        elif scheduler:
            try:
                self.client = Client(scheduler, timeout="20s")
            except (OSError, TimeoutError, ValueError) as exc:
                raise UserInputError(f"cannot reach the dask scheduler at {scheduler!r} "
                                     f"({type(exc).__name__}: {exc})".splitlines()[0]) from None
            self.description = f"dask cluster at {scheduler}"
        else:
            n = int(workers or os.cpu_count() or 1)
            extra = ({"env": dict(WORKER_ENV), "preload": ["hollowbody.calibrate.worker_setup"]}
                     if processes else {})
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=processes,
                                        dashboard_address=":0", silence_logs=logging.ERROR,
                                        **extra)
            self.client = Client(self.cluster)
            self.description = (f"dask LocalCluster, {n} worker "
                                f"{'processes' if processes else 'threads'}")

    @property
    def workers(self) -> int:
        """Number of workers currently connected."""
        return max(1, len(self.client.scheduler_info().get("workers", {})))

    def run(self, fn: Callable[[Any], Any], tasks: Sequence[Any]) -> Iterator[Result]:
        from dask.distributed import as_completed

        if not tasks:
            return
        tag = uuid.uuid4().hex[:8]
        name = getattr(fn, "__name__", "task")
        futures = [self.client.submit(fn, t, key=f"hollowbody-{name}-{tag}-{i}", pure=False,
                                      retries=self.retries) for i, t in enumerate(tasks)]
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for fut in as_completed(futures):
                i = index[fut.key]
                try:
                    res = fut.result()
                except Exception as exc:  # KilledWorker and friends
                    yield i, None, exc
                    continue
                yield i, res, None
        finally:
            pending = [f for f in futures if not f.done()]
            if pending:
                self.client.cancel(pending)

    def broadcast(self, fn: Callable[[Any], Any], arg: Any) -> None:
        """Call ``fn(arg)`` once on every connected worker (as a task) and wait."""
        from dask.distributed import wait

        workers = list(self.client.scheduler_info().get("workers", {}))
        tag = uuid.uuid4().hex[:8]
        futures = [self.client.submit(fn, arg, key=f"hollowbody-broadcast-{tag}-{i}",
                                      workers=[w], allow_other_workers=False, pure=False)
                   for i, w in enumerate(workers)]
        wait(futures)

    def close(self) -> None:
        try:
            self.client.close()
        finally:
            if self.cluster is not None:
                self.cluster.close()

    def __enter__(self) -> DaskRunner:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def make_runner(workers: int | None = None, scheduler: str | None = None,
                retries: int = 2, batch: Any = None) -> SerialRunner | DaskRunner:
    """``batch`` given (a :class:`hollowbody.calibrate.cluster.JobSpec`): SLURM or PBS
    jobs through dask-jobqueue; ``scheduler`` given: that cluster; ``workers`` == 1:
    this process; otherwise a LocalCluster of ``workers`` processes (default: one per
    CPU)."""
    if batch is not None:
        from hollowbody.calibrate.cluster import batch_cluster

        return DaskRunner(retries=retries, cluster=batch_cluster(batch),
                          description=f"{batch.system.upper()}: {batch.jobs} job(s) of "
                                      f"{batch.cores_per_job} core(s)"
                                      f"{' on ' + batch.queue if batch.queue else ''}")
    if scheduler:
        return DaskRunner(scheduler=scheduler, retries=retries)
    n = int(workers or os.cpu_count() or 1)
    if n < 1:
        raise UserInputError(f"--workers must be at least 1 (got {n})")
    if n == 1:
        return SerialRunner()
    return DaskRunner(workers=n, retries=retries)
