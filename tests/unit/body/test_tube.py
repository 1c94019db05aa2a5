"""The layered tube mesher: volumes, orientation, shell normals."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.body.anatomy import closed_shell
from hollowbody.body.tube import Ellipses, _signed_volume, layered_tube, stations


def _polygon_area(r: float, n: int) -> float:
    return 0.5 * n * r * r * np.sin(2.0 * np.pi / n)


def test_prism_volume_is_the_polygon_annulus() -> None:
    """Circles of radius 10 and 50 mm, 12 around, 100 mm long: the hexahedra fill the
    annulus between the two 12-gons exactly (prisms of plane quadrilaterals: the
    centre Jacobian gives their volume exactly; 1e-9 relative)."""
    z, owner = stations([0.0, 40.0, 100.0], 25.0)
    assert z.tolist() == pytest.approx([0, 20, 40, 60, 80, 100])
    assert owner.tolist() == [0, 0, 1, 1, 1]
    n = z.size
    t = layered_tube(z, Ellipses.constant(n, 10.0, 10.0), Ellipses.constant(n, 50.0, 50.0),
                     np.linspace(0.0, 1.0, 4), 12)
    h = t.hexes(np.arange(n - 1), np.arange(3))
    v = _signed_volume(t.nodes(), h)
    assert (v > 0.0).all()
    exact = 100.0 * (_polygon_area(50.0, 12) - _polygon_area(10.0, 12))
    assert v.sum() == pytest.approx(exact, rel=1e-9)


def test_shell_normals_point_outward() -> None:
    n = 3
    z = np.array([-100.0, -50.0, 0.0])  # a limb runs to negative local z
    t = layered_tube(z, Ellipses.constant(n, 8.0, 8.0),
                     Ellipses(np.zeros(n), np.full(n, 5.0), np.full(n, 40.0), np.full(n, 30.0)),
                     np.linspace(0.0, 1.0, 3), 10)
    x = t.nodes()
    for ring in (0, 2):
        q = x[t.quads(ring, np.arange(2))]
        normal = np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])
        radial = q.mean(axis=1) - np.array([0.0, 0.0 if ring == 0 else 5.0, 0.0])
        radial[:, 2] = 0.0
        assert (np.einsum("ij,ij->i", normal, radial) > 0.0).all()
    assert (_signed_volume(x, t.hexes(np.arange(2), np.arange(2))) > 0.0).all()


@pytest.mark.parametrize("shape", ["box", "ellipsoid"])
def test_closed_shell_is_closed_and_outward(shape: str) -> None:
    """Every edge is shared by exactly two quads (closed surface) and the enclosed volume
    by the divergence theorem is positive: box 8 abc exactly; ellipsoid below 4/3 pi abc."""
    semi = np.array([30.0, 20.0, 10.0])
    p, q = closed_shell(shape, semi, 4)
    edges = np.sort(np.stack([q, np.roll(q, -1, axis=1)], axis=-1).reshape(-1, 2), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert (counts == 2).all()
    tri = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    vol = np.einsum("ij,ij->i", p[tri[:, 0]], np.cross(p[tri[:, 1]], p[tri[:, 2]])).sum() / 6
    if shape == "box":
        assert vol == pytest.approx(8.0 * semi.prod(), rel=1e-12)
    else:
        assert 0.8 * 4.0 / 3.0 * np.pi * semi.prod() < vol < 4.0 / 3.0 * np.pi * semi.prod()
