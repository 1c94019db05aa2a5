"""Shell (plane-stress) materials: one packed description for the shell kernels.

:class:`PlaneStressMaterial` holds what the Belytschko-Tsay kernels need of a
material: a packed float64 parameter vector (indices ``P_*`` of
:mod:`hollowbody.materials.plane_stress_plasticity`), the isotropic hardening
table (effective plastic strain -> yield stress, GPa) and an optional strain
rate curve. :func:`shell_material` builds it from a
:class:`~hollowbody.model.model.MaterialDef` of kind ``elastic``,
``plastic003`` or ``pwl024`` (the laws live in ``shell_elastic``,
``mat003_plastic_kinematic`` and ``mat024_piecewise_linear``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.materials.plane_stress_plasticity import (
    KIND_ELASTIC,
    N_PARAMS,
    P_C,
    P_CS_C,
    P_CS_P,
    P_E,
    P_FAIL,
    P_G,
    P_HK,
    P_KIND,
    P_NU,
    P_RATE_CURVE,
    P_RHO,
)
from hollowbody.model.model import Curve, MaterialDef

#: Material kinds that shells can run.
SHELL_MATERIAL_KINDS = ("elastic", "plastic003", "pwl024")


@dataclass
class PlaneStressMaterial:
    """A shell material, packed for the kernels.

    kind: 0 elastic, 1 elastic-plastic; e_mod (GPa), nu, density (kg/mm^3);
    hk: kinematic hardening modulus (GPa); hard_x / hard_y: (m,) float64
    isotropic hardening table eps_p -> sigma_y (GPa), linearly extrapolated;
    cs_c (1/ms), cs_p: Cowper-Symonds constants (cs_c = 0: off); rate_x /
    rate_y: yield scale factor vs strain rate (1/ms) curve (empty: off); fail:
    effective plastic strain at failure (0: off).
    """

    kind: int
    e_mod: float
    nu: float
    density: float
    hk: float = 0.0
    hard_x: np.ndarray = field(default_factory=lambda: np.zeros(1))
    hard_y: np.ndarray = field(default_factory=lambda: np.full(1, np.inf))
    cs_c: float = 0.0
    cs_p: float = 1.0
    rate_x: np.ndarray = field(default_factory=lambda: np.zeros(1))
    rate_y: np.ndarray = field(default_factory=lambda: np.ones(1))
    fail: float = 0.0
    label: str = ""

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)), GPa."""
        return 0.5 * self.e_mod / (1.0 + self.nu)

    @property
    def wave_speed(self) -> float:
        """Plane-stress wave speed c = sqrt(E / (rho (1 - nu^2))), mm/ms."""
        return math.sqrt(self.e_mod / (self.density * (1.0 - self.nu ** 2)))

    def params(self) -> np.ndarray:
        """Packed parameter vector (N_PARAMS,) float64 for the kernels."""
        p = np.zeros(N_PARAMS)
        p[P_KIND] = self.kind
        p[P_E] = self.e_mod
        p[P_NU] = self.nu
        p[P_G] = self.shear_modulus
        p[P_HK] = self.hk
        p[P_CS_C] = self.cs_c
        p[P_CS_P] = self.cs_p if self.cs_p > 0.0 else 1.0
        p[P_FAIL] = self.fail
        p[P_RATE_CURVE] = 1.0 if (self.cs_c <= 0.0 and self.rate_x.size > 1) else 0.0
        p[P_C] = self.wave_speed
        p[P_RHO] = self.density
        return p

    def yield_stress(self, eps_p: float | np.ndarray) -> np.ndarray:
        """Static yield stress (GPa) at effective plastic strain(s), as the kernels see it."""
        x = np.atleast_1d(np.asarray(eps_p, dtype=np.float64))
        hx, hy = self.hard_x, self.hard_y
        if hx.size == 1:
            return np.full(x.shape, hy[0])
        s = (hy[-1] - hy[-2]) / (hx[-1] - hx[-2])
        out = np.interp(x, hx, hy)
        beyond = x > hx[-1]
        out[beyond] = hy[-1] + s * (x[beyond] - hx[-1])
        return out


def where(mat: MaterialDef, default_keyword: str) -> tuple[str, int, str]:
    """(file, line, keyword) of a material, for DeckError."""
    return mat.source.file, mat.source.line, mat.keyword or default_keyword


def elastic_constants(mat: MaterialDef, default_keyword: str) -> tuple[float, float, float]:
    """(E GPa, PR, density kg/mm^3) of ``mat``, checked (DeckError when invalid)."""
    e_mod = float(mat.params.get("E", 0.0))
    nu = float(mat.params.get("PR", 0.0))
    rho = float(mat.density)
    w = where(mat, default_keyword)
    if not e_mod > 0.0:
        raise DeckError(f"material {mat.mid}: E must be > 0 (got {e_mod})", *w)
    if not -1.0 < nu < 0.5:
        raise DeckError(f"material {mat.mid}: PR must be in (-1, 0.5) (got {nu})", *w)
    if not rho > 0.0:
        raise DeckError(f"material {mat.mid}: density must be > 0 (got {rho})", *w)
    return e_mod, nu, rho


def curve_arrays(lcid: int, curves: dict[int, Curve], mat: MaterialDef, what: str,
                 default_keyword: str) -> tuple[np.ndarray, np.ndarray]:
    """(x, y) float64 copies of curve ``lcid`` (DeckError when missing or not increasing)."""
    w = where(mat, default_keyword)
    if lcid not in curves:
        raise DeckError(f"material {mat.mid}: {what} curve {lcid} is not defined", *w)
    c = curves[lcid]
    x = np.asarray(c.x, dtype=np.float64).copy()
    y = np.asarray(c.y, dtype=np.float64).copy()
    if x.size < 1 or x.size != y.size or np.any(np.diff(x) <= 0.0):
        raise DeckError(f"material {mat.mid}: {what} curve {lcid} needs strictly "
                        "increasing abscissae", *w)
    return x, y


def shell_material(mat: MaterialDef, curves: dict[int, Curve] | None = None
                   ) -> PlaneStressMaterial:
    """The plane-stress description of ``mat`` for shells (DeckError if unsupported)."""
    from hollowbody.materials.mat003_plastic_kinematic import plastic_kinematic_shell
    from hollowbody.materials.mat024_piecewise_linear import piecewise_linear_shell
    from hollowbody.materials.shell_elastic import elastic_shell

    curves = curves or {}
    if mat.kind == "elastic":
        return elastic_shell(mat)
    if mat.kind == "plastic003":
        return plastic_kinematic_shell(mat)
    if mat.kind == "pwl024":
        return piecewise_linear_shell(mat, curves)
    raise DeckError(f"material {mat.mid} ({mat.keyword or mat.kind}) is not available for "
                    f"shell elements (available: {', '.join(SHELL_MATERIAL_KINDS)})",
                    *where(mat, mat.kind))


__all__ = ["KIND_ELASTIC", "PlaneStressMaterial", "SHELL_MATERIAL_KINDS", "shell_material"]
