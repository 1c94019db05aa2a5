"""Response corridors: lower and upper bounds of an experimental response.

A :class:`Corridor` holds a lower and an upper bound sampled at common
abscissae ``x`` (time in ms for force-time corridors, deflection in mm for
force-deflection corridors). It can be built

* from a closed polygon (:meth:`Corridor.from_polygon`), as corridors are
  published (e.g. Viano 1989): the bounds are the lowest and highest edge of
  the polygon over each abscissa;
* from separate upper and lower curves (:meth:`Corridor.from_bounds`);
* from specimen curves as mean +/- k standard deviations
  (:meth:`Corridor.from_specimens`).

:meth:`Corridor.fraction_inside` tells which share of a response lies between
the bounds; :func:`hollowbody.rating.plot.plot_corridor` draws a response
against a corridor and the specimen curves.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

ArrayPair = tuple[np.ndarray, np.ndarray]


@dataclass(frozen=True)
class Corridor:
    """Lower and upper bound of a response over abscissae ``x``.

    Attributes
    ----------
    x : ndarray, shape (n,)
        Abscissae, non-decreasing (a value may repeat once where a bound
        jumps); time [ms] or deflection [mm].
    lower, upper : ndarray, shape (n,)
        Bounds in the response's unit (e.g. kN), ``lower <= upper``; linear
        between the abscissae.
    center : ndarray, shape (n,), optional
        Mean response (corridors from specimens).
    outline : ndarray, shape (m, 2), optional
        Closed outline for drawing (the source polygon when there is one).
    name : str
        Label for plots and reports.
    """

    x: np.ndarray
    lower: np.ndarray
    upper: np.ndarray
    center: np.ndarray | None = None
    outline: np.ndarray | None = field(default=None, repr=False)
    name: str = ""

    def __post_init__(self) -> None:
        x = np.asarray(self.x, dtype=np.float64)
        lo = np.asarray(self.lower, dtype=np.float64)
        up = np.asarray(self.upper, dtype=np.float64)
        if x.ndim != 1 or x.size < 2 or lo.shape != x.shape or up.shape != x.shape:
            raise ValueError("corridor: x, lower and upper must be 1-D of equal length >= 2")
        if np.any(np.diff(x) < 0.0) or x[-1] <= x[0]:
            raise ValueError("corridor: abscissae must not decrease")
        if np.any(lo > up + 1e-12 * max(1.0, float(np.max(np.abs(up))))):
            raise ValueError("corridor: lower bound above upper bound")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "lower", lo)
        object.__setattr__(self, "upper", up)
        if self.outline is None:
            ring = np.concatenate([np.column_stack([x, up]), np.column_stack([x, lo])[::-1]])
            object.__setattr__(self, "outline", ring)

    # ----------------------------------------------------------------- queries
    @property
    def x_range(self) -> tuple[float, float]:
        """First and last abscissa."""
        return float(self.x[0]), float(self.x[-1])

    def bounds_at(self, xq: np.ndarray) -> ArrayPair:
        """Lower and upper bound at ``xq`` (shape (m,)); NaN outside the range."""
        xq = np.asarray(xq, dtype=np.float64)
        lo = np.interp(xq, self.x, self.lower)
        up = np.interp(xq, self.x, self.upper)
        outside = (xq < self.x[0]) | (xq > self.x[-1])
        lo[outside] = np.nan
        up[outside] = np.nan
        return lo, up

    def contains(self, xq: np.ndarray, yq: np.ndarray) -> np.ndarray:
        """Boolean array (shape (m,)): point inside the corridor (bounds included).

        Points outside the corridor's abscissa range are not inside.
        """
        lo, up = self.bounds_at(xq)
        yq = np.asarray(yq, dtype=np.float64)
        with np.errstate(invalid="ignore"):
            return (yq >= lo) & (yq <= up)

    def fraction_inside(self, xq: np.ndarray, yq: np.ndarray) -> float:
        """Share of the response samples inside the corridor, in [0, 1].

        Only samples whose abscissa lies in the corridor's range count, each
        with the same weight (so sample the response uniformly). Returns NaN
        when no sample lies in the range.

        Parameters
        ----------
        xq, yq : array_like, shape (m,)
            Response abscissae (ms or mm) and values.
        """
        xq = np.asarray(xq, dtype=np.float64)
        yq = np.asarray(yq, dtype=np.float64)
        if xq.shape != yq.shape:
            raise ValueError("fraction_inside: x and y must have the same shape")
        in_range = (xq >= self.x[0]) & (xq <= self.x[-1])
        if not np.any(in_range):
            return float("nan")
        return float(np.mean(self.contains(xq[in_range], yq[in_range])))

    def widened(self, delta: float) -> Corridor:
        """Corridor with both bounds moved outward by ``delta`` (>= 0)."""
        if delta < 0.0:
            raise ValueError("widened: delta must be >= 0")
        return Corridor(self.x, self.lower - delta, self.upper + delta, self.center,
                        None, self.name)

    # ------------------------------------------------------------ constructors
    @classmethod
    def from_polygon(cls, px: Sequence[float], py: Sequence[float], name: str = "") -> Corridor:
        """Corridor enclosed by a closed polygon.

        The polygon is closed automatically (a repeated first point is
        allowed). Over each abscissa the corridor runs from the lowest to the
        highest polygon edge, which is exact for polygons that a vertical line
        cuts at most twice; for others the holes are filled in. Vertical edges
        (steps) are kept as a repeated abscissa.

        Parameters
        ----------
        px, py : sequence of float, length >= 3
            Vertices (abscissa, value) in drawing order.
        """
        px = np.asarray(px, dtype=np.float64)
        py = np.asarray(py, dtype=np.float64)
        if px.ndim != 1 or px.shape != py.shape or px.size < 3:
            raise ValueError("polygon: need at least 3 vertices with x and y")
        if not (np.all(np.isfinite(px)) and np.all(np.isfinite(py))):
            raise ValueError("polygon: vertices must be finite")
        if px[0] == px[-1] and py[0] == py[-1]:
            px, py = px[:-1], py[:-1]
        x0, y0 = px, py
        x1, y1 = np.roll(px, -1), np.roll(py, -1)
        sloped = x0 != x1
        ex0, ey0, ex1, ey1 = x0[sloped], y0[sloped], x1[sloped], y1[sloped]
        left, right = np.minimum(ex0, ex1), np.maximum(ex0, ex1)
        xs = np.unique(px)
        if xs.size < 2:
            raise ValueError("polygon: all vertices have the same abscissa")
        pts_x: list[float] = []
        pts_lo: list[float] = []
        pts_up: list[float] = []
        for a, b in zip(xs[:-1], xs[1:]):
            span = (left <= a) & (right >= b)
            if not np.any(span):
                raise ValueError(f"polygon: no edge spans {a:g}..{b:g}; is it closed?")

            def at(xv: float, span: np.ndarray = span) -> np.ndarray:
                return ey0[span] + (ey1[span] - ey0[span]) * (xv - ex0[span]) / (
                    ex1[span] - ex0[span])

            mid = at(0.5 * (a + b))
            i_lo, i_up = int(np.argmin(mid)), int(np.argmax(mid))
            ya, yb = at(a), at(b)
            for xv, lo_v, up_v in ((a, ya[i_lo], ya[i_up]), (b, yb[i_lo], yb[i_up])):
                if pts_x and pts_x[-1] == xv and pts_lo[-1] == lo_v and pts_up[-1] == up_v:
                    continue
                pts_x.append(float(xv))
                pts_lo.append(float(lo_v))
                pts_up.append(float(up_v))
        outline = np.column_stack([np.append(px, px[0]), np.append(py, py[0])])
        return cls(np.array(pts_x), np.array(pts_lo), np.array(pts_up), None, outline, name)

    @classmethod
    def from_bounds(cls, x_lower: Sequence[float], y_lower: Sequence[float],
                    x_upper: Sequence[float], y_upper: Sequence[float],
                    name: str = "") -> Corridor:
        """Corridor between a lower and an upper curve given on their own abscissae.

        The corridor covers the abscissae both curves cover; both curves are
        interpolated linearly at the union of their vertices in that range.

        Parameters
        ----------
        x_lower, y_lower : sequence of float, shape (p,)
            Lower bound, abscissae non-decreasing.
        x_upper, y_upper : sequence of float, shape (q,)
            Upper bound, abscissae non-decreasing.
        """
        xl, yl = np.asarray(x_lower, dtype=np.float64), np.asarray(y_lower, dtype=np.float64)
        xu, yu = np.asarray(x_upper, dtype=np.float64), np.asarray(y_upper, dtype=np.float64)
        for xv, yv, what in ((xl, yl, "lower"), (xu, yu, "upper")):
            if xv.ndim != 1 or xv.shape != yv.shape or xv.size < 2:
                raise ValueError(f"{what} bound: need >= 2 points with x and y")
            if np.any(np.diff(xv) < 0.0):
                raise ValueError(f"{what} bound: abscissae must not decrease")
        a, b = max(xl[0], xu[0]), min(xl[-1], xu[-1])
        if b <= a:
            raise ValueError("lower and upper bound do not overlap")
        xs = np.unique(np.concatenate([xl, xu, [a, b]]))
        xs = xs[(xs >= a) & (xs <= b)]
        lo, up = np.interp(xs, xl, yl), np.interp(xs, xu, yu)
        return cls(xs, np.minimum(lo, up), np.maximum(lo, up), None, None, name)

    @classmethod
    def from_specimens(cls, curves: Sequence[ArrayPair], n_sd: float = 1.0,
                       n_points: int = 501, name: str = "") -> Corridor:
        """Mean +/- ``n_sd`` standard deviations of specimen curves.

        The curves are linearly resampled at ``n_points`` equally spaced
        abscissae over the range all of them cover; the standard deviation is
        the sample one (``ddof = 1``).

        Parameters
        ----------
        curves : sequence of (x, y) pairs, at least 2
            Specimen curves, each ``x`` strictly increasing (shape (p_i,)).
        """
        if len(curves) < 2:
            raise ValueError("from_specimens: need at least 2 curves")
        if n_points < 2 or n_sd < 0.0:
            raise ValueError("from_specimens: need n_points >= 2 and n_sd >= 0")
        pairs = [(np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64))
                 for x, y in curves]
        for x, y in pairs:
            if x.ndim != 1 or x.shape != y.shape or x.size < 2 or np.any(np.diff(x) <= 0.0):
                raise ValueError("from_specimens: each curve needs >= 2 points with "
                                 "strictly increasing x")
        a = max(float(x[0]) for x, _ in pairs)
        b = min(float(x[-1]) for x, _ in pairs)
        if b <= a:
            raise ValueError("from_specimens: the curves have no common range")
        xs = np.linspace(a, b, n_points)
        ys = np.vstack([np.interp(xs, x, y) for x, y in pairs])
        mean = ys.mean(axis=0)
        sd = ys.std(axis=0, ddof=1)
        return cls(xs, mean - n_sd * sd, mean + n_sd * sd, mean, None, name)


def plot_corridor(path, **kwargs):  # type: ignore[no-untyped-def]
    """Draw a response against a corridor; see :func:`hollowbody.rating.plot.plot_corridor`.

    Imported lazily so that using corridors does not import matplotlib.
    """
    from hollowbody.rating.plot import plot_corridor as _plot

    return _plot(path, **kwargs)
