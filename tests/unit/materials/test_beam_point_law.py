"""The beam stress-point law against closed forms: uniaxial hardening, pure shear,
combined loading on the yield surface, kinematic hardening (Bauschinger)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.materials.beam_plasticity import beam_point_update

E, G = 200.0, 76.9
SY = 0.25


def _point():
    return np.zeros((1, 1, 3)), np.zeros((1, 1, 3)), np.zeros((1, 1))


def _table(h):
    return np.array([0.0, 1.0]), np.array([SY, SY + h])


@pytest.mark.parametrize("h", [0.0, 2.0])
def test_uniaxial_follows_sigma_y_plus_h_eps_p(h):
    sig, back, ep = _point()
    hx, hy = _table(h)
    eps = 0.0
    for _ in range(200):
        beam_point_update(sig, back, 0, 0, ep, 1e-4, 0.0, 0.0, E, G, 0.0, True, hx, hy)
        eps += 1e-4
    eps_p = eps - sig[0, 0, 0] / E
    assert ep[0, 0] == pytest.approx(eps_p, rel=1e-10)
    assert sig[0, 0, 0] == pytest.approx(SY + h * eps_p, rel=1e-10)


def test_pure_shear_yields_at_sigma_y_over_sqrt3():
    sig, back, ep = _point()
    hx, hy = _table(0.0)
    for _ in range(100):
        beam_point_update(sig, back, 0, 0, ep, 0.0, 1e-4, 0.0, E, G, 0.0, True, hx, hy)
    assert sig[0, 0, 1] == pytest.approx(SY / math.sqrt(3.0), rel=1e-10)
    assert ep[0, 0] > 0.0


def test_combined_state_returns_onto_the_surface():
    sig, back, ep = _point()
    hx, hy = _table(1.0)
    beam_point_update(sig, back, 0, 0, ep, 5e-3, 3e-3, -2e-3, E, G, 0.0, True, hx, hy)
    q = math.sqrt(sig[0, 0, 0] ** 2 + 3 * (sig[0, 0, 1] ** 2 + sig[0, 0, 2] ** 2))
    assert q == pytest.approx(SY + 1.0 * ep[0, 0], rel=1e-10)
    # associated flow: the plastic strain increment is normal to the surface
    dp = np.array([5e-3 - sig[0, 0, 0] / E, 3e-3 - sig[0, 0, 1] / G, -2e-3 - sig[0, 0, 2] / G])
    n = np.array([sig[0, 0, 0], 3 * sig[0, 0, 1], 3 * sig[0, 0, 2]]) / q
    assert np.allclose(dp, ep[0, 0] * n, rtol=1e-8, atol=1e-14)


def test_kinematic_hardening_bauschinger():
    """Prager kinematic (hk = 2, no isotropic): after eps_p = 0.01 in tension,
    reverse yielding starts at sigma = sigma_y + 2 hk eps_p - 2 sigma_y."""
    sig, back, ep = _point()
    hx, hy = _table(0.0)
    hk = 2.0
    while ep[0, 0] < 0.01:
        beam_point_update(sig, back, 0, 0, ep, 1e-5, 0.0, 0.0, E, G, hk, True, hx, hy)
    top = sig[0, 0, 0]
    assert top == pytest.approx(SY + hk * ep[0, 0], rel=1e-8)
    e0 = ep[0, 0]
    while ep[0, 0] == e0:
        beam_point_update(sig, back, 0, 0, ep, -1e-6, 0.0, 0.0, E, G, hk, True, hx, hy)
    assert sig[0, 0, 0] == pytest.approx(top - 2 * SY, abs=2e-4)
