"""*MAT_PIECEWISE_LINEAR_PLASTICITY (LS-DYNA 024) for shells.

Isotropic hardening with the yield stress either bilinear (SIGY and ETAN:
``sigma_y = SIGY + E ETAN / (E - ETAN) eps_p``) or tabulated (LCSS > 0: a
curve of yield stress, GPa, vs effective plastic strain, starting at
eps_p = 0; SIGY and ETAN are then ignored, as in LS-DYNA). The table is
extrapolated linearly with its last slope. Strain-rate scaling of the yield
stress: Cowper-Symonds (C > 0 and P: ``1 + (rate / C)^(1/P)``), else a curve
LCSR of scale factor vs strain rate (1/ms); the rate is the von Mises
equivalent of the total strain rate (LS-DYNA VP = 0). LCSS pointing to a
table (rate-dependent curves) is not supported. FAIL > 0: an integration
point whose effective plastic strain reaches FAIL carries no stress; the
shell is deleted when all its points have failed. TDEL is not used.
"""

from __future__ import annotations

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.materials.mat003_plastic_kinematic import plastic_modulus
from hollowbody.materials.plane_stress_material import (
    PlaneStressMaterial,
    curve_arrays,
    elastic_constants,
    where,
)
from hollowbody.materials.plane_stress_plasticity import KIND_PLASTIC
from hollowbody.model.model import Curve, MaterialDef

KEYWORD = "MAT_PIECEWISE_LINEAR_PLASTICITY"


def piecewise_linear_shell(mat: MaterialDef, curves: dict[int, Curve]) -> PlaneStressMaterial:
    """Plane-stress description of a *MAT_PIECEWISE_LINEAR_PLASTICITY (DeckError if invalid)."""
    e_mod, nu, rho = elastic_constants(mat, KEYWORD)
    p = mat.params
    w = where(mat, KEYWORD)
    lcss = int(round(float(p.get("LCSS", 0.0))))
    lcsr = int(round(float(p.get("LCSR", 0.0))))
    c = float(p.get("C", 0.0))
    pp = float(p.get("P", 0.0))
    fail = float(p.get("FAIL", 0.0))
    if lcss > 0:
        hx, hy = curve_arrays(lcss, curves, mat, "LCSS", KEYWORD)
        if hx[0] < 0.0 or np.any(hy <= 0.0):
            raise DeckError(f"material {mat.mid}: LCSS curve {lcss} needs eps_p >= 0 and "
                            "yield stresses > 0", *w)
        if hx[0] > 0.0:  # start the table at eps_p = 0 with its first yield stress
            hx = np.concatenate(([0.0], hx))
            hy = np.concatenate(([hy[0]], hy))
    else:
        sigy = float(p.get("SIGY", 0.0))
        etan = float(p.get("ETAN", 0.0))
        if not sigy > 0.0:
            raise DeckError(f"material {mat.mid}: SIGY must be > 0 (got {sigy}) "
                            "when LCSS is not given", *w)
        if not 0.0 <= etan < e_mod:
            raise DeckError(f"material {mat.mid}: ETAN must be in [0, E) (got {etan})", *w)
        hx = np.array([0.0, 1.0])
        hy = np.array([sigy, sigy + plastic_modulus(e_mod, etan)])
    rate_x, rate_y = np.zeros(1), np.ones(1)
    if c > 0.0:
        if not pp > 0.0:
            raise DeckError(f"material {mat.mid}: P must be > 0 when C is given", *w)
    elif lcsr > 0:
        rate_x, rate_y = curve_arrays(lcsr, curves, mat, "LCSR", KEYWORD)
        if rate_x.size < 2:
            raise DeckError(f"material {mat.mid}: LCSR curve {lcsr} needs 2 points", *w)
    return PlaneStressMaterial(
        kind=KIND_PLASTIC, e_mod=e_mod, nu=nu, density=rho, hk=0.0, hard_x=hx, hard_y=hy,
        cs_c=max(c, 0.0), cs_p=pp if pp > 0.0 else 1.0, rate_x=rate_x, rate_y=rate_y,
        fail=max(fail, 0.0), label=f"{KEYWORD} {mat.mid}")
