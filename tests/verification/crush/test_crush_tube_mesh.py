"""The tube meshes of the crush benchmark: geometry, numbering, normals, trigger.

Exact checks (to 1e-12 mm): the untriggered walls lie on the mid-surface
(square: max(|x|, |y|) = C / 2; circular: radius D / 2), the rings are evenly
spaced, every quad's normal points outwards, and the trigger moves only its
ring, by the stated amplitude and shape.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.mesh import circular_tube, square_tube


def _normals(x: np.ndarray, q: np.ndarray) -> np.ndarray:
    p = x[q]
    n = np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    return n / np.linalg.norm(n, axis=1)[:, None]


def test_square_tube_geometry_and_numbering():
    x, q = square_tube(40.0, 2.0, 60.0, 8, 12)
    assert x.shape == (13 * 32, 3) and q.shape == (12 * 32, 4) and q.dtype == np.int32
    assert np.allclose(np.maximum(np.abs(x[:, 0]), np.abs(x[:, 1])), 20.0, atol=1e-12)
    assert np.allclose(np.unique(x[:, 2]), np.linspace(0.0, 60.0, 13))
    # ring k holds nodes k*m .. k*m + m - 1
    assert np.allclose(x[32:64, 2], 5.0) and np.allclose(x[:32, :2], x[32:64, :2])
    c = x[q].mean(axis=1)
    radial = np.where(np.abs(c[:, :1]) > np.abs(c[:, 1:2]),
                      np.column_stack([np.sign(c[:, 0]), 0 * c[:, 0]]),
                      np.column_stack([0 * c[:, 0], np.sign(c[:, 1])]))
    n = _normals(x, q)
    assert np.allclose(n[:, :2], radial, atol=1e-12) and np.allclose(n[:, 2], 0.0)
    edges = np.linalg.norm(x[q[:, 1]] - x[q[:, 0]], axis=1)
    assert np.allclose(edges, 5.0)


def test_square_trigger_moves_one_ring_by_its_amplitude():
    x0, _ = square_tube(40.0, 2.0, 60.0, 8, 12)
    x, _ = square_tube(40.0, 2.0, 60.0, 8, 12, trigger=0.5, trigger_level=2)
    moved = np.any(np.abs(x - x0) > 0.0, axis=1)
    ring = np.arange(10 * 32, 11 * 32)  # level nz - 2 = 10
    assert set(np.flatnonzero(moved)) <= set(ring)
    d = x[ring] - x0[ring]
    assert np.allclose(d[:, 2], 0.0)
    assert abs(np.abs(d).max() - 1.0) < 1e-12  # 0.5 t at mid-side
    corners = np.isclose(np.abs(x0[ring, 0]), 20.0) & np.isclose(np.abs(x0[ring, 1]), 20.0)
    assert np.allclose(d[corners], 0.0)
    # walls normal to x move inwards, walls normal to y outwards
    on_x = np.isclose(np.abs(x0[ring, 0]), 20.0) & ~corners
    on_y = np.isclose(np.abs(x0[ring, 1]), 20.0) & ~corners
    assert np.all(np.abs(x[ring][on_x, 0]) < 20.0)
    assert np.all(np.abs(x[ring][on_y, 1]) > 20.0)


def test_circular_tube_geometry_and_trigger():
    x, q = circular_tube(60.0, 2.0, 50.0, 24, 10)
    assert x.shape == (11 * 24, 3) and q.shape == (240, 4)
    assert np.allclose(np.hypot(x[:, 0], x[:, 1]), 30.0, atol=1e-12)
    c = x[q].mean(axis=1)
    n = _normals(x, q)
    assert np.all(np.einsum("ij,ij->i", n[:, :2], c[:, :2]) > 0.0)
    xt, _ = circular_tube(60.0, 2.0, 50.0, 24, 10, trigger=0.25, trigger_level=1)
    r = np.hypot(xt[:, 0], xt[:, 1])
    assert np.allclose(r[9 * 24:10 * 24], 30.5) and np.allclose(np.delete(r, np.s_[216:240]),
                                                                 30.0)
    xl, _ = circular_tube(60.0, 2.0, 50.0, 24, 10, trigger=0.25, lobes=4)
    rl = np.hypot(xl[216:240, 0], xl[216:240, 1])
    theta = 2.0 * math.pi * np.arange(24) / 24
    assert np.allclose(rl, 30.0 + 0.5 * np.cos(4 * theta))


@pytest.mark.parametrize("call", [
    lambda: square_tube(0.0, 1.0, 10.0, 4),
    lambda: square_tube(10.0, 1.0, 10.0, 4, 4, trigger=0.2, trigger_level=4),
    lambda: circular_tube(10.0, 1.0, 10.0, 2),
    lambda: circular_tube(10.0, 1.0, 10.0, 12, 4, trigger=0.2, lobes=1),
])
def test_bad_tube_input_is_refused(call):
    with pytest.raises(ValueError):
        call()
