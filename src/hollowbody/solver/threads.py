"""How many numba threads a run uses.

``threads`` settings: an integer N (at most N threads; numba can only lower
the count it started with, ``NUMBA_NUM_THREADS``, by default the number of
cores), ``"auto"`` (the policy below) or None (leave numba's current count,
e.g. one set with ``numba.set_num_threads`` by the caller).

The ``auto`` policy:

- one thread for a model below :data:`AUTO_MIN_WORK` elements plus contact
  nodes (too small for the threaded kernels to pay their start-up, see the
  ``PARALLEL_MIN`` thresholds of the kernels);
- else every thread numba can run, when waiting threads sleep: numba's OpenMP
  layer with ``OMP_WAIT_POLICY=passive``, which every run sets (unless the
  environment sets it) when numba has not started its threads yet, or another
  threading layer;
- else (OpenMP threads already started with the spinning default) no more
  threads than the cores the rest of the machine leaves idle (one-minute load
  average): a spinning thread that shares its core with another process
  holds up the others at every synchronisation, and two threads then run
  several times slower than one.

On the 2-core machine of BENCHMARKS.md the passive wait policy is what makes
two threads pay on a busy machine: the block test (solid, 40 km/h, 4 ms) with a
second process keeping one core busy took 18.7 s on one thread, 60 s on two
spinning threads and 11.3 s on two passive ones.

The command line uses ``auto`` (``--threads N|auto``); the Python API keeps
the caller's count unless ``threads`` is given. The count used is recorded in
``summary.json`` (``"threads"``).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

#: Elements plus contact nodes below which ``auto`` runs on one thread.
AUTO_MIN_WORK = 4096
#: Setting used by runs that do not give one (see :func:`set_default`).
_default: int | str | None = None


def set_default(setting: int | str | None) -> None:
    """Threads setting of runs that give none (the command line sets ``auto`` or
    ``--threads``); also asks for the passive OpenMP wait policy."""
    global _default
    _default = parse(setting) if setting is not None else None
    passive_wait()


def _threads_started() -> bool:
    from numba.np.ufunc import parallel

    return bool(getattr(parallel, "_is_initialized", True))


def passive_wait() -> bool:
    """Whether numba's waiting threads sleep instead of spinning.

    Sets ``OMP_WAIT_POLICY=passive`` when the environment does not set it and
    numba has not started its threads yet (OpenMP reads it at start-up only).
    """
    import numba

    if _threads_started():
        if numba.threading_layer() != "omp":
            return True  # tbb and workqueue threads sleep while they wait
        return os.environ.get("OMP_WAIT_POLICY", "").strip().lower() == "passive"
    os.environ.setdefault("OMP_WAIT_POLICY", "passive")
    return os.environ["OMP_WAIT_POLICY"].strip().lower() == "passive" or \
        numba.config.THREADING_LAYER in ("tbb", "workqueue")


def default() -> int | str | None:
    """The setting of runs that give none."""
    return _default


def parse(setting: int | str) -> int | str:
    """``"auto"`` or a positive integer (ValueError otherwise)."""
    if isinstance(setting, str):
        s = setting.strip().lower()
        if s == "auto":
            return "auto"
        try:
            setting = int(s)
        except ValueError:
            raise ValueError(f"threads must be a positive integer or 'auto' "
                             f"(got {setting!r})") from None
    if isinstance(setting, bool) or not isinstance(setting, int) or setting < 1:
        raise ValueError(f"threads must be a positive integer or 'auto' (got {setting!r})")
    return setting


def available_threads() -> int:
    """Most threads numba can run (``NUMBA_NUM_THREADS``, default: the cores)."""
    import numba

    return int(numba.config.NUMBA_NUM_THREADS)


def idle_cores(cores: int | None = None, load: float | None = None) -> int:
    """Cores not used by other processes: cores minus the one-minute load
    average (rounded), at least one."""
    if cores is None:
        cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else \
            (os.cpu_count() or 1)
    if load is None:
        try:
            load = os.getloadavg()[0]
        except OSError:  # not available on this platform
            load = 0.0
    return max(1, min(cores, int(cores - load + 0.5)))


def auto_threads(work: int, limit: int, idle: int, passive: bool = True) -> int:
    """The ``auto`` policy: 1 below :data:`AUTO_MIN_WORK`; else ``limit`` when
    waiting threads sleep (passive), ``min(limit, idle)`` when they spin.

    work: elements plus contact nodes of the model; limit: most threads numba
    can run; idle: cores not used by other processes.
    """
    if work < AUTO_MIN_WORK:
        return 1
    if passive:
        return max(1, limit)
    return max(1, min(limit, idle))


def model_work(plan) -> int:  # noqa: ANN001 - solver.setup.Assembly
    """Elements plus contact nodes of a run's plan (what the threaded kernels
    loop over)."""
    n = int(sum(plan.element_counts().values()))
    for c in plan.contacts:
        nodes = getattr(c, "nodes", None)  # the nodes of both sides
        if nodes is not None:
            n += int(len(nodes))
    return n


def resolve(setting: int | str | None, work: int) -> tuple[int, str]:
    """Thread count of a run and why: (n, reason)."""
    import numba

    passive = passive_wait()  # before numba starts its threads (the run's first kernel)
    if setting is None:
        return int(numba.get_num_threads()), "as set"
    setting = parse(setting)
    limit = available_threads()
    if setting == "auto":
        if work < AUTO_MIN_WORK:
            return 1, f"auto: small model ({work} elements and contact nodes < {AUTO_MIN_WORK})"
        if passive:
            return auto_threads(work, limit, limit), f"auto: {limit} available, passive wait"
        idle = idle_cores()
        return (auto_threads(work, limit, idle, passive=False),
                f"auto: {limit} available, spinning wait, {idle} idle core(s)")
    if setting > limit:
        return limit, f"{setting} requested, {limit} available (NUMBA_NUM_THREADS)"
    return setting, "requested"


@contextmanager
def using(n: int) -> Iterator[int]:
    """numba runs ``n`` threads inside the block; the previous count after it."""
    import numba

    old = numba.get_num_threads()
    numba.set_num_threads(n)
    try:
        yield n
    finally:
        numba.set_num_threads(old)
