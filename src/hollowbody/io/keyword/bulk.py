"""Vectorised parsing and formatting of bulk blocks (*NODE, *ELEMENT_...).

The data lines of a block become one C-contiguous ``(rows, width)`` byte
matrix (space padded; a single reshape when every line has the same length,
as writers produce), and fixed-width fields are parsed column-wise with
numpy: 8-column integers as uint64 words (SWAR digit arithmetic), other
integers by Horner's rule over the digit columns, reals with
``astype(float64)``. Rows that the fast path cannot read (free format with
commas, left-justified or signed integers, Fortran ``D`` exponents) are
re-read one by one, which is also how a bad number is located to its line.
Comment (``$``) and blank lines are skipped.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.io.keyword.cards import bad_number, format_float, parse_float, parse_int

_SPACE, _DOLLAR, _COMMA = 32, 36, 44
_SPACES = np.uint64(0x2020202020202020)


@dataclass
class RowTable:
    """Data rows of a bulk block.

    mat: (n, width) uint8 space-padded text, C-contiguous, width a multiple
    of 8; lines: (n,) int64 1-based file line of each row; free: {row: text}
    rows in free format (commas).
    """

    mat: np.ndarray
    lines: np.ndarray
    free: dict[int, str]
    file: str
    keyword: str

    @property
    def n(self) -> int:
        return int(self.mat.shape[0])

    def text(self, row: int) -> str:
        if row in self.free:
            return self.free[row]
        return self.mat[row].tobytes().decode("latin-1")

    def take(self, rows: slice) -> RowTable:
        """Sub-table of ``rows`` (e.g. every second row of a two-card format)."""
        idx = np.arange(self.n)[rows]  # increasing
        free = {}
        for r, t in self.free.items():
            k = int(np.searchsorted(idx, r))
            if k < idx.size and idx[k] == r:
                free[k] = t
        return RowTable(np.ascontiguousarray(self.mat[rows]), self.lines[rows], free,
                        self.file, self.keyword)


def row_table(block, width: int) -> RowTable:  # block: hollowbody.io.keyword.base.Block
    """The data rows of a bulk block as a space-padded matrix of >= ``width`` columns.

    Reads straight from the file buffer: when every line has the same length
    the rows are one reshape of it (a single copy makes them contiguous).
    """
    data, start, end, skip = block.data, block.begin, block.end, 0
    file, keyword = block.file, block.name
    if data.find(b"\r", start, end) >= 0:
        data = data[start:end].replace(b"\r", b"")
        start, end = 0, len(data)
    while start < end and data[start] in (_DOLLAR, 10):
        nxt = data.find(b"\n", start, end)
        start = end if nxt < 0 else nxt + 1
        skip += 1
    while end > start and data[end - 1] == 10:
        end -= 1
    first_line = block.body_line + skip
    w8 = -(-width // 8) * 8
    eol = data.find(b"\n", start, end)
    length = (end if eol < 0 else eol) - start
    n = (end - start + 1) // (length + 1) if end > start else 0
    uniform = length > 0 and end < len(data) and n * (length + 1) == end - start + 1 and \
        data.count(b"\n", start, end) == n - 1
    if uniform:
        rows = np.frombuffer(data, dtype=np.uint8, count=n * (length + 1),
                             offset=start).reshape(n, length + 1)
        uniform = bool((rows[:, length] == 10).all()) and \
            not bool((rows[:, 0] == _DOLLAR).any())
    if uniform:
        lines = first_line + np.arange(n, dtype=np.int64)
        if length >= w8:
            mat = np.ascontiguousarray(rows[:, :w8])
        else:
            mat = np.full((n, w8), _SPACE, dtype=np.uint8)
            mat[:, :length] = rows[:, :length]
        free: dict[int, str] = {}
        if data.find(b",", start, end) >= 0:
            commas = np.flatnonzero(rows[:, :length] == _COMMA) // length
            for r in np.unique(commas).tolist():
                free[r] = rows[r, :length].tobytes().decode("latin-1")
        return RowTable(mat, lines, free, file, keyword)
    body = data[start:end]
    split = body.split(b"\n") if body else []
    keep = [k for k, r in enumerate(split) if r[:1] != b"$" and r.strip()]
    kept = [split[k] for k in keep]
    buf = b"".join(r[:w8].ljust(w8) for r in kept)
    mat = np.frombuffer(buf, dtype=np.uint8).reshape(len(kept), w8).copy()
    lines = first_line + np.array(keep, dtype=np.int64)
    free = {r: t.decode("latin-1") for r, t in enumerate(kept) if b"," in t} \
        if b"," in body else {}
    return RowTable(mat, lines, free, file, keyword)


def _free_field(t: RowTable, row: int, index: int) -> str:
    parts = t.free[row].split(",")
    return parts[index].strip() if index < len(parts) else ""


def _slow_value(t: RowTable, row: int, text: str, name: str, kind: str) -> float | int:
    try:
        return parse_int(text) if kind == "i" else parse_float(text)
    except ValueError:
        raise bad_number(text, name, kind, t.file, int(t.lines[row]), t.keyword) from None


def _swar_ints(words: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Values of right-justified 8-column integer fields given as uint64 words.

    Returns (values int64, ok bool): ``ok`` is False where the field is not
    blanks followed by digits (sign, left-justified, other characters).
    """
    u = np.uint64
    m7f, m80 = u(0x7F7F7F7F7F7F7F7F), u(0x8080808080808080)

    def zero_bytes(y: np.ndarray) -> np.ndarray:  # 0x80 where a byte of y is 0
        return ~(((y & m7f) + m7f) | y | m7f)

    space = zero_bytes(words ^ _SPACES)
    nib = ((words ^ u(0x3030303030303030)) & u(0xF0F0F0F0F0F0F0F0)) | \
        (((words & u(0x0F0F0F0F0F0F0F0F)) + u(0x0606060606060606)) & u(0x1010101010101010))
    digit = zero_bytes(nib)
    prefix = (space >> u(7)) * u(0xFF)
    ok = ((space | digit) == m80) & ((prefix & (prefix + u(1))) == 0)
    v = (words | u(0x1010101010101010)) - u(0x3030303030303030)
    v = ((v & u(0x0F0F0F0F0F0F0F0F)) * u(2561)) >> u(8)
    v = ((v & u(0x00FF00FF00FF00FF)) * u(6553601)) >> u(16)
    v = ((v & u(0x0000FFFF0000FFFF)) * u(42949672960001)) >> u(32)
    return v.astype(np.int64), ok


def _horner_ints(sub: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """As :func:`_swar_ints` for fields of any width: sub (n, count, width) bytes."""
    digit = sub - np.uint8(48)
    isdig = digit < 10
    isspace = sub == _SPACE
    ok = (isdig | isspace).all(axis=2)
    if sub.shape[2] > 1:
        ok &= ~(isdig[:, :, :-1] & isspace[:, :, 1:]).any(axis=2)
    dz = np.where(isdig, digit, np.uint8(0))
    val = np.zeros(sub.shape[:2], dtype=np.int64)
    for c in range(sub.shape[2]):
        val *= 10
        val += dz[:, :, c]
    return val, ok


#: Blocks with at least this many fields use the compiled parsers of
#: :mod:`.fastparse` (smaller ones stay in numpy: no compiler needed).
FAST_MIN_FIELDS = 50_000


def _finish(t: RowTable, val: np.ndarray, slow: np.ndarray, blank: np.ndarray, start: int,
            width: int, names: list[str], first_index: int, default: float, kind: str) -> None:
    """Blank defaults, Python re-reads of ``slow`` fields and free-format rows, in place."""
    if default and blank.any():
        val[blank] = default
    if slow.any():
        for r, k in zip(*np.nonzero(slow)):
            if int(r) in t.free:
                continue
            a = start + width * int(k)
            text = t.mat[r, a:a + width].tobytes().decode("latin-1")
            val[r, k] = _slow_value(t, int(r), text, names[k], kind)
    for r in t.free:
        for k in range(val.shape[1]):
            s = _free_field(t, r, first_index + k)
            val[r, k] = _slow_value(t, r, s, names[k], kind) if s else default


def parse_ints(t: RowTable, start: int, width: int, count: int, names: list[str],
               first_index: int, default: int = 0) -> np.ndarray:
    """``count`` adjacent integer fields of ``width`` from column ``start``: (n, count) int64.

    ``names`` name the fields (for messages); ``first_index`` is the position
    of the first one among the card's fields (for free-format rows). Blank
    fields give ``default``.
    """
    n = t.n
    if n * count >= FAST_MIN_FIELDS:
        from hollowbody.io.keyword import fastparse as fp

        val, status = fp.parse_int_fields(t.mat, start, width, count)
        slow, blank = status == fp.SLOW, status == fp.BLANK
    elif width == 8 and start % 8 == 0:
        words = t.mat.view(np.uint64)[:, start // 8: start // 8 + count]
        val, ok = _swar_ints(words)
        slow, blank = ~ok, words == _SPACES
    else:
        sub = t.mat[:, start:start + width * count].reshape(n, count, width)
        val, ok = _horner_ints(sub)
        slow, blank = ~ok, (sub == _SPACE).all(axis=2)
    _finish(t, val, slow, blank, start, width, names, first_index, default, "i")
    return val


def parse_floats(t: RowTable, start: int, width: int, count: int, names: list[str],
                 first_index: int, default: float = 0.0) -> np.ndarray:
    """``count`` adjacent real fields of ``width`` from column ``start``: (n, count) float64."""
    n = t.n
    if n * count >= FAST_MIN_FIELDS:
        from hollowbody.io.keyword import fastparse as fp

        val, status = fp.parse_float_fields(t.mat, start, width, count, fp._POW10)
        _finish(t, val, status == fp.SLOW, status == fp.BLANK, start, width, names,
                first_index, default, "f")
        return val
    sub = np.ascontiguousarray(t.mat[:, start:start + width * count])
    if width % 8 == 0:
        blank = (sub.view(np.uint64).reshape(n, count, width // 8) == _SPACES).all(axis=2)
    else:
        blank = (sub.reshape(n, count, width) == _SPACE).all(axis=2)
    strs = sub.view(f"S{width}").reshape(n, count)
    if blank.any():
        strs = strs.copy()
        strs[blank] = b"0"
    slow = np.zeros((n, count), dtype=bool)
    try:
        val = strs.astype(np.float64)
    except ValueError:
        val = np.zeros((n, count))
        for r in range(n):
            for k in range(count):
                try:
                    val[r, k] = float(strs[r, k])
                except ValueError:
                    slow[r, k] = True
    _finish(t, val, slow, blank, start, width, names, first_index, default, "f")
    return val


# ---------------------------------------------------------------------------
# Writing


def float_texts(values: np.ndarray, width: int) -> list[str]:
    """Right-justified texts of ``values`` (any shape, flattened) fitting ``width``."""
    flat = np.asarray(values, dtype=np.float64).ravel().tolist()
    return [s.rjust(width) if len(s) <= width and s[-1] != "n" else format_float(v, width)
            for s, v in zip(map(repr, flat), flat)]


def int_texts(values: np.ndarray, width: int) -> list[str]:
    out = [str(v).rjust(width) for v in np.asarray(values, dtype=np.int64).ravel().tolist()]
    if out and max(len(s) for s in out) > width:
        raise ValueError(f"an id does not fit in {width} columns (use long format)")
    return out


def int_rows(values: np.ndarray, width: int) -> list[str]:
    """One line per row of the (n, k) integer array, ``k`` fields of ``width``."""
    a = np.asarray(values, dtype=np.int64)
    if a.size and (int(a.max()) >= 10 ** width or int(a.min()) <= -(10 ** (width - 1))):
        raise ValueError(f"an id does not fit in {width} columns (use long format)")
    if a.size == 0 or int(a.min()) < 0 or width > 18:
        fmt = f"%{width}d" * a.shape[1]
        return [fmt % tuple(r) for r in a.tolist()]
    n, k = a.shape
    out = np.empty((n, k * width + 1), dtype=np.uint8)
    out[:, -1] = 10
    cols = out[:, :-1].reshape(n, k, width)
    for j in range(width):  # digit j from the left, leading zeros as blanks
        p = 10 ** (width - 1 - j)
        cols[:, :, j] = np.where((a < p) & (j < width - 1), 32, 48 + (a // p) % 10)
    return out.tobytes().decode("ascii").split("\n")[:n]


def join_rows(columns: list[list[str]]) -> list[str]:
    """Lines from per-column text lists (all of equal length)."""
    return ["".join(parts).rstrip() for parts in zip(*columns)]
