"""How many numba threads a run uses, and how they wait.

``threads`` settings: an integer N (at most N threads; numba can only lower
the count it started with, ``NUMBA_NUM_THREADS``, by default the number of
cores), ``"auto"`` (the policy below) or None (leave numba's current count,
e.g. one set with ``numba.set_num_threads`` by the caller).

How waiting threads wait (:func:`wait_policy`), set by every run before numba
starts its threads unless the environment sets ``OMP_WAIT_POLICY`` or
``GOMP_SPINCOUNT``:

- ``short`` (Linux): OpenMP threads spin :data:`SHORT_SPIN` iterations (~0.5 ms)
  before they sleep, so the next parallel loop of the cycle finds them awake
  (~2 us instead of 60-140 us to wake a sleeping one); a run with more than one
  thread is watched by :class:`~hollowbody.solver.contention.ContentionGuard`,
  which drops it to one thread when its threads keep waiting for cores that
  other processes hold;
- ``passive`` (where the guard cannot watch, or ``OMP_WAIT_POLICY=passive``, or a
  threading layer other than OpenMP): waiting threads sleep at once;
- ``spin``: OpenMP's own default or ``OMP_WAIT_POLICY=active`` (long spins).

The ``auto`` policy:

- one thread for a model below :data:`AUTO_MIN_WORK` elements plus contact
  nodes (too small for the threaded kernels to pay their start-up, see the
  ``PARALLEL_MIN`` thresholds of the kernels);
- else every thread numba can run when waiting threads sleep or spin briefly
  (``passive``, ``short``);
- else (``spin``) no more threads than the cores the rest of the machine leaves
  idle (one-minute load average): a spinning thread that shares its core with
  another process holds up the others at every synchronisation, and two threads
  then run several times slower than one.

On the 2-core machine of BENCHMARKS.md: the block test (solid, 40 km/h, 4 ms)
with a second process keeping one core busy took 18.7 s on one thread, 60 s on
two long-spinning threads and 11.3 s on two passive ones; the calibrated hollow
block at 100 km/h on an idle machine took 7.1 s on one thread, 7.8 s on two passive
threads and 6.0 s on two short-spinning ones (medians of 3; contact kernels threaded
from :data:`PER_CYCLE_MIN_ROWS` rows), the solid block test (40 km/h, 20 ms) 27.1 s on
two passive threads and 22.3-23.3 s on two short-spinning ones.

The command line uses ``auto`` (``--threads N|auto``); the Python API keeps
the caller's count unless ``threads`` is given. The count used is recorded in
``summary.json`` (``"threads"``; ``"thread_changes"`` when the guard changed it).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager

from hollowbody.solver import contention

#: Elements plus contact nodes below which ``auto`` runs on one thread.
AUTO_MIN_WORK = 4096
#: GOMP_SPINCOUNT of the ``short`` wait policy: ~0.5 ms of spinning on the machine of
#: BENCHMARKS.md (the gaps between a cycle's parallel loops are shorter).
SHORT_SPIN = 20000
#: Largest GOMP_SPINCOUNT taken as a short spin (the contention guard bounds its cost).
SHORT_SPIN_MAX = 200000
#: Contact passes run their per-cycle kernels threaded from this many active rows when
#: threads spin (hollow block, 100 km/h, 2 short-spinning threads: contact 3.2 s from 128
#: rows, 3.3-3.5 s from 512, 3.6-4.0 s from 2,048, 4.1-4.2 s from 4,096) ...
PER_CYCLE_MIN_ROWS = 256
#: ... and when they sleep (hollowbody.contact.runtime.PARALLEL_MIN_ROWS).
PER_CYCLE_MIN_ROWS_PASSIVE = 4096
#: Setting used by runs that do not give one (see :func:`set_default`).
_default: int | str | None = None


def set_default(setting: int | str | None) -> None:
    """Threads setting of runs that give none (the command line sets ``auto`` or
    ``--threads``); also sets the wait policy (:func:`wait_policy`)."""
    global _default
    _default = parse(setting) if setting is not None else None
    wait_policy()


def _threads_started() -> bool:
    from numba.np.ufunc import parallel

    return bool(getattr(parallel, "_is_initialized", True))


def _spin_count(text: str) -> float | None:
    """libgomp's reading of GOMP_SPINCOUNT (a count, optional k/M/G/T suffix, or
    ``infinite``); None when it is not a count."""
    t = text.strip().lower()
    if t in ("infinite", "infinity"):
        return float("inf")
    scale = {"k": 1e3, "m": 1e6, "g": 1e9, "t": 1e12}.get(t[-1:], 1.0)
    try:
        return float(int(t[:-1] if scale != 1.0 else t)) * scale
    except ValueError:
        return None


def omp_policy(env: dict | None = None) -> str:
    """How libgomp's threads wait under the environment ``env`` (default
    ``os.environ``): ``passive``, ``short`` (a spin count of at most
    :data:`SHORT_SPIN_MAX`) or ``spin``. GOMP_SPINCOUNT takes precedence over
    OMP_WAIT_POLICY, as in libgomp."""
    env = os.environ if env is None else env
    n = _spin_count(env.get("GOMP_SPINCOUNT", ""))
    if n is not None:
        return "passive" if n == 0 else ("short" if n <= SHORT_SPIN_MAX else "spin")
    if env.get("OMP_WAIT_POLICY", "").strip().lower() == "passive":
        return "passive"
    return "spin"


def wait_policy() -> str:
    """How numba's waiting threads wait: ``passive``, ``short`` or ``spin`` (module
    docstring).

    Before numba starts its threads (OpenMP reads its settings at start-up only)
    and unless the environment sets OMP_WAIT_POLICY or GOMP_SPINCOUNT, sets
    ``GOMP_SPINCOUNT`` = :data:`SHORT_SPIN` where the contention guard can watch a
    run (:func:`hollowbody.solver.contention.available`), else
    ``OMP_WAIT_POLICY=passive``.
    """
    import numba

    if _threads_started():
        if numba.threading_layer() != "omp":
            return "passive"  # tbb and workqueue threads sleep while they wait
        return omp_policy()
    if "OMP_WAIT_POLICY" not in os.environ and "GOMP_SPINCOUNT" not in os.environ:
        if contention.available():
            os.environ["GOMP_SPINCOUNT"] = str(SHORT_SPIN)
        else:
            os.environ["OMP_WAIT_POLICY"] = "passive"
    if numba.config.THREADING_LAYER in ("tbb", "workqueue"):
        return "passive"
    return omp_policy()


def per_cycle_min_rows(policy: str | None = None) -> int:
    """Fewest active rows from which a contact pass runs its per-cycle kernels
    threaded under the wait policy (default: :func:`wait_policy`): a thread that
    spins wakes in ~2 us, a sleeping one in 60-140 us."""
    policy = wait_policy() if policy is None else policy
    return PER_CYCLE_MIN_ROWS if policy in ("short", "spin") else PER_CYCLE_MIN_ROWS_PASSIVE


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

    policy = wait_policy()  # before numba starts its threads (the run's first kernel)
    if setting is None:
        return int(numba.get_num_threads()), "as set"
    setting = parse(setting)
    limit = available_threads()
    if setting == "auto":
        if work < AUTO_MIN_WORK:
            return 1, f"auto: small model ({work} elements and contact nodes < {AUTO_MIN_WORK})"
        if policy != "spin":
            return (auto_threads(work, limit, limit),
                    f"auto: {limit} available, {policy} wait")
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
