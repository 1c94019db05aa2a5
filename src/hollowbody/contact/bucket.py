"""Bucket-sort broad phase: candidate segments per slave node (numba).

Each segment's bounding box, enlarged by its capture distance (how far from
the segment a node can still be in contact: contact thickness or release
depth) plus a *margin*, is registered in every cell of a uniform grid it
overlaps (cell size ~ the typical enlarged box, so a segment touches a few
cells). The (cell key, segment) pairs are sorted by key; a node looks up its
own cell by binary search and keeps the segments whose enlarged box contains
it. The result is a CSR list per slave node (``ptr`` (ns + 1,), ``seg``).

The list stays complete while every node has moved less than ``margin / 2``
since the sort (node and segment can then approach by at most ``margin``):
:class:`~hollowbody.contact.runtime.ContactRuntime` re-sorts every
``contact_sort_interval`` cycles or earlier when that bound is reached.
Grid cells are numbered densely (a counting sort groups the segments) unless
the grid has far more cells than pairs; then the keys are sorted and searched,
so a large, sparse model costs nothing extra.
"""

from __future__ import annotations

import numpy as np
from numba import get_num_threads, njit, prange

#: Fewer slave nodes than this: serial kernels (thread wake-up costs more;
#: on a machine busier than its cores, OpenMP's spinning threads far more).
PARALLEL_MIN_NODES = 16384
#: Items per parallel work unit (array arguments cost an incref/decref per call).
_CHUNK = 256
#: Bound on grid pairs per segment before the cell size is doubled.
_MAX_PAIRS_PER_SEGMENT = 27
#: Grids with at most this many cells (or 4 per grid pair) are dense: segments
#: grouped by a counting sort, a node's cell found by index.
_DENSE_CELLS = 1 << 20
_DENSE_PER_PAIR = 4


@njit(cache=True, inline="always")
def segment_box(s, x, seg, grow, lo, hi):
    """Box of segment s: lo[s] / hi[s] = min / max of its corners -/+ grow[s] (mm)."""
    for k in range(3):
        a = x[seg[s, 0], k]
        b = a
        for j in range(1, 4):
            v = x[seg[s, j], k]
            a = min(a, v)
            b = max(b, v)
        lo[s, k] = a - grow[s]
        hi[s, k] = b + grow[s]


@njit(cache=True)
def _boxes_range(s0, s1, x, seg, grow, lo, hi):
    for s in range(s0, s1):
        segment_box(s, x, seg, grow, lo, hi)


@njit(cache=True, parallel=True)
def _boxes_par(x, seg, grow, lo, hi):
    n = seg.shape[0]
    for c in prange((n + _CHUNK - 1) // _CHUNK):
        _boxes_range(c * _CHUNK, min(n, (c + 1) * _CHUNK), x, seg, grow, lo, hi)


@njit(cache=True)
def _boxes_ser(x, seg, grow, lo, hi):
    _boxes_range(0, seg.shape[0], x, seg, grow, lo, hi)


def segment_boxes(x: np.ndarray, seg: np.ndarray, grow: np.ndarray, lo: np.ndarray,
                  hi: np.ndarray, parallel: bool = False) -> None:
    """Enlarged bounding boxes: lo/hi (S, 3) mm = min/max of the corners -/+ grow (S,)."""
    (_boxes_par if parallel else _boxes_ser)(x, seg, grow, lo, hi)


@njit(cache=True)
def _extent(lo, hi, origin, top, ext):
    """Grid extent of the boxes lo / hi (S, 3) mm in one pass: origin, top (3,) the
    smallest lo and the largest hi per axis, ext (S,) each box's largest side (numpy's
    axis-0 reductions of these narrow arrays cost ~0.2 ms each for 6,000 boxes)."""
    for k in range(3):
        origin[k] = np.inf
        top[k] = -np.inf
    for s in range(lo.shape[0]):
        e = -np.inf
        for k in range(3):
            a = lo[s, k]
            b = hi[s, k]
            origin[k] = min(origin[k], a)
            top[k] = max(top[k], b)
            e = max(e, b - a)
        ext[s] = e


@njit(cache=True)
def _cell(v, origin, h):
    return np.int64(np.floor((v - origin) / h))


@njit(cache=True)
def _count_pairs(lo, hi, origin, h):
    cnt = np.empty(lo.shape[0], np.int64)
    for s in range(lo.shape[0]):
        c = np.int64(1)
        for k in range(3):
            c *= _cell(hi[s, k], origin[k], h) - _cell(lo[s, k], origin[k], h) + 1
        cnt[s] = c
    return cnt


@njit(cache=True)
def _fill_pairs(lo, hi, origin, h, dims, cnt, keys, segs):
    p = 0
    for s in range(lo.shape[0]):
        i0 = _cell(lo[s, 0], origin[0], h)
        i1 = _cell(hi[s, 0], origin[0], h)
        j0 = _cell(lo[s, 1], origin[1], h)
        j1 = _cell(hi[s, 1], origin[1], h)
        k0 = _cell(lo[s, 2], origin[2], h)
        k1 = _cell(hi[s, 2], origin[2], h)
        for k in range(k0, k1 + 1):
            for j in range(j0, j1 + 1):
                for i in range(i0, i1 + 1):
                    keys[p] = i + dims[0] * (j + dims[1] * k)
                    segs[p] = s
                    p += 1


@njit(cache=True)
def _lower_bound(a, v):
    lo = 0
    hi = a.shape[0]
    while lo < hi:
        mid = (lo + hi) >> 1
        if a[mid] < v:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit(cache=True)
def _cands_range(i0, i1, x, nodes, seg, lo, hi, origin, h, dims, skeys, cstart, ssegs,
                 ex_ptr, ex_seg, ptr, out, fill, mark):
    """Candidates of nodes i0 <= i < i1.

    fill 0: count into ptr[i + 1]; 1: write into out from ptr[i] (ptr already
    cumulative); 2 (serial, one pass): ptr[i + 1] = ptr[i] + count, written
    into out while it fits (the caller checks ptr[-1] <= out.size).
    mark (S,) int32: mark[s] == i leaves segment s out for node i. The node's
    exclusion list is stamped into it once, so a box hit costs one look-up,
    not a scan of the list (single-surface lists hold ~20 segments per node,
    most of them box hits); stamps need no clearing (start at -1).
    """
    for i in range(i0, i1):
        nd = nodes[i]
        px = x[nd, 0]
        py = x[nd, 1]
        pz = x[nd, 2]
        ci = _cell(px, origin[0], h)
        cj = _cell(py, origin[1], h)
        ck = _cell(pz, origin[2], h)
        n = 0
        base = ptr[i]
        if 0 <= ci < dims[0] and 0 <= cj < dims[1] and 0 <= ck < dims[2]:
            for e in range(ex_ptr[i], ex_ptr[i + 1]):
                mark[ex_seg[e]] = i
            key = ci + dims[0] * (cj + dims[1] * ck)
            if cstart.shape[0] > 0:  # dense grid: the cell's range directly
                q = cstart[key]
                q1 = cstart[key + 1]
            else:
                q = _lower_bound(skeys, key)
                q1 = q
                while q1 < skeys.shape[0] and skeys[q1] == key:
                    q1 += 1
            while q < q1:
                s = ssegs[q]
                q += 1
                if (lo[s, 0] <= px <= hi[s, 0] and lo[s, 1] <= py <= hi[s, 1]
                        and lo[s, 2] <= pz <= hi[s, 2]):
                    if (mark[s] == i or seg[s, 0] == nd or seg[s, 1] == nd
                            or seg[s, 2] == nd or seg[s, 3] == nd):
                        continue
                    if fill == 1 or (fill == 2 and base + n < out.shape[0]):
                        out[base + n] = s
                    n += 1
        if fill == 0:
            ptr[i + 1] = n
        elif fill == 2:
            ptr[i + 1] = base + n


@njit(cache=True, parallel=True)
def _cands_par(x, nodes, seg, lo, hi, origin, h, dims, skeys, cstart, ssegs, ex_ptr, ex_seg, ptr,
               out, fill, mark):
    """fill 0 or 1 of :func:`_cands_range`; mark (B, S): one stamp row per block
    of nodes (B blocks, a few per thread)."""
    n = nodes.shape[0]
    nb = mark.shape[0]
    per = (n + nb - 1) // nb
    for b in prange(nb):
        _cands_range(min(n, b * per), min(n, (b + 1) * per), x, nodes, seg, lo, hi, origin, h,
                     dims, skeys, cstart, ssegs, ex_ptr, ex_seg, ptr, out, fill, mark[b])


@njit(cache=True)
def _cands_ser(x, nodes, seg, lo, hi, origin, h, dims, skeys, cstart, ssegs, ex_ptr, ex_seg, ptr,
               out, fill, mark):
    _cands_range(0, nodes.shape[0], x, nodes, seg, lo, hi, origin, h, dims, skeys, cstart, ssegs,
                 ex_ptr, ex_seg, ptr, out, fill, mark)


@njit(cache=True)
def _counting_sort(keys, segs, cstart, ssegs):
    """Segments grouped by cell: cstart (C + 1,) int64 zeroed on entry, out: the
    cells' ranges in ssegs (P,) int32 (in order of keys within a cell)."""
    for p in range(keys.shape[0]):
        cstart[keys[p] + 1] += 1
    for c in range(1, cstart.shape[0]):
        cstart[c] += cstart[c - 1]
    for p in range(keys.shape[0]):
        k = keys[p]
        ssegs[cstart[k]] = segs[p]
        cstart[k] += 1
    for c in range(cstart.shape[0] - 1, 0, -1):
        cstart[c] = cstart[c - 1]
    cstart[0] = 0


def bucket_sort(x: np.ndarray, nodes: np.ndarray, seg: np.ndarray, grow: np.ndarray,
                ex_ptr: np.ndarray | None = None, ex_seg: np.ndarray | None = None,
                parallel: bool | None = None, size_hint: int = 0
                ) -> tuple[np.ndarray, np.ndarray]:
    """Candidate segments of each node.

    x: (L, 3) float64 mm; nodes: (ns,) int32 rows of x (the slave nodes);
    seg: (S, 4) int32 rows of x; grow: (S,) float64 mm how far around each
    segment's bounding box to look (capture distance + margin).
    ex_ptr / ex_seg: optional CSR per node of segments to leave out (besides
    the segments that contain the node, always left out).
    parallel: use the threaded kernels (default: when there are at least
    PARALLEL_MIN_NODES nodes). size_hint: expected number of candidates (the
    last sort's): the serial search then runs once into a buffer of about that
    size (twice only when it overflows).
    Returns ptr (ns + 1,) int64 and cand (ptr[-1],) int32 segment indices, each
    node's candidates in the order of the grid's segment list (the contact
    kernels' results do not depend on that order).
    """
    if parallel is None:
        parallel = nodes.shape[0] >= PARALLEL_MIN_NODES
    ns = nodes.shape[0]
    if ex_ptr is None or ex_seg is None:
        ex_ptr = np.zeros(ns + 1, np.int64)
        ex_seg = np.zeros(0, np.int32)
    ptr = np.zeros(ns + 1, np.int64)
    if seg.shape[0] == 0 or ns == 0:
        return ptr, np.zeros(0, np.int32)
    lo = np.empty((seg.shape[0], 3))
    hi = np.empty((seg.shape[0], 3))
    segment_boxes(x, seg, grow, lo, hi, parallel and seg.shape[0] >= 4 * PARALLEL_MIN_NODES)
    origin = np.empty(3)
    top = np.empty(3)
    ext = np.empty(seg.shape[0])
    _extent(lo, hi, origin, top, ext)
    h = float(np.median(ext))
    span = float((top - origin).max())
    h = max(h, span / 2.0e5, 1.0e-9)
    while True:
        cnt = _count_pairs(lo, hi, origin, h)
        if cnt.sum() <= _MAX_PAIRS_PER_SEGMENT * seg.shape[0] + 64:
            break
        h *= 2.0
    dims = (np.floor((top - origin) / h).astype(np.int64) + 1)
    total = int(cnt.sum())
    keys = np.empty(total, np.int64)
    segs = np.empty(total, np.int32)
    _fill_pairs(lo, hi, origin, h, dims, cnt, keys, segs)
    ncell = int(dims[0]) * int(dims[1]) * int(dims[2])
    if ncell <= max(_DENSE_CELLS, _DENSE_PER_PAIR * total):  # counting sort, dense grid
        cstart = np.zeros(ncell + 1, np.int64)
        ssegs = np.empty(total, np.int32)
        _counting_sort(keys, segs, cstart, ssegs)
        skeys = keys[:0]
    else:  # large, sparse grid: sorted keys, binary search
        cstart = np.zeros(0, np.int64)
        order = np.argsort(keys)
        skeys = keys[order]
        ssegs = segs[order]
    grid = (x, nodes, seg, lo, hi, origin, h, dims, skeys, cstart, ssegs, ex_ptr, ex_seg, ptr)
    if parallel:
        mark = np.full((min(4 * get_num_threads(), max(1, ns // _CHUNK)), seg.shape[0]), -1,
                       np.int32)
        _cands_par(*grid, np.zeros(0, np.int32), 0, mark)
        np.cumsum(ptr, out=ptr)
        cand = np.empty(int(ptr[-1]), np.int32)
        _cands_par(*grid, cand, 1, mark)
        return ptr, cand
    mark = np.full(seg.shape[0], -1, np.int32)
    buf = np.empty(max(1024, 4 * ns, (5 * size_hint) // 4), np.int32)
    _cands_ser(*grid, buf, 2, mark)
    if int(ptr[-1]) > buf.shape[0]:
        buf = np.empty(int(ptr[-1]), np.int32)
        _cands_ser(*grid, buf, 1, mark)
        return ptr, buf
    return ptr, buf[:int(ptr[-1])].copy()


def brute_force_candidates(x: np.ndarray, nodes: np.ndarray, seg: np.ndarray,
                           grow: np.ndarray) -> list[set[int]]:
    """Reference for tests: per node the segments whose enlarged box contains it."""
    lo = np.empty((seg.shape[0], 3))
    hi = np.empty((seg.shape[0], 3))
    segment_boxes(x, seg, grow, lo, hi)
    out = []
    for nd in nodes:
        p = x[nd]
        inside = np.all((lo <= p) & (p <= hi), axis=1)
        inside &= ~np.any(seg == nd, axis=1)
        out.append(set(np.nonzero(inside)[0].tolist()))
    return out
