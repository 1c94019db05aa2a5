"""MAT_181 single element in uniaxial tension and compression reproduces its input curve.

The element is driven quasi-statically by prescribing the homogeneous state
x = diag(lt, lt, l) X; the lateral stretch lt is solved so that the lateral
stress vanishes (free lateral faces). The engineering stress
T = sigma_zz * lt^2 must equal the curve's T(l - 1).

Tolerance 2 %: the Valanis-Landel series reproduces T exactly for an
incompressible material (it telescopes); what remains is the compressibility
(|T| / KM < 0.5 % with KM = 1 GPa vs |T| <= 2 MPa here), the table's
interpolation (grid step 1.2e-3 in ln l, < 1e-4 relative) and the series
truncation (1e-12). The observed error is far below the tolerance.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq

from hollowbody.elements.solid_group import SolidGroupRuntime
from hollowbody.materials.rubber_table import uniaxial_stress
from hollowbody.mesh import block_mesh
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, SolidGroup

MUSCLE_STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                          0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                       0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])


def element(km: float = 1.0, sgl: float = 20.0, sw: float = 10.0, st: float = 5.0):
    """One unit-cube element; the curve is given as force vs elongation of a specimen."""
    x0, conn = block_mesh((1, 1, 1))
    curve = Curve(9, MUSCLE_STRAIN * sgl, MUSCLE_MPA * 1e-3 * sw * st)
    mat = MaterialDef(3, "rubber181", 1e-6, {"KM": km, "MU": 0.1, "G": 0.0, "SIGF": 0.0,
                                             "SGL": sgl, "SW": sw, "ST": st, "LCID": 9})
    rt = SolidGroupRuntime(SolidGroup(1, np.array([1]), conn), mat, HourglassDef(0),
                           {9: curve}, x0)
    return rt, x0


def uniaxial_T(rt, x0, lam):
    f = np.zeros_like(x0)
    zero = np.zeros_like(x0)

    def lateral(lt):
        rt.add_forces(x0 * [lt, lt, lam], zero, 0.0, f)
        return rt.stress[0, 0]

    lt0 = lam**-0.5
    lt = brentq(lateral, 0.8 * lt0, 1.2 * lt0, xtol=1e-15, rtol=1e-14)
    rt.add_forces(x0 * [lt, lt, lam], zero, 0.0, f)
    s = rt.stress[0]
    assert abs(s[1]) < 1e-9 * abs(s[2]) + 1e-15
    np.testing.assert_allclose(s[3:], 0.0, atol=1e-12 * abs(s[2]))
    return s[2] * lt * lt, lt


@pytest.mark.parametrize("strain", [-0.6, -0.55, -0.5, -0.4, -0.3, -0.25, -0.2, -0.1, -0.05,
                                    0.05, 0.1, 0.2, 0.3, 0.4, 0.5])
def test_uniaxial_response_matches_curve(strain):
    rt, x0 = element()
    t_model, lt = uniaxial_T(rt, x0, 1.0 + strain)
    t_curve = float(uniaxial_stress(np.array([1.0 + strain]), MUSCLE_STRAIN,
                                    MUSCLE_MPA * 1e-3)[0])
    assert t_model == pytest.approx(t_curve, rel=0.02)
    # nearly incompressible: J = lt^2 l close to 1
    assert abs(lt * lt * (1.0 + strain) - 1.0) < 5e-3


def test_uniaxial_error_is_small_for_stiff_bulk():
    rt, x0 = element(km=10.0)
    errs = []
    for strain in np.linspace(-0.6, 0.5, 23):
        if abs(strain) < 1e-9:
            continue
        t_model, _ = uniaxial_T(rt, x0, 1.0 + strain)
        t_curve = float(uniaxial_stress(np.array([1.0 + strain]), MUSCLE_STRAIN,
                                        MUSCLE_MPA * 1e-3)[0])
        errs.append(abs(t_model / t_curve - 1.0))
    assert max(errs) < 2e-3


def test_initial_shear_modulus_and_wave_speed():
    rt, x0 = element()
    e0 = 0.5 * (0.061 / 0.1 + 0.0419 / 0.1) * 1e-3
    c = np.sqrt((1.0 + 4.0 / 3.0 * e0 / 3.0) / 1e-6)
    assert rt.wave_speed()[0] == pytest.approx(c, rel=1e-9)
