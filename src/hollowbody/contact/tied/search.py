"""Set-up search of tied contacts: the closest master segment of each slave node.

Candidates are the segments whose centroid lies within a radius of the node
(a k-d tree over the centroids); the node's closest point on each candidate
is :func:`hollowbody.contact.geometry.closest_point` (the projection shared
with the penalty contact), the closest candidate wins. Also the offsets of
nodes that keep their distance, in the tie frame (:func:`tie_frame`).
Runs once at set-up.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from scipy.spatial import cKDTree

from hollowbody.contact.geometry import closest_point, segment_point
from hollowbody.contact.tied.frame import tie_frame


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

    points: (k, 3) mm; seg: (s, 4) node indices; x: (n, 3) mm; radius mm. Returns
    the segment index (k,) int64 (-1 when no segment is near), natural coordinates
    (k, 2) and the distance (k,) mm to the closest point.
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
    """Offsets (k, 3) mm of points (k, 3) mm from their segment point x(u, v), in the
    tie frame (e1, e2, n components); seg (k, 4), uv (k, 2), x (n, 3) mm. Rows of
    degenerate segments are zero."""
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
        if not tie_frame(xs, uv[k, 0], uv[k, 1], tri, g, e):
            continue
        segment_point(xs, uv[k, 0], uv[k, 1], tri, w, q)
        for i in range(3):
            out[k, i] = ((points[k, 0] - q[0]) * e[i, 0] + (points[k, 1] - q[1]) * e[i, 1]
                         + (points[k, 2] - q[2]) * e[i, 2])
