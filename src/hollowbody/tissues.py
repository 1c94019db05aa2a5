"""Default soft-tissue properties (DESIGN.md section 5): the block test, the limb and
hollowize use them, so they sit below all three.

The paper's solid-tissue curves (its Fig. A1, A2) are not published as
numbers. Our defaults are a one-term Ogden law fitted to representative
high-rate compression data of skeletal muscle, tabulated as MAT_181 curves
(engineering stress vs engineering strain, compression negative):

    T(l) = (2 mu / alpha) (l^(alpha-1) - l^(-alpha/2-1)),
    mu = 0.1668 MPa, alpha = -1.479;  fat = 0.4 x muscle.

Bulk moduli are the paper's Table 1 (muscle 1000 MPa, fat 4.59 MPa);
densities 1.0e-6 (muscle) and 0.92e-6 kg/mm^3 (fat). Hollow-structure
material: the paper's fit (muscle E 100 MPa, yield 4 MPa; fat 50 / 2 MPa).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Engineering strain points of the default curves.
STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3, 0.5,
                   0.75, 1.0])
#: Engineering stress (MPa) of skeletal muscle at STRAIN.
MUSCLE_STRESS_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                              0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])
#: Engineering stress (MPa) of subcutaneous fat at STRAIN (0.4 x muscle, as tabulated).
FAT_STRESS_MPA = np.array([-4.74, -1.66, -0.760, -0.395, -0.217, -0.119, -0.0613, -0.0244, 0.0,
                           0.0168, 0.0286, 0.0372, 0.0482, 0.0555, 0.0591])

OGDEN_MU_MPA = 0.1668
OGDEN_ALPHA = -1.479


def ogden_uniaxial_stress_mpa(strain: np.ndarray, mu: float = OGDEN_MU_MPA,
                              alpha: float = OGDEN_ALPHA) -> np.ndarray:
    """Engineering stress (MPa) of the incompressible one-term Ogden law in uniaxial loading."""
    lam = 1.0 + np.asarray(strain, dtype=float)
    return (2.0 * mu / alpha) * (lam ** (alpha - 1.0) - lam ** (-alpha / 2.0 - 1.0))


@dataclass(frozen=True)
class Tissue:
    """Solid and hollow properties of one tissue (deck units: GPa, kg/mm^3).

    bulk_modulus: MAT_181 KM (GPa); density: kg/mm^3; strain, stress: the
    MAT_181 curve (engineering strain, engineering stress in GPa);
    hollow_E / hollow_yield: the paper's fitted shell material (GPa).
    """

    name: str
    bulk_modulus: float
    density: float
    strain: np.ndarray
    stress: np.ndarray
    hollow_E: float
    hollow_yield: float


TISSUES = {
    "muscle": Tissue("skeletal muscle", 1.0, 1.0e-6, STRAIN, MUSCLE_STRESS_MPA * 1e-3, 0.100,
                     0.004),
    "fat": Tissue("subcutaneous fat", 4.59e-3, 0.92e-6, STRAIN, FAT_STRESS_MPA * 1e-3, 0.050,
                  0.002),
}


def tissue(name: str) -> Tissue:
    """The :class:`Tissue` called ``name`` ('muscle' or 'fat'); ValueError otherwise."""
    try:
        return TISSUES[name]
    except KeyError:
        raise ValueError(f"unknown tissue {name!r}; choose one of {sorted(TISSUES)}") from None
