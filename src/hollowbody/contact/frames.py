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

Quadrilaterals also get two *slabs* (:func:`slab_bound`): the node must lie
within the segment's extent across each of its two edge directions, widened
by how far the normal tilts over the segment times the largest distance that
could still win. In the crushed hollow block (70 km/h) most projections left
after the first two tests end outside the segment (a node over the
neighbouring segment of a wall it touches); the slabs reject about half of
the projections (self contact, a recorded crushed state: 5870 -> 3131 per
cycle) at a few ns per pair; the slab data costs about 30 ns per segment and
cycle. (Making it only for the segments that reach the test, about half of
them, inside the detection kernel was slower: 1140 vs 1000 us per cycle of the
self contact in a recorded crushed state.)

Tried and left out (2026-11, hollow block at 70 km/h): a third, in-plane test
(the node inside every edge's half-plane, widened by the natural-coordinate
tolerance and a bound on the normal's tilt over a warped segment). It cut the
Newton projections by 30 % but tripled the cost of a frame; the contact time
was the same (6.0 vs 6.1 s in 6 ms of the block). The slabs above need no
square root for most segments and are tested after the cheap tests only.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from hollowbody.contact.geometry import INSIDE_TOL, _quad_coefficients

#: Relative bound on the tangential residual p - x_p - d n of a converged foot
#: point (last Newton step below 1e-6 in natural coordinates) times the segment's
#: size, allowed for by the slabs: generous (the residual is ~1e-6 of the size
#: before the last step and far smaller after it).
_RESIDUAL = 1.0e-5
#: Segments per parallel work item of :func:`segment_frames_of_parallel`.
_CHUNK = 256
#: Segments flatter than this (warp / radius) get no slab test.
_FLAT = 1.0e-3
#: Columns of the slab array (S, SLAB_COLS): per direction u (3), threshold, tilt.
SLAB_COLS = 10


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


@njit(cache=True, inline="always")
def slab_of(s, x, seg, nrm, rad2, warp, slab):
    """Slab data of segment s (row s of slab, see :func:`slab_bound`) from its corners
    in x and its frame (nrm, rad2, warp); no test (inf) for triangles, degenerate
    segments (zero normal) and flat ones (warp <= _FLAT times the radius: their
    projection takes one or a few Newton steps, the slabs would cost more)."""
    a = seg[s, 0]
    b = seg[s, 1]
    c = seg[s, 2]
    d = seg[s, 3]
    nx = nrm[s, 0]
    ny = nrm[s, 1]
    nz = nrm[s, 2]
    if (c == d or (nx == 0.0 and ny == 0.0 and nz == 0.0)
            or warp[s] * warp[s] <= _FLAT * _FLAT * rad2[s]):
        for j in range(SLAB_COLS):
            slab[s, j] = 0.0
        slab[s, 3] = np.inf
        slab[s, 8] = np.inf
    else:
        _slabs(s, x[a, 0], x[a, 1], x[a, 2], x[b, 0], x[b, 1], x[b, 2], x[c, 0], x[c, 1],
               x[c, 2], x[d, 0], x[d, 1], x[d, 2], nx, ny, nz, slab)


@njit(cache=True, inline="always")
def _slabs(s, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, nx, ny, nz, slab):
    """Slab data of quadrilateral s with corners 0..3 (mm) and unit normal n (see
    :func:`slab_bound`)."""
    a = 1.0 + INSIDE_TOL
    _, _, _, c1x, c1y, c1z, c2x, c2y, c2z, c3x, c3y, c3z = _quad_coefficients(
        x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3)
    # x_,xi x x_,eta = P + xi Q + eta R: P = c1 x c2, Q = c1 x c3, R = c3 x c2
    ppx = c1y * c2z - c1z * c2y
    ppy = c1z * c2x - c1x * c2z
    ppz = c1x * c2y - c1y * c2x
    qqx = c1y * c3z - c1z * c3y
    qqy = c1z * c3x - c1x * c3z
    qqz = c1x * c3y - c1y * c3x
    rrx = c3y * c2z - c3z * c2y
    rry = c3z * c2x - c3x * c2z
    rrz = c3x * c2y - c3y * c2x
    low = abs(ppx * nx + ppy * ny + ppz * nz) - a * (
        abs(qqx * nx + qqy * ny + qqz * nz) + abs(rrx * nx + rry * ny + rrz * nz))
    size = (abs(c1x) + abs(c1y) + abs(c1z) + abs(c2x) + abs(c2y) + abs(c2z)
            + abs(c3x) + abs(c3y) + abs(c3z))
    for k in range(2):
        if k == 0:  # u = n x c2 (across the eta edges)
            ux = ny * c2z - nz * c2y
            uy = nz * c2x - nx * c2z
            uz = nx * c2y - ny * c2x
        else:  # u = n x c1
            ux = ny * c1z - nz * c1y
            uy = nz * c1x - nx * c1z
            uz = nx * c1y - ny * c1x
        o = 5 * k
        slab[s, o] = ux
        slab[s, o + 1] = uy
        slab[s, o + 2] = uz
        slab[s, o + 3] = (a * (abs(c1x * ux + c1y * uy + c1z * uz)
                               + abs(c2x * ux + c2y * uy + c2z * uz))
                          + a * a * abs(c3x * ux + c3y * uy + c3z * uz)
                          + _RESIDUAL * size * (abs(ux) + abs(uy) + abs(uz)) + 1.0e-12)
        # |n_f . u| <= tilt / low when the normal is bounded (low > 0), and <= |u|
        u2 = ux * ux + uy * uy + uz * uz
        tilt = (abs(ppx * ux + ppy * uy + ppz * uz) + a * (
            abs(qqx * ux + qqy * uy + qqz * uz) + abs(rrx * ux + rry * uy + rrz * uz)))
        if low > 0.0 and tilt * tilt < u2 * low * low:
            tf = tilt / low
        else:
            tf = math.sqrt(u2)
        slab[s, o + 4] = (1.0 + 1.0e-9) * tf


@njit(cache=True, inline="always")
def slab_bound(s, rx, ry, rz, dmax, slab):
    """True when node p (r = p - cen[s], mm) has no foot point on quadrilateral s
    that the projection would report inside (natural coordinates within 1 +
    INSIDE_TOL, converged) at a distance |d| <= dmax (mm): the projection can be
    skipped. False for triangles (exact, cheap projection) and twisted segments.

    Why: with x(xi, eta) = c + xi c1 + eta c2 + xi eta c3, for any direction u the
    segment's points satisfy |(x - c) . u| <= a |c1 . u| + a |c2 . u| + a^2 |c3 . u|
    (a = 1 + INSIDE_TOL; a bilinear function's extremes are at the corners). A foot
    point has p = x + d n_f + r (n_f the unit normal there, r the tangential
    residual), and |n_f . u| <= (|P . u| + a (|Q . u| + |R . u|)) / low, since
    x_,xi x x_,eta = P + xi Q + eta R and low = |P . n| - a (|Q . n| + |R . n|)
    bounds its length from below. So |(p - c) . u| beyond the first bound plus
    dmax times the second (plus the residual) leaves no such foot point; tested
    for u = n x c2 and u = n x c1.
    """
    for o in (0, 5):
        val = abs(rx * slab[s, o] + ry * slab[s, o + 1] + rz * slab[s, o + 2])
        if val - slab[s, o + 3] > dmax * slab[s, o + 4]:
            return True
    return False


@njit(cache=True)
def segment_frames(x, seg, cen, nrm, rad2, warp, slab, with_slab=True):
    """Frames of every segment.

    x (L, 3) mm; seg (S, 4) int32 rows of x (triangles N4 == N3). Outputs:
    centroid cen (S, 3), unit mean normal nrm (S, 3), squared radius rad2 (S,)
    mm^2 (farthest corner), warp (S,) mm (farthest corner from the mean plane:
    the segment lies within +-warp of it), slab (S, SLAB_COLS) the slabs'
    directions, thresholds (mm, inf: no test) and tilt factors (:func:`slab_bound`);
    with_slab False leaves slab as it is.
    """
    if with_slab:
        for s in range(seg.shape[0]):
            _frame(s, x, seg, cen, nrm, rad2, warp)
            slab_of(s, x, seg, nrm, rad2, warp, slab)
    else:  # a loop of its own: the frames alone compile to faster code
        for s in range(seg.shape[0]):
            _frame(s, x, seg, cen, nrm, rad2, warp)


@njit(cache=True)
def segment_frames_of(x, seg, sact, cen, nrm, rad2, warp, slab, with_slab=True):
    """:func:`segment_frames` of the segments sact (m,) int32 only; the other
    rows are left as they are (the kernels read the frames of listed segments only)."""
    _frames_range(0, sact.shape[0], x, seg, sact, cen, nrm, rad2, warp, slab, with_slab)


@njit(cache=True)
def _frames_range(j0, j1, x, seg, sact, cen, nrm, rad2, warp, slab, with_slab):
    if with_slab:
        for j in range(j0, j1):
            _frame(sact[j], x, seg, cen, nrm, rad2, warp)
            slab_of(sact[j], x, seg, nrm, rad2, warp, slab)
    else:  # a loop of its own: the frames alone compile to faster code
        for j in range(j0, j1):
            _frame(sact[j], x, seg, cen, nrm, rad2, warp)


@njit(cache=True, parallel=True)
def segment_frames_of_parallel(x, seg, sact, cen, nrm, rad2, warp, slab, with_slab=True):
    """Threaded :func:`segment_frames_of` (each segment's rows written by one item)."""
    m = sact.shape[0]
    for c in prange((m + _CHUNK - 1) // _CHUNK):
        _frames_range(c * _CHUNK, min(m, (c + 1) * _CHUNK), x, seg, sact, cen, nrm, rad2, warp,
                      slab, with_slab)
