"""Plane-stress J2 plasticity with mixed linear kinematic / tabulated isotropic hardening.

The return mapping of Simo & Taylor (1986) in the plane-stress projected space
(Simo & Hughes, *Computational Inelasticity*, section 3.4), solved for the
consistency parameter by a safeguarded Newton iteration. sigma_zz is zero by
construction (the plane-stress constraint is built into the projected yield
function, there is no "secant" shortcut and no outer iteration).

Stress-like vectors are in-plane Voigt ``(xx, yy, xy)`` in GPa; strain
increments carry the engineering shear ``gamma_xy``. With the orthonormal modes

    m1 = (s_xx + s_yy)/sqrt(2),  m2 = (s_yy - s_xx)/sqrt(2),  m3 = sqrt(2) s_xy

the plane-stress elasticity is diagonal (E/(1-nu), 2G, 2G) and the von Mises
function is ``f^2 = m1^2/3 + m2^2 + m3^2 = (2/3) sigma_vm^2`` (P = diag(1/3, 1, 1)).

Kinematic hardening (Prager, modulus ``hk``) acts on the 3-D deviatoric back
stress alpha; it enters the plane-stress yield function through the
*effective in-plane back stress* ``abar = (a_xx - a_zz, a_yy - a_zz, a_xy)``
(the deviator of sigma - alpha equals that of (sigma - abar) with zero zz),
whose evolution ``d abar = (2/3) hk dgamma xi`` is exact, so a uniaxial test
gives sigma = sigma_y + hk eps_p as in 3-D. Each mode then returns as
``xi_i = xi_i^trial / (1 + dgamma a_i)`` with
``a_1 = E/(3(1-nu)) + 2 hk/3``, ``a_2 = a_3 = 2G + 2 hk/3``.

Isotropic hardening: the yield stress is a piecewise-linear table
``sigma_y(eps_p)`` (bilinear laws are a 2-point table), extrapolated linearly
with its last slope (LS-DYNA's MAT_024 convention), scaled by a strain-rate
factor computed by the caller (Cowper-Symonds or a curve).

Everything here is ``@njit`` and allocation-free: kernels call it per point.

Shell law ``KIND_PLASTIC`` (*MAT_PLASTIC_KINEMATIC and
*MAT_PIECEWISE_LINEAR_PLASTICITY; see :mod:`hollowbody.materials.shell_laws`).
"""

from __future__ import annotations

import math

from numba import njit

#: LLVM fast-math flags of the shell kernels: reassociation, reciprocals, contraction
#: (FMA) and approximate functions, but no "no-NaN / no-Inf" assumptions (dead
#: elements carry an infinite time step; NaNs must propagate to the loop's check).
FASTMATH = {"nsz", "arcp", "contract", "afn", "reassoc"}

SQ2 = math.sqrt(2.0)
SQ23 = math.sqrt(2.0 / 3.0)

#: Indices into the packed material parameter vector (float64) of a shell group.
P_KIND = 0  # 0 elastic, 1 elastic-plastic
P_E = 1  # Young's modulus, GPa
P_NU = 2  # Poisson's ratio
P_G = 3  # shear modulus, GPa
P_HK = 4  # kinematic hardening modulus, GPa
P_CS_C = 5  # Cowper-Symonds C, 1/ms (0 = off)
P_CS_P = 6  # Cowper-Symonds P
P_FAIL = 7  # effective plastic strain at failure (0 = off)
P_RATE_CURVE = 8  # 1 when the yield scale factor is a curve of strain rate (LCSR)
P_C = 9  # plane-stress wave speed sqrt(E / (rho (1 - nu^2))), mm/ms
P_RHO = 10  # density, kg/mm^3
N_PARAMS = 11

KIND_ELASTIC = 0
KIND_PLASTIC = 1
#: Shell law kind of this module (``PlaneStressMaterial.kind``).
KIND = KIND_PLASTIC

#: Relative tolerance of the consistency condition (also the elastic check).
YIELD_TOL = 1.0e-11
_MAX_IT = 60


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def table_eval(x: float, cx, cy) -> tuple[float, float]:
    """Piecewise-linear table value and slope at ``x``.

    cx, cy: (m,) float64, cx strictly increasing. Below cx[0]: cy[0] with slope 0;
    beyond cx[-1]: linear extrapolation with the last segment's slope; m == 1:
    constant.
    """
    m = cx.shape[0]
    if m == 1:
        return cy[0], 0.0
    if x <= cx[0]:
        return cy[0], 0.0
    if x >= cx[m - 1]:
        s = (cy[m - 1] - cy[m - 2]) / (cx[m - 1] - cx[m - 2])
        return cy[m - 1] + s * (x - cx[m - 1]), s
    lo = 0
    hi = m - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if cx[mid] <= x:
            lo = mid
        else:
            hi = mid
    s = (cy[hi] - cy[lo]) / (cx[hi] - cx[lo])
    return cy[lo] + s * (x - cx[lo]), s


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def effective_strain_rate(dxx: float, dyy: float, gxy: float) -> float:
    """Von Mises equivalent of an in-plane strain rate (1/ms), d_zz = -(d_xx + d_yy).

    gxy is the engineering shear rate. Used for strain-rate scaling of the yield
    stress (total strain rate, LS-DYNA's VP = 0).
    """
    dzz = -(dxx + dyy)
    dxy = 0.5 * gxy
    return math.sqrt((2.0 / 3.0) * (dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * dxy * dxy))


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def elastic_plane_stress(sxx: float, syy: float, sxy: float, dexx: float, deyy: float,
                         dgxy: float, e: float, nu: float) -> tuple[float, float, float]:
    """Hypoelastic plane-stress update sigma + C d_eps (GPa); d_eps with engineering shear."""
    c11 = e / (1.0 - nu * nu)
    c12 = nu * c11
    g = 0.5 * e / (1.0 + nu)
    return sxx + c11 * dexx + c12 * deyy, syy + c12 * dexx + c11 * deyy, sxy + g * dgxy


@njit(cache=True, error_model="numpy", fastmath=FASTMATH)
def plane_stress_return(sxx: float, syy: float, sxy: float, axx: float, ayy: float,
                        axy: float, ep: float, dexx: float, deyy: float, dgxy: float,
                        e: float, nu: float, hk: float, cx, cy, rate_factor: float):
    """One plane-stress elastic-plastic update (backward Euler, Simo-Taylor projection).

    Inputs: old stress (GPa), old effective in-plane back stress (GPa), old
    effective plastic strain ``ep``, strain increment (engineering shear),
    E (GPa), nu, kinematic modulus hk (GPa), isotropic hardening table
    (cx: eps_p, cy: sigma_y in GPa), strain-rate factor (>= 1) on sigma_y.

    Returns ``(sxx, syy, sxy, axx, ayy, axy, ep, dsum_p)``: new stress, new back
    stress, new effective plastic strain and the plastic in-plane volumetric
    increment ``d eps_p_xx + d eps_p_yy`` (= -d eps_p_zz, plastic incompressibility).
    """
    c11 = e / (1.0 - nu * nu)
    c12 = nu * c11
    g2 = e / (1.0 + nu)  # 2G
    txx = sxx + c11 * dexx + c12 * deyy
    tyy = syy + c12 * dexx + c11 * deyy
    txy = sxy + 0.5 * g2 * dgxy
    xxx = txx - axx
    xyy = tyy - ayy
    xxy = txy - axy
    x1 = (xxx + xyy) / SQ2
    x2 = (xyy - xxx) / SQ2
    x3 = SQ2 * xxy
    b1 = x1 * x1 / 3.0
    b2 = x2 * x2 + x3 * x3
    f2 = b1 + b2
    sy, hp = table_eval(ep, cx, cy)
    sy *= rate_factor
    if 1.5 * f2 <= sy * sy * (1.0 + YIELD_TOL):
        return txx, tyy, txy, axx, ayy, axy, ep, 0.0
    a1 = e / (3.0 * (1.0 - nu)) + (2.0 / 3.0) * hk
    a2 = g2 + (2.0 / 3.0) * hk
    # Consistency f(dg) = sqrt(2/3) sigma_y(ep + sqrt(2/3) dg f(dg)), solved as
    # psi(dg) = sqrt(2/3) sigma_y / f - 1 = 0: f ~ f_trial / (1 + a dg) makes psi nearly
    # linear in dg (exactly so for a1 = a2 without hardening), so Newton needs 1-3
    # steps; psi increases with dg, a bracket [lo, hi] guards the steps.
    dg = 0.0
    lo = 0.0
    hi = -1.0  # no upper bracket yet
    for _ in range(_MAX_IT):
        d1 = 1.0 + a1 * dg
        d2 = 1.0 + a2 * dg
        f2 = b1 / (d1 * d1) + b2 / (d2 * d2)
        f = math.sqrt(f2)
        sy, hp = table_eval(ep + SQ23 * dg * f, cx, cy)
        sy *= rate_factor
        hp *= rate_factor
        psi = SQ23 * sy / f - 1.0
        if abs(psi) <= YIELD_TOL:
            break
        if psi < 0.0:
            lo = dg
        else:
            hi = dg
        df = -(a1 * b1 / (d1 * d1 * d1) + a2 * b2 / (d2 * d2 * d2)) / f
        dpsi = SQ23 * (hp * SQ23 * (f + dg * df) * f - sy * df) / f2
        dgn = dg - psi / dpsi if dpsi > 0.0 else -1.0
        if dgn <= lo or (hi >= 0.0 and dgn >= hi):
            dgn = 0.5 * (lo + hi) if hi >= 0.0 else 2.0 * lo + 1.0e-12
        if hi >= 0.0 and hi - lo <= 1.0e-15 * hi:
            dg = dgn
            break
        dg = dgn
    d1 = 1.0 + a1 * dg
    d2 = 1.0 + a2 * dg
    y1 = x1 / d1
    y2 = x2 / d2
    y3 = x3 / d2
    f = math.sqrt(y1 * y1 / 3.0 + y2 * y2 + y3 * y3)
    yxx = (y1 - y2) / SQ2
    yyy = (y1 + y2) / SQ2
    yxy = y3 / SQ2
    ck = (2.0 / 3.0) * hk * dg
    axx += ck * yxx
    ayy += ck * yyy
    axy += ck * yxy
    return (yxx + axx, yyy + ayy, yxy + axy, axx, ayy, axy, ep + SQ23 * dg * f,
            SQ2 * dg * y1 / 3.0)


@njit(cache=True, error_model="numpy", fastmath=FASTMATH)
def rate_factor(mp, rx, ry, dxx: float, dyy: float, gxy: float) -> float:
    """Yield-stress scale factor for the strain rate of an in-plane rate (1/ms).

    Cowper-Symonds ``1 + (rate / C)^(1/P)`` when ``mp[P_CS_C] > 0``; the curve
    (rx: strain rate 1/ms, ry: factor) when ``mp[P_RATE_CURVE] > 0``; else 1.
    """
    if mp[P_CS_C] > 0.0:
        r = effective_strain_rate(dxx, dyy, gxy)
        if r <= 0.0:
            return 1.0
        return 1.0 + (r / mp[P_CS_C]) ** (1.0 / mp[P_CS_P])
    if mp[P_RATE_CURVE] > 0.0:
        r = effective_strain_rate(dxx, dyy, gxy)
        v, _ = table_eval(r, rx, ry)
        return v
    return 1.0

