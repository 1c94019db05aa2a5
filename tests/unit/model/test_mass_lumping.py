"""Lumped masses and mass properties (hollowbody.model.mass)."""

import numpy as np
import pytest

from hollowbody.mesh import standing_block
from hollowbody.model.mass import (
    hex_volumes,
    point_mass_properties,
    quad_areas,
    spread_element_mass,
)

UNIT_HEX = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                     [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)


def test_unit_cube_volume_and_affine_map():
    conn = np.arange(8)[None, :]
    assert hex_volumes(conn, UNIT_HEX)[0] == pytest.approx(1.0, rel=1e-14)
    # an affine map scales the volume by det(A) exactly
    a = np.array([[2.0, 0.3, 0.1], [0.0, 1.5, -0.2], [0.1, 0.0, 0.8]])
    assert hex_volumes(conn, UNIT_HEX @ a.T)[0] == pytest.approx(np.linalg.det(a), rel=1e-13)


def test_degenerate_wedge_and_tet_volumes():
    # wedge: N1 N2 N3 N4 N5 N5 N6 N6 -> prism of a right triangle (area 1/2) x height 1
    x = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 1, 0],
                  [0, 0, 1], [1, 0, 1], [0, 1, 1]], dtype=float)
    wedge = np.array([[0, 1, 2, 3, 4, 5, 6, 6]])
    assert hex_volumes(wedge, x)[0] == pytest.approx(0.5, rel=1e-13)
    tet = np.array([[0, 1, 2, 2, 4, 4, 4, 4]])
    assert hex_volumes(tet, x)[0] == pytest.approx(1.0 / 6.0, rel=1e-13)


def test_block_mass_is_rho_v_and_spread_to_distinct_nodes():
    x, conn = standing_block((30.0, 15.0, 15.0), 7.5)
    rho = 1.0e-6
    m = np.zeros(x.shape[0])
    spread_element_mass(m, conn, rho * hex_volumes(conn, x))
    assert m.sum() == pytest.approx(rho * 30 * 15 * 15, rel=1e-13)
    # a corner node carries 1/8 of one element
    assert m[0] == pytest.approx(rho * 7.5 ** 3 / 8.0, rel=1e-13)
    # a tet spreads over its 4 distinct nodes only
    m2 = np.zeros(8)
    spread_element_mass(m2, np.array([[0, 1, 2, 2, 4, 4, 4, 4]]), np.array([1.0]))
    assert m2[[0, 1, 2, 4]] == pytest.approx([0.25] * 4)
    assert m2[[3, 5, 6, 7]].sum() == 0.0


def test_quad_area_and_triangle():
    x = np.array([[0, 0, 0], [2, 0, 0], [2, 3, 0], [0, 3, 0]], dtype=float)
    assert quad_areas(np.array([[0, 1, 2, 3]]), x)[0] == pytest.approx(6.0)
    assert quad_areas(np.array([[0, 1, 2, 2]]), x)[0] == pytest.approx(3.0)


def test_point_mass_inertia_of_a_ring():
    # 360 equal point masses on a ring of radius r about z: Izz = M r^2, Ixx = Iyy = M r^2/2
    th = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    r, mass = 10.0, 2.0
    x = np.column_stack([r * np.cos(th), r * np.sin(th), np.zeros_like(th)])
    p = point_mass_properties(x, np.full(th.size, mass / th.size))
    assert p.mass == pytest.approx(mass)
    assert np.allclose(p.centre, 0.0, atol=1e-12)
    assert np.allclose(np.diag(p.inertia), [mass * r * r / 2, mass * r * r / 2, mass * r * r])
