"""Restrained axes of hexahedra and the volumetric step factor (set-up helpers)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.elements.solid_step_factor import (
    group_min_axes,
    restrained_axes,
    volumetric_step_factor,
)
from hollowbody.mesh import block_mesh


@pytest.mark.parametrize("counts,k", [((1, 1, 1), 0), ((3, 1, 1), 1), ((1, 1, 4), 1),
                                      ((4, 4, 1), 2), ((1, 3, 3), 2), ((2, 2, 2), 3)])
def test_min_restrained_axes_of_blocks(counts, k):
    _, conn = block_mesh(counts)
    (axes,) = restrained_axes([conn])
    assert group_min_axes(conn, axes) == k


def test_interior_elements_and_faces_shared_between_groups():
    _, conn = block_mesh((3, 3, 3))
    (axes,) = restrained_axes([conn])
    assert axes.max() == 3 and axes.min() == 3
    # a 2 x 1 x 1 bar split into two groups of one element: each has one neighbour axis
    _, bar = block_mesh((2, 1, 1))
    a, b = restrained_axes([bar[:1], bar[1:]])
    assert a.tolist() == [1] and b.tolist() == [1]


def test_degenerate_elements_and_empty_groups_count_as_lone():
    _, conn = block_mesh((2, 2, 2))
    wedge = conn.copy()
    wedge[0] = [wedge[0, 0], wedge[0, 1], wedge[0, 2], wedge[0, 3], wedge[0, 4], wedge[0, 4],
                wedge[0, 6], wedge[0, 6]]
    (axes,) = restrained_axes([wedge])
    assert group_min_axes(wedge, axes) == 0
    assert group_min_axes(np.zeros((0, 8), dtype=np.int64), np.zeros(0, dtype=np.int64)) == 0


def test_factor_by_axes_elastic():
    p = {"E": 0.2, "PR": 0.3}
    m_over_k = 1.0 + 4.0 / 3.0 * (3 * (1 - 2 * 0.3) / (2 * (1 + 0.3)))
    for k, gamma in [(0, 3.0), (1, 8.0 / 3.0), (2, 7.0 / 3.0), (3, 1.5), (5, 1.5)]:
        assert volumetric_step_factor("elastic", p, {}, k) == pytest.approx(
            math.sqrt(m_over_k / max(m_over_k, gamma)), rel=1e-12)
    assert volumetric_step_factor("elastic", {"E": 0.2, "PR": 0.0}, {}) == 1.0
    assert volumetric_step_factor("rigid", {}, {}) == 1.0
