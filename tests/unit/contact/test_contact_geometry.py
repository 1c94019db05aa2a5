"""Closest-point projection of nodes onto triangles and bilinear quadrilaterals."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact.geometry import project_segment


def _rot(ax, ay):
    cx, sx, cy, sy = np.cos(ax), np.sin(ax), np.cos(ay), np.sin(ay)
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    return ry @ rx


@pytest.mark.parametrize("tilt", [(0.0, 0.0), (0.3, -0.7)])
@pytest.mark.parametrize("tri", [False, True])
def test_projection_flat_and_tilted(tilt, tri):
    r = _rot(*tilt)
    base = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]], float)
    x = base @ r.T + np.array([5.0, -3.0, 1.0])
    seg = np.array([[0, 1, 2, 2]] if tri else [[0, 1, 2, 3]], np.int32)
    local = np.array([1.5, 0.5, -0.25])  # below the segment, inside the triangle too
    p = local @ r.T + np.array([5.0, -3.0, 1.0])
    ok, inside, qx, qy, qz, nx, ny, nz, *w = project_segment(p[0], p[1], p[2], x, seg, 0)
    assert ok and inside
    n = r @ np.array([0.0, 0.0, 1.0])
    np.testing.assert_allclose([nx, ny, nz], n, atol=1e-12)
    xp = np.array([qx, qy, qz])
    np.testing.assert_allclose(xp, np.array([1.5, 0.5, 0.0]) @ r.T + [5.0, -3.0, 1.0],
                               atol=1e-12)
    assert np.dot(p - xp, n) == pytest.approx(-0.25)
    w = np.array(w)
    assert w.sum() == pytest.approx(1.0)
    np.testing.assert_allclose(w @ x[seg[0]], xp, atol=1e-12)
    if not tri:
        np.testing.assert_allclose(w, [0.1875, 0.5625, 0.1875, 0.0625])  # bilinear N_a


def test_outside_point_is_flagged():
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    for seg in ([[0, 1, 2, 3]], [[0, 1, 2, 2]]):
        ok, inside, *_ = project_segment(1.5, 0.5, 0.1, x, np.array(seg, np.int32), 0)
        assert ok and not inside


def test_warped_quad_newton_matches_dense_search():
    rng = np.random.default_rng(3)
    x = np.array([[0, 0, 0], [1, 0, 0.2], [1.1, 1, -0.1], [0, 0.9, 0.3]], float)
    seg = np.array([[0, 1, 2, 3]], np.int32)
    g = np.linspace(-1, 1, 401)
    xi, eta = np.meshgrid(g, g, indexing="ij")
    n = np.stack([(1 - xi) * (1 - eta), (1 + xi) * (1 - eta), (1 + xi) * (1 + eta),
                  (1 - xi) * (1 + eta)], -1) / 4
    surf = n @ x
    for _ in range(20):
        p = np.array([rng.uniform(0.2, 0.8), rng.uniform(0.2, 0.8), rng.uniform(-0.3, 0.3)])
        ok, inside, qx, qy, qz, nx, ny, nz, *w = project_segment(p[0], p[1], p[2], x, seg, 0)
        assert ok and inside
        dmin = np.min(np.linalg.norm(surf - p, axis=-1))
        d = np.linalg.norm(p - [qx, qy, qz])
        assert d <= dmin + 1e-9 and d >= dmin - 5e-3
        # p - xp is along the surface normal at xp
        r = p - np.array([qx, qy, qz])
        assert np.linalg.norm(np.cross(r, [nx, ny, nz])) < 1e-8
        np.testing.assert_allclose(np.array(w) @ x, [qx, qy, qz], atol=1e-12)


def test_folded_quad_far_point_is_not_inside():
    """A wall segment folded by the crush (edges 12 mm, two corners 1 mm apart)
    and a node 9.6 mm from its nearest surface point: Newton does not converge
    there, and (p - xp) . n is only 0.8 mm. Taken as inside, that gave a false
    contact (hollow block, 70 km/h) that depended on which segments the bucket
    sort listed. The projection must say "not inside"; every point the
    projection does accept is a foot point (p - xp along n, |p - xp| = |d|)."""
    x = np.array([[-35.993, -36.171, 22.978], [-29.576, -39.538, 12.938],
                  [-30.552, -38.699, 12.912], [-35.745, -35.695, 27.803]])
    seg = np.array([[0, 1, 2, 3]], np.int32)
    ok, inside, *_ = project_segment(-23.850, -38.160, 17.768, x, seg, 0)
    assert not (ok and inside)
    rng = np.random.default_rng(11)
    lo, hi = x.min(axis=0) - 10.0, x.max(axis=0) + 10.0
    accepted = 0
    for p in rng.uniform(lo, hi, size=(2000, 3)):
        ok, inside, qx, qy, qz, nx, ny, nz, *w = project_segment(p[0], p[1], p[2], x, seg, 0)
        if not (ok and inside):
            continue
        accepted += 1
        r = p - np.array([qx, qy, qz])
        # tolerance: the last accepted Newton step (1e-6 in xi, eta) times the
        # segment's size (~12 mm) -> ~1e-5 mm of tangential residual
        assert np.linalg.norm(np.cross(r, [nx, ny, nz])) < 1e-4
    assert accepted > 50


def test_warm_start_finds_the_same_foot_point():
    """The contact kernel starts Newton for a node's last segment from its last
    contact point: from there the iteration must reach the foot point the
    cold start (the centre) reaches, to round-off (1e-9 mm; the iteration stops
    once its step is below 1e-10 in natural coordinates)."""
    from hollowbody.contact.geometry import project_quad

    rng = np.random.default_rng(5)
    c = np.array([[0, 0, 0], [1, 0, 0.2], [1.1, 1, -0.1], [0, 0.9, 0.3]], float).ravel()
    for _ in range(50):
        p = np.array([rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9), rng.uniform(-0.3, 0.3)])
        cold = project_quad(*p, *c)
        xi0, eta0 = rng.uniform(-1.0, 1.0, size=2)
        warm = project_quad(*p, *c, xi0, eta0)
        assert cold[0] and cold[1] and warm[0] and warm[1]
        np.testing.assert_allclose(warm[2:5], cold[2:5], atol=1e-9)
