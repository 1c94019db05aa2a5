"""Bucket-sort broad phase: candidate segments per slave node (numba).

Each segment's bounding box, enlarged by its capture distance (how far from
the segment a node can still be in contact: contact thickness or release
depth) plus a *margin*, is registered in every cell of a uniform grid it
overlaps (cell size ~ the typical enlarged box, so a segment touches a few
cells). The (cell key, segment) pairs are sorted by key; a node looks up its
own cell by binary search and keeps the segments whose enlarged box contains
it. The result is a CSR list per slave node (``ptr`` (ns + 1,), ``seg``).

The list stays complete while node and segment corners have approached by less
than ``margin`` along each axis since the sort (the boxes are axis-aligned; every
node within ``margin / 2`` of one common translation along each axis suffices):
:class:`~hollowbody.contact.runtime.ContactRuntime` re-sorts every
``contact_sort_interval`` cycles or earlier when that bound is reached.
Grid cells are numbered densely (a counting sort groups the segments) unless
the grid has far more cells than pairs; then the keys are sorted and searched,
so a large, sparse model costs nothing extra.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np
from numba import get_num_threads, njit, prange, set_parallel_chunksize

#: Fewer slave nodes than this: serial kernels (thread wake-up costs more;
#: on a machine busier than its cores, OpenMP's spinning threads far more).
PARALLEL_MIN_NODES = 16384
#: Items per parallel work unit (array arguments cost an incref/decref per call).
_CHUNK = 256
#: Blocks of nodes per thread in the threaded search, handed out to the threads one at
#: a time (dynamic scheduling: some balance when the box tests are estimated badly).
_BLOCKS_PER_THREAD = 2
#: Fewest nodes of a block in the threaded search.
_MIN_BLOCK_NODES = 256
#: Bound on grid pairs per segment before the cell size is doubled.
_MAX_PAIRS_PER_SEGMENT = 27
#: Grids with at most this many cells (or 4 per grid pair) are dense: segments
#: grouped by a counting sort, a node's cell found by index.
_DENSE_CELLS = 1 << 20
_DENSE_PER_PAIR = 4
#: Nodes are put in cell order by a counting sort while the grid has at most this
#: many cells per node, else by an argsort of their cells.
_COUNT_CELLS_PER_NODE = 4


@contextmanager
def dynamic_blocks() -> Iterator[None]:
    """Inside the block numba hands a prange's iterations to the threads one at a
    time (chunk size 1), as the threaded search's blocks of uneven work want."""
    old = set_parallel_chunksize(1)
    try:
        yield
    finally:
        set_parallel_chunksize(old)


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


@njit(cache=True, inline="always")
def _cell_range(key, skeys, cstart):
    """(q0, q1): the range of grid cell ``key`` in the sorted segment list (dense grid:
    cstart; sparse: a binary search of the sorted keys skeys)."""
    if cstart.shape[0] > 0:
        return cstart[key], cstart[key + 1]
    q0 = _lower_bound(skeys, key)
    q1 = q0
    while q1 < skeys.shape[0] and skeys[q1] == key:
        q1 += 1
    return q0, q1


@njit(cache=True, inline="always")
def _excluded(s, i, nd, seg, mark):
    """Segment s is left out for node row i (node nd): stamped in mark for it (its
    exclusion list) or one of its corners."""
    return (mark[s] == i or seg[s, 0] == nd or seg[s, 1] == nd or seg[s, 2] == nd
            or seg[s, 3] == nd)


@njit(cache=True)
def _node_keys(x, nodes, origin, h, dims, keys):
    """keys (ns,) int64: the grid cell of each node, -1 outside the grid."""
    for i in range(nodes.shape[0]):
        nd = nodes[i]
        ci = _cell(x[nd, 0], origin[0], h)
        cj = _cell(x[nd, 1], origin[1], h)
        ck = _cell(x[nd, 2], origin[2], h)
        if 0 <= ci < dims[0] and 0 <= cj < dims[1] and 0 <= ck < dims[2]:
            keys[i] = ci + dims[0] * (cj + dims[1] * ck)
        else:
            keys[i] = -1


@njit(cache=True)
def _cell_order(keys, ncell):
    """Node rows sorted by cell keys (ns,) int64 in [-1, ncell) (a stable counting sort)."""
    start = np.zeros(ncell + 2, np.int64)
    for i in range(keys.shape[0]):
        start[keys[i] + 2] += 1
    for c in range(2, ncell + 2):
        start[c] += start[c - 1]
    order = np.empty(keys.shape[0], np.int64)
    for i in range(keys.shape[0]):
        c = keys[i] + 1
        order[start[c]] = i
        start[c] += 1
    return order


@njit(cache=True)
def _max_run(cstart, skeys):
    """Most segments registered in one cell (dense: cstart ranges; sparse: runs of skeys)."""
    m = 0
    if cstart.shape[0] > 0:
        for c in range(cstart.shape[0] - 1):
            m = max(m, cstart[c + 1] - cstart[c])
        return m
    r = 0
    while r < skeys.shape[0]:
        r1 = r + 1
        while r1 < skeys.shape[0] and skeys[r1] == skeys[r]:
            r1 += 1
        m = max(m, r1 - r)
        r = r1
    return m


@njit(cache=True)
def _cands_cells(x, nodes, seg, lo, hi, skeys, cstart, ssegs, ex_ptr, ex_seg, order, nkeys,
                 cnt, start, tmp, box, hit, mark, rbegin, rend, nbegin, cap):
    """Candidates of the nodes order[rbegin:rend], cell by cell (serial).

    order (ns,): the node rows sorted by their cell nkeys (ns,) (-1: outside the
    grid, no candidates); rbegin and rend fall on cell boundaries. Written into tmp
    from nbegin up to cap (exclusive). The boxes of a cell's segments are copied once into box
    (6, M) (M >= the most segments of a cell) and tested against each node of the
    cell without branches into hit (M,) uint8, a loop the compiler vectorises (a box
    test that branches mispredicts about one time in ten; measured on the crushed
    hollow block's self-contact: 11.2 -> 4.7 ms per search with the cell order); the
    hits are then compacted and checked against the node's exclusions: mark (S,)
    int32, mark[s] == i leaves segment s out for node row i; the node's exclusion list
    is stamped into it once, so a hit costs one look-up, not a scan of the list
    (stamps need no clearing: they start at -1). A node's
    candidates go to tmp from start[i] (cnt[i] of them), in the order of the grid's
    segment list. While tmp has no room before cap for a node's whole cell, nodes are
    only counted (box hits, an upper bound). Returns the end of the entries written or
    counted: all were written if it is <= cap - M.
    """
    n = nbegin
    r = rbegin
    nn = rend
    while r < nn:
        key = nkeys[order[r]]
        r1 = r + 1
        while r1 < nn and nkeys[order[r1]] == key:
            r1 += 1
        m = 0
        q0 = 0
        if key >= 0:
            q0, q1 = _cell_range(key, skeys, cstart)
            m = q1 - q0
        for j in range(m):
            s = ssegs[q0 + j]
            for k in range(3):
                box[k, j] = lo[s, k]
                box[3 + k, j] = hi[s, k]
        b0 = box[0]
        b1 = box[1]
        b2 = box[2]
        b3 = box[3]
        b4 = box[4]
        b5 = box[5]
        for t in range(r, r1):
            i = order[t]
            nd = nodes[i]
            px = x[nd, 0]
            py = x[nd, 1]
            pz = x[nd, 2]
            start[i] = n
            n0 = n
            for j in range(m):  # no branch, no dependence: vectorised
                hit[j] = ((b0[j] <= px) & (px <= b3[j]) & (b1[j] <= py) & (py <= b4[j])
                          & (b2[j] <= pz) & (pz <= b5[j]))
            if n + m > cap:  # no room: count the box hits only
                for j in range(m):
                    n += hit[j]
                cnt[i] = n - n0
                continue
            for j in range(m):
                tmp[n] = j
                n += hit[j]
            if n > n0:
                for e in range(ex_ptr[i], ex_ptr[i + 1]):
                    mark[ex_seg[e]] = i
                w = n0
                for q in range(n0, n):
                    s = ssegs[q0 + tmp[q]]
                    if not _excluded(s, i, nd, seg, mark):
                        tmp[w] = s
                        w += 1
                n = w
            cnt[i] = n - n0
        r = r1
    return n


@njit(cache=True, parallel=True)
def _cands_blocks(x, nodes, seg, lo, hi, skeys, cstart, ssegs, ex_ptr, ex_seg, order, nkeys,
                  cnt, start, tmp, box, hit, mark, rows, nbeg, ncap, nend):
    """:func:`_cands_cells` of B blocks of nodes at once: block b takes order[rows[b]:
    rows[b + 1]] into tmp[nbeg[b]:ncap[b]] with its own work arrays box[b], hit[b],
    mark[b]; nend (B,) int64 out: each block's end (written if <= ncap[b] - M)."""
    for b in prange(rows.shape[0] - 1):
        nend[b] = _cands_cells(x, nodes, seg, lo, hi, skeys, cstart, ssegs, ex_ptr, ex_seg,
                               order, nkeys, cnt, start, tmp, box[b], hit[b], mark[b],
                               rows[b], rows[b + 1], nbeg[b], ncap[b])


@njit(cache=True)
def _block_rows(order, nkeys, skeys, cstart, nblocks, work):
    """(B + 1,) int64 bounds splitting order (ns,) into blocks of about equal work (box
    tests: the segments of each node's cell, from skeys / cstart) that start and end on
    cell boundaries (a cell's nodes stay in one block); work (B,) int64 out: the box
    tests of each block."""
    nn = order.shape[0]
    acc = np.zeros(nn + 1, np.int64)
    for r in range(nn):
        m = 0
        key = nkeys[order[r]]
        if key >= 0:
            q0, q1 = _cell_range(key, skeys, cstart)
            m = q1 - q0
        acc[r + 1] = acc[r] + m + 1
    rows = np.zeros(nblocks + 1, np.int64)
    r = 0
    for b in range(1, nblocks):
        goal = (b * acc[nn]) // nblocks
        while r < nn and acc[r] < goal:
            r += 1
        while 0 < r < nn and nkeys[order[r]] == nkeys[order[r - 1]]:
            r += 1
        rows[b] = r
    rows[nblocks] = nn
    for b in range(nblocks):
        work[b] = acc[rows[b + 1]] - acc[rows[b]]
    return rows


@njit(cache=True)
def _gather_rows(cnt, start, tmp, ptr, out):
    """CSR in node order: ptr (ns + 1,) from cnt (ns,), out the rows tmp[start[i]:][:cnt[i]]."""
    ptr[0] = 0
    for i in range(cnt.shape[0]):
        ptr[i + 1] = ptr[i] + cnt[i]
    for i in range(cnt.shape[0]):
        a = ptr[i]
        b = start[i]
        for k in range(cnt[i]):
            out[a + k] = tmp[b + k]


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
    parallel: search blocks of nodes (whole grid cells, _BLOCKS_PER_THREAD per
    thread) on numba's threads, each into its own part of one buffer (default:
    when there are at least PARALLEL_MIN_NODES nodes); the lists are the serial
    search's. size_hint: expected number of candidates (the last sort's): the
    search then runs once into a buffer of about that size (twice, every block
    again with exact room, only when a block overflows its part).
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
    nkeys = np.empty(ns, np.int64)
    _node_keys(x, nodes, origin, h, dims, nkeys)
    if ncell <= _COUNT_CELLS_PER_NODE * ns:
        norder = _cell_order(nkeys, ncell)
    else:
        norder = np.argsort(nkeys, kind="stable")
    mx = int(_max_run(cstart, skeys))
    nb = min(_BLOCKS_PER_THREAD * get_num_threads(), max(1, ns // _MIN_BLOCK_NODES)) \
        if parallel else 1
    parallel = parallel and nb > 1
    work = np.empty(nb, np.int64)
    rows = _block_rows(norder, nkeys, skeys, cstart, nb, work)
    box = np.empty((nb, 6, mx))
    hit = np.empty((nb, mx), np.uint8)
    mark = np.full((nb, seg.shape[0]), -1, np.int32)
    ncnt = np.empty(ns, np.int64)
    start = np.empty(ns, np.int64)
    # each block's room: its share (by box tests) of the expected total (the last
    # sort's), plus a cell; a block alone gets all of it
    room = max(1024, 4 * ns, (5 * size_hint) // 4)
    need = np.full(1, room, np.int64) if nb == 1 else \
        (3 * room * work) // (2 * max(int(work.sum()), 1)) + 1
    search = (x, nodes, seg, lo, hi, skeys, cstart, ssegs, ex_ptr, ex_seg, norder, nkeys, ncnt,
              start)
    for _attempt in range(2):
        ncap = np.cumsum(need + mx)
        nbeg = ncap - need - mx
        tmp = np.empty(int(ncap[-1]), np.int32)
        nend = np.empty(nb, np.int64)
        if parallel:
            with dynamic_blocks():
                _cands_blocks(*search, tmp, box, hit, mark, rows, nbeg, ncap, nend)
        else:
            nend[0] = _cands_cells(*search, tmp, box[0], hit[0], mark[0], 0, ns, 0, ncap[0])
        if np.all(nend <= ncap - mx):
            break
        # too small: nend - nbeg bounds each block's entries; all blocks again, now they fit
        need = np.maximum(nend - nbeg, 0)
        mark[:] = -1
    cand = np.empty(int(ncnt.sum()), np.int32)
    _gather_rows(ncnt, start, tmp, ptr, cand)
    return ptr, cand


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
