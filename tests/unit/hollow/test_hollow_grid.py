"""Hollow grid generator (hollowbody.hollow.grid)."""

import numpy as np
import pytest

from hollowbody.hollow.grid import hollow_box


@pytest.mark.parametrize("k", [1, 2, 4])
def test_paper_block_walls_area_and_counts(k):
    g = hollow_box((180.0, 180.0, 90.0), cell=30.0, thickness=1.5, elements_per_edge=k)
    # 7 x-planes and 7 y-planes of 180 x 90, 4 z-planes of 180 x 180
    assert g.wall_area == pytest.approx(7 * 180 * 90 * 2 + 4 * 180 * 180, rel=1e-12)
    assert g.quads.shape[0] == (7 * 6 * 3 * 2 + 4 * 6 * 6) * k * k
    assert np.bincount(g.orientation).tolist() == [7 * 18 * k * k, 7 * 18 * k * k, 4 * 36 * k * k]
    # every node is used, no duplicate coordinates (conforming)
    assert np.unique(g.quads).size == g.nodes.shape[0]
    assert np.unique(np.round(g.nodes, 6), axis=0).shape[0] == g.nodes.shape[0]


def test_walls_lie_on_cell_planes_and_quads_are_square():
    g = hollow_box((60.0, 30.0, 30.0), cell=30.0, elements_per_edge=3)
    x = g.nodes[g.quads]
    for axis in range(3):
        sel = g.orientation == axis
        coord = x[sel][:, :, axis]
        assert np.allclose(coord, coord[:, :1])  # planar along the normal axis
        assert np.allclose(np.mod(coord[:, 0], 30.0), 0.0)
    edges = np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
    assert np.allclose(edges, 10.0)


def test_mass_preserving_density():
    g = hollow_box((180.0, 180.0, 90.0))
    solid_mass = 1.0e-6 * 180 * 180 * 90
    rho = g.density_for_mass(solid_mass)
    assert rho * g.wall_area * g.thickness == pytest.approx(solid_mass)
    assert rho == pytest.approx(2.916 / (356400 * 1.5))


def test_bad_cell_size():
    with pytest.raises(ValueError, match="does not divide"):
        hollow_box((100.0, 90.0, 90.0), cell=30.0)
