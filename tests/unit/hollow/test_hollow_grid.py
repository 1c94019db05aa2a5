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


def test_imperfection_is_a_checkerboard_of_panel_buckling_modes():
    a = 0.3
    flat = hollow_box((60.0, 60.0, 30.0), cell=30.0, elements_per_edge=4)
    g = hollow_box((60.0, 60.0, 30.0), cell=30.0, elements_per_edge=4, imperfection=a)
    d = g.nodes - flat.nodes
    # nodes on cell edges (where walls meet) do not move: the grid stays conforming
    on_edge = (np.isclose(np.mod(flat.nodes, 30.0), 0.0).sum(axis=1) >= 2)
    assert np.allclose(d[on_edge], 0.0)
    # panel-interior nodes move only along their wall's normal, by a sin(pi u/c) sin(pi v/c)
    inner = ~on_edge
    assert (np.count_nonzero(d[inner], axis=1) == 1).all()
    amp = np.abs(d[inner]).max(axis=1)
    assert amp.max() == pytest.approx(a)  # panel centre (u = v = c/2)
    assert amp.min() == pytest.approx(a * np.sin(np.pi / 4) ** 2)
    # neighbouring panels of one wall bulge to opposite sides
    x = flat.nodes
    centre = inner & np.isclose(x[:, 2], 0.0) & np.isclose(np.mod(x[:, 0], 30.0), 15.0) \
        & np.isclose(np.mod(x[:, 1], 30.0), 15.0)
    signs = np.sign(d[centre, 2])
    assert sorted(signs.tolist()) == [-1.0, -1.0, 1.0, 1.0]
    # the wall area (and so the mass-preserving density) barely changes
    assert g.wall_area == pytest.approx(flat.wall_area, rel=1e-3)


def test_bad_imperfection():
    with pytest.raises(ValueError, match="imperfection"):
        hollow_box((60.0, 60.0, 30.0), cell=30.0, imperfection=20.0)
