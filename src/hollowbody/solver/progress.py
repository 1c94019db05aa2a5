"""Progress display: simulated time, cycle, time step and ETA on a terminal.

Silent when stdout is not a TTY or when ``quiet``; updates at most a few
times per second so it costs nothing measurable.
"""

from __future__ import annotations

import sys
import time


class Progress:
    """Context manager showing a rich progress bar over simulated time (ms)."""

    def __init__(self, end_time: float, quiet: bool = False, label: str = "run") -> None:
        self.end_time = end_time
        self.enabled = (not quiet) and sys.stdout.isatty()
        self.label = label
        self._last = 0.0
        self._bar = None
        self._task = None

    def __enter__(self) -> Progress:
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

    def update(self, t: float, cycle: int, dt: float, force: bool = False) -> None:
        if not self.enabled:
            return
        now = time.monotonic()
        if not force and now - self._last < 0.25:
            return
        self._last = now
        self._bar.update(self._task, completed=min(t, self.end_time), t=t, cycle=cycle, dt=dt)

    def __exit__(self, *exc: object) -> None:
        if self.enabled and self._bar is not None:
            self._bar.__exit__(None, None, None)
