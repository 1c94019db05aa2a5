"""J2 plasticity of a beam stress point: axial stress with two transverse shears.

A stress point of an integrated beam carries ``(sigma, tau_s, tau_t)`` (GPa):
the axial stress and the shear stresses on the section in the s and t
directions; the other stresses are zero (the beam assumption). The elastic law
is ``dsigma = E deps``, ``dtau = G_s dgamma`` (G_s: the shear modulus times the
section's shear factor SHRF) and the von Mises function of this state is

    f = sqrt(xi_0^2 + 3 xi_s^2 + 3 xi_t^2) - sigma_y(eps_p),   xi = stress - back stress.

Associated flow ``deps_p = dlam df/dsigma`` with ``eps_p += dlam`` (the
effective plastic strain of the uniaxial limit), Prager kinematic hardening of
modulus ``hk`` (``dalpha_0 = hk dlam n_0``, ``dalpha_s = (hk / 3) dlam n_s`` so
that uniaxial and pure-shear tests give sigma_y + hk eps_p) and a tabulated
isotropic yield stress (:func:`~hollowbody.materials.plane_stress_plasticity.table_eval`,
the shells' hardening tables: MAT_003 bilinear, MAT_024 curve or bilinear),
times a strain-rate factor the caller computes (Cowper-Symonds or a curve of
the point's effective strain rate ``sqrt(deps^2 + (dgam_s^2 + dgam_t^2) / 3) / dt``).
The return is exact for this form: each component scales back as
``xi_i = xi_i^trial / (1 + a_i dlam / sigma_y)`` with ``a_0 = E + hk``,
``a_s = a_t = 3 G_s + hk`` and the scalar consistency equation is solved by a
safeguarded Newton iteration (closed form when the shears are zero).
Allocation-free ``@njit``: the beam kernels call it per point.
"""

from __future__ import annotations

import math

from numba import njit

from hollowbody.materials.plane_stress_plasticity import table_eval

_MAX_IT = 50
_TOL = 1.0e-12


@njit(cache=True, error_model="numpy")
def _yield(eps_p: float, hard_x, hard_y, scale: float) -> tuple[float, float]:
    """Yield stress (GPa) and its slope at eps_p, times the strain-rate factor."""
    sy, h = table_eval(eps_p, hard_x, hard_y)
    return scale * sy, scale * h


@njit(cache=True, error_model="numpy")
def _residual(dlam: float, x0: float, x1: float, x2: float, a0: float, a1: float,
              eps_p: float, hard_x, hard_y, scale: float) -> tuple[float, float]:
    """g(dlam) = |xi(dlam)| - sigma_y(eps_p + dlam) and dg/ddlam."""
    sy, h = _yield(eps_p + dlam, hard_x, hard_y, scale)
    d0 = 1.0 + a0 * dlam / sy
    d1 = 1.0 + a1 * dlam / sy
    p0 = x0 / d0
    p1 = x1 / d1
    p2 = x2 / d1
    q = math.sqrt(p0 * p0 + 3.0 * (p1 * p1 + p2 * p2))
    dd0 = a0 / sy - a0 * dlam * h / (sy * sy)
    dd1 = a1 / sy - a1 * dlam * h / (sy * sy)
    dq = -(p0 * p0 * dd0 / d0 + 3.0 * (p1 * p1 + p2 * p2) * dd1 / d1) / max(q, 1e-300)
    return q - sy, dq - h


@njit(cache=True, error_model="numpy")
def beam_point_update(sig, back, i: int, k: int, eps_p, deps: float, dgs: float,
                      dgt: float, e_mod: float, g_s: float, hk: float, plastic: bool,
                      hard_x, hard_y, scale: float = 1.0) -> float:
    """Update stress point (i, k) in place; returns the plastic strain increment dlam.

    sig, back: (e, p, 3) GPa (sigma, tau_s, tau_t); eps_p: (e, p) effective
    plastic strain; deps, dgs, dgt: axial strain and engineering shear strain
    increments; e_mod, g_s (GPa): Young's modulus and SHRF * G; hk (GPa):
    kinematic modulus; plastic: False for an elastic law; hard_x, hard_y: (m,)
    isotropic hardening table (effective plastic strain -> yield stress GPa);
    scale: strain-rate factor of the yield stress (1: none).
    """
    s0 = sig[i, k, 0] + e_mod * deps
    s1 = sig[i, k, 1] + g_s * dgs
    s2 = sig[i, k, 2] + g_s * dgt
    if not plastic:
        sig[i, k, 0] = s0
        sig[i, k, 1] = s1
        sig[i, k, 2] = s2
        return 0.0
    b0 = back[i, k, 0]
    b1 = back[i, k, 1]
    b2 = back[i, k, 2]
    x0 = s0 - b0
    x1 = s1 - b1
    x2 = s2 - b2
    ep = eps_p[i, k]
    sy0, h0 = _yield(ep, hard_x, hard_y, scale)
    q = math.sqrt(x0 * x0 + 3.0 * (x1 * x1 + x2 * x2))
    if q <= sy0 * (1.0 + _TOL):
        sig[i, k, 0] = s0
        sig[i, k, 1] = s1
        sig[i, k, 2] = s2
        return 0.0
    a0 = e_mod + hk
    a1 = 3.0 * g_s + hk
    if x1 == 0.0 and x2 == 0.0:
        # uniaxial: closed form on the current hardening segment, then Newton
        dlam = (q - sy0) / (a0 + h0)
    else:
        dlam = (q - sy0) / (max(a0, a1) + h0)
    lo = 0.0
    hi = q / min(e_mod, 3.0 * g_s) + 1.0
    for _ in range(_MAX_IT):
        g, dg = _residual(dlam, x0, x1, x2, a0, a1, ep, hard_x, hard_y, scale)
        sy, _h = _yield(ep + dlam, hard_x, hard_y, scale)
        if abs(g) <= _TOL * sy:
            break
        if g > 0.0:
            lo = dlam
        else:
            hi = dlam
        step = dlam - g / dg if dg < 0.0 else 0.5 * (lo + hi)
        dlam = step if lo < step < hi else 0.5 * (lo + hi)
    sy, _h = _yield(ep + dlam, hard_x, hard_y, scale)
    d0 = 1.0 + a0 * dlam / sy
    d1 = 1.0 + a1 * dlam / sy
    x0 /= d0
    x1 /= d1
    x2 /= d1
    back[i, k, 0] = b0 + hk * dlam * x0 / sy
    back[i, k, 1] = b1 + hk * dlam * x1 / sy
    back[i, k, 2] = b2 + hk * dlam * x2 / sy
    sig[i, k, 0] = x0 + back[i, k, 0]
    sig[i, k, 1] = x1 + back[i, k, 1]
    sig[i, k, 2] = x2 + back[i, k, 2]
    eps_p[i, k] = ep + dlam
    return dlam
