"""Tabulated Valanis-Landel function of MAT_181 (simplified rubber).

From the uniaxial engineering stress ``T(l)`` of an incompressible specimen
(Kolling et al. 2007) the principal Kirchhoff stress function is the series::

    f(l) = sum_{k>=0} l_k T(l_k),   l_k = l^((-1/2)^k)

(it telescopes: ``f(l) - f(l^(-1/2)) = l T(l)``, the incompressible uniaxial
response). The deviatoric principal Kirchhoff stresses of the element are
``tau_i = f(l_i) - (1/3) sum_j f(l_j)`` over the isochoric principal stretches.

The curve is LS-DYNA's: force vs change in gauge length; strain = x / SGL,
stress = y / (SW * ST); compression negative. Between its points T is
linear in strain; beyond its ends T is extrapolated linearly with the slope of
the end segment (documented behaviour: a curve that stops early keeps its last
slope). The series is summed until ``|ln l_k| < 1e-12`` (about 40 terms).

``f`` and the tangent ``g = (1/2) df/dln(l)`` (a shear modulus; ``g(1) = G0``
for a smooth curve) are tabulated on a uniform grid of ``ln l`` over
[ln 0.05, ln 6] (4096 points, l = 1 on a node), so the element kernel only
interpolates; outside the grid they are extrapolated linearly in ``ln l``.

Stability: the law satisfies the Baker-Ericksen inequality iff f is
increasing. :func:`check_rubber_curve` reports where it is not.
Units: stresses in GPa (deck units), stretches dimensionless.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from hollowbody.model.model import Curve

LAM_MIN = 0.05
LAM_MAX = 6.0
N_TABLE = 4096
#: Stretch range checked by default (isochoric principal stretches of an
#: 80 % uniaxial compression reach 0.2 and 2.24).
CHECK_RANGE = (0.2, 3.0)


def curve_stress_strain(curve: Curve, sgl: float, sw: float, st: float
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Engineering strain (m,) and stress (m,) GPa from a MAT_181 force curve."""
    if sgl <= 0.0 or sw <= 0.0 or st <= 0.0:
        raise ValueError(f"curve {curve.lcid}: SGL, SW, ST must be > 0 "
                         f"(got {sgl}, {sw}, {st})")
    strain = np.asarray(curve.x, dtype=np.float64) / sgl
    stress = np.asarray(curve.y, dtype=np.float64) / (sw * st)
    if strain.size < 2 or np.any(np.diff(strain) <= 0.0):
        raise ValueError(f"curve {curve.lcid}: abscissae must be strictly increasing "
                         "(at least 2 points)")
    return strain, stress


def uniaxial_stress(lam: np.ndarray, strain: np.ndarray, stress: np.ndarray) -> np.ndarray:
    """T(l): engineering stress at stretch l (array), linear extrapolation at both ends."""
    e = np.asarray(lam, dtype=np.float64) - 1.0
    t = np.interp(e, strain, stress)
    s0 = (stress[1] - stress[0]) / (strain[1] - strain[0])
    s1 = (stress[-1] - stress[-2]) / (strain[-1] - strain[-2])
    t = np.where(e < strain[0], stress[0] + s0 * (e - strain[0]), t)
    t = np.where(e > strain[-1], stress[-1] + s1 * (e - strain[-1]), t)
    return t


def kirchhoff_function(lam: np.ndarray, strain: np.ndarray, stress: np.ndarray,
                       tol: float = 1e-12, max_terms: int = 200) -> np.ndarray:
    """f(l) = sum_k l_k T(l_k) (same shape as lam, GPa), summed to |ln l_k| < tol."""
    ln = np.log(np.asarray(lam, dtype=np.float64))
    f = np.zeros_like(ln)
    for _ in range(max_terms):
        lk = np.exp(ln)
        f += lk * uniaxial_stress(lk, strain, stress)
        ln = -0.5 * ln
        if np.max(np.abs(ln), initial=0.0) < tol:
            break
    return f


def initial_modulus(strain: np.ndarray, stress: np.ndarray) -> float:
    """E0 (GPa): mean of the curve's slopes just left and right of zero strain."""
    h = 1e-9 * max(1.0, float(np.max(np.abs(strain))))
    lo = (np.interp(0.0, strain, stress) - np.interp(-h, strain, stress)) / h
    hi = (np.interp(h, strain, stress) - np.interp(0.0, strain, stress)) / h
    if strain[0] >= 0.0:
        lo = hi
    if strain[-1] <= 0.0:
        hi = lo
    return 0.5 * (lo + hi)


@dataclass
class RubberTable:
    """Tables of f and g = (1/2) df/dln(l) on a uniform ln(l) grid.

    ln0: ln of the first stretch; inv_dln: 1 / grid step; f, g: (N,) float64
    GPa; e0: initial Young's modulus (GPa); lcid: curve id (for messages).
    """

    ln0: float
    inv_dln: float
    f: np.ndarray
    g: np.ndarray
    e0: float
    lcid: int = 0


def build_rubber_table(curve: Curve, sgl: float = 1.0, sw: float = 1.0, st: float = 1.0,
                       lam_min: float = LAM_MIN, lam_max: float = LAM_MAX,
                       n: int = N_TABLE) -> RubberTable:
    """Tabulate f and its tangent for a MAT_181 curve (see module docstring)."""
    strain, stress = curve_stress_strain(curve, sgl, sw, st)
    # uniform grid with l = 1 on a node: f(1) = 0 exactly and the curve's kink at
    # zero strain (different slopes of the two branches) sits on a node
    lo, hi = math.log(lam_min), math.log(lam_max)
    step = (hi - lo) / (n - 1)
    i0 = round(-lo / step)
    ln = (np.arange(n) - i0) * step
    f = kirchhoff_function(np.exp(ln), strain, stress)
    g = 0.5 * np.gradient(f, ln)
    return RubberTable(ln0=float(ln[0]), inv_dln=float(1.0 / (ln[1] - ln[0])), f=f, g=g,
                       e0=initial_modulus(strain, stress), lcid=curve.lcid)


@njit(cache=True, inline="always", fastmath={"contract"})
def table_lookup(tab, ln0, inv_dln, ln_lam):
    """Kernel: linear interpolation of tab (N,) at ln(l), linear extrapolation outside."""
    u = (ln_lam - ln0) * inv_dln
    m = tab.shape[0]
    if u <= 0.0:
        i = 0
    elif u >= m - 1:
        i = m - 2
    else:
        i = int(u)
    t = u - i
    return tab[i] + t * (tab[i + 1] - tab[i])


def check_rubber_curve(curve: Curve, sgl: float = 1.0, sw: float = 1.0, st: float = 1.0,
                       lam_range: tuple[float, float] = CHECK_RANGE,
                       n: int = 2001) -> list[str]:
    """Warnings (empty when fine) if f is not increasing over ``lam_range``.

    f must increase with the stretch for the law to be stable (Baker-Ericksen
    inequality). Each message names the curve id, the stretch interval where f
    decreases and the corresponding uniaxial strain.
    """
    strain, stress = curve_stress_strain(curve, sgl, sw, st)
    lam = np.exp(np.linspace(math.log(lam_range[0]), math.log(lam_range[1]), n))
    f = kirchhoff_function(lam, strain, stress)
    df = np.diff(f)
    bad = df <= 0.0
    msgs: list[str] = []
    if not np.any(bad):
        return msgs
    # group consecutive decreasing intervals
    idx = np.nonzero(bad)[0]
    starts = [int(idx[0])]
    ends: list[int] = []
    for a, b in zip(idx[:-1], idx[1:]):
        if b != a + 1:
            ends.append(int(a))
            starts.append(int(b))
    ends.append(int(idx[-1]))
    for s, e in zip(starts, ends):
        lo, hi = float(lam[s]), float(lam[e + 1])
        msgs.append(
            f"curve {curve.lcid}: simplified rubber (MAT_181) stress function f(l) "
            f"decreases for stretch {lo:.3g} <= l <= {hi:.3g} (uniaxial strain "
            f"{lo - 1.0:+.3g} .. {hi - 1.0:+.3g}); the material is unstable there "
            "(Baker-Ericksen). Extend or smooth the tension and compression branches "
            "so that they match.")
    return msgs
