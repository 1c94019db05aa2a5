"""Plane-stress J2 return mapping (hollowbody.materials.plane_stress_plasticity)."""

import math

import numpy as np
import pytest

from hollowbody.materials.plane_stress_plasticity import (
    effective_strain_rate,
    elastic_plane_stress,
    plane_stress_return,
    table_eval,
)

E, NU = 210.0, 0.3
BILINEAR = (np.array([0.0, 1.0]), np.array([0.3, 0.3 + 2.0]))


def vm(sxx, syy, sxy):
    return math.sqrt(sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy)


def test_table_eval_interpolates_and_extrapolates_linearly():
    cx, cy = np.array([0.0, 0.1, 0.3]), np.array([0.2, 0.3, 0.34])
    assert table_eval(0.05, cx, cy) == pytest.approx((0.25, 1.0))
    assert table_eval(0.5, cx, cy) == pytest.approx((0.38, 0.2))
    assert table_eval(-1.0, cx, cy) == pytest.approx((0.2, 0.0))
    assert table_eval(3.0, np.zeros(1), np.full(1, 0.5)) == (0.5, 0.0)


def test_elastic_below_yield_equals_plane_stress_hooke():
    out = plane_stress_return(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-4, -2e-4, 3e-4, E, NU, 0.0,
                              *BILINEAR, 1.0)
    ref = elastic_plane_stress(0.0, 0.0, 0.0, 1e-4, -2e-4, 3e-4, E, NU)
    assert out[:3] == pytest.approx(ref, rel=1e-14)
    assert out[6] == 0.0 and out[7] == 0.0


@pytest.mark.parametrize("de", [(0.01, 0.0, 0.0), (0.005, 0.004, 0.0), (0.0, 0.0, 0.02),
                                (0.02, -0.015, 0.01), (0.3, 0.1, -0.2)])
@pytest.mark.parametrize("hk", [0.0, 1.0])
def test_return_is_on_the_yield_surface_and_consistent(de, hk):
    cx, cy = np.array([0.0, 0.05, 0.2]), np.array([0.3, 0.4, 0.45])
    sxx, syy, sxy, axx, ayy, axy, ep, dsum = plane_stress_return(
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, *de, E, NU, hk, cx, cy, 1.0)
    assert ep > 0.0
    sy, _ = table_eval(ep, cx, cy)
    assert vm(sxx - axx, syy - ayy, sxy - axy) == pytest.approx(sy, rel=1e-9)
    # elastic strain = total - plastic; the plastic part follows the normality rule
    g = 0.5 * E / (1 + NU)
    ee_xx = (sxx - NU * syy) / E
    ee_yy = (syy - NU * sxx) / E
    ep_xx, ep_yy, ep_xy = de[0] - ee_xx, de[1] - ee_yy, de[2] - sxy / g
    xi = np.array([sxx - axx, syy - ayy, sxy - axy])
    flow = np.array([(2 * xi[0] - xi[1]) / 3, (2 * xi[1] - xi[0]) / 3, 2 * xi[2]])
    lam = ep_xx / flow[0] if abs(flow[0]) > 1e-8 else ep_xy / flow[2]
    assert np.array([ep_xx, ep_yy, ep_xy]) == pytest.approx(lam * flow, rel=1e-7, abs=1e-12)
    assert dsum == pytest.approx(ep_xx + ep_yy, rel=1e-7, abs=1e-13)
    # effective plastic strain = sqrt(2/3 eps_p : eps_p) with eps_p_zz = -(xx + yy)
    ezz = -(ep_xx + ep_yy)
    eq = math.sqrt(2 / 3 * (ep_xx ** 2 + ep_yy ** 2 + ezz ** 2 + 0.5 * ep_xy ** 2))
    assert ep == pytest.approx(eq, rel=1e-7)


def uniaxial_path(hk, cx, cy, strains):
    """Strain-driven uniaxial stress (sigma_yy = 0 by Newton on eps_yy) at a material point."""
    s = np.zeros(3)
    a = np.zeros(3)
    ep = 0.0
    exx_old = 0.0
    out = []
    for exx in strains:
        dexx = exx - exx_old
        exx_old = exx
        deyy = -NU * dexx
        for _ in range(30):
            r = plane_stress_return(*s, *a, ep, dexx, deyy, 0.0, E, NU, hk, cx, cy, 1.0)
            if abs(r[1]) < 1e-13:
                break
            h = 1e-9
            r2 = plane_stress_return(*s, *a, ep, dexx, deyy + h, 0.0, E, NU, hk, cx, cy, 1.0)
            deyy -= r[1] / ((r2[1] - r[1]) / h)
        s, a, ep = np.array(r[:3]), np.array(r[3:6]), r[6]
        out.append((s[0], ep))
    return out


def test_uniaxial_isotropic_and_kinematic_hardening_with_reversal():
    h = 2.0
    up = list(np.linspace(0.0, 0.02, 41))
    # reverse by 0.0031: a stress drop of 0.651 GPa, beyond 2 sigma_y = 0.6 (kinematic
    # re-yields) but short of 2 sigma_max = 0.674 (isotropic stays elastic)
    path = up + list(np.linspace(0.02, 0.02 - 0.0031, 41))[1:]
    iso = uniaxial_path(0.0, np.array([0.0, 1.0]), np.array([0.3, 0.3 + h]), path)
    kin = uniaxial_path(h, np.array([0.0, 1.0]), np.array([0.3, 0.3]), path)
    for (s_i, ep_i), (s_k, _) in zip(iso[:41], kin[:41]):  # monotonic: identical
        assert s_i == pytest.approx(s_k, rel=1e-9, abs=1e-12)
        if ep_i > 0:
            assert s_i == pytest.approx(0.3 + h * ep_i, rel=1e-9)
    smax = iso[40][0]
    # on reversal: isotropic yields again at -smax, kinematic at smax - 2 sigma_y
    s_iso_end, s_kin_end = iso[-1][0], kin[-1][0]
    assert iso[-1][1] == iso[40][1]  # isotropic: no reverse yielding
    assert kin[-1][1] > kin[40][1]  # kinematic reverse-yielded
    assert s_kin_end == pytest.approx(-(0.3 - h * (2 * kin[40][1] - kin[-1][1])), rel=1e-6)
    assert s_iso_end == pytest.approx(smax - E * 0.0031, rel=1e-6)


def test_one_large_increment_converges():
    cx, cy = np.array([0.0, 0.01, 0.02, 0.5]), np.array([0.2, 0.5, 0.55, 0.6])
    r = plane_stress_return(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5, -0.2, 0.3, E, NU, 0.0, cx, cy,
                            1.3)
    sy, _ = table_eval(r[6], cx, cy)
    assert vm(*r[:3]) == pytest.approx(1.3 * sy, rel=1e-9)


def test_effective_strain_rate_of_uniaxial_incompressible_flow():
    assert effective_strain_rate(1.0, -0.5, 0.0) == pytest.approx(1.0)
    assert effective_strain_rate(0.0, 0.0, 2.0) == pytest.approx(2.0 / math.sqrt(3.0))
