"""Segment frames: per-segment data for the contact kernels' rejection tests.

Before the closest-point projection of a node onto a candidate segment (a
Newton iteration on a bilinear quadrilateral, ~0.1 us; see
:mod:`hollowbody.contact.geometry`), the kernel rejects pairs that cannot be
in contact with two tests on data computed here once per segment and cycle:
the distance from the segment's mean plane, ``|(p - cen) . n| > lim + warp``
(n the unit normal from the diagonals, warp the farthest corner from the mean
plane, lim the pair's contact distance), and the distance from the centroid
across the normal, against the farthest corner.

Only the frames of segments in some node's near list are needed
(:func:`segment_frames_of`; :mod:`hollowbody.contact.nearlist`).

Tried and left out (2026-11, hollow block at 70 km/h): a third, in-plane test
(the node inside every edge's half-plane, widened by the natural-coordinate
tolerance and a bound on the normal's tilt over a warped segment). It cut the
Newton projections by 30 % but tripled the cost of a frame; the contact time
was the same (6.0 vs 6.1 s in 6 ms of the block).
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True, inline="always")
def _frame(s, x, seg, cen, nrm, rad2, warp):
    """Frame of segment s (see :func:`segment_frames`)."""
    a = seg[s, 0]
    b = seg[s, 1]
    c = seg[s, 2]
    d = seg[s, 3]
    tri = c == d
    nc = 3.0 if tri else 4.0
    for k in range(3):
        tot = x[a, k] + x[b, k] + x[c, k]
        if not tri:
            tot += x[d, k]
        cen[s, k] = tot / nc
    ux = x[c, 0] - x[a, 0]
    uy = x[c, 1] - x[a, 1]
    uz = x[c, 2] - x[a, 2]
    vx = x[d, 0] - x[b, 0]
    vy = x[d, 1] - x[b, 1]
    vz = x[d, 2] - x[b, 2]
    nx = uy * vz - uz * vy
    ny = uz * vx - ux * vz
    nz = ux * vy - uy * vx
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    if nn > 0.0:
        nx /= nn
        ny /= nn
        nz /= nn
    nrm[s, 0] = nx
    nrm[s, 1] = ny
    nrm[s, 2] = nz
    r = 0.0
    h = 0.0
    for j in range(4):
        q = seg[s, j]
        dx = x[q, 0] - cen[s, 0]
        dy = x[q, 1] - cen[s, 1]
        dz = x[q, 2] - cen[s, 2]
        r = max(r, dx * dx + dy * dy + dz * dz)
        h = max(h, abs(dx * nx + dy * ny + dz * nz))
    rad2[s] = r
    warp[s] = h


@njit(cache=True)
def segment_frames(x, seg, cen, nrm, rad2, warp):
    """Frames of every segment.

    x (L, 3) mm; seg (S, 4) int32 rows of x (triangles N4 == N3). Outputs:
    centroid cen (S, 3), unit mean normal nrm (S, 3), squared radius rad2 (S,)
    mm^2 (farthest corner), warp (S,) mm (farthest corner from the mean plane:
    the segment lies within +-warp of it).
    """
    for s in range(seg.shape[0]):
        _frame(s, x, seg, cen, nrm, rad2, warp)


@njit(cache=True)
def segment_frames_of(x, seg, sact, cen, nrm, rad2, warp):
    """:func:`segment_frames` of the segments sact (m,) int32 only; the other
    rows are left as they are (the kernels read the frames of listed segments only)."""
    for j in range(sact.shape[0]):
        _frame(sact[j], x, seg, cen, nrm, rad2, warp)
