"""*MAT_ELASTIC parameters/update and the scalar 3x3 symmetric eigen-solver."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.errors import DeckError
from hollowbody.materials.mat001_elastic import (
    P_BULK,
    P_C,
    P_LAMBDA,
    P_MU,
    elastic_params,
    elastic_stress_update,
    elastic_update,
)
from hollowbody.materials.sym3_eigen import jacobi_eig3
from hollowbody.model.model import MaterialDef


def test_elastic_params():
    p = elastic_params(MaterialDef(1, "elastic", 7.85e-6, {"E": 210.0, "PR": 0.3}))
    assert p[P_MU] == pytest.approx(210.0 / 2.6)
    assert p[P_LAMBDA] == pytest.approx(210.0 * 0.3 / (1.3 * 0.4))
    assert p[P_BULK] == pytest.approx(210.0 / (3 * 0.4))
    # steel: c = sqrt(E (1 - nu) / ((1 + nu)(1 - 2 nu) rho)) ~ 6000 mm/ms (= m/s)
    assert p[P_C] == pytest.approx(math.sqrt(210.0 * 0.7 / (1.3 * 0.4) / 7.85e-6))
    assert 5500.0 < p[P_C] < 6200.0


@pytest.mark.parametrize("bad", [{"E": 0.0, "PR": 0.3}, {"E": 1.0, "PR": 0.5}])
def test_elastic_params_reject_bad_input(bad):
    with pytest.raises(DeckError):
        elastic_params(MaterialDef(1, "elastic", 1e-6, bad))


def test_elastic_update_uniaxial_strain():
    p = elastic_params(MaterialDef(1, "elastic", 1e-6, {"E": 1.0, "PR": 0.25}))
    s = elastic_update(0, 0, 0, 0, 0, 0, 1e-3, 0, 0, 0, 0, 0, p[P_LAMBDA], p[P_MU])
    assert s[0] == pytest.approx((p[P_LAMBDA] + 2 * p[P_MU]) * 1e-3)
    assert s[1] == pytest.approx(p[P_LAMBDA] * 1e-3)
    shear = elastic_update(0, 0, 0, 0, 0, 0, 0, 0, 0, 5e-4, 0, 0, p[P_LAMBDA], p[P_MU])
    assert shear[3] == pytest.approx(p[P_MU] * 1e-3)  # G * engineering shear strain
    vec = elastic_stress_update(np.zeros((1, 6)), np.array([[1e-3, 0, 0, 5e-4, 0, 0]]), p)
    np.testing.assert_allclose(vec[0, [0, 1, 3]], [s[0], s[1], shear[3]])


@pytest.mark.parametrize("seed", range(6))
def test_jacobi_eigen_random(seed):
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(3, 3))
    a = a + a.T
    vec = np.eye(3)
    lam = jacobi_eig3(a[0, 0], a[1, 1], a[2, 2], a[0, 1], a[1, 2], a[0, 2], vec)
    np.testing.assert_allclose(vec.T @ vec, np.eye(3), atol=1e-14)
    np.testing.assert_allclose(vec @ np.diag(lam) @ vec.T, a, atol=1e-13)
    np.testing.assert_allclose(np.sort(lam), np.linalg.eigvalsh(a), atol=1e-13)


def test_jacobi_repeated_eigenvalues_and_warm_start():
    r = np.linalg.qr(np.random.default_rng(1).normal(size=(3, 3)))[0]
    a = r @ np.diag([2.0, 2.0, 5.0]) @ r.T
    vec = np.eye(3)
    lam = jacobi_eig3(a[0, 0], a[1, 1], a[2, 2], a[0, 1], a[1, 2], a[0, 2], vec)
    np.testing.assert_allclose(np.sort(lam), [2.0, 2.0, 5.0], atol=1e-14)
    np.testing.assert_allclose(vec @ np.diag(lam) @ vec.T, a, atol=1e-14)
    # warm start with the exact basis: no rotation needed
    vec2 = r.copy()
    lam2 = jacobi_eig3(a[0, 0], a[1, 1], a[2, 2], a[0, 1], a[1, 2], a[0, 2], vec2)
    np.testing.assert_allclose(lam2, [2.0, 2.0, 5.0], atol=1e-14)
    np.testing.assert_allclose(vec2, r, atol=1e-14)
    iso = np.eye(3)
    assert jacobi_eig3(1.0, 1.0, 1.0, 0.0, 0.0, 0.0, iso) == (1.0, 1.0, 1.0)
