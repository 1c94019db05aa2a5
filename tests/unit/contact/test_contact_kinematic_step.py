"""The contact's kinematic step limit (hollowbody.contact.kinematic_step) on single pairs.

A unit-free check of the rule ``dt = max(alpha B, D - (1 - alpha) B) / w`` (alpha 0.5):
D the node's distance to the far edge of the contact band, B the band's width, w the
closing speed. Every expected value is that formula worked by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.contact.frames import SLAB_COLS, segment_frames
from hollowbody.contact.kinematic_step import (
    KIN_FRACTION,
    approach_step,
    approach_step_serial,
    max_speed2,
    narrowest_band,
    work_arrays,
)

# a 2 x 2 mm segment in z = 0 (normal +z), rows 0-3; the node is row 4
SEG_X = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]])


def limit(node_z, node_vz, *, two=True, seg_t=2.0, node_t=0.0, depth=0.0, seg_vz=0.0,
          node_x=0.0, parallel=False):
    x = np.vstack([SEG_X, [[node_x, 0.0, node_z]]])
    v = np.zeros((5, 3))
    v[:4, 2] = seg_vz
    v[4, 2] = node_vz
    seg = np.array([[0, 1, 2, 3]], np.int32)
    cen, nrm, rad2, warp = np.zeros((1, 3)), np.zeros((1, 3)), np.zeros(1), np.zeros(1)
    segment_frames(x, seg, cen, nrm, rad2, warp, np.zeros((1, SLAB_COLS)), False)
    kern = approach_step if parallel else approach_step_serial
    wd, wr = work_arrays(1)
    return kern(np.array([0], np.int32), x, v, np.array([4], np.int32), np.array([node_t]), seg,
                np.array([seg_t]), np.array([depth]), np.array([1 if two else 0], np.int8),
                cen, nrm, rad2, np.array([0, 1], np.int64), np.array([0], np.int32),
                KIN_FRACTION, wd, wr)


@pytest.mark.parametrize("parallel", [False, True])
def test_two_sided_segment(parallel):
    """Reach (0 + 2) / 2 = 1 mm = B. From 5 mm at 10 mm/ms: the node may land 0.5 mm into
    the band, (5 - 0.5) / 10 = 0.45 ms. Inside (0.6 mm, either side, closing on the
    mid-surface): 0.5 B / w = 0.05 ms. Leaving, at rest, or moving with the segment:
    no limit. The node's own contact thickness widens the band."""
    assert limit(5.0, -10.0, parallel=parallel) == (pytest.approx(0.45, rel=1e-12), 0)
    assert limit(0.6, -10.0, parallel=parallel)[0] == pytest.approx(0.05, rel=1e-12)
    assert limit(-0.6, 10.0, parallel=parallel)[0] == pytest.approx(0.05, rel=1e-12)
    assert limit(0.6, 10.0, parallel=parallel) == (math.inf, -1)
    assert limit(0.6, 0.0, parallel=parallel)[0] == math.inf
    assert limit(0.6, -10.0, seg_vz=-10.0, parallel=parallel)[0] == math.inf
    # segment closing on a node at rest: the relative speed counts
    assert limit(5.0, 0.0, seg_vz=10.0, parallel=parallel)[0] == pytest.approx(0.45, rel=1e-12)
    # node thickness 2: B = 2, (5 - 1) / 10
    assert limit(5.0, -10.0, node_t=2.0, parallel=parallel)[0] == pytest.approx(0.4, rel=1e-12)


def test_one_sided_face_counts_the_release_depth():
    """A solid face (one-sided): B = reach + depth = 0.5 + 2, D = d + depth. At d = 1 mm
    closing at 10 mm/ms: max(1.25, 3 - 1.25) / 10 = 0.175 ms; behind the face but inside
    the band (d = -1): max(1.25, 1 - 1.25) / 10 = 0.125 ms; beyond the release depth
    (d = -3) or moving out (+n): no limit."""
    kw = {"two": False, "seg_t": 0.0, "node_t": 1.0, "depth": 2.0}
    assert limit(1.0, -10.0, **kw)[0] == pytest.approx(0.175, rel=1e-12)
    assert limit(-1.0, -10.0, **kw)[0] == pytest.approx(0.125, rel=1e-12)
    assert limit(-3.0, -10.0, **kw)[0] == math.inf
    assert limit(-1.0, 10.0, **kw)[0] == math.inf


def test_node_beside_the_segment_does_not_count():
    """Outside the circumscribed circle (radius sqrt(2) mm) the pair is not a closing
    contact: no limit; just inside it is."""
    assert limit(0.6, -10.0, node_x=1.5)[0] == math.inf
    assert limit(0.6, -10.0, node_x=1.4)[0] == pytest.approx(0.05, rel=1e-12)


def test_narrowest_band_bounds_every_pair():
    """The pass-level bound: thinnest node 0 mm; two-sided 2 mm segment: reach 1;
    one-sided face (thickness 0, depth 0.4): 0 + 0.4; pairs with no band (zero
    thickness and depth) never limit and are left out."""
    band = narrowest_band(np.array([0.0, 3.0]), np.array([2.0, 0.0, 0.0, 0.0]),
                          np.array([0.0, 0.4, 0.0, 0.0]), np.array([1, 0, 1, 0], np.int8))
    assert band == pytest.approx(0.4, rel=1e-12)
    assert narrowest_band(np.array([0.0]), np.array([0.0]), np.array([0.0]),
                          np.array([1], np.int8)) == math.inf
    assert max_speed2(np.array([[3.0, 4.0, 0.0], [0.0, 1.0, 1.0]])) == 25.0
    # the bound holds for the single pairs above: dt_kin >= alpha B / (2 v_max)
    for z, vz in ((5.0, -10.0), (0.6, -10.0), (-0.6, 10.0)):
        assert limit(z, vz)[0] >= KIN_FRACTION * 1.0 / (2.0 * 10.0)


@pytest.mark.parametrize("parallel", [False, True])
def test_skipping_pairs_keeps_the_smallest_step_below_the_limit(parallel):
    """Many nodes over a grid of segments, random positions and velocities: with a limit
    and the closing-speed bound 2 v_max the kernel skips pairs but returns the same
    step (bit for bit) and row as the plain search whenever that step is below the
    limit, and (inf, -1) otherwise."""
    rng = np.random.default_rng(7)
    n_side = 6  # 6 x 6 segments of 2 mm (two-sided and one-sided mixed)
    g = np.arange(n_side + 1) * 2.0
    gx, gy = np.meshgrid(g, g, indexing="ij")
    xs = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    idx = np.arange(gx.size).reshape(n_side + 1, n_side + 1)
    seg = np.array([[idx[i, j], idx[i + 1, j], idx[i + 1, j + 1], idx[i, j + 1]]
                    for i in range(n_side) for j in range(n_side)], np.int32)
    ns = 300
    nodes_x = np.column_stack([rng.uniform(0, 2 * n_side, ns), rng.uniform(0, 2 * n_side, ns),
                               rng.uniform(-4.0, 4.0, ns)])
    x = np.vstack([xs, nodes_x])
    x[: xs.shape[0], 2] += rng.normal(0.0, 0.05, xs.shape[0])  # slightly warped
    nodes = np.arange(xs.shape[0], x.shape[0], dtype=np.int32)
    nseg = seg.shape[0]
    cen, nrm, rad2, warp = np.zeros((nseg, 3)), np.zeros((nseg, 3)), np.zeros(nseg), np.zeros(nseg)
    segment_frames(x, seg, cen, nrm, rad2, warp, np.zeros((nseg, SLAB_COLS)), False)
    ptr = np.arange(0, (ns + 1) * nseg, nseg, dtype=np.int64)  # every node sees every segment
    cand = np.tile(np.arange(nseg, dtype=np.int32), ns)
    thick = rng.uniform(0.0, 2.0, ns)
    s_thick = rng.uniform(0.5, 2.0, nseg)
    s_depth = rng.uniform(0.0, 1.0, nseg)
    s_two = rng.integers(0, 2, nseg).astype(np.int8)
    act = np.arange(ns, dtype=np.int32)
    kern = approach_step if parallel else approach_step_serial
    wd, wr = work_arrays(ns)
    checked = 0
    for _trial in range(20):
        v = rng.normal(0.0, 10.0, x.shape)
        wmax = 2.0 * math.sqrt(max_speed2(v))
        args = (act, x, v, nodes, thick, seg, s_thick, s_depth, s_two, cen, nrm, rad2, ptr,
                cand, KIN_FRACTION, wd, wr)
        plain = kern(*args)
        assert math.isfinite(plain[0])
        for lim in (math.inf, 1.5 * plain[0], plain[0], 0.5 * plain[0]):
            got = kern(*args, lim, wmax)
            if plain[0] < lim:
                assert got == plain
                checked += 1
            else:
                assert got == (math.inf, -1)
    assert checked == 40
