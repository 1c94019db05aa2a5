"""Contention guard: a threaded run that has to wait for cores goes on with one thread.

numba's OpenMP threads wait for the next parallel loop by spinning for a short
while (``GOMP_SPINCOUNT``, the ``short`` policy of :mod:`hollowbody.solver.threads`)
before they sleep: a thread that spins wakes in ~2 us instead of 60-140 us, which
is what lets the per-cycle kernels of a contact (a fraction of a millisecond each)
gain from a second thread. On a machine whose cores are taken by other processes
the same spinning hurts: a thread that spins holds a core another thread of the run
needs, and every synchronisation waits for the descheduled one (the hollow block at
100 km/h with another process keeping one of two cores busy: 7.1 s on one thread,
7.4 s on two sleeping threads, 9.4-9.7 s on two threads spinning 20,000 iterations,
20-23 s with 200,000).

The guard watches what the kernel reports: the time the run's threads spent
runnable but waiting for a core (``/proc/self/task/*/schedstat``, second field,
ns), per second of wall time and per thread. On an idle machine that share is
1-3 %; with a second process on one of two cores it is 23 % (sleeping threads)
to 45 % (spinning ones). After :data:`WINDOWS` windows of :data:`WINDOW_SECONDS`
in a row above :data:`THRESHOLD` the run drops to one thread for the rest of the
run (its results then differ from an undisturbed run's in round-off only) and says
so in the log and ``summary.json`` (``threads_dropped``). It never goes back up: with
one thread the share no longer tells whether a second core is free.

Linux only (:func:`available`); elsewhere runs keep the passive wait policy.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

#: Seconds of wall time per measurement window.
WINDOW_SECONDS = 0.5
#: Share of each thread's wall time spent waiting for a core above which a window counts
#: as contended (idle machine: 0.01-0.03; one of two cores busy: 0.23-0.45).
THRESHOLD = 0.15
#: Contended windows in a row before the run drops to one thread (a short burst of
#: another process, e.g. a compile, does not count).
WINDOWS = 2

_TASKS = "/proc/self/task"


def run_delay() -> float:
    """Seconds this process's threads have spent runnable but waiting for a core
    (sum over its tasks of the second field of ``/proc/self/task/*/schedstat``);
    NaN when the kernel does not report it."""
    total = 0
    try:
        tids = os.listdir(_TASKS)
    except OSError:
        return float("nan")
    seen = False
    for tid in tids:
        try:
            with open(f"{_TASKS}/{tid}/schedstat") as f:
                total += int(f.read().split()[1])
            seen = True
        except (OSError, IndexError, ValueError):
            continue  # a task that ended meanwhile
    return total * 1.0e-9 if seen else float("nan")


def available() -> bool:
    """Whether this platform reports the run delay (:func:`run_delay`)."""
    return run_delay() == run_delay()  # not NaN


class ContentionGuard:
    """Drops a threaded run to one thread when its threads keep waiting for cores.

    threads: the run's thread count (the guard does nothing below 2);
    set_threads: called with 1 when the run drops (``numba.set_num_threads``);
    delay, clock: seconds waited (:func:`run_delay`) and wall seconds
    (``time.perf_counter``), replaceable for tests.
    """

    def __init__(self, threads: int, set_threads: Callable[[int], None] | None = None,
                 delay: Callable[[], float] = run_delay,
                 clock: Callable[[], float] = time.perf_counter) -> None:
        self.threads = int(threads)
        self.active = self.threads > 1
        self._set = set_threads
        self._delay = delay
        self._clock = clock
        self._w0 = clock()
        self._d0 = delay() if self.active else 0.0
        if self._d0 != self._d0:  # NaN: not reported here
            self.active = False
        self._run = 0
        #: waiting share of each window measured so far (the last :data:`WINDOWS`)
        self.shares: list[float] = []
        #: (share that made the run drop, or None)
        self.dropped: float | None = None

    def check(self) -> float | None:
        """Called once per cycle (cheap between windows). Returns the waiting share
        when the run has just dropped to one thread, else None."""
        if not self.active:
            return None
        w = self._clock()
        if w - self._w0 < WINDOW_SECONDS:
            return None
        d = self._delay()
        share = (d - self._d0) / ((w - self._w0) * self.threads)
        self._w0, self._d0 = w, d
        self.shares = (self.shares + [share])[-WINDOWS:]
        self._run = self._run + 1 if share > THRESHOLD else 0
        if self._run < WINDOWS:
            return None
        self.active = False
        self.dropped = share
        if self._set is None:
            import numba

            numba.set_num_threads(1)
        else:
            self._set(1)
        return share
