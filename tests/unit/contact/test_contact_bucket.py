"""Bucket-sort broad phase against brute force on random meshes."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact import bucket
from hollowbody.contact.bucket import brute_force_candidates, bucket_sort


def _random_mesh(rng, n_nodes, n_seg, spread):
    x = rng.uniform(0.0, spread, size=(n_nodes, 3))
    seg = np.empty((n_seg, 4), np.int32)
    for s in range(n_seg):
        # segments of nearby nodes: pick a node and 3 of its near neighbours
        a = rng.integers(n_nodes)
        d = np.linalg.norm(x - x[a], axis=1)
        near = np.argsort(d)[1:8]
        seg[s] = [a, *rng.choice(near, 3, replace=False)]
        if rng.random() < 0.3:
            seg[s, 3] = seg[s, 2]  # triangle
    return x, seg


@pytest.mark.parametrize("grid", ["dense", "sparse"])
@pytest.mark.parametrize("parallel", [False, True])
@pytest.mark.parametrize("seed", range(5))
def test_bucket_sort_equals_brute_force(seed, parallel, grid, monkeypatch):
    """Both grid layouts (dense: counting sort; sparse: sorted keys), serial and
    threaded, give exactly the brute-force lists; the serial one-pass buffer is
    made too small on purpose (size_hint 0 and 1024 entries for ~10^4 pairs)."""
    if grid == "sparse":
        monkeypatch.setattr(bucket, "_DENSE_CELLS", 0)
        monkeypatch.setattr(bucket, "_DENSE_PER_PAIR", 0)
    rng = np.random.default_rng(seed)
    x, seg = _random_mesh(rng, 400, 300, spread=[50.0, 20.0, 5.0][seed % 3])
    grow = rng.uniform(0.0, 2.0, size=seg.shape[0])
    if seed == 4:
        grow[0] = 200.0  # one huge box must not break the grid
    nodes = rng.choice(x.shape[0], 250, replace=False).astype(np.int32)
    ptr, cand = bucket_sort(x, nodes, seg, grow, parallel=parallel)
    ref = brute_force_candidates(x, nodes, seg, grow)
    for i in range(nodes.shape[0]):
        got = cand[ptr[i]:ptr[i + 1]].tolist()
        assert len(got) == len(set(got))
        assert set(got) == ref[i]


def test_exclusion_lists_and_empty_inputs():
    rng = np.random.default_rng(11)
    x, seg = _random_mesh(rng, 100, 80, spread=10.0)
    nodes = np.arange(100, dtype=np.int32)
    grow = np.full(80, 3.0)
    ptr, cand = bucket_sort(x, nodes, seg, grow)
    ex_ptr = np.zeros(101, np.int64)
    ex_ptr[1:] = np.cumsum(np.diff(ptr) > 0)
    first = np.array([cand[ptr[i]] for i in range(100) if ptr[i + 1] > ptr[i]], np.int32)
    p2, c2 = bucket_sort(x, nodes, seg, grow, ex_ptr, first)
    assert p2[-1] == ptr[-1] - first.shape[0]
    for i in range(100):
        rest = set(cand[ptr[i]:ptr[i + 1]].tolist())
        if ptr[i + 1] > ptr[i]:
            rest.discard(int(cand[ptr[i]]))
        assert set(c2[p2[i]:p2[i + 1]].tolist()) == rest
    p0, c0 = bucket_sort(x, nodes, seg[:0], grow[:0])
    assert p0.shape == (101,) and c0.size == 0


def test_one_pass_buffer_overflow_and_hint_agree():
    """The serial search writes into a buffer sized from size_hint; when that is
    too small it runs again into an exact one. Lists are the same either way."""
    rng = np.random.default_rng(2)
    x, seg = _random_mesh(rng, 300, 400, spread=8.0)
    nodes = np.arange(300, dtype=np.int32)
    grow = np.full(400, 3.0)
    small = bucket_sort(x, nodes, seg, grow, parallel=False, size_hint=0)
    assert small[1].size > 1024 + 4 * 300  # the first buffer overflowed
    big = bucket_sort(x, nodes, seg, grow, parallel=False, size_hint=10 ** 6)
    par = bucket_sort(x, nodes, seg, grow, parallel=True)
    par_hint = bucket_sort(x, nodes, seg, grow, parallel=True, size_hint=small[1].size)
    for p, c in (big, par, par_hint):
        np.testing.assert_array_equal(p, small[0])
        np.testing.assert_array_equal(c, small[1])


@pytest.mark.parametrize("per_thread", [1, 3, 50])
def test_threaded_search_blocks_give_the_serial_lists(per_thread, monkeypatch):
    """The threaded search splits the nodes into blocks of whole grid cells, each
    written into its own part of one buffer (re-run when a block overflows its
    part): any number of blocks, more blocks than cells included, gives the serial
    lists entry for entry."""
    monkeypatch.setattr(bucket, "_BLOCKS_PER_THREAD", per_thread)
    monkeypatch.setattr(bucket, "_MIN_BLOCK_NODES", 1)
    rng = np.random.default_rng(11)
    x, seg = _random_mesh(rng, 400, 500, spread=9.0)
    nodes = rng.permutation(400)[:350].astype(np.int32)
    grow = rng.uniform(0.5, 3.0, size=500)
    ser = bucket_sort(x, nodes, seg, grow, parallel=False)
    assert ser[1].size > 1024 + 4 * 350  # a first buffer without a hint overflows
    for hint in (0, ser[1].size // 3, ser[1].size):
        par = bucket_sort(x, nodes, seg, grow, parallel=True, size_hint=hint)
        np.testing.assert_array_equal(par[0], ser[0])
        np.testing.assert_array_equal(par[1], ser[1])


def test_block_rows_keep_cells_whole():
    """Block bounds fall on cell boundaries, ascend, cover every node, and split the
    work (the segments of each node's cell, plus one per node) as evenly as whole
    cells allow."""
    sizes = np.array([5, 1, 0, 7, 3, 3, 9, 1, 1, 2])
    keys = np.repeat(np.arange(10), sizes).astype(np.int64)
    segs_in_cell = np.array([4, 0, 2, 30, 1, 1, 5, 0, 9, 3])
    cstart = np.concatenate([[0], np.cumsum(segs_in_cell)]).astype(np.int64)
    order = np.arange(keys.size)
    per_node = segs_in_cell[keys] + 1
    for nb in (1, 2, 3, 7, 40):
        work = np.empty(nb, np.int64)
        rows = bucket._block_rows(order, keys, keys[:0], cstart, nb, work)
        assert rows[0] == 0 and rows[-1] == keys.size and np.all(np.diff(rows) >= 0)
        for r in rows[1:-1]:
            assert r in (0, keys.size) or keys[r] != keys[r - 1]
        for b in range(nb):
            assert work[b] == per_node[rows[b]:rows[b + 1]].sum()
    work = np.empty(2, np.int64)
    rows = bucket._block_rows(order, keys, keys[:0], cstart, 2, work)
    assert rows[1] == 13  # cell 3 (7 nodes x 31) is most of the work: cut after it


@pytest.mark.parametrize("grid", ["dense", "sparse"])
@pytest.mark.parametrize("node_order", ["counting", "argsort"])
def test_serial_and_threaded_lists_in_the_same_order(grid, node_order, monkeypatch):
    """The serial search walks the nodes cell by cell and gathers the rows back into
    node order; each node's list must be the threaded search's, entry for entry
    (the grid's segment order), in both grid layouts and with both node orders (a
    counting sort of the cells, or an argsort when the grid has far more cells than
    nodes)."""
    if node_order == "argsort":
        monkeypatch.setattr(bucket, "_COUNT_CELLS_PER_NODE", 0)
    if grid == "sparse":
        monkeypatch.setattr(bucket, "_DENSE_CELLS", 0)
        monkeypatch.setattr(bucket, "_DENSE_PER_PAIR", 0)
    rng = np.random.default_rng(7)
    x, seg = _random_mesh(rng, 500, 600, spread=12.0)
    nodes = rng.permutation(500)[:400].astype(np.int32)
    grow = rng.uniform(0.2, 2.5, size=600)
    ser = bucket_sort(x, nodes, seg, grow, parallel=False)
    par = bucket_sort(x, nodes, seg, grow, parallel=True)
    assert ser[1].size > 0
    np.testing.assert_array_equal(ser[0], par[0])
    np.testing.assert_array_equal(ser[1], par[1])


def test_near_filter_serial_and_threaded_equal_the_box_test():
    """Near lists: the listed pairs whose current box (enlarged by grow) holds the
    node, plus the node's held segment, in the far list's order; the serial filter
    (no branches) and the threaded one give the same lists and the same set of
    segments in them."""
    from hollowbody.contact.nearlist import near_filter, near_filter_parallel

    rng = np.random.default_rng(5)
    x, seg = _random_mesh(rng, 300, 400, spread=10.0)
    nodes = np.arange(300, dtype=np.int32)
    ptr, cand = bucket_sort(x, nodes, seg, np.full(400, 2.0))
    x = x + rng.normal(0.0, 0.3, x.shape)  # moved since the sort
    grow = rng.uniform(0.0, 1.0, 400)
    oseg = np.full(300, -1, np.int32)
    held = rng.choice(300, 40, replace=False)
    oseg[held] = cand[ptr[held]]  # some held segments (listed, maybe not near)
    has = ptr[held + 1] > ptr[held]
    oseg[held[~has]] = -1
    sact = np.unique(cand).astype(np.int32)
    lo, hi = np.zeros((400, 3)), np.zeros((400, 3))
    bucket.segment_boxes(x, seg, grow, lo, hi)
    want = []
    for i in range(300):
        row = cand[ptr[i]:ptr[i + 1]]
        inside = np.all((lo[row] <= x[i]) & (x[i] <= hi[row]), axis=1) | (row == oseg[i])
        want.append(row[inside])
    out = []
    for fn, extra in ((near_filter, ()), (near_filter_parallel, (1,)),
                      (near_filter_parallel, (4,)), (near_filter_parallel, (7,))):
        nptr = np.zeros(301, np.int64)
        ncand = np.empty(cand.size, np.int32)
        nsact = np.zeros(400, np.int32)
        m = fn(x, nodes, seg, grow, ptr, cand, oseg, sact, np.zeros((400, 3)),
               np.zeros((400, 3)), nptr, ncand, np.zeros(400, np.int64), 1, nsact, *extra)
        for i in range(300):
            np.testing.assert_array_equal(ncand[nptr[i]:nptr[i + 1]], want[i])
        out.append(nsact[:m].copy())
    assert 0 < nptr[-1] < cand.size
    np.testing.assert_array_equal(out[0], np.unique(np.concatenate(want)))
    for o in out[1:]:
        np.testing.assert_array_equal(o, out[0])


def test_cell_order_is_a_stable_sort():
    """The counting sort of node cells (-1: outside the grid) equals a stable argsort."""
    rng = np.random.default_rng(3)
    keys = rng.integers(-1, 40, size=1000).astype(np.int64)
    np.testing.assert_array_equal(bucket._cell_order(keys, 40),
                                  np.argsort(keys, kind="stable"))
