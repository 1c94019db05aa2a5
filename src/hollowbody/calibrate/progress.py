"""Progress of a calibration: a rich bar on a terminal, one line per generation otherwise.

Shown: generation, evaluations done / planned, best fitness so far, failed
evaluations and an estimate of the time left (from the evaluations run in
this run; cached ones count as done and cost nothing).
"""

from __future__ import annotations

import sys
import time
from typing import TextIO


def _fmt_seconds(s: float | None) -> str:
    if s is None or s != s:
        return "?"
    s = int(round(s))
    if s < 60:
        return f"{s} s"
    if s < 3600:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s // 3600} h {(s % 3600) // 60:02d} min"


class CalibrationProgress:
    """Base reporter: counts evaluations and estimates the time left; prints nothing."""

    def __init__(self) -> None:
        self.planned = 0
        self.done = 0
        self.generation = 0
        self.generations = 0
        self.best: float | None = None
        self.failed = 0
        self._t0 = time.perf_counter()
        self._run_here = 0

    def start(self, planned: int, generations: int) -> None:
        """planned: evaluations over the whole calibration (population x generations)."""
        self.planned = planned
        self.generations = generations
        self._t0 = time.perf_counter()

    def start_generation(self, generation: int, size: int) -> None:
        self.generation = generation

    def evaluated(self, record: dict, cached: bool) -> None:
        """One evaluation finished (or was found in the cache)."""
        self.done += 1
        if not cached:
            self._run_here += 1
        if record.get("status") != "normal termination":
            self.failed += 1
        f = record.get("fitness")
        if record.get("status") == "normal termination" and f is not None:
            self.best = f if self.best is None else min(self.best, f)

    def eta_seconds(self) -> float | None:
        """Seconds left at this run's rate of evaluations run (None: unknown)."""
        if self._run_here == 0:
            return None
        rate = (time.perf_counter() - self._t0) / self._run_here
        return max(0, self.planned - self.done) * rate

    def end_generation(self, stats: dict) -> None:
        pass

    def message(self, text: str) -> None:
        pass

    def close(self) -> None:
        pass


class LineProgress(CalibrationProgress):
    """One line per generation (logs, pipes, CI)."""

    def __init__(self, stream: TextIO | None = None) -> None:
        super().__init__()
        self.stream = stream or sys.stdout

    def end_generation(self, stats: dict) -> None:
        best = stats.get("best")
        mean = stats.get("mean")
        print(f"generation {stats['generation']}/{self.generations}: "
              f"{self.done}/{self.planned} evaluations, best "
              f"{'n/a' if best is None else f'{best:.4g}'}, mean "
              f"{'n/a' if mean is None else f'{mean:.4g}'}, {stats.get('failed', 0)} failed, "
              f"ETA {_fmt_seconds(self.eta_seconds())}", file=self.stream, flush=True)

    def message(self, text: str) -> None:
        print(text, file=self.stream, flush=True)


class RichProgress(CalibrationProgress):
    """A rich progress bar: generation, evaluations done/planned, best fitness, ETA."""

    def __init__(self) -> None:
        super().__init__()
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
        )

        self._bar = Progress(TextColumn("{task.description}"), BarColumn(),
                             MofNCompleteColumn(), TextColumn("evaluations"),
                             TimeElapsedColumn(), TextColumn("ETA {task.fields[eta]}"),
                             transient=False)
        self._task = None

    def _desc(self) -> str:
        best = "n/a" if self.best is None else f"{self.best:.4g}"
        return (f"generation {self.generation}/{self.generations}  best {best}  "
                f"failed {self.failed}")

    def start(self, planned: int, generations: int) -> None:
        super().start(planned, generations)
        self._bar.start()
        self._task = self._bar.add_task(self._desc(), total=planned, eta="?")

    def start_generation(self, generation: int, size: int) -> None:
        super().start_generation(generation, size)
        self._update()

    def evaluated(self, record: dict, cached: bool) -> None:
        super().evaluated(record, cached)
        self._update()

    def _update(self) -> None:
        if self._task is not None:
            self._bar.update(self._task, completed=self.done, description=self._desc(),
                             eta=_fmt_seconds(self.eta_seconds()))

    def message(self, text: str) -> None:
        self._bar.console.print(text)

    def close(self) -> None:
        self._bar.stop()


def make_progress(quiet: bool = False) -> CalibrationProgress:
    """Rich bar on a terminal, lines otherwise, nothing when quiet."""
    if quiet:
        return CalibrationProgress()
    if sys.stdout.isatty():
        return RichProgress()
    return LineProgress()
