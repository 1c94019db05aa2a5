"""*MAT_ELASTIC (LS-DYNA 001): isotropic hypoelastic solid.

Objective stress rate with the Hughes-Winget incremental rotation ``Q``
(second-order accurate Jaumann rate, exactly orthogonal)::

    sigma^{n+1} = Q sigma^n Q^T + lambda tr(de) I + 2 mu de,   de = dt D_mid

Wave speed ``c = sqrt((K + 4G/3) / rho)``. Units: GPa, kg/mm^3, mm/ms.
Parameters are packed into a float64 vector (indices ``P_*``) so the element
kernels take plain arrays.

Solid law interface (see :mod:`hollowbody.materials.solid_laws`):
:func:`solid_params`, :func:`solid_wave_speed0`, :func:`solid_hourglass_moduli`,
:func:`solid_history`, :func:`solid_erode` and the kernel :func:`solid_update`. No history.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from hollowbody.errors import DeckError
from hollowbody.materials.tensor3 import rotate_sym
from hollowbody.model.model import Curve, MaterialDef

P_LAMBDA, P_MU, P_BULK, P_RHO, P_C = range(5)
N_PARAMS = 5

#: Material kind of the law (``MaterialDef.kind``) and its keyword.
KIND = "elastic"
KEYWORD = "MAT_ELASTIC"
#: Names of the per-element history arrays (:func:`solid_history`): none.
HISTORY_FIELDS: tuple[str, ...] = ()


def elastic_params(mat: MaterialDef) -> np.ndarray:
    """Packed parameters (N_PARAMS,) float64 of a *MAT_ELASTIC definition.

    Raises DeckError for E <= 0, PR outside (-1, 0.5) or density <= 0.
    """
    e_mod = float(mat.params.get("E", 0.0))
    nu = float(mat.params.get("PR", 0.0))
    rho = float(mat.density)
    where = (mat.source.file, mat.source.line, mat.keyword or "MAT_ELASTIC")
    if e_mod <= 0.0:
        raise DeckError(f"material {mat.mid}: E must be > 0 (got {e_mod})", *where)
    if not -1.0 < nu < 0.5:
        raise DeckError(f"material {mat.mid}: PR must be in (-1, 0.5) (got {nu})", *where)
    if rho <= 0.0:
        raise DeckError(f"material {mat.mid}: density must be > 0 (got {rho})", *where)
    mu = e_mod / (2.0 * (1.0 + nu))
    lam = e_mod * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    bulk = e_mod / (3.0 * (1.0 - 2.0 * nu))
    p = np.zeros(N_PARAMS)
    p[P_LAMBDA] = lam
    p[P_MU] = mu
    p[P_BULK] = bulk
    p[P_RHO] = rho
    p[P_C] = math.sqrt((bulk + 4.0 * mu / 3.0) / rho)
    return p


@njit(cache=True, inline="always", fastmath={"contract"})
def elastic_update(s0, s1, s2, s3, s4, s5, d0, d1, d2, d3, d4, d5, lam, mu):
    """Kernel: new stress from the rotated old stress and the strain increment.

    s*: rotated old Cauchy stress (GPa, Voigt xx yy zz xy yz zx); d*: strain
    increment dt*D (tensor components, i.e. d3 = dt*D_xy); lam, mu: Lame
    constants (GPa). Returns the six new stress components.
    """
    tr = lam * (d0 + d1 + d2)
    m2 = 2.0 * mu
    return (s0 + tr + m2 * d0, s1 + tr + m2 * d1, s2 + tr + m2 * d2,
            s3 + m2 * d3, s4 + m2 * d4, s5 + m2 * d5)


def elastic_stress_update(stress: np.ndarray, de: np.ndarray, params: np.ndarray) -> np.ndarray:
    """Vectorised small-increment update (no rotation), for tests and tools.

    stress: (e, 6) GPa; de: (e, 6) strain increments (tensor shear
    components); params: packed parameters. Returns the new (e, 6) stress.
    """
    lam, mu = params[P_LAMBDA], params[P_MU]
    out = stress + 2.0 * mu * de
    out[:, :3] += lam * de[:, :3].sum(axis=1, keepdims=True)
    return out


# -- solid law interface --------------------------------------------------------------
def solid_params(mat: MaterialDef, curves: dict[int, Curve]) -> tuple[np.ndarray, ...]:
    """Parameter tuple of the solid kernel: ``(elastic_params(mat),)`` (DeckError if invalid)."""
    return (elastic_params(mat),)


def solid_wave_speed0(params: tuple[np.ndarray, ...]) -> float:
    """Initial dilatational wave speed (mm/ms) sqrt((K + 4G/3) / rho)."""
    return float(params[0][P_C])


def solid_hourglass_moduli(params: tuple[np.ndarray, ...]) -> tuple[float, float]:
    """Shear and bulk moduli (GPa) of the assumed-strain hourglass stiffness (IHQ 6),
    from the card's E and PR."""
    mp = params[0]
    return float(mp[P_MU]), float(mp[P_BULK])


def solid_history(params: tuple[np.ndarray, ...], n_elem: int) -> dict[str, np.ndarray]:
    """Per-element history arrays by name (:data:`HISTORY_FIELDS`): none."""
    return {}


def solid_erode(history: tuple[np.ndarray, ...], idx: np.ndarray) -> None:
    """Reset the history of eroded elements ``idx``: nothing to reset."""


@njit(cache=True, inline="always", fastmath={"contract"})
def solid_constants(params):
    """Kernel: the scalars of ``params`` the update uses, read once per call.

    Returns (lambda, mu GPa, rho0 kg/mm^3, c mm/ms, lambda + 2 mu GPa).
    """
    mp = params[0]
    lam = mp[P_LAMBDA]
    mu = mp[P_MU]
    return lam, mu, mp[P_RHO], mp[P_C], lam + 2.0 * mu


@njit(cache=True, inline="always", fastmath={"contract"})
def solid_update(e, dt, vol, vol0, l, xe, b0, lm, rot, work, stress, consts, params, history):
    """Kernel: new stress of element ``e`` (hypoelastic, Hughes-Winget rotation).

    dt ms; vol, vol0 current / initial volume mm^3; l = vol^(1/3) mm; xe (8, 3)
    mm nodal positions relative to node 1; b0 (e, 8, 3) reference gradients;
    lm (3, 3) 1/ms mid-step velocity gradient; rot (3, 3) incremental rotation;
    work (3, 3) scratch; stress (e, 6) GPa old stress (read only); consts from
    :func:`solid_constants`; params ``(mp,)``; history ``()``. Returns (s0..s5
    GPa new stress, rho kg/mm^3 current density, modulus GPa for the hourglass
    stiffness, c mm/ms wave speed).
    """
    lam, mu, rho0, c, modulus = consts
    d0 = dt * lm[0, 0]
    d1 = dt * lm[1, 1]
    d2 = dt * lm[2, 2]
    d3 = 0.5 * dt * (lm[0, 1] + lm[1, 0])
    d4 = 0.5 * dt * (lm[1, 2] + lm[2, 1])
    d5 = 0.5 * dt * (lm[2, 0] + lm[0, 2])
    r0, r1, r2, r3, r4, r5 = rotate_sym(rot, stress[e, 0], stress[e, 1], stress[e, 2],
                                        stress[e, 3], stress[e, 4], stress[e, 5])
    n0, n1, n2, n3, n4, n5 = elastic_update(r0, r1, r2, r3, r4, r5,
                                            d0, d1, d2, d3, d4, d5, lam, mu)
    rho = rho0 * vol0 / vol
    return n0, n1, n2, n3, n4, n5, rho, modulus, c
