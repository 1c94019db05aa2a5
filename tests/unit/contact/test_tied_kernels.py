"""Tied-contact kernels (hollowbody.contact.tied) on hand-made arrays."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact.geometry import closest_point, project_segment, shape_weights
from hollowbody.contact.tied import TieSet
from hollowbody.contact.tied.search import closest_segments, local_offsets

# a warped quadrilateral (corner 3 lifted) and a triangle (N4 == N3), nodes 0-6
X0 = np.array([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [11.0, 9.0, 0.0], [-1.0, 10.0, 2.0],
               [20.0, 0.0, 0.0], [30.0, 1.0, 0.0], [24.0, 8.0, 1.0]])
SEG = np.array([[0, 1, 2, 3], [4, 5, 6, 6]])


def _rotation(axis, angle):
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


def _brute(xs, tri, p, n=401):
    """Smallest distance from p to a dense grid of points of the segment."""
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n)))
    if tri:
        u, v = (u + 1) / 2, (v + 1) / 2
        keep = u + v <= 1.0
        u, v = u[keep], v[keep]
        w = np.column_stack([1 - u - v, u, v, 0 * u])
    else:
        w = np.column_stack([(1 + u * a) * (1 + v * b) / 4
                             for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    return np.linalg.norm(w @ xs - p, axis=1).min()


@pytest.mark.parametrize("s", [0, 1])
def test_closest_point_matches_brute_force(s):
    rng = np.random.default_rng(1)
    xs = X0[SEG[s]]
    tri = bool(SEG[s, 3] == SEG[s, 2])
    for p in xs.mean(axis=0) + rng.normal(scale=8.0, size=(12, 3)):
        u, v, d2 = closest_point(xs, tri, p)
        w = np.zeros(4)
        shape_weights(u, v, tri, w)
        assert np.sqrt(d2) == pytest.approx(np.linalg.norm(w @ xs - p), rel=1e-12)
        assert np.sqrt(d2) <= _brute(xs, tri, p) + 1e-9
        assert np.sqrt(d2) >= _brute(xs, tri, p) - 0.05  # grid resolution


@pytest.mark.parametrize("s", [0, 1])
def test_closest_point_is_the_contact_projection_on_the_segment(s):
    """Where the contact's foot point lies on the segment, the tie's closest point is
    that point (one projection: same natural coordinates to round-off)."""
    rng = np.random.default_rng(4)
    xs = X0[SEG[s]]
    tri = bool(SEG[s, 3] == SEG[s, 2])
    seg = SEG[s:s + 1].astype(np.int32) - SEG[s].min()
    x = X0[SEG[s].min():SEG[s].max() + 1]
    n_on = 0
    for p in xs.mean(axis=0) + rng.normal(scale=[3.0, 3.0, 2.0], size=(40, 3)):
        ok, inside, *_, w0, w1, w2, w3 = project_segment(p[0], p[1], p[2], x, seg, 0)
        w = np.array([w0, w1, w2, w3])
        if not (ok and inside and w.min() >= 0.0):
            continue
        n_on += 1
        u, v, _ = closest_point(xs, tri, p)
        wt = np.zeros(4)
        shape_weights(u, v, tri, wt)
        np.testing.assert_allclose(wt, w, rtol=0, atol=1e-12)
    assert n_on > 10


def test_closest_point_on_a_folded_quad_is_the_true_closest_point():
    """The folded wall segment of the contact's projection test, where Newton does not
    converge for this node and (p - xp) . n of its last iterate is only 0.8 mm: the
    closest point is the true one (brute force: 7.5 mm), not a false foot point."""
    xs = np.array([[-35.993, -36.171, 22.978], [-29.576, -39.538, 12.938],
                   [-30.552, -38.699, 12.912], [-35.745, -35.695, 27.803]])
    p = np.array([-23.850, -38.160, 17.768])
    u, v, d2 = closest_point(xs, False, p)
    assert np.sqrt(d2) <= _brute(xs, False, p) + 1e-9
    assert np.sqrt(d2) >= _brute(xs, False, p) - 0.05
    assert np.sqrt(d2) > 7.0


def _ties(points, project=True):
    seg, uv, d = closest_segments(points, SEG, X0, radius=40.0)
    sg = SEG[seg]
    w = np.zeros((points.shape[0], 4))
    for k in range(points.shape[0]):
        shape_weights(uv[k, 0], uv[k, 1], bool(sg[k, 3] == sg[k, 2]), w[k])
    off = np.zeros((points.shape[0], 3)) if project else local_offsets(points, sg, uv, X0)
    n0 = X0.shape[0]
    node = n0 + np.arange(points.shape[0])
    return TieSet(node=node, seg=sg, w=w, uv=uv, off=off, cid=np.ones(node.size, np.int64),
                  shell_edge=np.ones(node.size, bool), rigid_node=np.zeros(n0 + node.size, bool),
                  fixed_node=np.zeros(n0 + node.size, bool)), d


@pytest.mark.parametrize("project", [True, False])
def test_slaves_follow_a_rigid_motion_exactly(project):
    """Translate and rotate the segments rigidly: every slave (on the surface or
    offset from it) lands where the rigid motion puts it, velocity = its displacement / dt."""
    pts = np.array([[3.0, 4.0, 0.7], [9.0, 8.5, -1.2], [24.0, 3.0, 2.5], [12.0, -1.0, 0.3]])
    ties, _ = _ties(pts, project)
    xq = np.einsum("ka,kac->kc", ties.w, X0[ties.seg])
    start = xq if project else pts
    x = np.vstack([X0, start])
    rot, shift, dt = _rotation([0.3, -1.0, 0.5], 0.8), np.array([5.0, -3.0, 7.0]), 0.01
    new = x @ rot.T + shift
    v = np.zeros_like(x)
    v[:7] = (new[:7] - x[:7]) / dt
    x_next = x.copy()
    x_next[:7] = new[:7]
    x_next[7:] = 123.0  # whatever the free update did to the slaves
    w = np.zeros_like(x)
    ties.follow(x_next, v, w, dt)
    scale = np.abs(new).max()
    assert np.abs(x_next[7:] - new[7:]).max() < 1e-12 * scale
    assert np.abs(v[7:] - (new[7:] - start) / dt).max() < 1e-10 * scale / dt


def test_distribute_keeps_resultant_and_moment():
    pts = np.array([[3.0, 4.0, 0.0], [24.0, 3.0, 0.5]])
    ties, _ = _ties(pts, project=True)
    n = 9
    rng = np.random.default_rng(5)
    f = rng.normal(size=(n, 3))
    mom = rng.normal(size=(n, 3))
    x = np.vstack([X0, np.einsum("ka,kac->kc", ties.w, X0[ties.seg])])
    ties.rot = np.array([True, False])
    f0, m0 = f.copy(), mom.copy()
    ties.distribute(f, mom)
    assert np.allclose(f[7:], 0.0) and np.allclose(mom[7], 0.0) and np.allclose(mom[8], m0[8])
    assert np.allclose(f.sum(axis=0), f0.sum(axis=0), atol=1e-13)
    assert np.allclose(np.cross(x, f).sum(axis=0) + mom.sum(axis=0) - m0[8],
                       np.cross(x, f0).sum(axis=0) + m0.sum(axis=0) - m0[8], atol=1e-12)


def test_mass_transfer_and_initial_join_keep_momentum():
    pts = np.array([[3.0, 4.0, 0.0], [9.0, 8.0, 1.5], [24.0, 3.0, 0.5]])
    ties, _ = _ties(pts, project=True)
    n = 10
    rng = np.random.default_rng(7)
    m_true = rng.uniform(0.5, 2.0, n)
    v = rng.normal(size=(n, 3))
    p0 = (m_true[:, None] * v).sum(axis=0)
    mass, inertia = m_true.copy(), np.zeros(n)
    ties.transfer_mass(mass, inertia)
    assert mass.sum() == pytest.approx(m_true.sum(), rel=1e-14)
    assert np.all(mass[7:] == 0.0)
    x = np.vstack([X0, pts])
    ties.start(x, v, np.zeros_like(v))
    # momentum of the effective masses = the given momentum = that of the true masses
    assert np.allclose((mass[:, None] * v).sum(axis=0), p0, rtol=0, atol=1e-13)
    assert np.allclose((m_true[:, None] * v).sum(axis=0), p0, rtol=0, atol=1e-13)
    assert np.allclose(v[7:], np.einsum("ka,kac->kc", ties.w, v[ties.seg]), atol=1e-15)


def test_initial_join_changes_nothing_when_slaves_move_with_their_segments():
    pts = np.array([[3.0, 4.0, 0.0], [9.0, 8.0, 1.5], [24.0, 3.0, 0.5]])
    ties, _ = _ties(pts, project=True)
    mass = np.ones(10)
    ties.transfer_mass(mass, np.zeros(10))
    x = np.vstack([X0, np.einsum("ka,kac->kc", ties.w, X0[ties.seg])])
    grad = np.array([[0.1, 0.2, -0.3], [0.0, 0.5, 0.1], [0.2, -0.1, 0.3]])
    v = x @ grad.T + np.array([1.0, 2.0, 3.0])  # a linear velocity field
    v0 = v.copy()
    ties.start(x, v, np.zeros_like(v))
    assert np.allclose(v, v0, rtol=0, atol=1e-14)
