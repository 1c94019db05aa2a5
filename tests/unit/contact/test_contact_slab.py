"""The detection's cheap rejections never drop a pair that could be in contact.

* the slab test (frames.slab_bound) before the Newton projection: whenever the
  projection finds a foot point inside the segment at a distance |d| <= dmax, the
  slab test must not reject the pair; checked on random warped, twisted and
  non-convex quadrilaterals against the projection itself, and the detection with
  the slabs gives the same results to the last bit as without them on piles of
  crumpled shells (the crushed hollow block's situation);
* the far lists' distance cut (nearlist.distance_cut): every pair with a foot
  point within the contact distance after every node and corner has moved up to
  half the margin is kept.

Each test also checks that the rejection does reject (a test that rejects nothing
would pass trivially).
"""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit

from hollowbody.contact.detect import detect_pass_serial
from hollowbody.contact.frames import SLAB_COLS, segment_frames, slab_bound
from hollowbody.contact.geometry import project_corners
from hollowbody.contact.nearlist import distance_cut, distance_cut_parallel


@njit(cache=True)
def _check_slabs(pts, x, seg, cen, nrm, slab, dmax, out):
    """out[k] = (qualifies, rejected) for point k against segment k % S."""
    for k in range(pts.shape[0]):
        s = k % seg.shape[0]
        a, b, c, d = seg[s, 0], seg[s, 1], seg[s, 2], seg[s, 3]
        px, py, pz = pts[k, 0], pts[k, 1], pts[k, 2]
        ok, inside, qx, qy, qz, nx, ny, nz, w0, w1, w2, w3 = project_corners(
            px, py, pz, x[a, 0], x[a, 1], x[a, 2], x[b, 0], x[b, 1], x[b, 2],
            x[c, 0], x[c, 1], x[c, 2], x[d, 0], x[d, 1], x[d, 2], c == d, 0.0, 0.0)
        dd = abs((px - qx) * nx + (py - qy) * ny + (pz - qz) * nz)
        out[k, 0] = 1 if (ok and inside and dd <= dmax) else 0
        out[k, 1] = 1 if slab_bound(s, px - cen[s, 0], py - cen[s, 1], pz - cen[s, 2], dmax,
                                    slab) else 0


def _random_quads(rng, n, distort):
    """n quadrilaterals about an 8 mm square, corners moved by up to ``distort`` mm
    (in-plane and out of plane: warped, twisted, trapezoidal, some folded)."""
    sq = np.array([[-4.0, -4.0, 0.0], [4.0, -4.0, 0.0], [4.0, 4.0, 0.0], [-4.0, 4.0, 0.0]])
    x = np.empty((4 * n, 3))
    for s in range(n):
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))  # random orientation
        corners = sq + rng.uniform(-distort, distort, size=(4, 3))
        x[4 * s:4 * s + 4] = corners @ q.T + rng.uniform(-50.0, 50.0, size=3)
    seg = np.arange(4 * n, dtype=np.int32).reshape(n, 4)
    return x, seg


@pytest.mark.parametrize("distort", [0.5, 1.5, 3.0])
def test_slab_never_rejects_a_foot_point_within_reach(distort):
    rng = np.random.default_rng(7)
    n = 300
    x, seg = _random_quads(rng, n, distort)
    cen = np.zeros((n, 3))
    nrm = np.zeros((n, 3))
    rad2 = np.zeros(n)
    warp = np.zeros(n)
    slab = np.zeros((n, SLAB_COLS))
    segment_frames(x, seg, cen, nrm, rad2, warp, slab)
    m = 200 * n
    s = np.arange(m) % n
    # points around each segment: up to 1.6 times its size laterally, +-4 mm off it
    pts = cen[s] + rng.uniform(-7.0, 7.0, size=(m, 3))
    for dmax in (0.05, 0.5, 1.5, 3.0):
        out = np.zeros((m, 2), np.int8)
        _check_slabs(pts, x, seg, cen, nrm, slab, dmax, out)
        qualifies = out[:, 0] == 1
        rejected = out[:, 1] == 1
        assert not np.any(qualifies & rejected), (distort, dmax)
        # and it rejects: most of the points that do not qualify at small dmax
        assert qualifies.sum() > 100
        if dmax <= 0.5:
            assert rejected.sum() > 0.3 * (~qualifies).sum(), (distort, dmax)


def _crumpled_pile(rng, layers=4, n=7, gap=1.2, amp=0.9):
    """``layers`` crumpled shell plates of n x n quads (4 mm), ``gap`` mm apart with
    random out-of-plane and in-plane corner offsets up to ``amp`` mm."""
    xs, segs = [], []
    base = 0
    for layer in range(layers):
        g = np.stack(np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij"), -1)
        xy = 4.0 * g.reshape(-1, 2).astype(float)
        xl = np.column_stack([xy, np.full(len(xy), gap * layer)])
        xl += rng.uniform(-amp, amp, size=xl.shape)
        xs.append(xl)
        for i in range(n):
            for j in range(n):
                a = base + i * (n + 1) + j
                segs.append([a, a + n + 1, a + n + 2, a + 1])
        base += len(xl)
    return np.vstack(xs), np.array(segs, dtype=np.int32)


def _all_pairs(nodes, seg):
    """Every segment not containing the node, for every node (CSR)."""
    lists = [[s for s in range(seg.shape[0]) if nd not in seg[s]] for nd in nodes]
    ptr = np.zeros(len(lists) + 1, np.int64)
    ptr[1:] = np.cumsum([len(c) for c in lists])
    return ptr, np.array([s for c in lists for s in c], dtype=np.int32)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_detection_with_slabs_equals_detection_without(seed):
    """Several cycles of detection on a pile of crumpled shells (two-sided, 1.5 mm,
    release depth 1.6 mm): nodes in contact with two or three layers at once, the
    remembered contacts carried from cycle to cycle. With the slab tests and with
    every slab switched off (threshold inf), every output is the same to the bit."""
    rng = np.random.default_rng(seed)
    x, seg = _crumpled_pile(rng)
    ns, nseg = x.shape[0], seg.shape[0]
    nodes = np.arange(ns, dtype=np.int32)
    n_thick = np.full(ns, 1.5)
    s_thick = np.full(nseg, 1.5)
    s_depth = np.full(nseg, 1.6)
    s_two = np.ones(nseg, np.int8)
    ptr, cand = _all_pairs(nodes, seg)
    act = nodes.copy()

    def state():
        return [np.zeros((ns, 3)), np.full(ns, -1, np.int32), np.zeros((ns, 4)), np.zeros(ns),
                np.zeros(ns, np.int8), np.full(ns, -1, np.int32), np.zeros(ns),
                np.full(ns, -1, np.int32), np.zeros(ns), np.zeros(ns)]

    with_slab, without = state(), state()
    rejected = 0
    v = rng.normal(0.0, 0.05, size=x.shape)
    for _ in range(6):
        cen = np.zeros((nseg, 3))
        nrm = np.zeros((nseg, 3))
        rad2 = np.zeros(nseg)
        warp = np.zeros(nseg)
        slab = np.zeros((nseg, SLAB_COLS))
        segment_frames(x, seg, cen, nrm, rad2, warp, slab)
        off = slab.copy()
        off[:, 3] = np.inf
        off[:, 8] = np.inf
        for sl, st in ((slab, with_slab), (off, without)):
            detect_pass_serial(act, x, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm,
                               rad2, warp, sl, ptr, cand, *st)
        for a, b in zip(with_slab, without):
            np.testing.assert_array_equal(a, b)
        # the slabs do reject pairs here (at the contact distance of a fresh node)
        for i in range(0, ns, 5):
            r = x[nodes[i]] - cen[cand[ptr[i]:ptr[i + 1]]]
            rejected += sum(slab_bound(s, *r[k], 1.5, slab)
                            for k, s in enumerate(cand[ptr[i]:ptr[i + 1]]))
        x = x + v
    assert (with_slab[1] >= 0).sum() > ns // 4  # many nodes in contact
    assert rejected > 100


@njit(cache=True)
def _pairs_within_reach(y, seg, reach):
    """(k, 2) node-segment pairs of the pile whose foot point lies inside the segment
    within ``reach`` mm of its plane (the segment's own corners left out)."""
    out = np.empty((y.shape[0] * seg.shape[0], 2), dtype=np.int64)
    k = 0
    for i in range(y.shape[0]):
        for s in range(seg.shape[0]):
            if seg[s, 0] == i or seg[s, 1] == i or seg[s, 2] == i or seg[s, 3] == i:
                continue
            a, b, c, e = y[seg[s, 0]], y[seg[s, 1]], y[seg[s, 2]], y[seg[s, 3]]
            r = project_corners(y[i, 0], y[i, 1], y[i, 2], a[0], a[1], a[2], b[0], b[1], b[2],
                                c[0], c[1], c[2], e[0], e[1], e[2], False, 0.0, 0.0)
            ok, inside, qx, qy, qz, nx, ny, nz = r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7]
            if ok and inside and abs((y[i, 0] - qx) * nx + (y[i, 1] - qy) * ny
                                     + (y[i, 2] - qz) * nz) < reach:
                out[k, 0] = i
                out[k, 1] = s
                k += 1
    return out[:k]


def test_distance_cut_keeps_every_pair_that_can_come_into_contact():
    """Random crumpled pile; far lists of every pair cut at margin 1 mm; then every
    node and corner moved by up to 0.5 mm (random directions, 20 draws): every pair
    with a foot point inside its segment within the contact distance is still listed."""
    rng = np.random.default_rng(3)
    x, seg = _crumpled_pile(rng, layers=3, n=6, gap=2.5, amp=1.2)
    ns, nseg = x.shape[0], seg.shape[0]
    nodes = np.arange(ns, dtype=np.int32)
    n_thick = np.full(ns, 1.5)
    s_thick = np.full(nseg, 1.5)
    s_depth = np.full(nseg, 1.6)
    s_two = np.ones(nseg, np.int8)
    cen = np.zeros((nseg, 3))
    nrm = np.zeros((nseg, 3))
    rad2 = np.zeros(nseg)
    warp = np.zeros(nseg)
    slab = np.zeros((nseg, SLAB_COLS))
    segment_frames(x, seg, cen, nrm, rad2, warp, slab)
    ptr, cand = _all_pairs(nodes, seg)
    total = cand.shape[0]
    oseg = np.full(ns, -1, np.int32)
    margin = 1.0
    m = distance_cut(x, nodes, n_thick, s_thick, s_depth, s_two, cen, nrm, rad2, warp, oseg,
                     margin, ptr, cand)
    assert m < total // 2  # the cut removes most of the pairs
    kept = {(i, int(s)) for i in range(ns) for s in cand[ptr[i]:ptr[i + 1]]}
    reach = 1.6  # max(reach 1.5, release depth 1.6)
    found = 0
    for _ in range(20):
        d = rng.normal(size=x.shape)
        d *= (0.5 * margin * rng.uniform(0.0, 1.0, size=(ns, 1))
              / np.linalg.norm(d, axis=1, keepdims=True))
        y = x + d
        pairs = _pairs_within_reach(y, seg, reach)
        found += len(pairs)
        missed = [(int(i), int(s)) for i, s in pairs if (int(i), int(s)) not in kept]
        assert not missed
    assert found > 200


@pytest.mark.parametrize("nblocks", [1, 2, 3, 7, 40])
def test_threaded_distance_cut_gives_the_serial_lists(nblocks):
    """The threaded cut (blocks of rows compacted each in its own range, then moved
    together) gives the serial cut's lists entry for entry, with rows kept whole
    (some rows hold a current contact segment, kept whatever its distance), also
    with more blocks than rows have pairs for (empty blocks)."""
    rng = np.random.default_rng(11)
    x, seg = _crumpled_pile(rng, layers=3, n=6, gap=2.5, amp=1.2)
    ns, nseg = x.shape[0], seg.shape[0]
    nodes = np.arange(ns, dtype=np.int32)
    frames = [np.zeros((nseg, 3)), np.zeros((nseg, 3)), np.zeros(nseg), np.zeros(nseg)]
    segment_frames(x, seg, *frames, np.zeros((nseg, SLAB_COLS)))
    oseg = np.full(ns, -1, np.int32)
    oseg[rng.choice(ns, ns // 5, replace=False)] = rng.integers(0, nseg, ns // 5)
    args = (x, nodes, rng.uniform(0.5, 2.0, ns), np.full(nseg, 1.5), np.full(nseg, 1.6),
            np.ones(nseg, np.int8), *frames, oseg, 1.0)
    ptr_a, cand_a = _all_pairs(nodes, seg)
    ptr_b, cand_b = ptr_a.copy(), cand_a.copy()
    ma = distance_cut(*args, ptr_a, cand_a)
    mb = distance_cut_parallel(*args, ptr_b, cand_b, nblocks)
    assert ma == mb and ma < cand_a.shape[0] // 2
    assert np.array_equal(ptr_a, ptr_b) and np.array_equal(cand_a[:ma], cand_b[:mb])
