"""Compiled field parsers for large bulk blocks (numba, one pass over the bytes).

Used by :mod:`.bulk` when a block has many fields (the numpy path stays for
small blocks, so reading a small deck never needs the compiler). Reals are
converted exactly: the decimal mantissa (up to 15 significant digits) is
scaled by an exact power of ten with one multiplication or division, which is
correctly rounded (Clinger's fast path) and equals Python's ``float``. Fields
outside that path (more digits, large exponents) or malformed ones are
flagged and re-read by the caller in Python.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: Status codes per field.
OK, BLANK, SLOW = 0, 1, 2

_POW10 = np.array([10.0 ** k for k in range(23)])


@njit(cache=True)
def parse_int_fields(mat, start, width, count):  # pragma: no cover - compiled
    """Integers of ``count`` fields of ``width`` from column ``start``.

    mat: (n, w) uint8. Returns values (n, count) int64 and status (n, count)
    int8 (OK, BLANK or SLOW = re-read in Python).
    """
    n = mat.shape[0]
    val = np.zeros((n, count), np.int64)
    status = np.zeros((n, count), np.int8)
    for r in range(n):
        for k in range(count):
            a = start + k * width
            e = a + width
            i = a
            while i < e and mat[r, i] == 32:
                i += 1
            if i == e:
                status[r, k] = BLANK
                continue
            neg = False
            c = mat[r, i]
            if c == 45 or c == 43:
                neg = c == 45
                i += 1
            v = 0
            nd = 0
            while i < e and 48 <= mat[r, i] <= 57:
                v = v * 10 + (mat[r, i] - 48)
                nd += 1
                i += 1
            while i < e and mat[r, i] == 32:
                i += 1
            if i != e or nd == 0 or nd > 18:
                status[r, k] = SLOW
                continue
            val[r, k] = -v if neg else v
    return val, status


@njit(cache=True)
def parse_float_fields(mat, start, width, count, pow10):  # pragma: no cover - compiled
    """Reals of ``count`` fields of ``width`` from column ``start`` (see module doc)."""
    n = mat.shape[0]
    val = np.zeros((n, count), np.float64)
    status = np.zeros((n, count), np.int8)
    for r in range(n):
        for k in range(count):
            a = start + k * width
            e = a + width
            i = a
            while i < e and mat[r, i] == 32:
                i += 1
            if i == e:
                status[r, k] = BLANK
                continue
            neg = False
            c = mat[r, i]
            if c == 45 or c == 43:
                neg = c == 45
                i += 1
            mant = 0
            sig = 0  # significant digits in mant
            nd = 0  # digits seen
            scale = 0  # power of ten to apply
            while i < e and 48 <= mat[r, i] <= 57:
                d = mat[r, i] - 48
                if mant or d:
                    mant = mant * 10 + d
                    sig += 1
                nd += 1
                i += 1
            if i < e and mat[r, i] == 46:
                i += 1
                while i < e and 48 <= mat[r, i] <= 57:
                    d = mat[r, i] - 48
                    if mant or d:
                        mant = mant * 10 + d
                        sig += 1
                    scale -= 1
                    nd += 1
                    i += 1
            bad = nd == 0 or sig > 15
            if i < e and mat[r, i] != 32:
                c = mat[r, i]
                if c == 69 or c == 101 or c == 68 or c == 100:  # E e D d
                    i += 1
                elif not (c == 45 or c == 43):
                    bad = True
                eneg = False
                if i < e and (mat[r, i] == 45 or mat[r, i] == 43):
                    eneg = mat[r, i] == 45
                    i += 1
                ev = 0
                ne = 0
                while i < e and 48 <= mat[r, i] <= 57:
                    if ev < 10000:
                        ev = ev * 10 + (mat[r, i] - 48)
                    ne += 1
                    i += 1
                if ne == 0:
                    bad = True
                scale += -ev if eneg else ev
            while i < e and mat[r, i] == 32:
                i += 1
            if bad or i != e:
                status[r, k] = SLOW
                continue
            if mant == 0:
                x = 0.0
            elif 0 <= scale <= 22:
                x = mant * pow10[scale]
            elif -22 <= scale < 0:
                x = mant / pow10[-scale]
            else:
                status[r, k] = SLOW
                continue
            val[r, k] = -x if neg else x
    return val, status
