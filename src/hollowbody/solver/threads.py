"""How many numba threads a run uses.

``threads`` settings: an integer N (at most N threads; numba can only lower
the count it started with, ``NUMBA_NUM_THREADS``, by default the number of
cores), ``"auto"`` (the policy below) or None (leave numba's current count,
e.g. one set with ``numba.set_num_threads`` by the caller).

The ``auto`` policy: one thread for a model below :data:`AUTO_MIN_WORK`
elements plus contact slave nodes (too small for the threaded kernels to pay
their start-up, see the ``PARALLEL_MIN`` thresholds of the kernels), and no more
threads than the cores left idle by the rest of the machine (one-minute load
average; a thread that has to share its core with another process slows every
other thread down at each synchronisation). With numba's OpenMP layer the
command line also sets ``OMP_WAIT_POLICY=passive`` unless it is set already,
so waiting threads sleep instead of spinning on a busy machine.

The command line uses ``auto`` (``--threads N|auto``); the Python API keeps
the caller's count unless ``threads`` is given. The count used is recorded in
``summary.json`` (``"threads"``).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

#: Elements plus contact slave nodes below which ``auto`` runs on one thread.
AUTO_MIN_WORK = 4096
#: Setting used by runs that do not give one (see :func:`set_default`).
_default: int | str | None = None


def set_default(setting: int | str | None) -> None:
    """Threads setting of runs that give none (the command line sets ``auto`` or
    ``--threads``); also sets the passive OpenMP wait policy unless given."""
    global _default
    _default = parse(setting) if setting is not None else None
    os.environ.setdefault("OMP_WAIT_POLICY", "passive")


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


def auto_threads(work: int, limit: int, idle: int) -> int:
    """The ``auto`` policy: 1 below :data:`AUTO_MIN_WORK`, else ``min(limit, idle)``.

    work: elements plus contact slave nodes of the model; limit: most threads
    numba can run; idle: cores not used by other processes.
    """
    if work < AUTO_MIN_WORK:
        return 1
    return max(1, min(limit, idle))


def model_work(plan) -> int:  # noqa: ANN001 - solver.setup.Assembly
    """Elements plus contact slave nodes of a run's plan (what the threaded kernels
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

    if setting is None:
        return int(numba.get_num_threads()), "as set"
    setting = parse(setting)
    limit = available_threads()
    if setting == "auto":
        idle = idle_cores()
        n = auto_threads(work, limit, idle)
        if work < AUTO_MIN_WORK:
            why = f"auto: small model ({work} elements and contact nodes < {AUTO_MIN_WORK})"
        else:
            why = f"auto: {limit} available, {idle} idle core(s)"
        return n, why
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
