"""Closed-form mean crush forces of thin-walled tubes in axial progressive crushing.

The yardstick of the crush benchmark (docs/crush.md). Every formula is for a
rigid-perfectly-plastic wall of flow stress ``sigma0`` (GPa), thickness ``t``
(mm) and the fully plastic bending moment per unit length

    M_0 = sigma0 t^2 / 4      (kN mm / mm)

so forces come out in kN. Square tubes: side C (mm) of the mid-surface;
circular tubes: mean diameter D = 2 R (mm).

The flow stress: for an elastic-perfectly-plastic law it is the yield stress;
for a hardening law :func:`flow_stress` gives the energy-equivalent flow
stress, the mean of the hardening curve over the plastic strain range 0 ..
eps_u, ``sigma0 = (1 / eps_u) int_0^eps_u sigma(eps_p) d eps_p`` (a constant
stress that does the same plastic work per unit volume). The benchmark's
materials are rate-insensitive (no Cowper-Symonds term), so the dynamic
corrections of Abramowicz & Jones for strain-rate sensitive mild steel do not
apply and are not included: for rate-insensitive materials at 5-15 m/s the
quasi-static forms are the reference.

Constants and their sources (the references in the function docstrings):

- 38.12 and H = 0.99 t^(1/3) C^(2/3): Wierzbicki & Abramowicz (1983);
- 52.22 = 38.12 / 0.73 and the effective crush distance delta_e / (2H) = 0.73:
  Abramowicz & Jones (1984a);
- 25.23, 15.09 and delta_e / (2H) = 0.86 - 0.568 sqrt(t / D): Abramowicz &
  Jones (1986);
- 22.27 = 4 pi^(3/2) and H = sqrt(pi R t / 2): Alexander (1960), re-derived
  here (module doc of :func:`circular_alexander`).

The constants 38.12, 0.99, 52.22, 0.73, 25.23, 15.09, 0.86 and 0.568 are
those quoted by N. Jones, *Structural Impact* (Cambridge University Press,
1989; 2nd ed. 2012), chapters 7 and 8, for the papers named; the primary
papers could not be read in full while this module was written (their
abstracts and notation lists were: the 1984 circular-tube paper defines M_0
with the plane-strain factor, (2 / sqrt 3) sigma0 t^2 / 4, which the forms
here do not use -- the brief's and Jones's M_0 = sigma0 t^2 / 4 is used
throughout). Only 22.27 is verified here, by the derivation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Effective crush distance of a square tube's fold, delta_e / (2 H)
#: (Abramowicz & Jones 1984a).
SQUARE_EFFECTIVE = 0.73


def plastic_moment(sigma0: float, t: float) -> float:
    """M_0 = sigma0 t^2 / 4 (kN mm per mm) of a wall of thickness t (mm), sigma0 (GPa)."""
    return 0.25 * sigma0 * t * t


def flow_stress(sigy: float, etan: float = 0.0, eps_u: float = 0.3,
                curve: np.ndarray | None = None) -> float:
    """Energy-equivalent flow stress (GPa): the mean yield stress over 0 .. ``eps_u``
    plastic strain.

    Linear hardening ``sigy + etan * E / (E - etan) eps_p`` is approximated by
    ``sigy + etan eps_p`` when ``curve`` is None (etan << E; with etan = 0 the
    result is ``sigy``); ``curve`` (k, 2) (plastic strain, stress GPa) is a
    piecewise-linear hardening curve (MAT_024 LCSS), held constant past its end.
    eps_u = 0.3 is a typical plastic strain at the fold hinges of
    C/t = 20-50 tubes (the fold radius is a few t).
    """
    if eps_u <= 0.0:
        raise ValueError("eps_u must be > 0")
    if curve is None:
        return sigy + 0.5 * etan * eps_u
    e = np.linspace(0.0, eps_u, 401)
    s = np.interp(e, curve[:, 0], curve[:, 1])
    return float(np.trapezoid(s, e) / eps_u)


def square_half_fold(c: float, t: float) -> float:
    """Half-fold length H = 0.99 t^(1/3) C^(2/3) (mm) of a square tube (side C, wall t, mm).

    Wierzbicki, T., Abramowicz, W. (1983), On the crushing mechanics of
    thin-walled structures, J. Appl. Mech. 50, 727-734.
    """
    return 0.99 * t ** (1.0 / 3.0) * c ** (2.0 / 3.0)


def square_wierzbicki_abramowicz(c: float, t: float, sigma0: float) -> float:
    """Mean crush force (kN) of a square tube: P_m / M_0 = 38.12 (C / t)^(1/3).

    Wierzbicki, T., Abramowicz, W. (1983), On the crushing mechanics of
    thin-walled structures, J. Appl. Mech. 50, 727-734 (the super-folding
    element; the whole fold length 2 H crushed).
    """
    return 38.12 * (c / t) ** (1.0 / 3.0) * plastic_moment(sigma0, t)


def square_abramowicz_jones(c: float, t: float, sigma0: float) -> float:
    """Mean crush force (kN) of a square tube with the effective crush distance:
    P_m / M_0 = 52.22 (C / t)^(1/3) (= 38.12 / 0.73).

    Abramowicz, W., Jones, N. (1984a), Dynamic axial crushing of square tubes,
    Int. J. Impact Engng 2(2), 179-208 (symmetric mode, quasi-static, without
    the Cowper-Symonds factor).
    """
    return 52.22 * (c / t) ** (1.0 / 3.0) * plastic_moment(sigma0, t)


def circular_half_fold(d: float, t: float) -> float:
    """Half-fold length H = sqrt(pi R t / 2) (mm) of Alexander's concertina fold (D = 2R)."""
    return math.sqrt(0.25 * math.pi * d * t)


def circular_alexander(d: float, t: float, sigma0: float) -> float:
    """Mean crush force (kN) of a circular tube, concertina mode:
    P_m / M_0 = 4 pi^(3/2) sqrt(D / t) = 22.27 sqrt(D / t).

    Alexander, J. M. (1960), An approximate analysis of the collapse of thin
    cylindrical shells under axial loading, Q. J. Mech. Appl. Math. 13, 10-15.
    Re-derived: one fold of length 2 H with three circumferential hinges
    (bending 2 pi R M_0 2 pi) and the hoop stretching of the two legs
    (2 pi sigma0 t H^2) equals P_m 2 H; the minimum over H is at
    H^2 = pi R t / 2, P_m = 8 pi sqrt(pi / 2) M_0 sqrt(R / t). The lower
    reference: it neither crushes the fold less than 2 H nor folds in and
    out of the original radius.
    """
    return 4.0 * math.pi ** 1.5 * math.sqrt(d / t) * plastic_moment(sigma0, t)


def circular_abramowicz_jones(d: float, t: float, sigma0: float,
                              effective: bool = True) -> float:
    """Mean crush force (kN) of a circular tube, axisymmetric mode:
    P_m / M_0 = (25.23 sqrt(D / t) + 15.09) / (0.86 - 0.568 sqrt(t / D)) with the
    effective crush distance (``effective``), without it the numerator alone.

    Abramowicz, W., Jones, N. (1986), Dynamic progressive buckling of circular
    and square tubes, Int. J. Impact Engng 4(4), 243-270 (quasi-static form,
    without the Cowper-Symonds factor).
    """
    p = (25.23 * math.sqrt(d / t) + 15.09) * plastic_moment(sigma0, t)
    if effective:
        p /= 0.86 - 0.568 * math.sqrt(t / d)
    return p


@dataclass(frozen=True)
class CrushReference:
    """The analytical yardstick of one tube: each form's mean force (kN), the range
    [low, high] (kN) over them, the closed-form half-fold length H (mm) and the
    effective crush distance factor delta_e / (2 H)."""

    forms: dict[str, float]
    half_fold: float
    effective: float

    @property
    def low(self) -> float:
        return min(self.forms.values())

    @property
    def high(self) -> float:
        return max(self.forms.values())


def square_reference(c: float, t: float, sigma0: float) -> CrushReference:
    """Yardstick of a square tube (side C, wall t mm; sigma0 GPa): Wierzbicki &
    Abramowicz (1983) and Abramowicz & Jones (1984a)."""
    return CrushReference(
        forms={"Wierzbicki-Abramowicz 1983": square_wierzbicki_abramowicz(c, t, sigma0),
               "Abramowicz-Jones 1984": square_abramowicz_jones(c, t, sigma0)},
        half_fold=square_half_fold(c, t), effective=SQUARE_EFFECTIVE)


def circular_reference(d: float, t: float, sigma0: float) -> CrushReference:
    """Yardstick of a circular tube (diameter D, wall t mm; sigma0 GPa): Alexander
    (1960), Abramowicz & Jones (1986) without and with the effective crush distance."""
    return CrushReference(
        forms={"Alexander 1960": circular_alexander(d, t, sigma0),
               "Abramowicz-Jones 1986": circular_abramowicz_jones(d, t, sigma0, False),
               "Abramowicz-Jones 1986 effective": circular_abramowicz_jones(d, t, sigma0)},
        half_fold=circular_half_fold(d, t), effective=0.86 - 0.568 * math.sqrt(t / d))
