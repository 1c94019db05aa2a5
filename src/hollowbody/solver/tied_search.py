"""Set-up geometry of tied contacts: closest point of a node on a segment, and the search.

A segment is a 4-node facet (triangles with ``N4 == N3``). Quadrilaterals use
the bilinear map x(xi, eta) = sum_a N_a(xi, eta) x_a on [-1, 1]^2 with
N_a = (1 + xi xi_a)(1 + eta eta_a) / 4 (LS-DYNA corner order); triangles the
linear map x(r, s) = (1 - r - s) x_1 + r x_2 + s x_3 on r, s >= 0, r + s <= 1.
Both are called "natural coordinates" (u, v) below.

The closest point is the interior stationary point of |x(u, v) - p|^2 (Newton)
when it lies inside the segment, else the closest point on its (straight)
edges. The tie frame at (u, v): e1 = g1 / |g1|, n = g1 x g2 / |g1 x g2|,
e2 = n x e1 with g1 = dx/du, g2 = dx/dv; it turns with the segment, so an
offset stored in it follows any rigid motion exactly.

Everything here runs once at set-up (numba kernels over arrays; the search
uses a k-d tree over segment centroids).
"""

from __future__ import annotations

import numpy as np
from numba import njit
from scipy.spatial import cKDTree

_XI = (-1.0, 1.0, 1.0, -1.0)
_ETA = (-1.0, -1.0, 1.0, 1.0)


@njit(cache=True)
def shape_weights(u: float, v: float, tri: bool, out: np.ndarray) -> None:
    """Shape-function values (4,) at natural coordinates (u, v) into ``out``."""
    if tri:
        out[0] = 1.0 - u - v
        out[1] = u
        out[2] = v
        out[3] = 0.0
    else:
        for a in range(4):
            out[a] = 0.25 * (1.0 + u * _XI[a]) * (1.0 + v * _ETA[a])


@njit(cache=True)
def tangents(xs: np.ndarray, u: float, v: float, tri: bool, g: np.ndarray) -> None:
    """Tangents g[0] = dx/du, g[1] = dx/dv (2, 3) of segment corners xs (4, 3) mm."""
    for k in range(3):
        if tri:
            g[0, k] = xs[1, k] - xs[0, k]
            g[1, k] = xs[2, k] - xs[0, k]
        else:
            g0 = 0.0
            g1 = 0.0
            for a in range(4):
                g0 += 0.25 * _XI[a] * (1.0 + v * _ETA[a]) * xs[a, k]
                g1 += 0.25 * _ETA[a] * (1.0 + u * _XI[a]) * xs[a, k]
            g[0, k] = g0
            g[1, k] = g1


@njit(cache=True)
def frame(xs: np.ndarray, u: float, v: float, tri: bool, g: np.ndarray,
          e: np.ndarray) -> bool:
    """Orthonormal tie frame e (3, 3) rows e1, e2, n at (u, v); False if degenerate.

    g: (2, 3) work array (tangents on return).
    """
    tangents(xs, u, v, tri, g)
    n0 = g[0, 1] * g[1, 2] - g[0, 2] * g[1, 1]
    n1 = g[0, 2] * g[1, 0] - g[0, 0] * g[1, 2]
    n2 = g[0, 0] * g[1, 1] - g[0, 1] * g[1, 0]
    nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    l1 = np.sqrt(g[0, 0] ** 2 + g[0, 1] ** 2 + g[0, 2] ** 2)
    if nn <= 0.0 or l1 <= 0.0:
        return False
    for k in range(3):
        e[0, k] = g[0, k] / l1
    e[2, 0] = n0 / nn
    e[2, 1] = n1 / nn
    e[2, 2] = n2 / nn
    e[1, 0] = e[2, 1] * e[0, 2] - e[2, 2] * e[0, 1]
    e[1, 1] = e[2, 2] * e[0, 0] - e[2, 0] * e[0, 2]
    e[1, 2] = e[2, 0] * e[0, 1] - e[2, 1] * e[0, 0]
    return True


@njit(cache=True)
def _point(xs: np.ndarray, u: float, v: float, tri: bool, w: np.ndarray,
           out: np.ndarray) -> None:
    shape_weights(u, v, tri, w)
    for k in range(3):
        out[k] = w[0] * xs[0, k] + w[1] * xs[1, k] + w[2] * xs[2, k] + w[3] * xs[3, k]


@njit(cache=True)
def _dist2(xs: np.ndarray, u: float, v: float, tri: bool, p: np.ndarray, w: np.ndarray,
           q: np.ndarray) -> float:
    _point(xs, u, v, tri, w, q)
    return (q[0] - p[0]) ** 2 + (q[1] - p[1]) ** 2 + (q[2] - p[2]) ** 2


@njit(cache=True)
def _edge_param(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> float:
    """Parameter t in [0, 1] of the point of segment a-b closest to p."""
    d0 = b[0] - a[0]
    d1 = b[1] - a[1]
    d2 = b[2] - a[2]
    dd = d0 * d0 + d1 * d1 + d2 * d2
    if dd <= 0.0:
        return 0.0
    t = ((p[0] - a[0]) * d0 + (p[1] - a[1]) * d1 + (p[2] - a[2]) * d2) / dd
    return min(max(t, 0.0), 1.0)


@njit(cache=True)
def closest_point(xs: np.ndarray, tri: bool, p: np.ndarray) -> tuple[float, float, float]:
    """Natural coordinates (u, v) of the point of segment xs (4, 3) closest to p (3,),
    and the squared distance (mm^2)."""
    w = np.zeros(4)
    q = np.zeros(3)
    g = np.zeros((2, 3))
    best_u, best_v, best = 0.0, 0.0, np.inf
    # interior stationary point
    u = 1.0 / 3.0 if tri else 0.0
    v = 1.0 / 3.0 if tri else 0.0
    ok = True
    for _ in range(30):
        _point(xs, u, v, tri, w, q)
        tangents(xs, u, v, tri, g)
        r0, r1, r2 = q[0] - p[0], q[1] - p[1], q[2] - p[2]
        f0 = g[0, 0] * r0 + g[0, 1] * r1 + g[0, 2] * r2
        f1 = g[1, 0] * r0 + g[1, 1] * r1 + g[1, 2] * r2
        a11 = g[0, 0] ** 2 + g[0, 1] ** 2 + g[0, 2] ** 2
        a22 = g[1, 0] ** 2 + g[1, 1] ** 2 + g[1, 2] ** 2
        a12 = g[0, 0] * g[1, 0] + g[0, 1] * g[1, 1] + g[0, 2] * g[1, 2]
        if not tri:  # second derivative x_{,uv} = sum xi_a eta_a x_a / 4
            for k in range(3):
                h = 0.25 * (xs[0, k] - xs[1, k] + xs[2, k] - xs[3, k])
                a12 += h * (q[k] - p[k])
        det = a11 * a22 - a12 * a12
        if det == 0.0 or not np.isfinite(det):
            ok = False
            break
        du = -(a22 * f0 - a12 * f1) / det
        dv = -(a11 * f1 - a12 * f0) / det
        u += du
        v += dv
        if abs(u) > 10.0 or abs(v) > 10.0:
            ok = False
            break
        if abs(du) + abs(dv) < 1e-13:
            break
    eps = 1e-10
    if ok:
        inside = (u >= -eps and v >= -eps and u + v <= 1.0 + eps) if tri else \
            (abs(u) <= 1.0 + eps and abs(v) <= 1.0 + eps)
        if inside:
            if tri:
                u, v = min(max(u, 0.0), 1.0), min(max(v, 0.0), 1.0)
            else:
                u, v = min(max(u, -1.0), 1.0), min(max(v, -1.0), 1.0)
            best_u, best_v, best = u, v, _dist2(xs, u, v, tri, p, w, q)
    # edges (straight lines in both maps)
    n_edges = 3 if tri else 4
    for k in range(n_edges):
        a = xs[k]
        b = xs[(k + 1) % n_edges]
        t = _edge_param(a, b, p)
        if tri:
            if k == 0:
                eu, ev = t, 0.0
            elif k == 1:
                eu, ev = 1.0 - t, t
            else:
                eu, ev = 0.0, 1.0 - t
        else:
            if k == 0:
                eu, ev = -1.0 + 2.0 * t, -1.0
            elif k == 1:
                eu, ev = 1.0, -1.0 + 2.0 * t
            elif k == 2:
                eu, ev = 1.0 - 2.0 * t, 1.0
            else:
                eu, ev = -1.0, 1.0 - 2.0 * t
        d2 = _dist2(xs, eu, ev, tri, p, w, q)
        if best == np.inf or d2 < best - 1e-14 * max(best, 1.0):
            best_u, best_v, best = eu, ev, d2
    return best_u, best_v, best


@njit(cache=True)
def _best_segments(xp: np.ndarray, ptr: np.ndarray, cand: np.ndarray, seg: np.ndarray,
                   x: np.ndarray, out_seg: np.ndarray, out_uv: np.ndarray,
                   out_d: np.ndarray) -> None:
    """For every point k: the candidate segment cand[ptr[k]:ptr[k+1]] closest to xp[k].

    Fills out_seg (k,) (-1: no candidate), out_uv (k, 2), out_d (k,) mm.
    """
    xs = np.zeros((4, 3))
    for k in range(xp.shape[0]):
        out_seg[k] = -1
        out_d[k] = np.inf
        for c in range(ptr[k], ptr[k + 1]):
            s = cand[c]
            for a in range(4):
                for j in range(3):
                    xs[a, j] = x[seg[s, a], j]
            tri = seg[s, 3] == seg[s, 2]
            u, v, d2 = closest_point(xs, tri, xp[k])
            d = np.sqrt(d2)
            if out_seg[k] < 0 or d < out_d[k] - 1e-12 * max(d, 1.0):
                out_seg[k], out_d[k] = s, d
                out_uv[k, 0], out_uv[k, 1] = u, v


def closest_segments(points: np.ndarray, seg: np.ndarray, x: np.ndarray,
                     radius: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Closest segment of every point among those whose centroid lies within ``radius``.

    points: (k, 3) mm; seg: (s, 4) node indices; x: (n, 3) mm. Returns the segment
    index (k,) int64 (-1 when no segment is near), natural coordinates (k, 2) and
    the distance (k,) mm to the closest point.
    """
    k = points.shape[0]
    out_seg = np.full(k, -1, np.int64)
    out_uv = np.zeros((k, 2))
    out_d = np.full(k, np.inf)
    if k == 0 or seg.shape[0] == 0:
        return out_seg, out_uv, out_d
    xs = x[seg]
    tri = seg[:, 3] == seg[:, 2]
    cen = xs.mean(axis=1)
    cen[tri] = xs[tri, :3].mean(axis=1)
    lists = cKDTree(cen).query_ball_point(points, r=radius)
    counts = np.fromiter((len(c) for c in lists), np.int64, count=k)
    ptr = np.zeros(k + 1, np.int64)
    np.cumsum(counts, out=ptr[1:])
    cand = np.fromiter((s for c in lists for s in c), np.int64, count=int(ptr[-1]))
    _best_segments(np.ascontiguousarray(points, dtype=np.float64), ptr, cand,
                   np.ascontiguousarray(seg, dtype=np.int64),
                   np.ascontiguousarray(x, dtype=np.float64), out_seg, out_uv, out_d)
    return out_seg, out_uv, out_d


def local_offsets(points: np.ndarray, seg: np.ndarray, uv: np.ndarray,
                  x: np.ndarray) -> np.ndarray:
    """Offsets (k, 3) of points from their segment point x(u, v), in the tie frame
    (e1, e2, n components, mm); rows of degenerate segments are zero."""
    out = np.zeros((points.shape[0], 3))
    _local_offsets(np.ascontiguousarray(points, dtype=np.float64),
                   np.ascontiguousarray(seg, dtype=np.int64), np.ascontiguousarray(uv),
                   np.ascontiguousarray(x, dtype=np.float64), out)
    return out


@njit(cache=True)
def _local_offsets(points: np.ndarray, seg: np.ndarray, uv: np.ndarray, x: np.ndarray,
                   out: np.ndarray) -> None:
    xs = np.zeros((4, 3))
    g = np.zeros((2, 3))
    e = np.zeros((3, 3))
    w = np.zeros(4)
    q = np.zeros(3)
    for k in range(points.shape[0]):
        for a in range(4):
            for j in range(3):
                xs[a, j] = x[seg[k, a], j]
        tri = seg[k, 3] == seg[k, 2]
        if not frame(xs, uv[k, 0], uv[k, 1], tri, g, e):
            continue
        _point(xs, uv[k, 0], uv[k, 1], tri, w, q)
        for i in range(3):
            out[k, i] = ((points[k, 0] - q[0]) * e[i, 0] + (points[k, 1] - q[1]) * e[i, 1]
                         + (points[k, 2] - q[2]) * e[i, 2])
