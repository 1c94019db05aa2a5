"""*MAT_PLASTIC_KINEMATIC (LS-DYNA 003) for shells.

Bilinear elastic-plastic law with mixed hardening: tangent modulus ETAN gives
the plastic modulus ``H = E ETAN / (E - ETAN)``; BETA = 1 is purely isotropic
(sigma_y = SIGY + H eps_p), BETA = 0 purely kinematic (Prager back stress of
modulus H), 0 < BETA < 1 mixes them (isotropic BETA H, kinematic (1-BETA) H).
SRC, SRP: Cowper-Symonds strain-rate scaling of the yield stress,
``1 + (rate / SRC)^(1 / SRP)`` (SRC = 0: off). The failure strain (FS) of
LS-DYNA's card is not part of the model parameters and is not used.
The plane-stress return mapping is
:func:`hollowbody.materials.plane_stress_plasticity.plane_stress_return`.
"""

from __future__ import annotations

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.materials.plane_stress_material import (
    PlaneStressMaterial,
    elastic_constants,
    where,
)
from hollowbody.materials.plane_stress_plasticity import KIND_PLASTIC
from hollowbody.model.model import MaterialDef

KEYWORD = "MAT_PLASTIC_KINEMATIC"


def plastic_modulus(e_mod: float, etan: float) -> float:
    """H = E ETAN / (E - ETAN), GPa (ETAN < E)."""
    return e_mod * etan / (e_mod - etan)


def plastic_kinematic_shell(mat: MaterialDef) -> PlaneStressMaterial:
    """Plane-stress description of a *MAT_PLASTIC_KINEMATIC (DeckError when invalid)."""
    e_mod, nu, rho = elastic_constants(mat, KEYWORD)
    p = mat.params
    sigy = float(p.get("SIGY", 0.0))
    etan = float(p.get("ETAN", 0.0))
    beta = float(p.get("BETA", 0.0))
    src = float(p.get("SRC", 0.0))
    srp = float(p.get("SRP", 0.0))
    w = where(mat, KEYWORD)
    if not sigy > 0.0:
        raise DeckError(f"material {mat.mid}: SIGY must be > 0 (got {sigy})", *w)
    if not 0.0 <= etan < e_mod:
        raise DeckError(f"material {mat.mid}: ETAN must be in [0, E) (got {etan})", *w)
    if not 0.0 <= beta <= 1.0:
        raise DeckError(f"material {mat.mid}: BETA must be in [0, 1] (got {beta})", *w)
    if src > 0.0 and not srp > 0.0:
        raise DeckError(f"material {mat.mid}: SRP must be > 0 when SRC is given", *w)
    h = plastic_modulus(e_mod, etan)
    return PlaneStressMaterial(
        kind=KIND_PLASTIC, e_mod=e_mod, nu=nu, density=rho, hk=(1.0 - beta) * h,
        hard_x=np.array([0.0, 1.0]), hard_y=np.array([sigy, sigy + beta * h]),
        cs_c=max(src, 0.0), cs_p=srp if srp > 0.0 else 1.0, label=f"{KEYWORD} {mat.mid}")
