"""Uniform gradient, exact volume and degenerate shapes of the one-point hexahedron."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.elements.hex8_kinematics import (
    HG_BASE,
    SHAPE_HEX,
    SHAPE_TET,
    SHAPE_WEDGE,
    canonical_connectivity,
    characteristic_lengths,
    hex8_gradients,
    hex8_volume_derivatives,
)

CUBE = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                 [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)
XI = np.array([-1, 1, 1, -1, -1, 1, 1, -1], dtype=float)
ETA = np.array([-1, -1, 1, 1, -1, -1, 1, 1], dtype=float)
ZETA = np.array([-1, -1, -1, -1, 1, 1, 1, 1], dtype=float)


def distorted_hex(seed: int = 3, amount: float = 0.25) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return CUBE * [2.0, 1.5, 1.0] + rng.uniform(-amount, amount, size=(8, 3))


def gauss_volume(xe: np.ndarray) -> float:
    """Exact trilinear volume by 2x2x2 Gauss quadrature (det J is of degree <= 2 per axis)."""
    g = 1.0 / np.sqrt(3.0)
    vol = 0.0
    for r in (-g, g):
        for s in (-g, g):
            for t in (-g, g):
                dn = np.stack([XI * (1 + s * ETA) * (1 + t * ZETA),
                               ETA * (1 + r * XI) * (1 + t * ZETA),
                               ZETA * (1 + r * XI) * (1 + s * ETA)]) / 8.0  # (3, 8)
                vol += np.linalg.det(dn @ xe)
    return vol


def tet_split_volume(xe: np.ndarray) -> float:
    tets = [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]]
    return sum(np.linalg.det(np.stack([xe[b] - xe[a], xe[c] - xe[a], xe[d] - xe[a]])) / 6.0
               for a, b, c, d in tets)


def grads(xe: np.ndarray) -> tuple[np.ndarray, float]:
    out = np.empty((8, 3))
    v = hex8_volume_derivatives(np.ascontiguousarray(xe, dtype=float), out)
    return out / v, v


def test_unit_cube_volume_and_gradient():
    b, v = grads(CUBE)
    assert v == pytest.approx(1.0, abs=1e-15)
    # b of the unit cube is the shape-function gradient at the centre: +-1/4
    expected = np.stack([XI, ETA, ZETA], axis=1) / 4.0
    np.testing.assert_allclose(b, expected, atol=1e-15)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_gradient_sums_to_zero_and_reproduces_linear_fields(seed):
    xe = distorted_hex(seed)
    b, v = grads(xe)
    np.testing.assert_allclose(b.sum(axis=0), 0.0, atol=1e-13)
    np.testing.assert_allclose(xe.T @ b, np.eye(3), atol=1e-13)


@pytest.mark.parametrize("seed", [0, 5])
def test_gradient_is_volume_derivative(seed):
    xe = distorted_hex(seed)
    b, v = grads(xe)
    h = 1e-6
    for a in range(8):
        for i in range(3):
            xp = xe.copy()
            xm = xe.copy()
            xp[a, i] += h
            xm[a, i] -= h
            dv = (grads(xp)[1] - grads(xm)[1]) / (2 * h)
            assert dv == pytest.approx(v * b[a, i], abs=1e-8)


@pytest.mark.parametrize("seed", [0, 1, 7])
def test_volume_of_warped_hex_is_exact_trilinear_volume(seed):
    xe = distorted_hex(seed, amount=0.3)
    assert grads(xe)[1] == pytest.approx(gauss_volume(xe), rel=1e-13)


def test_volume_of_sheared_hex_matches_tetrahedra():
    a = np.array([[1.0, 0.4, 0.2], [0.1, 2.0, -0.3], [0.0, 0.25, 0.8]])
    xe = CUBE @ a.T + [5.0, -3.0, 100.0]
    v = grads(xe)[1]
    assert v == pytest.approx(np.linalg.det(a), rel=1e-13)
    assert v == pytest.approx(tet_split_volume(xe), rel=1e-13)


def test_wedge_volume_and_constant_strain():
    p = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0], [0, 0, 1.5], [0, 1, 1.5]], float)
    conn = np.array([[0, 1, 2, 3, 4, 4, 5, 5]])
    conn_k, shape = canonical_connectivity(conn)
    assert shape[0] == SHAPE_WEDGE
    np.testing.assert_array_equal(conn_k, conn)
    b, vol = hex8_gradients(conn_k, p)
    assert vol[0] == pytest.approx(0.5 * 2 * 1.5 * 1.0, rel=1e-14)
    a = np.array([[0.01, 0.002, -0.003], [0.004, -0.02, 0.001], [0.0, 0.005, 0.03]])
    u = p @ a.T
    grad = u[conn_k[0]].T @ b[0]
    np.testing.assert_allclose(grad, a, atol=1e-15)


@pytest.mark.parametrize("pattern", [[0, 1, 2, 3, 3, 3, 3, 3], [0, 1, 2, 2, 3, 3, 3, 3]])
def test_tetrahedron_volume_and_constant_strain(pattern):
    rng = np.random.default_rng(4)
    p = rng.random((4, 3))
    if np.linalg.det(np.stack([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) < 0:
        p[[1, 2]] = p[[2, 1]]
    exact = np.linalg.det(np.stack([p[1] - p[0], p[2] - p[0], p[3] - p[0]])) / 6.0
    conn_k, shape = canonical_connectivity(np.array([pattern]))
    assert shape[0] == SHAPE_TET
    np.testing.assert_array_equal(conn_k[0], [0, 1, 2, 2, 3, 3, 3, 3])
    b, vol = hex8_gradients(conn_k, p)
    assert vol[0] == pytest.approx(exact, rel=1e-12)
    a = rng.normal(scale=0.01, size=(3, 3))
    grad = (p @ a.T)[conn_k[0]].T @ b[0]
    np.testing.assert_allclose(grad, a, atol=1e-14)


def test_lsdyna_tet_pattern_needs_rewriting():
    """As a trilinear map, N1 N2 N3 N4 N4 N4 N4 N4 holds only half the tetrahedron."""
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    _, vol = hex8_gradients(np.array([[0, 1, 2, 3, 3, 3, 3, 3]]), p)
    assert vol[0] == pytest.approx(1.0 / 12.0)


def test_shapes_and_characteristic_lengths():
    p = np.vstack([CUBE * 2.0, [[0, 0, 3.0]]])
    conn = np.array([[0, 1, 2, 3, 4, 5, 6, 7]])
    conn_k, shape = canonical_connectivity(conn)
    assert shape[0] == SHAPE_HEX
    assert characteristic_lengths(conn_k, p, shape)[0] == pytest.approx(2.0)
    # right tetrahedron with unit legs: smallest altitude 1/sqrt(3)
    tet = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    conn_k, shape = canonical_connectivity(np.array([[0, 1, 2, 3, 3, 3, 3, 3]]))
    assert characteristic_lengths(conn_k, tet, shape)[0] == pytest.approx(1 / np.sqrt(3))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_hourglass_vectors_orthogonal_to_linear_fields(seed):
    xe = distorted_hex(seed, amount=0.3)
    b, _ = grads(xe)
    for h in HG_BASE:
        gamma = h - b @ (xe.T @ h)  # (8,)
        assert abs(gamma.sum()) < 1e-13
        np.testing.assert_allclose(xe.T @ gamma, 0.0, atol=1e-13)
