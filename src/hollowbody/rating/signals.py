"""Curve checks and resampling shared by the rating methods.

A *curve* here is a pair of 1-D float arrays ``(t, y)`` of equal length ``n``:
``t`` is time in ms (strictly increasing), ``y`` the signal in any unit (force
in kN, acceleration in mm/ms^2, ...). Both rating methods (ISO/TS 18571 and
CORA) compare a *reference* curve (test) with a *candidate* (comparison,
simulation) curve after resampling both onto one uniform time base.

Everything here raises :class:`CurveError` for curves that cannot be rated.
It is a :class:`~hollowbody.errors.UserInputError` (one line, exit code 2 on the
command line) and a :class:`ValueError` (for library callers).
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np

from hollowbody.errors import UserInputError

Which = Literal["reference", "candidate", "both"]

#: Sampling step of the common time base by default: 0.1 ms = 10 kHz, the
#: sampling rate ISO/TS 18571 asks for.
DEFAULT_DT = 0.1


class CurveError(UserInputError, ValueError):
    """A curve that cannot be rated.

    ``which`` says which input is to blame (``"reference"``, ``"candidate"``
    or ``"both"``) so that callers who read the curves from files can name the
    file in the message.
    """

    def __init__(self, message: str, which: Which | None = None) -> None:
        super().__init__(message)
        self.which = which


def check_curve(t: np.ndarray, y: np.ndarray,
                which: Which = "reference") -> tuple[np.ndarray, np.ndarray]:
    """Return ``(t, y)`` as float64 arrays after checking them.

    Parameters
    ----------
    t : array_like, shape (n,)
        Time [ms], strictly increasing, finite.
    y : array_like, shape (n,)
        Signal, finite.
    which : str
        Name of the curve used in error messages.

    Raises
    ------
    CurveError
        If the arrays are not 1-D, differ in length, hold fewer than 2 samples,
        hold NaN/inf, or the time does not increase strictly.
    """
    t = np.asarray(t, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if t.ndim != 1 or y.ndim != 1:
        raise CurveError(f"{which} curve: time and values must be 1-D arrays", which)
    if t.shape != y.shape:
        raise CurveError(f"{which} curve: {t.size} time values but {y.size} signal values",
                         which)
    if t.size < 2:
        raise CurveError(f"{which} curve: needs at least 2 samples, got {t.size}", which)
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(y))):
        raise CurveError(f"{which} curve: contains NaN or infinite values", which)
    steps = np.diff(t)
    if np.any(steps <= 0.0):
        i = int(np.argmax(steps <= 0.0))
        raise CurveError(
            f"{which} curve: time must increase strictly (sample {i + 2}: "
            f"t = {t[i + 1]:g} after {t[i]:g})", which)
    return t, y


def common_interval(t_ref: np.ndarray, t_cmp: np.ndarray, t_start: float | None = None,
                    t_end: float | None = None) -> tuple[float, float]:
    """Time interval ``[start, end]`` (ms) covered by both curves.

    ``t_start``/``t_end`` (ms) narrow the interval further when given.

    Raises
    ------
    CurveError
        If the curves do not overlap in time or the interval is empty.
    """
    start = max(float(t_ref[0]), float(t_cmp[0]))
    end = min(float(t_ref[-1]), float(t_cmp[-1]))
    if end <= start:
        raise CurveError(
            f"the time ranges do not overlap (reference {t_ref[0]:g}..{t_ref[-1]:g} ms, "
            f"candidate {t_cmp[0]:g}..{t_cmp[-1]:g} ms)", "both")
    if t_start is not None:
        start = max(start, float(t_start))
    if t_end is not None:
        end = min(end, float(t_end))
    if end <= start:
        raise CurveError(f"the evaluation interval {start:g}..{end:g} ms is empty", "both")
    return start, end


def uniform_grid(start: float, end: float, dt: float) -> np.ndarray:
    """Uniform time base ``start, start + dt, ...`` up to ``end`` (ms).

    Returns
    -------
    ndarray, shape (m,)
        ``m = floor((end - start) / dt) + 1``; the last point is ``<= end``
        (a round-off of 1e-9 steps is forgiven so that ``end`` itself is kept
        when the interval is a whole number of steps).
    """
    if not (dt > 0.0 and math.isfinite(dt)):
        raise ValueError(f"time step dt must be positive, got {dt}")
    m = int(math.floor((end - start) / dt + 1e-9)) + 1
    return start + dt * np.arange(m, dtype=np.float64)


def resample(t: np.ndarray, y: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Linear interpolation of the curve ``(t, y)`` at ``grid`` (shape (m,))."""
    return np.interp(grid, t, y)


def on_common_base(t_ref: np.ndarray, y_ref: np.ndarray, t_cmp: np.ndarray,
                   y_cmp: np.ndarray, dt: float, start: float,
                   end: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Both curves linearly resampled on ``uniform_grid(start, end, dt)``.

    Returns
    -------
    grid, ref, cmp : ndarray, shape (m,)
        Time base [ms] and the two resampled signals.

    Raises
    ------
    CurveError
        If the interval holds fewer than 3 samples at this ``dt``.
    """
    grid = uniform_grid(start, end, dt)
    if grid.size < 3:
        raise CurveError(
            f"the evaluation interval {start:g}..{end:g} ms holds only {grid.size} "
            f"samples at dt = {dt:g} ms; use a smaller time step", "both")
    return grid, resample(t_ref, y_ref, grid), resample(t_cmp, y_cmp, grid)


def shifted_pair(ref: np.ndarray, cmp: np.ndarray, lag: int) -> tuple[np.ndarray, np.ndarray]:
    """Overlapping parts of two equally sampled signals after a time shift.

    ``lag > 0`` means the candidate lags the reference by ``lag`` samples
    (``cmp[i + lag]`` pairs with ``ref[i]``); ``lag < 0`` the opposite.

    Returns
    -------
    ref_part, cmp_part : ndarray, shape (n - |lag|,)
    """
    n = ref.size
    if lag >= 0:
        return ref[: n - lag], cmp[lag:]
    return ref[-lag:], cmp[: n + lag]


def best_lag(scores: np.ndarray, max_lag: int, tol: float = 1e-12) -> int:
    """Lag with the highest score, ties broken toward the smallest shift.

    ``scores`` (shape (2 * max_lag + 1,)) holds the score of lag
    ``-max_lag .. max_lag``; NaN entries are ignored. Scores within ``tol`` of
    the maximum count as ties (so that round-off cannot pick the winner).
    Among tied lags the order ``0, +1, -1, +2, -2, ...`` decides: the unshifted
    position beats any shift and, at equal shift, a late candidate (positive
    lag) beats an early one. Returns 0 when every score is NaN.
    """
    valid = scores[~np.isnan(scores)]
    if valid.size == 0:
        return 0
    floor = float(valid.max()) - tol
    for k in range(max_lag + 1):
        for lag in ((k,) if k == 0 else (k, -k)):
            if scores[lag + max_lag] >= floor:  # NaN compares False
                return lag
    return 0  # pragma: no cover - the maximum itself always qualifies
