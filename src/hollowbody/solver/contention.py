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
in a row above :data:`THRESHOLD` the run drops to one thread (its results then
differ from an undisturbed run's in round-off only). With one thread the share no
longer tells whether a second core is free, so the run tries its threads again
after :data:`RETRY_SECONDS` of wall time, for one window: when they no longer wait
it keeps them, else it drops again and waits twice as long before the next try (up
to :data:`RETRY_MAX_SECONDS`). Kept changes are said in the log and listed in
``summary.json`` (``thread_changes``); a long run on a machine whose other load
comes and goes follows it.

Linux only (:func:`available`); elsewhere runs keep the passive wait policy.
"""

from __future__ import annotations

import math
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
#: Wall seconds on one thread before the run tries its threads again ...
RETRY_SECONDS = 30.0
#: ... doubled after each try that found them still waiting, up to this.
RETRY_MAX_SECONDS = 480.0

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
    return not math.isnan(run_delay())


class ContentionGuard:
    """Drops a threaded run to one thread while its threads keep waiting for cores,
    and gives them back when cores are free again (module docstring).

    threads: the run's thread count (the guard does nothing below 2);
    set_threads: called with the new count (default ``numba.set_num_threads``);
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
        if math.isnan(self._d0):  # not reported here
            self.active = False
        self._run = 0
        #: threads the run uses now
        self.current = self.threads
        self._probing = False
        self._retry = RETRY_SECONDS
        self._next_try = 0.0
        #: waiting share of each window measured so far (the last :data:`WINDOWS`)
        self.shares: list[float] = []
        #: tries that found the threads still waiting
        self.failed_tries = 0

    def _use(self, n: int) -> None:
        self.current = n
        if self._set is None:
            import numba

            numba.set_num_threads(n)
        else:
            self._set(n)

    def check(self) -> tuple[int, float] | None:
        """Called once per cycle (cheap between windows). Returns (new thread count,
        waiting share of the window that decided it) when the run has just dropped to
        one thread or got its threads back for good; None otherwise (also while a try
        is under way, and when a try fails: the count goes back to one silently)."""
        if not self.active:
            return None
        w = self._clock()
        if self.current == 1:  # waiting for the next try
            if w < self._next_try:
                return None
            self._use(self.threads)
            self._probing = True
            self._w0, self._d0 = w, self._delay()
            return None
        if w - self._w0 < WINDOW_SECONDS:
            return None
        d = self._delay()
        share = (d - self._d0) / ((w - self._w0) * self.current)
        self._w0, self._d0 = w, d
        self.shares = (self.shares + [share])[-WINDOWS:]
        if self._probing:
            self._probing = False
            if share > THRESHOLD:  # still busy: one thread again, wait longer
                self.failed_tries += 1
                self._retry = min(2.0 * self._retry, RETRY_MAX_SECONDS)
                self._use(1)
                self._next_try = w + self._retry
                return None
            self._retry = RETRY_SECONDS
            self._run = 0
            return self.threads, share
        self._run = self._run + 1 if share > THRESHOLD else 0
        if self._run < WINDOWS:
            return None
        self._run = 0
        self._use(1)
        self._next_try = w + self._retry
        return 1, share
