"""Near lists: the bucket sort's candidate lists cut down to the pairs close now.

Two levels of lists, each valid (complete) while every node of the contact
has moved less than half its margin along each axis since it was made, relative
to one common translation (:func:`~hollowbody.contact.penalty.gather`; the lists'
boxes are axis-aligned), and each holding every
node's current contact segment (:func:`keep_current`):

* the *far* lists of :func:`~hollowbody.contact.bucket.bucket_sort`: every
  segment whose box, enlarged by capture + m_far, holds the node; rebuilt
  over the whole grid (costly: ~5 ms for 6,000 segments);
* the *near* lists, made from the far lists alone (:func:`near_filter`): the
  listed pairs whose current box, enlarged by capture + m_near (m_near <
  m_far), holds the node. Cheap (a box test per listed pair), so they are
  rebuilt often, and the contact kernels then test and project only them.

The far lists are first cut by distance (:func:`distance_cut`, at the sort):
a box hit farther from the segment than the contact distance plus sqrt(3) far
margins (what node and segment can approach in space while they approach by
less than the margin along each axis) cannot come into contact before the next
sort and is left out.

A pair that is not in the near list cannot be in contact before the near
bound is reached (the argument of the bucket sort: node and segment surface
approach by at most the margin along each axis), and a pair not in the far list not before
the far bound is reached, when both levels are rebuilt. So the forces are
those of a search over every pair. Measured in the hollow block at 70 km/h
(m_far = 0.5, m_near = 0.1 of the median segment size): the near lists hold
about a third of the far lists' pairs.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from hollowbody.contact.bucket import segment_box
from hollowbody.contact.law import release_depth

_CHUNK = 256
#: Bound on sum |N_a| of the shape functions over a segment widened by the
#: natural-coordinate tolerance (quadrilaterals 1.0201, triangles 1.04): its
#: points lie within this factor of the corners' distances from the centroid.
_WIDEN = 1.05


@njit(cache=True)
def _boxes_of(j0, j1, x, seg, grow, sact, lo, hi):
    """Boxes (bucket.segment_box) of the segments sact[j0:j1]."""
    for j in range(j0, j1):
        segment_box(sact[j], x, seg, grow, lo, hi)


@njit(cache=True, inline="always")
def _near(s, held, px, py, pz, lo, hi):
    """Pair (node at p, segment s) is near: s is the node's held segment or its box
    lo / hi holds p (bitwise operators: no branch)."""
    return ((s == held) | ((lo[s, 0] <= px) & (px <= hi[s, 0]) & (lo[s, 1] <= py)
                           & (py <= hi[s, 1]) & (lo[s, 2] <= pz) & (pz <= hi[s, 2])))


@njit(cache=True)
def _near_rows_serial(i0, i1, x, nodes, ptr, cand, oseg, lo, hi, nptr, ncand, mark, stamp):
    """Near pairs of rows i0 <= i < i1 (a listed pair whose box holds the node, and
    the node's current contact segment oseg[i]: it may hold the node deeper than
    any box reaches), written into ncand from ptr[i0]; row i's count into nptr[i + 1].

    No branches in the pair loop: each listed segment is written and the count
    moves on only for a near pair (a box test that branches mispredicts about one
    time in five; the far lists keep about a third of their pairs); the write
    position never passes the read one. Stamps mark[s] = stamp for every segment
    written (threads may write the same stamp to the same entry: same value, no
    harm). Returns the end of the entries written."""
    n = ptr[i0]
    for i in range(i0, i1):
        nd = nodes[i]
        px = x[nd, 0]
        py = x[nd, 1]
        pz = x[nd, 2]
        held = oseg[i]
        n0 = n
        for q in range(ptr[i], ptr[i + 1]):
            s = cand[q]
            ncand[n] = s
            n += _near(s, held, px, py, pz, lo, hi)
        for q in range(n0, n):
            mark[ncand[q]] = stamp
        nptr[i + 1] = n - n0
    return n


@njit(cache=True)
def _compact(ptr, rows, nend, nptr, ncand):
    """Near lists of row blocks rows[b]:rows[b + 1] (written from ptr[rows[b]] to
    nend[b], row counts in nptr[i + 1]) moved into one CSR: nptr cumulative from 0.
    Blocks only move towards the front (a near list is part of its far list)."""
    w = 0
    nptr[0] = 0
    for b in range(rows.shape[0] - 1):
        r = ptr[rows[b]]
        if r != w:
            for q in range(r, nend[b]):
                ncand[w + q - r] = ncand[q]
        w += nend[b] - r
        for i in range(rows[b], rows[b + 1]):
            nptr[i + 1] += nptr[i]


@njit(cache=True)
def _marked(mark, stamp, nsact):
    """The segments s with mark[s] == stamp, ascending, into nsact; their number."""
    m = 0
    for s in range(mark.shape[0]):
        if mark[s] == stamp:
            nsact[m] = s
            m += 1
    return m


@njit(cache=True)
def near_filter(x, nodes, seg, grow, ptr, cand, oseg, sact, lo, hi, nptr, ncand, mark, stamp,
                nsact):
    """Near lists from the far lists at the current coordinates.

    x (L, 3) mm; nodes (ns,) int32 rows of x; seg (S, 4) int32 rows of x;
    grow (S,) mm capture distance + near margin; ptr (ns + 1,) int64 / cand
    int32: the far lists; sact (k,) int32 the segments in them (their boxes
    are recomputed into lo / hi (S, 3) mm, other rows untouched); oseg (ns,)
    int32 each node's current contact segment (-1: none), kept in its near list
    (the far lists hold it: :func:`keep_current`).
    Outputs: nptr (ns + 1,) int64 and ncand (>= ptr[-1],) int32 the near
    lists (a subset of each far list, same order); nsact (S,) int32 its first
    m entries the segments in the near lists, ascending.
    mark (S,) int64 scratch with stamp (int) larger than any value in it.
    Returns m.
    """
    _boxes_of(0, sact.shape[0], x, seg, grow, sact, lo, hi)
    rows = np.array([0, nodes.shape[0]], np.int64)
    nend = np.empty(1, np.int64)
    nend[0] = _near_rows_serial(0, nodes.shape[0], x, nodes, ptr, cand, oseg, lo, hi, nptr,
                                ncand, mark, stamp)
    _compact(ptr, rows, nend, nptr, ncand)
    return _marked(mark, stamp, nsact)


@njit(cache=True, parallel=True)
def near_filter_parallel(x, nodes, seg, grow, ptr, cand, oseg, sact, lo, hi, nptr, ncand,
                         mark, stamp, nsact, nblocks):
    """Threaded :func:`near_filter` (same lists): the boxes, then nblocks blocks of rows
    at once, each written into its own far lists' place, then moved together (callers
    hand the blocks out one at a time: :func:`~hollowbody.contact.bucket.dynamic_blocks`)."""
    ns = nodes.shape[0]
    nk = sact.shape[0]
    for c in prange((nk + _CHUNK - 1) // _CHUNK):
        _boxes_of(c * _CHUNK, min(nk, (c + 1) * _CHUNK), x, seg, grow, sact, lo, hi)
    rows = np.empty(nblocks + 1, np.int64)
    for b in range(nblocks + 1):
        rows[b] = (b * ns) // nblocks
    nend = np.empty(nblocks, np.int64)
    for b in prange(nblocks):
        nend[b] = _near_rows_serial(rows[b], rows[b + 1], x, nodes, ptr, cand, oseg, lo, hi,
                                    nptr, ncand, mark, stamp)
    _compact(ptr, rows, nend, nptr, ncand)
    return _marked(mark, stamp, nsact)


@njit(cache=True, inline="always")
def _keeps(i, s, px, py, pz, tn, s_thick, s_depth, s_two, cen, nrm, rad2, warp, oseg, margin):
    """Pair (row i at p, segment s) can come into contact before the next sort
    (:func:`distance_cut`)."""
    if s == oseg[i]:
        return True
    reach = 0.5 * (tn + s_thick[s])
    reach = max(reach, release_depth(s_depth[s], reach, s_two[s] != 0))
    rx = px - cen[s, 0]
    ry = py - cen[s, 1]
    rz = pz - cen[s, 2]
    dn = abs(rx * nrm[s, 0] + ry * nrm[s, 1] + rz * nrm[s, 2])
    lat = math.sqrt(max(rx * rx + ry * ry + rz * rz - dn * dn, 0.0))
    rad = math.sqrt(rad2[s])
    el = max(lat - _WIDEN * rad, 0.0)
    en = max(dn - _WIDEN * warp[s], 0.0)
    lim = (1.0 + 1.0e-6) * reach + _WIDEN * margin + 1.0e-4 * rad + 1.0e-9
    return el * el + en * en <= lim * lim


@njit(cache=True)
def _cut_rows(r0, r1, x, nodes, n_thick, s_thick, s_depth, s_two, cen, nrm, rad2, warp, oseg,
              margin, ptr, cand, nptr):
    """Rows r0:r1 of :func:`distance_cut`: their kept pairs compacted from ptr[r0] on
    (in place), nptr[i] the new start of row i; returns the end of the kept pairs."""
    w = ptr[r0]
    for i in range(r0, r1):
        nd = nodes[i]
        px = x[nd, 0]
        py = x[nd, 1]
        pz = x[nd, 2]
        tn = n_thick[i]
        nptr[i] = w
        for q in range(ptr[i], ptr[i + 1]):
            s = cand[q]
            if _keeps(i, s, px, py, pz, tn, s_thick, s_depth, s_two, cen, nrm, rad2, warp,
                      oseg, margin):
                cand[w] = s
                w += 1
    return w


@njit(cache=True)
def distance_cut(x, nodes, n_thick, s_thick, s_depth, s_two, cen, nrm, rad2, warp, oseg, margin,
                 ptr, cand):
    """Leave out of the far lists (in place) the pairs that cannot come into
    contact before the next sort; returns the new number of pairs.

    x (L, 3) mm; nodes (ns,) int32 rows of x; n_thick (ns,), s_thick, s_depth
    (S,) mm, s_two (S,) int8 as in :func:`~hollowbody.contact.detect.detect_pass`;
    cen, nrm, rad2, warp (S, ...) the segment frames at x
    (:func:`~hollowbody.contact.frames.segment_frames`); oseg (ns,) int32 the
    segment each node is in contact with (kept: it may hold the node deeper);
    margin mm: node and segment approach by less than this (in space) until the
    next sort (sqrt(3) times the sort's margin, see
    :func:`~hollowbody.contact.penalty.gather`); ptr (ns + 1,) int64 / cand int32
    the lists, compacted in place (each row keeps its order).

    A pair is in contact only at a foot point x_p on the segment (natural
    coordinates within the tolerance) with |p - x_p| below the contact distance
    max(reach, release depth). The segment's points lie in the cylinder about
    its centroid of radius _WIDEN sqrt(rad2) and half height _WIDEN warp along
    its normal, so the distance of p from that cylinder bounds |p - x_p| from
    below; node and segment points approach by at most _WIDEN margin before the
    next sort. A pair farther than the contact distance plus that is left out.
    """
    ns = nodes.shape[0]
    nptr = np.empty(ns + 1, np.int64)
    w = _cut_rows(0, ns, x, nodes, n_thick, s_thick, s_depth, s_two, cen, nrm, rad2, warp, oseg,
                  margin, ptr, cand, nptr)
    nptr[ns] = w
    ptr[:] = nptr
    return w


@njit(cache=True, parallel=True)
def distance_cut_parallel(x, nodes, n_thick, s_thick, s_depth, s_two, cen, nrm, rad2, warp, oseg,
                          margin, ptr, cand, nblocks):
    """:func:`distance_cut` on numba's threads: ``nblocks`` blocks of rows with about
    equal numbers of pairs, each compacted within its own range of cand, then moved
    together (the same lists as the serial cut)."""
    ns = nodes.shape[0]
    total = ptr[ns]
    rows = np.empty(nblocks + 1, np.int64)
    rows[0] = 0
    r = 0
    for b in range(1, nblocks):
        goal = (b * total) // nblocks
        while r < ns and ptr[r] < goal:
            r += 1
        rows[b] = r
    rows[nblocks] = ns
    nptr = np.empty(ns + 1, np.int64)
    ends = np.empty(nblocks, np.int64)
    for b in prange(nblocks):
        ends[b] = _cut_rows(rows[b], rows[b + 1], x, nodes, n_thick, s_thick, s_depth, s_two,
                            cen, nrm, rad2, warp, oseg, margin, ptr, cand, nptr)
    w = 0
    for b in range(nblocks):  # blocks in order: each moves down (never past a later one)
        r0 = rows[b]
        r1 = rows[b + 1]
        if r0 == r1:
            continue
        src = ptr[r0]
        shift = src - w
        for q in range(src, ends[b]):
            cand[q - shift] = cand[q]
        for i in range(r0, r1):
            nptr[i] -= shift
        w += ends[b] - src
    nptr[ns] = w
    ptr[:] = nptr
    return w


@njit(cache=True)
def _missing_current(ptr, cand, oseg, alive):
    """How many rows i have a live current segment oseg[i] not in their list."""
    n = 0
    for i in range(oseg.shape[0]):
        s = oseg[i]
        if s < 0 or not alive[s]:
            continue
        found = False
        for q in range(ptr[i], ptr[i + 1]):
            if cand[q] == s:
                found = True
                break
        if not found:
            n += 1
    return n


@njit(cache=True)
def _with_current(ptr, cand, oseg, alive, nptr, ncand):
    """Copy the lists into nptr / ncand, appending each missing live oseg[i]."""
    w = 0
    for i in range(oseg.shape[0]):
        nptr[i] = w
        s = oseg[i]
        found = s < 0 or not alive[s]
        for q in range(ptr[i], ptr[i + 1]):
            ncand[w] = cand[q]
            w += 1
            if cand[q] == s:
                found = True
        if not found:
            ncand[w] = s
            w += 1
    nptr[oseg.shape[0]] = w


def keep_current(ptr: np.ndarray, cand: np.ndarray, oseg: np.ndarray, alive: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Far lists (CSR ptr (ns + 1,) int64, cand int32) that hold every node's
    current contact segment oseg (ns,) int32 (-1: none) when it is ``alive``
    (S,) bool: the detection accepts the segment that held a node last cycle down
    to the release depth plus the penetration it was found with, which can be
    deeper than the box of any sort or filter reaches. Without it the pair was
    dropped whenever the lists were rebuilt while the node was that deep (a
    held contact let go, and a run that depended on when the lists were
    rebuilt). Returns the same arrays when nothing is missing."""
    n = _missing_current(ptr, cand, oseg, alive)
    if n == 0:
        return ptr, cand
    nptr = np.empty_like(ptr)
    ncand = np.empty(cand.shape[0] + n, dtype=cand.dtype)
    _with_current(ptr, cand, oseg, alive, nptr, ncand)
    return nptr, ncand
