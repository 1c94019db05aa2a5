"""Reading curves and corridors from CSV files for the rating tools.

Accepted files: comma- or semicolon-separated text with one header row of
column names (the delimiter is taken from the header row). With semicolons a
decimal comma is accepted (``1,5``). Lines that are empty or start with ``#``
are skipped; a column may end early (blank cells below its last value).

Every problem is raised as :class:`~hollowbody.errors.UserInputError` with one
message that names the file and, where it applies, the line and column.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hollowbody.errors import UserInputError


@dataclass(frozen=True)
class CsvTable:
    """Header and raw cells of a CSV file (cells stripped, lines 1-based)."""

    path: str
    header: list[str]
    rows: list[tuple[int, list[str]]]
    delimiter: str


def read_table(path: str | Path) -> CsvTable:
    """Read a comma/semicolon CSV file with a header row.

    Raises
    ------
    UserInputError
        Missing or unreadable file, no header, or no data rows.
    """
    p = Path(path)
    name = str(path)
    try:
        text = p.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise UserInputError(f"{name}: file not found") from None
    except IsADirectoryError:
        raise UserInputError(f"{name}: is a directory, not a CSV file") from None
    except UnicodeDecodeError:
        raise UserInputError(f"{name}: not a text file (cannot decode as UTF-8)") from None
    except OSError as err:
        raise UserInputError(f"{name}: cannot read ({err.strerror})") from None
    lines = [(i + 1, line) for i, line in enumerate(text.splitlines())
             if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise UserInputError(f"{name}: file is empty (expected a header row and data)")
    head_no, head = lines[0]
    delimiter = ";" if head.count(";") >= head.count(",") and ";" in head else ","
    header = [c.strip().strip('"') for c in head.split(delimiter)]
    rows = [(no, [c.strip().strip('"') for c in line.split(delimiter)])
            for no, line in lines[1:]]
    if not rows:
        raise UserInputError(f"{name}: no data rows below the header (line {head_no})")
    return CsvTable(name, header, rows, delimiter)


def _column_index(table: CsvTable, spec: str | int) -> int:
    """Index of a column given by name or 1-based number."""
    if isinstance(spec, int) or (isinstance(spec, str) and spec.strip().isdigit()):
        k = int(spec)
        if not 1 <= k <= len(table.header):
            raise UserInputError(f"{table.path}: has {len(table.header)} columns, "
                                 f"no column {k}")
        return k - 1
    names = [h.lower() for h in table.header]
    key = str(spec).strip().lower()
    if key not in names:
        raise UserInputError(f"{table.path}: no column {spec!r} (columns: "
                             f"{', '.join(table.header)})")
    return names.index(key)


def _parse(table: CsvTable, text: str, line: int, col: int) -> float:
    cell = text
    if table.delimiter == ";" and "," in cell and "." not in cell:
        cell = cell.replace(",", ".")
    try:
        value = float(cell)
    except ValueError:
        value = math.nan
        ok = False
    else:
        ok = math.isfinite(value)
    if not ok:
        raise UserInputError(f"{table.path}:{line}: column {table.header[col]!r}: "
                             f"{text!r} is not a finite number")
    return value


def read_columns(path: str | Path, columns: Sequence[str | int]) -> tuple[np.ndarray, ...]:
    """Numeric columns of a CSV file, stopping where the columns end.

    Parameters
    ----------
    path : str or Path
    columns : sequence of str or int
        Column names (case-insensitive) or 1-based numbers.

    Returns
    -------
    tuple of ndarray, each shape (n,)
        One array per requested column; rows where all requested cells are
        blank end the data (trailing blank rows are fine).

    Raises
    ------
    UserInputError
        Missing column, non-numeric cell, a blank cell beside filled ones, a
        filled row after the data ended, or no data.
    """
    table = read_table(path)
    idx = [_column_index(table, c) for c in columns]
    data: list[list[float]] = [[] for _ in idx]
    ended_at = None
    for line, cells in table.rows:
        got = [cells[i] if i < len(cells) else "" for i in idx]
        filled = [g != "" for g in got]
        if not any(filled):
            ended_at = ended_at or line
            continue
        if ended_at is not None:
            raise UserInputError(f"{table.path}:{line}: data after the blank row at line "
                                 f"{ended_at} in column(s) "
                                 f"{', '.join(repr(table.header[i]) for i in idx)}")
        if not all(filled):
            missing = next(i for i, f in zip(idx, filled) if not f)
            raise UserInputError(f"{table.path}:{line}: column {table.header[missing]!r} "
                                 "is blank")
        for k, (i, g) in enumerate(zip(idx, got)):
            data[k].append(_parse(table, g, line, i))
    if not data[0]:
        raise UserInputError(f"{table.path}: no numbers in column(s) "
                             f"{', '.join(repr(table.header[i]) for i in idx)}")
    return tuple(np.array(d, dtype=np.float64) for d in data)


def read_curve(path: str | Path, columns: Sequence[str | int] = (1, 2)) -> tuple[
        np.ndarray, np.ndarray]:
    """Time [ms] and value arrays (shape (n,)) of a curve in a CSV file.

    Parameters
    ----------
    columns : (time column, value column)
        Names or 1-based numbers; default the first two columns.

    Raises
    ------
    UserInputError
        As :func:`read_columns`, plus fewer than 2 samples or time that does not
        increase strictly (naming the line).
    """
    if len(columns) != 2:
        raise UserInputError("a curve needs exactly two columns: time and value")
    t, y = read_columns(path, columns)
    if t.size < 2:
        raise UserInputError(f"{path}: the curve has only {t.size} sample; at least 2 needed")
    steps = np.diff(t)
    if np.any(steps <= 0.0):
        k = int(np.argmax(steps <= 0.0))
        table = read_table(path)
        line = table.rows[k + 1][0]
        raise UserInputError(f"{path}:{line}: time {t[k + 1]:g} does not increase "
                             f"(previous {t[k]:g}); time must increase strictly")
    return t, y


def read_corridor(path: str | Path, name: str = "corridor"):  # noqa: ANN201 - Corridor
    """A corridor from a CSV with a header row: two columns (a closed polygon x, y) or
    three (x, lower, upper). UserInputError naming the file otherwise."""
    from hollowbody.rating.corridors import Corridor

    ncol = len(read_table(path).header)
    try:
        if ncol == 2:
            x, y = read_columns(path, (1, 2))
            return Corridor.from_polygon(x, y, name=name)
        if ncol >= 3:
            x, lo, up = read_columns(path, (1, 2, 3))
            return Corridor(x, lo, up, name=name)
    except ValueError as err:
        raise UserInputError(f"{path}: {err}") from None
    raise UserInputError(f"{path}: a corridor needs 2 columns (polygon x, y) or 3 columns "
                         "(x, lower, upper)")
