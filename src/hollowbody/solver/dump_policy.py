"""When a run writes its restart files, and how many it keeps.

LS-DYNA writes a restart file every CYCL cycles (*DATABASE_BINARY_D3DUMP) and
keeps them all; its running restart files (*DATABASE_BINARY_RUNRSF) are
overwritten in turn. A run of many hours wants something in between: a
restart file every few minutes of wall time, whatever the time step does, and
only the newest few kept on disk (a hollow body model's file is tens of MB).
:class:`DumpPolicy` holds the three rules (cycles, minutes of wall time,
files kept) and whether a run that ends normally writes one more, so that it
can be continued to a later end time.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from hollowbody.solver import restart as rs


@dataclass
class DumpPolicy:
    """Restart files of one run.

    cycles: a restart file every N cycles (0: not by cycles);
    minutes: a restart file every M minutes of wall time (0: not by time);
    keep: after each new file, delete the older ``d3dumpNN`` files of the run
    folder but the newest K (0: keep all, LS-DYNA's way);
    at_end: a run that ends normally writes one more (to be continued later).
    """

    cycles: int = 0
    minutes: float = 0.0
    keep: int = 0
    at_end: bool = False
    _last: float = field(default_factory=time.perf_counter, repr=False)

    def __post_init__(self) -> None:
        if self.cycles < 0:
            raise ValueError(f"cycles between restart files must be >= 0 (got {self.cycles})")
        if not self.minutes >= 0.0:
            raise ValueError(f"minutes between restart files must be >= 0 (got {self.minutes})")
        if self.keep < 0:
            raise ValueError(f"restart files kept must be >= 0 (got {self.keep})")

    @property
    def active(self) -> bool:
        """Writes restart files while the run goes on."""
        return self.cycles > 0 or self.minutes > 0.0

    def due(self, cycle: int) -> bool:
        """A restart file is due after ``cycle``."""
        if self.cycles > 0 and cycle % self.cycles == 0:
            return True
        return self.minutes > 0.0 and time.perf_counter() - self._last >= 60.0 * self.minutes

    def written(self) -> None:
        """A restart file was just written: the wall-time interval starts again."""
        self._last = time.perf_counter()

    def kept_after(self, folder: Path, new: str) -> set[str] | None:
        """Names of the restart files of ``folder`` that :meth:`prune` keeps once ``new``
        is written (None: all are kept)."""
        if self.keep <= 0:
            return None
        names = [p.name for p in rs.dump_files(folder) if p.name != new] + [new]
        return set(names[-self.keep:])

    def prune(self, folder: Path) -> list[str]:
        """Delete the restart files of ``folder`` that :meth:`kept_after` its newest
        does not keep; the names deleted."""
        files = rs.dump_files(folder)
        kept = self.kept_after(folder, files[-1].name) if files else None
        if kept is None:
            return []
        gone = []
        for p in (f for f in files if f.name not in kept):
            try:
                p.unlink()
            except OSError:
                continue
            gone.append(p.name)
        return gone
