"""Tabulated Valanis-Landel function of MAT_181 and its stability check."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from hollowbody.errors import DeckError
from hollowbody.materials.mat181_simplified_rubber import (
    P_BULK,
    P_G0,
    rubber_deviatoric,
    rubber_friction,
    rubber_params,
)
from hollowbody.materials.rubber_table import (
    build_rubber_table,
    check_rubber_curve,
    curve_stress_strain,
    initial_modulus,
    kirchhoff_function,
    table_lookup,
    uniaxial_stress,
)
from hollowbody.model.model import Curve, MaterialDef

STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                   0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                   0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148]) * 1e-3  # GPa
FAT = np.array([-4.74, -1.66, -0.760, -0.395, -0.217, -0.119, -0.0613, -0.0244, 0.0,
                0.0168, 0.0286, 0.0372, 0.0482, 0.0555, 0.0591]) * 1e-3


def ogden_T(lam, mu=0.1668e-3, alpha=-1.479):
    return 2 * mu / alpha * (lam ** (alpha - 1) - lam ** (-alpha / 2 - 1))


def test_curve_scaling_to_stress_strain():
    c = Curve(5, STRAIN * 20.0, MUSCLE * 10.0 * 5.0)
    e, s = curve_stress_strain(c, 20.0, 10.0, 5.0)
    np.testing.assert_allclose(e, STRAIN)
    np.testing.assert_allclose(s, MUSCLE)


def test_uniaxial_stress_interpolates_and_extrapolates_linearly():
    t = uniaxial_stress(np.array([1.0, 1.15, 0.15, 2.5]), STRAIN, MUSCLE)
    assert t[0] == 0.0
    assert t[1] == pytest.approx(0.5 * (0.0419 + 0.0716) * 1e-3)
    slope0 = (MUSCLE[1] - MUSCLE[0]) / 0.1
    assert t[2] == pytest.approx(MUSCLE[0] + slope0 * (-0.85 + 0.8))
    slope1 = (MUSCLE[-1] - MUSCLE[-2]) / 0.25
    assert t[3] == pytest.approx(MUSCLE[-1] + slope1 * 0.5)


def test_series_telescopes_to_uniaxial_stress():
    lam = np.exp(np.linspace(math.log(0.2), math.log(2.0), 50))
    f = kirchhoff_function(lam, STRAIN, MUSCLE)
    f_half = kirchhoff_function(lam**-0.5, STRAIN, MUSCLE)
    np.testing.assert_allclose(f - f_half, lam * uniaxial_stress(lam, STRAIN, MUSCLE),
                               atol=1e-15)


def test_series_reproduces_ogden_kirchhoff_function():
    """For a one-term Ogden law f(l) = (2 mu / alpha) (l^alpha - 1) exactly (up to a constant)."""
    mu, alpha = 0.1668e-3, -1.479
    strain = np.linspace(-0.95, 4.0, 4000)
    stress = ogden_T(1 + strain, mu, alpha)
    lam = np.array([0.3, 0.6, 0.9, 1.0, 1.3, 2.0])
    f = kirchhoff_function(lam, strain, stress)
    f_ogden = 2 * mu / alpha * (lam**alpha - 1.0)
    np.testing.assert_allclose(f - f[3], f_ogden, rtol=2e-3, atol=1e-9)


def test_muscle_table_matches_design_ogden_fit():
    """DESIGN section 5: the table is a one-term Ogden fit (within 5 %)."""
    lam = 1.0 + STRAIN[STRAIN != 0.0]
    np.testing.assert_allclose(MUSCLE[STRAIN != 0.0], ogden_T(lam), rtol=0.05)
    np.testing.assert_allclose(FAT, 0.4 * MUSCLE, rtol=0.01, atol=1e-7)


def test_table_lookup_and_tangent():
    tab = build_rubber_table(Curve(1, STRAIN, MUSCLE))
    for lam in (0.25, 0.7, 1.0, 1.4, 2.5):
        f_tab = table_lookup(tab.f, tab.ln0, tab.inv_dln, math.log(lam))
        f_ref = kirchhoff_function(np.array([lam]), STRAIN, MUSCLE)[0]
        # linear interpolation on a 1.2e-3 grid in ln(l); f has kinks (the curve is
        # piecewise linear), hence 1e-3
        assert f_tab == pytest.approx(f_ref, rel=1e-3, abs=1e-10)
    e0 = initial_modulus(STRAIN, MUSCLE)
    assert e0 == pytest.approx(0.5 * (0.61 + 0.419) * 1e-3)
    g1 = table_lookup(tab.g, tab.ln0, tab.inv_dln, 0.0)
    assert g1 == pytest.approx(e0 / 3.0, rel=0.02)
    # linear extrapolation outside the grid
    lo = table_lookup(tab.f, tab.ln0, tab.inv_dln, tab.ln0 - 0.1)
    slope = (tab.f[1] - tab.f[0]) * tab.inv_dln
    assert lo == pytest.approx(tab.f[0] - 0.1 * slope)


def test_design_tables_pass_the_stability_check():
    assert check_rubber_curve(Curve(1, STRAIN, MUSCLE)) == []
    assert check_rubber_curve(Curve(2, STRAIN, FAT)) == []


def test_hand_drawn_curve_that_stops_early_is_flagged():
    """Stops at +0.5 strain with a steep last segment, extrapolated linearly."""
    keep = STRAIN <= 0.5
    bad = MUSCLE[keep].copy()
    bad[-1] = 1.0e-3  # 0.3 -> 0.5: steep rise, continued by the linear extrapolation
    msgs = check_rubber_curve(Curve(77, STRAIN[keep], bad))
    assert len(msgs) == 1
    assert "curve 77" in msgs[0] and "Baker-Ericksen" in msgs[0]
    assert "0.2 <= l <= 0.59" in msgs[0]


def rubber_mat(lcid=3, **over):
    p = {"KM": 1.0, "MU": 0.1, "G": 0.0, "SIGF": 0.0, "SGL": 1.0, "SW": 1.0, "ST": 1.0,
         "LCID": lcid}
    p.update(over)
    return MaterialDef(9, "rubber181", 1e-6, p, keyword="MAT_SIMPLIFIED_RUBBER")


def test_rubber_params_warns_and_checks():
    keep = STRAIN <= 0.5
    bad = MUSCLE[keep].copy()
    bad[-1] = 1.0e-3
    with pytest.warns(UserWarning, match="curve 3"):
        rubber_params(rubber_mat(), {3: Curve(3, STRAIN[keep], bad)})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        p, tab = rubber_params(rubber_mat(), {3: Curve(3, STRAIN, MUSCLE)})
    assert p[P_BULK] == 1.0
    assert p[P_G0] == pytest.approx(tab.e0 / 3.0)
    with pytest.raises(DeckError, match="LCID 4"):
        rubber_params(rubber_mat(lcid=4), {3: Curve(3, STRAIN, MUSCLE)})
    with pytest.raises(DeckError, match="KM"):
        rubber_params(rubber_mat(KM=0.0), {3: Curve(3, STRAIN, MUSCLE)})


def test_deviatoric_stress_is_traceless_and_coaxial():
    tab = build_rubber_table(Curve(1, STRAIN, MUSCLE))
    rng = np.random.default_rng(0)
    for _ in range(5):
        vec = np.eye(3)
        f = np.eye(3) + rng.normal(scale=0.2, size=(3, 3))
        t = rubber_deviatoric(*f.ravel(), vec, tab.f, tab.g, tab.ln0, tab.inv_dln)
        tau = np.array([[t[0], t[3], t[5]], [t[3], t[1], t[4]], [t[5], t[4], t[2]]])
        b = f @ f.T
        assert abs(np.trace(tau)) < 1e-15
        np.testing.assert_allclose(tau @ b, b @ tau, atol=1e-15)  # isotropic function
        # principal values from the closed form
        mu_i, n = np.linalg.eigh(b)
        lnl = 0.5 * (np.log(mu_i) - np.log(mu_i).mean())
        fv = kirchhoff_function(np.exp(lnl), STRAIN, MUSCLE)
        np.testing.assert_allclose(np.sort(np.linalg.eigvalsh(tau)), np.sort(fv - fv.mean()),
                                   rtol=1e-4, atol=1e-10)


def test_friction_stress_is_limited():
    s = rubber_friction(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.01, -0.005, -0.005, 0.0, 0.0, 0.0,
                        1e-3, 2e-6)
    dev = np.array(s)
    eq = math.sqrt(1.5 * (dev[:3] @ dev[:3]) + 3 * (dev[3:] @ dev[3:]))
    assert eq == pytest.approx(2e-6)
    small = rubber_friction(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-6, -5e-7, -5e-7, 0.0, 0.0, 0.0,
                            1e-3, 2e-6)
    assert small[0] == pytest.approx(2e-9)
