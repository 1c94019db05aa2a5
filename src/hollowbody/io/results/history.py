"""History files (LS-DYNA database names, CSV with units in the header).

Each file is opened at the start of a run and flushed after every row, so a
run that dies (error termination, Ctrl-C, a crash) keeps every row written
before. Column names carry their unit in brackets, e.g. ``time [ms]``.
"""

from __future__ import annotations

import csv
from pathlib import Path
from typing import IO

import numpy as np


class HistoryWriter:
    """One CSV history: ``write(row)`` appends and flushes.

    columns: names with units, e.g. ``["time [ms]", "fz [kN]"]``.
    resume: (byte offset, rows) of :meth:`position` saved earlier: the file is
    cut there and written on (a resumed run), instead of started anew.
    """

    def __init__(self, path: Path, columns: list[str],
                 resume: tuple[int, int] | None = None) -> None:
        self.path = Path(path)
        self.columns = columns
        if resume is not None and self.path.is_file():
            offset, rows = resume
            fh = open(self.path, "r+", newline="")
            fh.truncate(offset)
            fh.seek(offset)
            self._fh: IO[str] | None = fh
            self._csv = csv.writer(fh)
            self.rows = rows
            return
        self._fh = open(self.path, "w", newline="")
        self._csv = csv.writer(self._fh)
        self._csv.writerow(columns)
        self._fh.flush()
        self.rows = 0

    def position(self) -> tuple[int, int]:
        """(byte offset of the end, rows written): where a resumed run goes on."""
        return (self._fh.tell() if self._fh is not None else 0, self.rows)

    def write(self, row: list[float | int | str]) -> None:
        if self._fh is None:
            return
        self._csv.writerow([_fmt(v) for v in row])
        self._fh.flush()
        self.rows += 1

    def close(self) -> None:
        if self._fh is not None:
            self._fh.close()
            self._fh = None


def _fmt(v: object) -> str:
    if isinstance(v, (float, np.floating)):
        return f"{float(v):.9g}"
    return str(v)


def read_history(path: str | Path) -> dict[str, np.ndarray]:
    """Read a history CSV written by :class:`HistoryWriter` into columns.

    Returns {column name with unit: (rows,) array}; numeric columns as
    float64, others as str.
    """
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    out: dict[str, np.ndarray] = {}
    for j, name in enumerate(header):
        col = [r[j] for r in body]
        try:
            out[name] = np.array(col, dtype=np.float64)
        except ValueError:
            out[name] = np.array(col, dtype=str)
    return out
