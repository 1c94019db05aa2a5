"""What a run is doing: progress over simulated time and the kernel-compile notice.

:class:`Progress` shows the run's simulated time, cycle, time step and
estimated time left:

- on a terminal, a rich progress bar (updated at most four times a second);
  while it is shown, the run's messages to stderr are printed through the
  bar's console, above it, so a warning never breaks the bar;
- when stdout is not a terminal (a log file, a batch job), one line every
  ``interval`` seconds of wall time, ``progress: t=... ms (..%), cycle ...,
  dt=... ms, ETA ...``;
- nothing when ``quiet``.

Progress lines and notices also go to the run log (``messages.log``) through
the ``log`` callable, at the same interval, whatever the display (also when
``quiet``).

:class:`CompileWatch` listens to numba's compile events: the first time a
kernel is compiled (not loaded from numba's cache) it says so, since the first
run of a model can spend tens of seconds there, and it adds up the compile time.
"""

from __future__ import annotations

import logging
import sys
import threading
import time
from collections.abc import Callable

#: Seconds of wall time between progress lines when stdout is not a terminal.
LINE_INTERVAL = 10.0
#: Seconds between updates of the terminal bar.
BAR_INTERVAL = 0.25
#: Notice shown when kernels start compiling.
COMPILE_NOTICE = "compiling kernels for this model (first run only)"

Log = Callable[[str, int], None]


def _clock(seconds: float) -> str:
    """Wall time as ``1h02m``, ``3m05s`` or ``12s``."""
    s = int(round(seconds))
    if s >= 3600:
        return f"{s // 3600}h{(s % 3600) // 60:02d}m"
    if s >= 60:
        return f"{s // 60}m{s % 60:02d}s"
    return f"{s}s"


class Progress:
    """Context manager showing the run's progress over simulated time (ms).

    quiet: show nothing; interval: seconds between lines (and log entries);
    log: ``log(message, level)`` into the run log, or None; tty: whether stdout
    is a terminal (default: ask it).
    """

    def __init__(self, end_time: float, quiet: bool = False, label: str = "run",
                 interval: float = LINE_INTERVAL, log: Log | None = None,
                 tty: bool | None = None) -> None:
        self.end_time = end_time
        self.quiet = quiet
        self.tty = sys.stdout.isatty() if tty is None else tty
        self.enabled = (not quiet) and self.tty  # the rich bar
        self.lines = (not quiet) and not self.tty
        self.label = label
        self.interval = interval
        self.log = log
        self._last = 0.0
        self._last_line = 0.0
        self._wall0: float | None = None
        self._t0 = 0.0
        self._bar = None
        self._task = None
        self._streams: list = []
        self._latest: tuple[float, int, float] | None = None

    def __enter__(self) -> Progress:
        now = time.monotonic()
        self._last_line = now
        if self.enabled:
            from rich.progress import BarColumn, TextColumn, TimeRemainingColumn
            from rich.progress import Progress as RichProgress
            self._bar = RichProgress(
                TextColumn("[bold]{task.description}"), BarColumn(),
                TextColumn("t={task.fields[t]:.4g}/{task.total:.4g} ms"),
                TextColumn("cycle {task.fields[cycle]}"),
                TextColumn("dt={task.fields[dt]:.3e} ms"),
                TimeRemainingColumn(), transient=False)
            self._bar.__enter__()
            self._task = self._bar.add_task(self.label, total=self.end_time, t=0.0,
                                            cycle=0, dt=0.0)
        return self

    def attach(self, logger: logging.Logger) -> None:
        """Print ``logger``'s stderr messages through the bar's console while it is
        shown (rich has redirected ``sys.stderr`` to it; the handler still holds the
        stream it was made with)."""
        if not self.enabled or self._bar is None:
            return
        for h in logger.handlers:
            if type(h) is logging.StreamHandler and h.stream in (sys.__stderr__, sys.__stdout__):
                self._streams.append((h, h.setStream(sys.stderr)))

    def note(self, message: str, level: int = logging.INFO) -> None:
        """A message for the user (display and run log)."""
        if self.log is not None:
            self.log(message, level)
        if self.enabled and self._bar is not None:
            self._bar.console.print(message, markup=False, highlight=False)
        elif self.lines:
            print(message, flush=True)

    def begin(self, t: float) -> None:
        """The loop starts at simulated time ``t``: the ETA counts from here (not
        from the set-up and the kernel compilation)."""
        self._wall0 = time.monotonic()
        self._t0 = t
        self._last_line = self._wall0

    def eta(self, t: float, now: float | None = None) -> float | None:
        """Seconds of wall time left at simulated time ``t`` (None before any
        progress)."""
        if self._wall0 is None:
            return None
        now = time.monotonic() if now is None else now
        done = t - self._t0
        if done <= 0.0:
            return None
        return max(0.0, (self.end_time - t) * (now - self._wall0) / done)

    def line(self, t: float, cycle: int, dt: float) -> str:
        """The progress line at simulated time ``t``."""
        pct = 100.0 * t / self.end_time if self.end_time > 0 else 100.0
        eta = self.eta(t)
        return (f"progress: t={t:.4g}/{self.end_time:.4g} ms ({pct:.0f}%), cycle {cycle}, "
                f"dt={dt:.3e} ms, ETA {'n/a' if eta is None else _clock(eta)}")

    def update(self, t: float, cycle: int, dt: float, force: bool = False) -> None:
        """After each cycle: log a line when due (and print it when stdout is not a
        terminal), redraw the bar."""
        self._latest = (t, cycle, dt)
        now = time.monotonic()
        if force or now - self._last_line >= self.interval:
            self._last_line = now
            text = self.line(t, cycle, dt)
            if self.log is not None:
                self.log(text, logging.INFO)
            if self.lines:
                print(text, flush=True)
        if not self.enabled:
            return
        if not force and now - self._last < BAR_INTERVAL:
            return
        self._last = now
        self._bar.update(self._task, completed=min(t, self.end_time), t=t, cycle=cycle, dt=dt)

    def __exit__(self, *exc: object) -> None:
        for h, old in reversed(self._streams):
            h.setStream(old)
        self._streams.clear()
        if self.enabled and self._bar is not None:
            if self._latest is not None:  # the bar ends where the run ended
                t, cycle, dt = self._latest
                self._bar.update(self._task, completed=min(t, self.end_time), t=t,
                                 cycle=cycle, dt=dt)
            self._bar.__exit__(None, None, None)


class CompileWatch:
    """Context manager listening to numba's compile events.

    on_first: called when the first kernel inside the block starts compiling;
    ``seconds``: wall time spent compiling (outermost compilations only, so a
    kernel and the functions it calls count once); ``count``: kernels compiled;
    both start from the given values (what an earlier watch counted).
    """

    def __init__(self, on_first: Callable[[], None] | None = None, seconds: float = 0.0,
                 count: int = 0) -> None:
        self.on_first = on_first
        self.seconds = seconds
        self.count = count
        self._depth = 0
        self._t0 = 0.0
        self._cm = None
        self._thread = 0
        self._seen = False

    @property
    def compiled(self) -> bool:
        """Whether anything was compiled inside the block."""
        return self.count > 0

    def __enter__(self) -> CompileWatch:
        from numba.core import event

        watch = self
        self._thread = threading.get_ident()

        class _Listener(event.Listener):  # listeners are process-wide: this thread only
            def on_start(self, ev: event.Event) -> None:
                if threading.get_ident() == watch._thread:
                    watch._start()

            def on_end(self, ev: event.Event) -> None:
                if threading.get_ident() == watch._thread:
                    watch._end()

        self._cm = event.install_listener("numba:compile", _Listener())
        self._cm.__enter__()
        return self

    def _start(self) -> None:
        if self._depth == 0:
            self._t0 = time.perf_counter()
            self.count += 1
            if not self._seen and self.on_first is not None:
                self.on_first()
            self._seen = True
        self._depth += 1

    def _end(self) -> None:
        self._depth -= 1
        if self._depth == 0:
            self.seconds += time.perf_counter() - self._t0

    def __exit__(self, *exc: object) -> None:
        if self._cm is not None:
            self._cm.__exit__(None, None, None)
            self._cm = None
