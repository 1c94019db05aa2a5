"""ISO/TS 18571 objective rating metric for non-ambiguous signals.

The rating compares a reference signal ``T(t)`` (test) with a candidate
``C(t)`` (computation) and combines four sub-scores, each in [0, 1]:

* corridor score ``Z`` (clause 6.2),
* phase score ``E_P``, magnitude score ``E_M`` and slope score ``E_S``
  (clause 6.3; magnitude and slope are computed on the phase-corrected curves),
* overall rating ``R = w_Z Z + w_P E_P + w_M E_M + w_S E_S`` with
  0.4 / 0.2 / 0.2 / 0.2 (clause 6.1), graded excellent (R > 0.94),
  good (0.80 < R <= 0.94), fair (0.58 < R <= 0.80) or poor (R <= 0.58).

Clause numbers refer to ISO/TS 18571:2014 (clause 5: data requirements,
clause 6: the ISO metric). Units: time in ms, the signals in any one unit.

Choices where the published definitions leave room (also listed in
``docs/rating.md``):

* The evaluation interval is the time both curves cover (narrowed by
  ``t_start``/``t_end``); both curves are linearly resampled on a uniform base
  with ``dt`` = 0.1 ms (10 kHz) starting at the interval start.
* Cross-correlation is Pearson's coefficient of the overlapping parts; the
  search covers ``|n| <= floor(eps_p * N)`` samples; ties go to the smaller
  shift, then to a late candidate (positive shift). When every coefficient is
  undefined (a constant signal) the shift is 0.
* The phase score uses ``eps_p * N`` (not rounded) as the allowed shift.
* DTW: squared local cost, steps (1,0), (0,1), (1,1) without weights, a
  Sakoe-Chiba band of radius ``max(1, ceil(0.1 * n))`` samples (cells with
  ``|i - j| < radius``), diagonal preferred on ties.
* Magnitude and slope errors are L1 norms, normalised by the reference's L1
  norm. Slopes are central differences (one-sided at the ends) smoothed by a
  centred 9-point moving average whose window shrinks symmetrically
  (1, 3, 5, 7 points) at the ends.
* Weights that do not sum to 1 are normalised by their sum.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from hollowbody.rating.kernels import dtw_band_path, sliding_correlation
from hollowbody.rating.signals import (
    DEFAULT_DT,
    CurveError,
    best_lag,
    check_curve,
    common_interval,
    on_common_base,
    shifted_pair,
)

#: Grade limits on the overall rating R (lower bound exclusive).
GRADES = ((0.94, "excellent"), (0.80, "good"), (0.58, "fair"), (-math.inf, "poor"))


@dataclass(frozen=True)
class IsoParameters:
    """Parameters of the ISO/TS 18571 metric (defaults are the standard's).

    Attributes
    ----------
    a_0, b_0 : float
        Inner / outer corridor half-width as a fraction of the reference's
        absolute maximum (0.05 / 0.5).
    k_z : float
        Exponent of the corridor score between the corridors (2).
    eps_p : float
        Largest time shift as a fraction of the interval (0.2).
    k_p : float
        Exponent of the phase score (1).
    eps_m : float
        Magnitude error at which the magnitude score reaches 0 (0.5).
    k_m : float
        Exponent of the magnitude score (1).
    eps_s : float
        Slope error at which the slope score reaches 0 (2.0).
    k_s : float
        Exponent of the slope score (1).
    dtw_window : float
        Sakoe-Chiba band radius as a fraction of the shifted length (0.1).
    smooth_points : int
        Length of the moving average applied to the slopes (9, odd).
    w_z, w_p, w_m, w_s : float
        Weights of corridor, phase, magnitude, slope score (0.4/0.2/0.2/0.2).
    dt : float
        Sampling step of the common time base [ms] (0.1 ms = 10 kHz).
    t_start, t_end : float or None
        Evaluation interval limits [ms]; None = where both curves exist.
    """

    a_0: float = 0.05
    b_0: float = 0.5
    k_z: float = 2.0
    eps_p: float = 0.2
    k_p: float = 1.0
    eps_m: float = 0.5
    k_m: float = 1.0
    eps_s: float = 2.0
    k_s: float = 1.0
    dtw_window: float = 0.1
    smooth_points: int = 9
    w_z: float = 0.4
    w_p: float = 0.2
    w_m: float = 0.2
    w_s: float = 0.2
    dt: float = DEFAULT_DT
    t_start: float | None = None
    t_end: float | None = None

    def __post_init__(self) -> None:
        if not 0.0 <= self.a_0 < self.b_0:
            raise ValueError(f"ISO 18571: need 0 <= a_0 < b_0, got {self.a_0}, {self.b_0}")
        for name in ("k_z", "k_p", "k_m", "k_s", "eps_m", "eps_s", "dt"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"ISO 18571: {name} must be positive")
        if not 0.0 <= self.eps_p < 1.0:
            raise ValueError(f"ISO 18571: eps_p must be in [0, 1), got {self.eps_p}")
        if not 0.0 <= self.dtw_window <= 1.0:
            raise ValueError(f"ISO 18571: dtw_window must be in [0, 1], got {self.dtw_window}")
        if self.smooth_points < 1 or self.smooth_points % 2 == 0:
            raise ValueError("ISO 18571: smooth_points must be a positive odd number")
        weights = (self.w_z, self.w_p, self.w_m, self.w_s)
        if min(weights) < 0.0 or sum(weights) <= 0.0:
            raise ValueError("ISO 18571: weights must be >= 0 with a positive sum")

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass(frozen=True)
class IsoResult:
    """Result of :func:`iso18571`; every sub-score and the quantities behind it.

    Scores (all in [0, 1]): ``corridor`` (Z), ``phase`` (E_P), ``magnitude``
    (E_M), ``slope`` (E_S), ``overall`` (R) and the ``grade`` of R.
    Details: ``shift_samples`` / ``shift`` [ms] of the best phase alignment
    (positive: candidate late), ``rho`` (its Pearson coefficient, NaN if
    undefined), ``eps_mag`` and ``eps_slope`` (L1 errors), ``t_norm`` (absolute
    maximum of the reference), ``t_start``/``t_end`` [ms] and ``n_samples`` of
    the evaluation interval, and the ``parameters`` used.
    """

    corridor: float
    phase: float
    magnitude: float
    slope: float
    overall: float
    grade: str
    shift_samples: int
    shift: float
    rho: float
    eps_mag: float
    eps_slope: float
    t_norm: float
    t_start: float
    t_end: float
    n_samples: int
    parameters: dict[str, Any] = field(default_factory=dict)

    def scores(self) -> dict[str, float]:
        """The five scores by name (Z, EP, EM, ES, R)."""
        return {"Z": self.corridor, "EP": self.phase, "EM": self.magnitude,
                "ES": self.slope, "R": self.overall}

    def to_dict(self) -> dict[str, Any]:
        out = asdict(self)
        out["method"] = "ISO/TS 18571"
        return out


def grade(r: float) -> str:
    """Verbal grade of an overall ISO rating ``r``."""
    for limit, name in GRADES:
        if r > limit:
            return name
    return "poor"  # pragma: no cover - r is never below -inf


def corridor_score(ref: np.ndarray, cmp: np.ndarray, a_0: float = 0.05, b_0: float = 0.5,
                   k_z: float = 2.0) -> tuple[float, float]:
    """Corridor score Z (clause 6.2) and the normalisation ``t_norm``.

    Inner and outer corridor half-widths are ``a_0 * t_norm`` and
    ``b_0 * t_norm`` around the reference, ``t_norm = max|ref|``. A sample
    scores 1 inside the inner corridor, 0 outside the outer one and
    ``((delta_o - |ref - cmp|) / (delta_o - delta_i)) ** k_z`` between; Z is
    the mean over the samples.

    Parameters
    ----------
    ref, cmp : ndarray, shape (n,)
        Reference and candidate on the same time base.

    Raises
    ------
    CurveError
        If the reference is zero everywhere (no corridor can be built).
    """
    t_norm = float(np.max(np.abs(ref)))
    if t_norm == 0.0:
        raise CurveError("reference curve is zero over the whole evaluation interval; "
                         "the corridor score is undefined", "reference")
    delta_i = a_0 * t_norm
    delta_o = b_0 * t_norm
    dev = np.abs(ref - cmp)
    c = np.clip((delta_o - dev) / (delta_o - delta_i), 0.0, 1.0) ** k_z
    c[dev <= delta_i] = 1.0
    return float(np.mean(c)), t_norm


def phase_shift(ref: np.ndarray, cmp: np.ndarray, eps_p: float = 0.2) -> tuple[int, float]:
    """Time shift (samples) maximising Pearson's cross-correlation (clause 6.3).

    Lags up to ``floor(eps_p * n)`` samples are searched both ways; see
    :func:`hollowbody.rating.signals.best_lag` for the tie rule.

    Returns
    -------
    lag, rho : int, float
        ``lag > 0``: the candidate is late by ``lag`` samples. ``rho`` is NaN
        when no coefficient is defined (a constant signal).
    """
    n = ref.size
    max_lag = max(0, min(int(math.floor(eps_p * n)), n - 2))
    rho = sliding_correlation(ref, cmp, max_lag, True)
    lag = best_lag(rho, max_lag)
    return lag, float(rho[lag + max_lag])


def phase_score(lag: int, n: int, eps_p: float = 0.2, k_p: float = 1.0) -> float:
    """Phase score E_P (clause 6.3): 1 without shift, 0 at ``eps_p * n`` samples."""
    allowed = eps_p * n
    if lag == 0:
        return 1.0
    if abs(lag) >= allowed:
        return 0.0
    return ((allowed - abs(lag)) / allowed) ** k_p


def _ratio_score(err: float, limit: float, k: float) -> float:
    """``((limit - err) / limit) ** k`` clipped to [0, 1]."""
    if err <= 0.0:
        return 1.0
    if err >= limit:
        return 0.0
    return ((limit - err) / limit) ** k


def _l1_error(ref: np.ndarray, cmp: np.ndarray) -> float:
    """``sum|cmp - ref| / sum|ref|``; 0 for two zero signals, inf if only ref is zero."""
    num = float(np.sum(np.abs(cmp - ref)))
    den = float(np.sum(np.abs(ref)))
    if den == 0.0:
        return 0.0 if num == 0.0 else math.inf
    return num / den


def magnitude_error(ref: np.ndarray, cmp: np.ndarray, window: float = 0.1) -> float:
    """Magnitude error after dynamic time warping (clause 6.3).

    Parameters
    ----------
    ref, cmp : ndarray, shape (m,)
        Phase-corrected reference and candidate (same length).
    window : float
        Sakoe-Chiba band radius as a fraction of ``m``; the radius is
        ``max(1, ceil(window * m))`` samples and cells with ``|i - j| < radius``
        are allowed.

    Returns
    -------
    float
        ``sum|C_w - T_w| / sum|T_w|`` over the warping path.
    """
    radius = max(1, int(math.ceil(window * ref.size - 1e-9)))
    ix, iy = dtw_band_path(np.ascontiguousarray(ref), np.ascontiguousarray(cmp), radius)
    return _l1_error(ref[ix], cmp[iy])


def smoothed_slope(y: np.ndarray, dt: float, points: int = 9) -> np.ndarray:
    """Derivative of ``y`` (shape (m,), step ``dt`` ms) smoothed by a moving average.

    Central differences inside, one-sided differences at the two ends
    (``numpy.gradient``); then a centred ``points``-point moving average whose
    half-width shrinks to ``min(h, i, m-1-i)`` near the ends, so sample 0 keeps
    its own value, sample 1 averages 3 values, and so on.

    Returns
    -------
    ndarray, shape (m,)
        Slope in signal units per ms.
    """
    d = np.gradient(y, dt) if y.size > 1 else np.zeros_like(y)
    half = points // 2
    m = d.size
    csum = np.concatenate(([0.0], np.cumsum(d)))
    i = np.arange(m)
    h = np.minimum(half, np.minimum(i, m - 1 - i))
    return (csum[i + h + 1] - csum[i - h]) / (2 * h + 1)


def slope_error(ref: np.ndarray, cmp: np.ndarray, dt: float, points: int = 9) -> float:
    """Slope error ``sum|C' - T'| / sum|T'|`` of the smoothed slopes (clause 6.3)."""
    return _l1_error(smoothed_slope(ref, dt, points), smoothed_slope(cmp, dt, points))


def rate_sampled(ref: np.ndarray, cmp: np.ndarray, params: IsoParameters | None = None,
                 t_start: float = 0.0) -> IsoResult:
    """ISO/TS 18571 rating of two signals already on one time base.

    Parameters
    ----------
    ref, cmp : ndarray, shape (n,), n >= 3
        Reference and candidate sampled every ``params.dt`` ms.
    t_start : float
        Time of the first sample [ms] (only reported).
    """
    p = params or IsoParameters()
    ref = np.ascontiguousarray(ref, dtype=np.float64)
    cmp = np.ascontiguousarray(cmp, dtype=np.float64)
    n = ref.size
    z, t_norm = corridor_score(ref, cmp, p.a_0, p.b_0, p.k_z)
    lag, rho = phase_shift(ref, cmp, p.eps_p)
    e_p = phase_score(lag, n, p.eps_p, p.k_p)
    ref_s, cmp_s = shifted_pair(ref, cmp, lag)
    eps_mag = magnitude_error(ref_s, cmp_s, p.dtw_window)
    e_m = _ratio_score(eps_mag, p.eps_m, p.k_m)
    eps_slope = slope_error(ref_s, cmp_s, p.dt, p.smooth_points)
    e_s = _ratio_score(eps_slope, p.eps_s, p.k_s)
    w_sum = p.w_z + p.w_p + p.w_m + p.w_s
    r = (p.w_z * z + p.w_p * e_p + p.w_m * e_m + p.w_s * e_s) / w_sum
    return IsoResult(
        corridor=z, phase=e_p, magnitude=e_m, slope=e_s, overall=r, grade=grade(r),
        shift_samples=lag, shift=lag * p.dt, rho=rho, eps_mag=eps_mag, eps_slope=eps_slope,
        t_norm=t_norm, t_start=t_start, t_end=t_start + (n - 1) * p.dt, n_samples=n,
        parameters=p.to_dict())


def iso18571(t_ref: np.ndarray, y_ref: np.ndarray, t_cmp: np.ndarray, y_cmp: np.ndarray,
             params: IsoParameters | None = None) -> IsoResult:
    """ISO/TS 18571 rating of a candidate curve against a reference curve.

    Both curves are resampled (linear interpolation) on a uniform time base of
    step ``params.dt`` (clause 5 asks for 10 kHz: dt = 0.1 ms) over the
    interval both cover, narrowed by ``params.t_start``/``t_end``.

    Parameters
    ----------
    t_ref, y_ref : array_like, shape (n,)
        Reference (test) curve: time [ms], signal.
    t_cmp, y_cmp : array_like, shape (m,)
        Candidate (simulation) curve: time [ms], signal in the reference's unit.
    params : IsoParameters, optional
        Metric parameters; the standard's values by default.

    Returns
    -------
    IsoResult

    Raises
    ------
    CurveError
        Bad curves, no common interval, or a reference that is zero throughout.
    """
    p = params or IsoParameters()
    t_ref, y_ref = check_curve(t_ref, y_ref, "reference")
    t_cmp, y_cmp = check_curve(t_cmp, y_cmp, "candidate")
    start, end = common_interval(t_ref, t_cmp, p.t_start, p.t_end)
    grid, ref, cmp = on_common_base(t_ref, y_ref, t_cmp, y_cmp, p.dt, start, end)
    return rate_sampled(ref, cmp, p, t_start=float(grid[0]))
