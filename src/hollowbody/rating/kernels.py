"""Numba kernels of the curve ratings: sliding cross-correlation and banded DTW.

Both are O(n * w) loops (``w`` = number of lags or band width) that dominate the
cost of rating long curves; everything else is vectorised numpy.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

#: Work (samples x lags) above which the cross-correlation runs in parallel
#: threads; below it the thread start-up costs more than it saves.
PARALLEL_WORK = 4_000_000


@njit(cache=True)
def _prefix_and_scale(x: np.ndarray, y: np.ndarray):  # pragma: no cover - jit
    n = x.size
    px = np.zeros(n + 1)
    py = np.zeros(n + 1)
    scale_x = 0.0
    scale_y = 0.0
    for i in range(n):
        px[i + 1] = px[i] + x[i]
        py[i + 1] = py[i] + y[i]
        scale_x = max(scale_x, abs(x[i]))
        scale_y = max(scale_y, abs(y[i]))
    return px, py, scale_x, scale_y


@njit(cache=True)
def _corr_at_lag(x, y, px, py, scale_x, scale_y, lag, centred):  # pragma: no cover - jit
    """Correlation of the overlapping parts at one lag (see sliding_correlation)."""
    n = x.size
    x0 = 0 if lag >= 0 else -lag
    y0 = lag if lag >= 0 else 0
    m = n - abs(lag)
    mx = 0.0
    my = 0.0
    if centred:
        mx = (px[x0 + m] - px[x0]) / m
        my = (py[y0 + m] - py[y0]) / m
    sxy = 0.0
    sxx = 0.0
    syy = 0.0
    for i in range(m):
        a = x[x0 + i] - mx
        b = y[y0 + i] - my
        sxy += a * b
        sxx += a * a
        syy += b * b
    # a part that is constant up to round-off has no defined correlation
    if sxx <= (1e-12 * scale_x) ** 2 * m or syy <= (1e-12 * scale_y) ** 2 * m:
        return np.nan
    r = sxy / math.sqrt(sxx * syy)
    return min(1.0, max(-1.0, r))


@njit(cache=True)
def _sliding_serial(x, y, max_lag, centred):  # pragma: no cover - jit
    px, py, sx, sy = _prefix_and_scale(x, y)
    out = np.empty(2 * max_lag + 1)
    for k in range(2 * max_lag + 1):
        out[k] = _corr_at_lag(x, y, px, py, sx, sy, k - max_lag, centred)
    return out


@njit(cache=True, parallel=True)
def _sliding_parallel(x, y, max_lag, centred):  # pragma: no cover - jit
    px, py, sx, sy = _prefix_and_scale(x, y)
    out = np.empty(2 * max_lag + 1)
    for k in prange(2 * max_lag + 1):
        out[k] = _corr_at_lag(x, y, px, py, sx, sy, k - max_lag, centred)
    return out


def sliding_correlation(x: np.ndarray, y: np.ndarray, max_lag: int,
                        centred: bool) -> np.ndarray:
    """Normalised cross-correlation of ``x`` and ``y`` for every lag.

    Parameters
    ----------
    x, y : ndarray, shape (n,), float64
        Equally sampled signals (reference ``x``, candidate ``y``).
    max_lag : int
        Largest shift in samples, ``0 <= max_lag <= n - 2``.
    centred : bool
        True: Pearson correlation of the overlapping parts (means removed,
        ISO/TS 18571). False: uncentred normalised cross-correlation
        ``sum(x*y) / sqrt(sum(x^2) * sum(y^2))`` (CORA).

    Returns
    -------
    ndarray, shape (2 * max_lag + 1,)
        Entry ``k`` is the correlation at lag ``k - max_lag``; lag ``m > 0``
        pairs ``x[i]`` with ``y[i + m]`` (candidate late by ``m`` samples).
        NaN where a part has zero variance (centred) or zero energy (uncentred).
    """
    x = np.ascontiguousarray(x, dtype=np.float64)
    y = np.ascontiguousarray(y, dtype=np.float64)
    if not 0 <= max_lag <= x.size - 2 or y.size != x.size:
        raise ValueError("sliding_correlation: need equal lengths n and 0 <= max_lag <= n-2")
    if x.size * (2 * max_lag + 1) >= PARALLEL_WORK:
        return _sliding_parallel(x, y, max_lag, centred)
    return _sliding_serial(x, y, max_lag, centred)


@njit(cache=True)
def dtw_band_path(x: np.ndarray, y: np.ndarray,
                  radius: int) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover - jit
    """Dynamic time warping path of two equally long signals in a Sakoe-Chiba band.

    Local cost ``(x[i] - y[j])**2``; steps (1, 0), (0, 1) and (1, 1), each
    adding the local cost of the cell it enters once (no slope weighting);
    the path runs from (0, 0) to (n-1, n-1) through cells with
    ``|i - j| < radius``. On equal cumulative costs the diagonal predecessor
    wins, then (i-1, j), then (i, j-1).

    Parameters
    ----------
    x, y : ndarray, shape (n,), float64
    radius : int
        Band radius, ``>= 1`` (1 allows only the diagonal).

    Returns
    -------
    ix, iy : ndarray, shape (p,), int64
        Indices into ``x`` and ``y`` along the warping path, ``n <= p <= 2n-1``.

    Notes
    -----
    Time O(n * radius); memory ``n * (2 * radius - 1)`` bytes for the step
    directions (20 MB for n = 10 000 and a 10 % band).
    """
    n = x.size
    w = 2 * radius - 1          # cells per row; column c <-> j = i + c - (radius - 1)
    off = radius - 1
    inf = np.inf
    prev = np.full(w, inf)
    cur = np.full(w, inf)
    step = np.zeros((n, w), dtype=np.int8)  # 0 diagonal, 1 from (i-1, j), 2 from (i, j-1)
    for i in range(n):
        c_lo = max(0, off - i)          # first column with j >= 0
        c_hi = min(w, n - i + off)      # one past the last column with j < n
        for c in range(c_lo):
            cur[c] = inf
        for c in range(c_hi, w):
            cur[c] = inf
        for c in range(c_lo, c_hi):
            j = i + c - off
            d = x[i] - y[j]
            d = d * d
            if i == 0 and j == 0:
                cur[c] = d
                continue
            best = inf
            move = 0
            if i > 0 and j > 0 and prev[c] < best:
                best = prev[c]
                move = 0
            if i > 0 and c + 1 < w and prev[c + 1] < best:
                best = prev[c + 1]
                move = 1
            if j > 0 and c > 0 and cur[c - 1] < best:
                best = cur[c - 1]
                move = 2
            cur[c] = d + best
            step[i, c] = move
        for c in range(w):
            prev[c] = cur[c]
    ix = np.empty(2 * n, dtype=np.int64)
    iy = np.empty(2 * n, dtype=np.int64)
    i = n - 1
    j = n - 1
    p = 0
    while True:
        ix[p] = i
        iy[p] = j
        p += 1
        if i == 0 and j == 0:
            break
        move = step[i, j - i + off]
        if move == 0:
            i -= 1
            j -= 1
        elif move == 1:
            i -= 1
        else:
            j -= 1
    return ix[:p][::-1].copy(), iy[:p][::-1].copy()
