"""The crush benchmark's measures from a plate force-displacement curve.

Mean crush force over the stable folding range
-----------------------------------------------
``P_m = (1 / (d1 - d0)) int_{d0}^{d1} F(d) dd`` with, by default,

- ``d0 = 2 H`` (H the closed-form half-fold length): the initial buckling
  peak (2-4 P_m) rises and falls within the first ~H of crush, and after 2 H
  of plate travel the first fold (crushed over 0.73 x 2 H in the
  Abramowicz-Jones picture) is complete; from there on the force oscillates
  about P_m once per fold;
- ``d1 = 0.7 L``: short of the effective crush length (~0.73 L for square
  tubes, Abramowicz & Jones 1984a), beyond which the folded stack locks and
  the force rises steeply (densification, not folding).

The window should hold at least one fold's crush distance, else the mean
depends on the phase of the oscillation where the window ends;
:func:`crush_window` refuses windows shorter than ``2 H x effective``.

Half-fold length from the force oscillation
-------------------------------------------
Each fold gives one major force peak, and a fold of length 2 H crushes over
``delta_e = effective x 2 H`` of plate travel; the mean distance between
successive major peaks in the window therefore estimates
``2 H x effective``, and ``H ~ spacing / (2 effective)`` (with the same
effective-crush factor as the closed form, so the comparison is of fold
lengths, not of that factor). The peaks are counted from H / 2 on (past the
initial buckling peak, which comes within the first mm) to d1, so that a
coarse run with few folds still gives two. Peaks are taken on the force resampled every
0.1 mm and smoothed over 0.1 x 2 H; a major peak rises by at least 10 % of
P_m above the troughs on either side (prominence). A run whose folds make two
peaks each gives about half the closed-form length: read it as such.

Units: mm, kN, J.
"""

from __future__ import annotations

import numpy as np
from scipy.signal import find_peaks


def crush_window(length: float, half_fold: float, effective: float,
                 start: float | None = None, end: float | None = None) -> tuple[float, float]:
    """The stable folding range (d0, d1) mm of a tube of ``length`` mm (module doc);
    ValueError when it is shorter than one fold's crush distance."""
    d0 = 2.0 * half_fold if start is None else start
    d1 = 0.7 * length if end is None else end
    if d1 - d0 < 2.0 * half_fold * effective:
        raise ValueError(f"crush window {d0:.1f}-{d1:.1f} mm is shorter than one fold's "
                         f"crush distance {2.0 * half_fold * effective:.1f} mm: the tube is "
                         "too short for a mean crush force")
    return d0, d1


def _uniform(d: np.ndarray, f: np.ndarray, step: float = 0.1) -> tuple[np.ndarray, np.ndarray]:
    """The curve on a uniform displacement grid (d increasing; repeated d averaged out)."""
    order = np.argsort(d, kind="stable")
    d, f = d[order], f[order]
    grid = np.arange(d[0], d[-1] + 0.5 * step, step)
    return grid, np.interp(grid, d, f)


def mean_force(d: np.ndarray, f: np.ndarray, d0: float, d1: float) -> float:
    """Mean of F (kN) over the crush d in [d0, d1] mm: the work over the window / its length.

    d (k,) mm increasing plate travel, f (k,) kN. ValueError when the curve does
    not reach d1.
    """
    d = np.asarray(d, dtype=float)
    f = np.asarray(f, dtype=float)
    if d.size < 2 or d.max() < d1 - 1e-9:
        raise ValueError(f"the curve ends at {d.max() if d.size else 0.0:.1f} mm, before the "
                         f"end of the crush window {d1:.1f} mm")
    grid = np.linspace(d0, d1, max(2, int(np.ceil((d1 - d0) / 0.05)) + 1))
    g = np.interp(grid, d, f)
    return float(np.trapezoid(g, grid) / (d1 - d0))


def work(d: np.ndarray, f: np.ndarray) -> float:
    """Work (J = kN mm) of the force f (k,) kN over the travel d (k,) mm (trapezoidal)."""
    return float(np.trapezoid(np.asarray(f, float), np.asarray(d, float)))


def fold_peaks(d: np.ndarray, f: np.ndarray, d0: float, d1: float, half_fold: float,
               p_mean: float) -> np.ndarray:
    """Displacements (mm) of the major force peaks in [d0, d1] (module doc)."""
    grid, g = _uniform(np.asarray(d, float), np.asarray(f, float))
    step = grid[1] - grid[0] if grid.size > 1 else 0.1
    w = max(1, int(round(0.2 * half_fold / step)))
    smooth = np.convolve(g, np.ones(w) / w, mode="same")
    peaks, _ = find_peaks(smooth, prominence=0.10 * abs(p_mean),
                          distance=max(1, int(0.5 * half_fold / step)))
    at = grid[peaks]
    return at[(at >= d0) & (at <= d1)]


def half_fold_from_peaks(peaks: np.ndarray, effective: float) -> float:
    """H (mm) from the mean spacing of successive major peaks: spacing / (2 effective);
    nan with fewer than two peaks."""
    if peaks.size < 2:
        return float("nan")
    return float(np.mean(np.diff(peaks)) / (2.0 * effective))
