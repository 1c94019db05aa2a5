"""CORA (CORrelation and Analysis) rating as in CORAplus 4.

CORA rates a candidate signal ``y(t)`` against a reference ``x(t)`` over an
*interval of evaluation* with two independent methods and combines them:

* **corridor method** Z: inner and outer corridors around the reference
  (half-widths ``a_0 * Y_norm`` and ``b_0 * Y_norm``, or corridors given by the
  user); a sample scores 1 inside the inner corridor, 0 outside the outer one
  and ``((delta_o - d) / (delta_o - delta_i)) ** K`` between; Z is the mean;
* **cross-correlation method** E = G_V * V + G_G * G + G_P * P from the time
  shift ``delta`` that maximises the normalised cross-correlation
  ``K_xy = sum(x * y) / sqrt(sum(x^2) * sum(y^2))`` of the overlapping parts:

  - phase rating P: 1 for ``|delta| <= D_MIN * T``, 0 for ``|delta| >= D_MAX * T``,
    ``((D_MAX*T - |delta|) / (D_MAX*T - D_MIN*T)) ** K_P`` between
    (``T`` = length of the interval of evaluation);
  - size rating G: ratio of the smaller to the larger signal energy
    ``sum(x^2)``, ``sum(y^2)`` of the shifted parts, to the power ``K_G``;
  - progression rating V: ``((K_xy + 1) / 2) ** K_V``;
* **total** R = G_1 * Z + G_2 * E.

Weights are divided by their sum when ``wf_norm`` is true (CORA's WF_NORM).
Time is in ms; the signals in any one unit.

Choices where the published descriptions leave room (listed in
``docs/rating.md`` too):

* Automatic interval of evaluation from the reference ``x``: ``t_a`` is the
  first, ``t_b`` the last time at which ``|x|`` reaches ``A_THRES`` /
  ``B_THRES`` times ``max|x|`` (linear interpolation between samples); the
  interval is ``[t_a - A_EVAL * (t_b - t_a), t_b + B_DELTA_END * (t_b - t_a)]``,
  clipped to the reference's time range and then to the time both curves cover.
* Both signals are linearly resampled on a uniform base (``dt`` = 0.1 ms by
  default) starting at the interval start.
* The time shift is searched over ``|delta| <= (1 - INT_MIN) * T`` within the
  interval (the signals are cut to the interval and then shifted, so the
  overlap never falls below INT_MIN); ties go to the smaller shift, then to a
  late candidate. Without any defined K_xy (a zero signal) the shift is 0 and
  V is 0.
* ``Y_norm`` is the reference's absolute maximum in the interval unless given.
* User corridors: between inner and outer corridor the distance is measured
  on the side the candidate leaves the inner corridor; samples outside the
  user corridor's time range are not rated. A single corridor (lower/upper
  bound) is the inner corridor; its outer corridor lies ``(b_0 - a_0) * Y_norm``
  outside, so the band between them is as wide as with the default corridors.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from hollowbody.rating.corridors import Corridor
from hollowbody.rating.kernels import sliding_correlation
from hollowbody.rating.signals import (
    DEFAULT_DT,
    CurveError,
    best_lag,
    check_curve,
    common_interval,
    on_common_base,
    shifted_pair,
)

#: CORAplus names of the parameters, in CORAplus order.
CORA_NAMES = {
    "a_thres": "A_THRES", "b_thres": "B_THRES", "a_eval": "A_EVAL",
    "b_delta_end": "B_DELTA_END", "t_min": "T_MIN", "t_max": "T_MAX", "k": "K",
    "g_1": "G_1", "a_0": "a_0", "b_0": "b_0", "d_min": "D_MIN", "d_max": "D_MAX",
    "int_min": "INT_MIN", "k_v": "K_V", "k_g": "K_G", "k_p": "K_P", "g_v": "G_V",
    "g_g": "G_G", "g_p": "G_P", "g_2": "G_2", "wf_norm": "WF_NORM", "y_norm": "Y_NORM",
    "dt": "DT",
}


@dataclass(frozen=True)
class CoraParameters:
    """CORA parameters; defaults are CORAplus 4's defaults.

    Attributes
    ----------
    a_thres, b_thres : float
        Start / end thresholds of the automatic interval of evaluation as a
        fraction of the reference's absolute maximum (0.03 / 0.075).
    a_eval : float
        Extension of the interval before ``t_a`` as a fraction of
        ``t_b - t_a`` (0.01).
    b_delta_end : float
        Extension of the interval after ``t_b`` as a fraction of
        ``t_b - t_a`` (0.2).
    t_min, t_max : float or None
        Interval of evaluation [ms]; None = automatic (each end separately).
    k : float
        Exponent of the corridor rating between the corridors (2).
    a_0, b_0 : float
        Inner / outer corridor half-width as a fraction of Y_norm (0.05 / 0.5).
    d_min, d_max : float
        Time shifts rated 1 / 0 by the phase rating, as a fraction of the
        interval length (0.01 / 0.12).
    int_min : float
        Minimum overlap of the shifted signals as a fraction of the interval (0.8).
    k_v, k_g, k_p : float
        Exponents of progression, size and phase rating (10 / 1 / 1).
    g_v, g_g, g_p : float
        Weights of progression, size and phase rating (0.5 / 0.25 / 0.25).
    g_1, g_2 : float
        Weights of corridor and cross-correlation method (0.5 / 0.5).
    wf_norm : bool
        Divide weights by their sums (True).
    y_norm : float or None
        Corridor normalisation; None = reference's absolute maximum in the interval.
    dt : float
        Sampling step of the common time base [ms] (0.1).
    """

    a_thres: float = 0.03
    b_thres: float = 0.075
    a_eval: float = 0.01
    b_delta_end: float = 0.2
    t_min: float | None = None
    t_max: float | None = None
    k: float = 2.0
    a_0: float = 0.05
    b_0: float = 0.5
    d_min: float = 0.01
    d_max: float = 0.12
    int_min: float = 0.8
    k_v: float = 10.0
    k_g: float = 1.0
    k_p: float = 1.0
    g_v: float = 0.5
    g_g: float = 0.25
    g_p: float = 0.25
    g_1: float = 0.5
    g_2: float = 0.5
    wf_norm: bool = True
    y_norm: float | None = None
    dt: float = DEFAULT_DT

    def __post_init__(self) -> None:
        for name in ("a_thres", "b_thres"):
            if not 0.0 < getattr(self, name) < 1.0:
                raise ValueError(f"CORA: {CORA_NAMES[name]} must be in (0, 1)")
        for name in ("a_eval", "b_delta_end"):
            if not getattr(self, name) >= 0.0:
                raise ValueError(f"CORA: {CORA_NAMES[name]} must be >= 0")
        if not 0.0 <= self.a_0 < self.b_0:
            raise ValueError("CORA: need 0 <= a_0 < b_0")
        if not 0.0 <= self.d_min < self.d_max:
            raise ValueError("CORA: need 0 <= D_MIN < D_MAX")
        if not 0.0 < self.int_min <= 1.0:
            raise ValueError("CORA: INT_MIN must be in (0, 1]")
        for name in ("k", "k_v", "k_g", "k_p", "dt"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"CORA: {CORA_NAMES[name]} must be positive")
        for group in (("g_v", "g_g", "g_p"), ("g_1", "g_2")):
            values = [getattr(self, g) for g in group]
            if min(values) < 0.0 or sum(values) <= 0.0:
                raise ValueError(f"CORA: weights {', '.join(CORA_NAMES[g] for g in group)} "
                                 "must be >= 0 with a positive sum")
        if self.y_norm is not None and not self.y_norm > 0.0:
            raise ValueError("CORA: Y_NORM must be positive")
        if self.t_min is not None and self.t_max is not None and self.t_max <= self.t_min:
            raise ValueError("CORA: T_MAX must be greater than T_MIN")

    def to_dict(self) -> dict[str, Any]:
        """Parameters under their CORAplus names (None = automatic)."""
        return {CORA_NAMES[k]: v for k, v in asdict(self).items()}


@dataclass(frozen=True)
class UserCorridors:
    """Inner and outer corridors given by the user, sampled at ``time``.

    Attributes
    ----------
    time : ndarray, shape (n,)
        Time [ms], strictly increasing.
    inner_lower, inner_upper, outer_lower, outer_upper : ndarray, shape (n,)
        Corridor bounds in the signal's unit;
        ``outer_lower <= inner_lower <= inner_upper <= outer_upper``.
    """

    time: np.ndarray
    inner_lower: np.ndarray
    inner_upper: np.ndarray
    outer_lower: np.ndarray
    outer_upper: np.ndarray

    def __post_init__(self) -> None:
        t = np.asarray(self.time, dtype=np.float64)
        arrays = [np.asarray(getattr(self, n), dtype=np.float64) for n in
                  ("inner_lower", "inner_upper", "outer_lower", "outer_upper")]
        if any(a.shape != t.shape for a in arrays) or t.ndim != 1 or t.size < 2:
            raise ValueError("user corridors: all arrays must have the time array's shape (n,)")
        if np.any(np.diff(t) <= 0.0):
            raise ValueError("user corridors: time must increase strictly")
        il, iu, ol, ou = arrays
        if np.any(ol > il) or np.any(il > iu) or np.any(iu > ou):
            raise ValueError("user corridors: need outer_lower <= inner_lower <= "
                             "inner_upper <= outer_upper")


@dataclass(frozen=True)
class CoraResult:
    """Result of :func:`cora`: every rating and the quantities behind it.

    Ratings (in [0, 1]): ``total`` (R), ``corridor`` (Z), ``cross_correlation``
    (E), ``phase`` (P), ``size`` (G), ``progression`` (V). Details:
    ``t_start``/``t_end`` [ms] and ``n_samples`` of the interval of
    evaluation, ``y_norm``, the best time ``shift`` [ms] / ``shift_samples``
    (positive: candidate late), its cross-correlation ``k_xy`` and the
    ``parameters`` under their CORAplus names.
    """

    total: float
    corridor: float
    cross_correlation: float
    phase: float
    size: float
    progression: float
    t_start: float
    t_end: float
    n_samples: int
    y_norm: float
    shift: float
    shift_samples: int
    k_xy: float
    user_corridors: bool
    parameters: dict[str, Any] = field(default_factory=dict)

    def scores(self) -> dict[str, float]:
        """The six ratings by name (Z, E, P, G, V, R)."""
        return {"Z": self.corridor, "E": self.cross_correlation, "P": self.phase,
                "G": self.size, "V": self.progression, "R": self.total}

    def to_dict(self) -> dict[str, Any]:
        out = asdict(self)
        out["method"] = "CORA"
        return out


def _first_crossing(t: np.ndarray, a: np.ndarray, level: float) -> float:
    """First time the piecewise-linear ``a`` (>= 0) reaches ``level``."""
    i = int(np.argmax(a >= level))
    if i == 0:
        return float(t[0])
    return float(np.interp(level, [a[i - 1], a[i]], [t[i - 1], t[i]]))


def _last_crossing(t: np.ndarray, a: np.ndarray, level: float) -> float:
    """Last time the piecewise-linear ``a`` (>= 0) is at or above ``level``."""
    j = a.size - 1 - int(np.argmax(a[::-1] >= level))
    if j == a.size - 1:
        return float(t[-1])
    return float(np.interp(level, [a[j + 1], a[j]], [t[j + 1], t[j]]))


def evaluation_interval(t: np.ndarray, x: np.ndarray,
                        params: CoraParameters | None = None) -> tuple[float, float]:
    """Interval of evaluation [ms] from the reference curve ``(t, x)``.

    ``T_MIN``/``T_MAX`` are used where given; the missing ends follow the
    automatic rule described in the module docstring.

    Raises
    ------
    CurveError
        If the reference is zero everywhere (it never reaches the thresholds).
    """
    p = params or CoraParameters()
    t, x = check_curve(t, x, "reference")
    a = np.abs(x)
    peak = float(a.max())
    if peak == 0.0:
        raise CurveError(
            f"reference curve never reaches the thresholds A_THRES = {p.a_thres:g} / "
            f"B_THRES = {p.b_thres:g} of its absolute maximum: it is zero everywhere",
            "reference")
    t_a = _first_crossing(t, a, p.a_thres * peak)
    t_b = _last_crossing(t, a, p.b_thres * peak)
    span = t_b - t_a
    start = p.t_min if p.t_min is not None else max(float(t[0]), t_a - p.a_eval * span)
    end = p.t_max if p.t_max is not None else min(float(t[-1]), t_b + p.b_delta_end * span)
    if end <= start:
        raise CurveError(
            f"reference curve: the interval of evaluation {start:g}..{end:g} ms is empty; "
            "set T_MIN and T_MAX", "reference")
    return float(start), float(end)


def corridor_rating(cmp: np.ndarray, inner_lower: np.ndarray, inner_upper: np.ndarray,
                    outer_lower: np.ndarray, outer_upper: np.ndarray,
                    k: float = 2.0) -> np.ndarray:
    """Per-sample corridor rating (shape (n,)) of ``cmp`` between the corridors.

    1 inside the inner corridor, 0 on or outside the outer corridor, else
    ``((outer - y) / (outer - inner)) ** k`` measured on the side where the
    sample leaves the inner corridor.
    """
    above = cmp > inner_upper
    below = cmp < inner_lower
    out = np.ones_like(cmp)
    with np.errstate(divide="ignore", invalid="ignore"):
        up = (outer_upper - cmp) / (outer_upper - inner_upper)
        lo = (cmp - outer_lower) / (inner_lower - outer_lower)
    out[above] = np.clip(np.nan_to_num(up[above], nan=0.0), 0.0, 1.0) ** k
    out[below] = np.clip(np.nan_to_num(lo[below], nan=0.0), 0.0, 1.0) ** k
    return out


def cross_correlation_ratings(ref: np.ndarray, cmp: np.ndarray, dt: float,
                              params: CoraParameters | None = None) -> dict[str, float]:
    """Phase, size and progression rating and their weighted sum.

    Parameters
    ----------
    ref, cmp : ndarray, shape (n,)
        Reference and candidate on one time base of step ``dt`` [ms] covering
        the interval of evaluation.

    Returns
    -------
    dict
        ``phase``, ``size``, ``progression``, ``cross_correlation``,
        ``shift_samples``, ``shift`` [ms], ``k_xy``.
    """
    p = params or CoraParameters()
    n = ref.size
    span = (n - 1) * dt
    max_lag = max(0, min(int(math.floor((1.0 - p.int_min) * span / dt + 1e-9)), n - 2))
    kxy_all = sliding_correlation(np.ascontiguousarray(ref), np.ascontiguousarray(cmp),
                                  max_lag, False)
    lag = best_lag(kxy_all, max_lag)
    k_xy = float(kxy_all[lag + max_lag])
    delta = abs(lag) * dt
    d_lo, d_hi = p.d_min * span, p.d_max * span
    if delta <= d_lo:
        phase = 1.0
    elif delta >= d_hi:
        phase = 0.0
    else:
        phase = ((d_hi - delta) / (d_hi - d_lo)) ** p.k_p
    ref_s, cmp_s = shifted_pair(ref, cmp, lag)
    e_x = float(np.dot(ref_s, ref_s))
    e_y = float(np.dot(cmp_s, cmp_s))
    size = 1.0 if max(e_x, e_y) == 0.0 else (min(e_x, e_y) / max(e_x, e_y)) ** p.k_g
    progression = 0.0 if math.isnan(k_xy) else ((k_xy + 1.0) / 2.0) ** p.k_v
    w = (p.g_v + p.g_g + p.g_p) if p.wf_norm else 1.0
    e = (p.g_v * progression + p.g_g * size + p.g_p * phase) / w
    return {"phase": phase, "size": size, "progression": progression, "cross_correlation": e,
            "shift_samples": lag, "shift": lag * dt, "k_xy": k_xy}


def _user_bounds(grid: np.ndarray, corridors: UserCorridors | Corridor,
                 gap: float) -> tuple[np.ndarray, list[np.ndarray]]:
    """Grid points inside the user corridors' time range and the four bounds there.

    A single :class:`~hollowbody.rating.corridors.Corridor` is the inner
    corridor; its outer corridor lies ``gap`` = (b_0 - a_0) * Y_norm outside.
    """
    if isinstance(corridors, Corridor):
        ct = corridors.x
        inner = (corridors.lower, corridors.upper)
        outer = (corridors.lower - gap, corridors.upper + gap)
    else:
        ct = np.asarray(corridors.time, dtype=np.float64)
        inner = (corridors.inner_lower, corridors.inner_upper)
        outer = (corridors.outer_lower, corridors.outer_upper)
    inside = (grid >= ct[0]) & (grid <= ct[-1])
    g = grid[inside]
    bounds = [np.interp(g, ct, np.asarray(b, dtype=np.float64))
              for b in (inner[0], inner[1], outer[0], outer[1])]
    return inside, bounds


def cora(t_ref: np.ndarray, y_ref: np.ndarray, t_cmp: np.ndarray, y_cmp: np.ndarray,
         params: CoraParameters | None = None,
         corridors: UserCorridors | Corridor | None = None) -> CoraResult:
    """CORA rating of a candidate curve against a reference curve.

    Parameters
    ----------
    t_ref, y_ref : array_like, shape (n,)
        Reference (test) curve: time [ms], signal.
    t_cmp, y_cmp : array_like, shape (m,)
        Candidate (simulation) curve: time [ms], signal in the reference's unit.
    params : CoraParameters, optional
        CORA parameters (CORAplus defaults).
    corridors : UserCorridors or Corridor, optional
        Inner/outer corridors for the corridor method instead of the
        ``a_0``/``b_0`` corridors around the reference. A single
        :class:`~hollowbody.rating.corridors.Corridor` (e.g. an experimental
        corridor) is taken as the inner corridor, with the outer corridor
        ``(b_0 - a_0) * Y_norm`` outside it.

    Returns
    -------
    CoraResult

    Raises
    ------
    CurveError
        Bad curves, a reference that never reaches the thresholds, no common
        interval, or user corridors that do not overlap the interval.
    """
    p = params or CoraParameters()
    t_ref, y_ref = check_curve(t_ref, y_ref, "reference")
    t_cmp, y_cmp = check_curve(t_cmp, y_cmp, "candidate")
    start, end = evaluation_interval(t_ref, y_ref, p)
    start, end = common_interval(t_ref, t_cmp, start, end)
    grid, ref, cmp = on_common_base(t_ref, y_ref, t_cmp, y_cmp, p.dt, start, end)
    y_norm = p.y_norm if p.y_norm is not None else float(np.max(np.abs(ref)))
    if y_norm == 0.0:
        raise CurveError("reference curve is zero over the whole interval of evaluation; "
                         "set Y_NORM", "reference")
    if corridors is None:
        c = corridor_rating(cmp, ref - p.a_0 * y_norm, ref + p.a_0 * y_norm,
                            ref - p.b_0 * y_norm, ref + p.b_0 * y_norm, p.k)
    else:
        inside, bounds = _user_bounds(grid, corridors, (p.b_0 - p.a_0) * y_norm)
        if not np.any(inside):
            raise CurveError("the user corridors do not overlap the interval of evaluation "
                             f"{start:g}..{end:g} ms", "reference")
        c = corridor_rating(cmp[inside], *bounds, p.k)
    z = float(np.mean(c))
    xc = cross_correlation_ratings(ref, cmp, p.dt, p)
    w = (p.g_1 + p.g_2) if p.wf_norm else 1.0
    total = (p.g_1 * z + p.g_2 * xc["cross_correlation"]) / w
    return CoraResult(
        total=total, corridor=z, cross_correlation=xc["cross_correlation"], phase=xc["phase"],
        size=xc["size"], progression=xc["progression"], t_start=float(grid[0]),
        t_end=float(grid[-1]), n_samples=int(grid.size), y_norm=float(y_norm),
        shift=xc["shift"], shift_samples=int(xc["shift_samples"]), k_xy=xc["k_xy"],
        user_corridors=corridors is not None, parameters=p.to_dict())
