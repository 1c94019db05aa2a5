"""*MAT_SIMPLIFIED_RUBBER/FOAM (LS-DYNA 181), rubber branch (Kolling et al. 2007).

Hyperelastic, total form from the element's deformation gradient ``F``
(from the reference uniform gradients, ``F = sum_a x_a (x) B0_a``)::

    b = F F^T,  eigen-pairs (mu_i, n_i) of b   (Jacobi, no LAPACK)
    ln l_i = (1/2) (ln mu_i - (1/3) sum_j ln mu_j)      isochoric stretches
    tau_i = f(l_i) - (1/3) sum_j f(l_j)                 f from rubber_table
    sigma = (1/J) sum_i tau_i n_i (x) n_i + KM (J - 1) I + 2 eta D' + s_f

with ``J = V / V0`` (element volume ratio, consistent with the volume the
solver checks), ``D'`` the deviatoric mid-step rate of deformation.

Viscous damping (MU): ``eta = MU rho c_s l``, ``c_s = sqrt(G0 / rho)`` the
shear wave speed, ``l = V^(1/3)``. Then MU is the fraction of critical damping
of the element's highest shear mode (``omega ~ 2 c_s / l``), which matches the
keyword manual's description of MU as a dimensionless damping coefficient
(recommended 0.05..0.5, default 0.1). LS-DYNA does not publish its exact
formula; this is our documented choice.

Frictional (frequency-independent) damping (G, SIGF): a deviatoric stress
``s_f`` (a spring G in series with a friction element): rotated with the
element, incremented by ``2 G dt D'``, scaled back to
``sqrt(3/2 s_f:s_f) <= SIGF``. Off when G = 0 or SIGF = 0.

Wave speed (time step, hourglass): ``c = sqrt((KM + 4/3 (G_t + G)) / rho)``
with ``G_t = max(G0, g(l_i))`` the larger of the initial shear modulus
``G0 = E0 / 3`` and the current tangent of the tabulated law, so stiffening
rubber keeps a stable step. Units: GPa, kg/mm^3, mm/ms.

Solid law interface (see :mod:`hollowbody.materials.solid_laws`):
:func:`solid_params`, :func:`solid_wave_speed0`, :func:`solid_hourglass_moduli`,
:func:`solid_history`, :func:`solid_erode` and the kernel :func:`solid_update`. History: the
frictional stress ``_fric`` (e, 6) GPa ((1, 6) when friction is off) and the
eigenvectors ``_eig`` (e, 3, 3) of F F^T of the last call (warm start of the
eigen-solver).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from numba import njit

from hollowbody.errors import DeckError
from hollowbody.materials.rubber_table import (
    RubberTable,
    build_rubber_table,
    check_rubber_curve,
    table_lookup,
)
from hollowbody.materials.sym3_eigen import jacobi_eig3
from hollowbody.materials.tensor3 import rotate_sym
from hollowbody.model.model import Curve, MaterialDef

P_BULK, P_MU, P_G0, P_RHO, P_CS, P_GF, P_SIGF, P_LN0, P_INVD = range(9)
N_PARAMS = 9

#: LS-DYNA default of MU.
MU_DEFAULT = 0.1

#: Material kind of the law (``MaterialDef.kind``) and its keyword.
KIND = "rubber181"
KEYWORD = "MAT_SIMPLIFIED_RUBBER"
#: Names of the per-element history arrays, in the order of the kernel's history tuple.
HISTORY_FIELDS: tuple[str, ...] = ("_fric", "_eig")

_THIRD = 1.0 / 3.0


def rubber_params(mat: MaterialDef, curves: dict[int, Curve],
                  check: bool = True) -> tuple[np.ndarray, RubberTable]:
    """Packed parameters (N_PARAMS,) float64 and the f/g tables of a MAT_181 card.

    Emits ``warnings.warn`` (UserWarning) for every Baker-Ericksen problem of
    the curve (see :func:`~hollowbody.materials.rubber_table.check_rubber_curve`)
    when ``check``. Raises DeckError for a missing curve or bad parameters.
    """
    p = mat.params
    where = (mat.source.file, mat.source.line, mat.keyword or "MAT_SIMPLIFIED_RUBBER")
    lcid = int(p.get("LCID", 0))
    if lcid not in curves:
        raise DeckError(f"material {mat.mid}: curve LCID {lcid} is not defined", *where)
    km = float(p.get("KM", 0.0))
    rho = float(mat.density)
    if km <= 0.0:
        raise DeckError(f"material {mat.mid}: KM must be > 0 (got {km})", *where)
    if rho <= 0.0:
        raise DeckError(f"material {mat.mid}: density must be > 0 (got {rho})", *where)
    sgl = float(p.get("SGL", 1.0)) or 1.0
    sw = float(p.get("SW", 1.0)) or 1.0
    st = float(p.get("ST", 1.0)) or 1.0
    mu = float(p.get("MU", MU_DEFAULT))
    try:
        table = build_rubber_table(curves[lcid], sgl, sw, st)
    except ValueError as err:
        raise DeckError(f"material {mat.mid}: {err}", *where) from None
    if table.e0 <= 0.0:
        raise DeckError(f"material {mat.mid}: curve {lcid} has no positive initial slope "
                        "at zero strain", *where)
    if check:
        for msg in check_rubber_curve(curves[lcid], sgl, sw, st):
            warnings.warn(f"material {mat.mid}: {msg}", UserWarning, stacklevel=2)
    g0 = table.e0 / 3.0
    out = np.zeros(N_PARAMS)
    out[P_BULK] = km
    out[P_MU] = max(mu, 0.0)
    out[P_G0] = g0
    out[P_RHO] = rho
    out[P_CS] = math.sqrt(g0 / rho)
    out[P_GF] = max(float(p.get("G", 0.0)), 0.0)
    out[P_SIGF] = max(float(p.get("SIGF", 0.0)), 0.0)
    out[P_LN0] = table.ln0
    out[P_INVD] = table.inv_dln
    return out, table


def rubber_wave_speed0(params: np.ndarray) -> float:
    """Initial dilatational wave speed (mm/ms) sqrt((KM + 4/3 (G0 + G)) / rho)."""
    return math.sqrt((params[P_BULK] + 4.0 / 3.0 * (params[P_G0] + params[P_GF]))
                     / params[P_RHO])


@njit(cache=True, inline="always", fastmath={"contract"})
def rubber_deviatoric(f00, f01, f02, f10, f11, f12, f20, f21, f22, vec, ftab, gtab, ln0, invd):
    """Kernel: deviatoric Kirchhoff stress of the tabulated law.

    f..: deformation gradient F (row i, column j); vec (3, 3): on entry an
    orthonormal start basis for the eigen-solver (the identity, or the
    element's eigenvectors of the previous step: then one or two Jacobi
    sweeps suffice), on return the eigenvectors of F F^T; ftab, gtab
    (N,) GPa tables; ln0, invd: grid origin and inverse step. Returns
    (t0..t5, gt): tau' in Voigt order (GPa) and the largest current tangent
    shear modulus gt (GPa).
    """
    b0 = f00 * f00 + f01 * f01 + f02 * f02
    b1 = f10 * f10 + f11 * f11 + f12 * f12
    b2 = f20 * f20 + f21 * f21 + f22 * f22
    b3 = f00 * f10 + f01 * f11 + f02 * f12
    b4 = f10 * f20 + f11 * f21 + f12 * f22
    b5 = f00 * f20 + f01 * f21 + f02 * f22
    m0, m1, m2 = jacobi_eig3(b0, b1, b2, b3, b4, b5, vec)
    tiny = 1e-300
    l0 = math.log(max(m0, tiny))
    l1 = math.log(max(m1, tiny))
    l2 = math.log(max(m2, tiny))
    lm = (l0 + l1 + l2) / 3.0
    x0 = 0.5 * (l0 - lm)
    x1 = 0.5 * (l1 - lm)
    x2 = 0.5 * (l2 - lm)
    fa = table_lookup(ftab, ln0, invd, x0)
    fb = table_lookup(ftab, ln0, invd, x1)
    fc = table_lookup(ftab, ln0, invd, x2)
    gt = max(table_lookup(gtab, ln0, invd, x0), table_lookup(gtab, ln0, invd, x1),
             table_lookup(gtab, ln0, invd, x2))
    fm = (fa + fb + fc) / 3.0
    ta = fa - fm
    tb = fb - fm
    tc = fc - fm
    n00, n01, n02 = vec[0, 0], vec[0, 1], vec[0, 2]
    n10, n11, n12 = vec[1, 0], vec[1, 1], vec[1, 2]
    n20, n21, n22 = vec[2, 0], vec[2, 1], vec[2, 2]
    t0 = ta * n00 * n00 + tb * n01 * n01 + tc * n02 * n02
    t1 = ta * n10 * n10 + tb * n11 * n11 + tc * n12 * n12
    t2 = ta * n20 * n20 + tb * n21 * n21 + tc * n22 * n22
    t3 = ta * n00 * n10 + tb * n01 * n11 + tc * n02 * n12
    t4 = ta * n10 * n20 + tb * n11 * n21 + tc * n12 * n22
    t5 = ta * n00 * n20 + tb * n01 * n21 + tc * n02 * n22
    return t0, t1, t2, t3, t4, t5, gt


@njit(cache=True, inline="always", fastmath={"contract"})
def rubber_friction(s0, s1, s2, s3, s4, s5, e0, e1, e2, e3, e4, e5, gf, sigf):
    """Kernel: frictional damping stress update.

    s*: rotated old frictional stress (GPa, Voigt); e*: deviatoric strain
    increment dt*D' (tensor components); gf: spring shear modulus; sigf: limit
    (von Mises measure). Returns the new six components.
    """
    n0 = s0 + 2.0 * gf * e0
    n1 = s1 + 2.0 * gf * e1
    n2 = s2 + 2.0 * gf * e2
    n3 = s3 + 2.0 * gf * e3
    n4 = s4 + 2.0 * gf * e4
    n5 = s5 + 2.0 * gf * e5
    j2 = 0.5 * (n0 * n0 + n1 * n1 + n2 * n2) + n3 * n3 + n4 * n4 + n5 * n5
    eq = math.sqrt(3.0 * j2)
    if eq > sigf:
        r = sigf / eq
        n0 *= r
        n1 *= r
        n2 *= r
        n3 *= r
        n4 *= r
        n5 *= r
    return n0, n1, n2, n3, n4, n5


# -- solid law interface --------------------------------------------------------------
def solid_params(mat: MaterialDef, curves: dict[int, Curve]) -> tuple[np.ndarray, ...]:
    """Parameter tuple of the solid kernel: (packed parameters, f table, g table), GPa.

    Validation and warnings as :func:`rubber_params`.
    """
    mp, table = rubber_params(mat, curves)
    return (mp, table.f, table.g)


def solid_wave_speed0(params: tuple[np.ndarray, ...]) -> float:
    """Initial dilatational wave speed (mm/ms), :func:`rubber_wave_speed0`."""
    return rubber_wave_speed0(params[0])


def solid_hourglass_moduli(params: tuple[np.ndarray, ...]) -> tuple[float, float]:
    """Small-strain shear and bulk moduli (GPa) of the assumed-strain hourglass
    stiffness (IHQ 6): ``G0 = E0 / 3`` from the curve's initial slope and KM. (The
    element uses the larger of G0 and the current tangent, see hex8_solid_kernels.)"""
    return float(params[0][P_G0]), float(params[0][P_BULK])


def friction_on(mp: np.ndarray) -> bool:
    """True when the frictional damping is active (G > 0 and SIGF > 0)."""
    return bool(mp[P_GF] > 0.0 and mp[P_SIGF] > 0.0)


def solid_history(params: tuple[np.ndarray, ...], n_elem: int) -> dict[str, np.ndarray]:
    """History arrays by name: ``_fric`` (e, 6) GPa frictional stress ((1, 6) when
    friction is off) and ``_eig`` (e, 3, 3) eigenvector warm starts (identity)."""
    fric = np.zeros((n_elem if friction_on(params[0]) else 1, 6))
    eig = np.zeros((n_elem, 3, 3))
    eig[:, [0, 1, 2], [0, 1, 2]] = 1.0
    return {"_fric": fric, "_eig": eig}


def solid_erode(history: tuple[np.ndarray, ...], idx: np.ndarray) -> None:
    """Zero the frictional stress of eroded elements ``idx``."""
    fric = history[0]
    if fric.shape[0] == history[1].shape[0]:
        fric[idx] = 0.0


@njit(cache=True, fastmath={"contract"})
def _friction_step(e, rot, fric, e0, e1, e2, e3, e4, e5, gf, sigf):
    """Rotate, increment and limit the frictional stress fric[e] (GPa); returns it.

    A function of its own, not IR-inlined (LLVM still inlines it): written
    inline in :func:`solid_update`, its stores to ``fric`` were lost once the
    update was inlined into the parallel element loop (numba 0.68), which the
    bit-for-bit comparison with the former rubber kernel showed.
    """
    r0, r1, r2, r3, r4, r5 = rotate_sym(rot, fric[e, 0], fric[e, 1], fric[e, 2],
                                        fric[e, 3], fric[e, 4], fric[e, 5])
    r0, r1, r2, r3, r4, r5 = rubber_friction(r0, r1, r2, r3, r4, r5, e0, e1, e2, e3, e4, e5,
                                             gf, sigf)
    fric[e, 0] = r0
    fric[e, 1] = r1
    fric[e, 2] = r2
    fric[e, 3] = r3
    fric[e, 4] = r4
    fric[e, 5] = r5
    return r0, r1, r2, r3, r4, r5


@njit(cache=True, inline="always", fastmath={"contract"})
def solid_constants(params):
    """Kernel: the scalars of ``params`` the update uses, read once per call.

    Returns (KM, MU, G0, rho0, c_s, G, SIGF, table origin, table inverse step,
    friction on).
    """
    mp = params[0]
    gf = mp[P_GF]
    sigf = mp[P_SIGF]
    return (mp[P_BULK], mp[P_MU], mp[P_G0], mp[P_RHO], mp[P_CS], gf, sigf, mp[P_LN0],
            mp[P_INVD], gf > 0.0 and sigf > 0.0)


@njit(cache=True, inline="always", fastmath={"contract"})
def solid_update(e, dt, vol, vol0, l, xe, b0, lm, rot, work, stress, consts, params, history):
    """Kernel: new stress of element ``e`` (hyperelastic + damping, module docstring).

    dt ms; vol, vol0 current / initial volume mm^3; l = vol^(1/3) mm; xe (8, 3)
    mm nodal positions relative to node 1 (F = sum_a x_a (x) b0_a); b0 (e, 8, 3)
    1/mm reference gradients; lm (3, 3) 1/ms mid-step velocity gradient; rot
    (3, 3) incremental rotation; work (3, 3) scratch (eigenvectors); stress
    (e, 6) unused (total form); consts from :func:`solid_constants`; params
    (mp, ftab, gtab); history (fric, eig), updated for element e. Returns
    (s0..s5 GPa, rho kg/mm^3, modulus GPa, c mm/ms).
    """
    bulk, mu_d, g0, rho0, cs, gf, sigf, ln0, invd, use_fric = consts
    ftab = params[1]
    gtab = params[2]
    fric = history[0]
    eig = history[1]
    vec = work
    f00 = f01 = f02 = f10 = f11 = f12 = f20 = f21 = f22 = 0.0
    for a in range(8):
        xa, ya, za = xe[a, 0], xe[a, 1], xe[a, 2]
        ba0, ba1, ba2 = b0[e, a, 0], b0[e, a, 1], b0[e, a, 2]
        f00 += xa * ba0
        f01 += xa * ba1
        f02 += xa * ba2
        f10 += ya * ba0
        f11 += ya * ba1
        f12 += ya * ba2
        f20 += za * ba0
        f21 += za * ba1
        f22 += za * ba2
    for i in range(3):
        vec[i, 0] = eig[e, i, 0]
        vec[i, 1] = eig[e, i, 1]
        vec[i, 2] = eig[e, i, 2]
    t0, t1, t2, t3, t4, t5, gt = rubber_deviatoric(f00, f01, f02, f10, f11, f12,
                                                   f20, f21, f22, vec, ftab, gtab,
                                                   ln0, invd)
    for i in range(3):
        eig[e, i, 0] = vec[i, 0]
        eig[e, i, 1] = vec[i, 1]
        eig[e, i, 2] = vec[i, 2]
    jac = vol / vol0
    rho = rho0 / jac
    gtan = max(g0, gt)
    modulus = bulk + 4.0 / 3.0 * (gtan + gf)
    c = math.sqrt(modulus / rho)
    d0 = lm[0, 0]
    d1 = lm[1, 1]
    d2 = lm[2, 2]
    d3 = 0.5 * (lm[0, 1] + lm[1, 0])
    d4 = 0.5 * (lm[1, 2] + lm[2, 1])
    d5 = 0.5 * (lm[2, 0] + lm[0, 2])
    trd = d0 + d1 + d2
    dm = trd * _THIRD
    eta2 = 2.0 * mu_d * rho * cs * l
    p = bulk * (jac - 1.0)
    ij = 1.0 / jac
    n0 = t0 * ij + p + eta2 * (d0 - dm)
    n1 = t1 * ij + p + eta2 * (d1 - dm)
    n2 = t2 * ij + p + eta2 * (d2 - dm)
    n3 = t3 * ij + eta2 * d3
    n4 = t4 * ij + eta2 * d4
    n5 = t5 * ij + eta2 * d5
    if use_fric:
        r0, r1, r2, r3, r4, r5 = _friction_step(e, rot, fric, dt * (d0 - dm), dt * (d1 - dm),
                                                dt * (d2 - dm), dt * d3, dt * d4, dt * d5,
                                                gf, sigf)
        n0 += r0
        n1 += r1
        n2 += r2
        n3 += r3
        n4 += r4
        n5 += r5
    return n0, n1, n2, n3, n4, n5, rho, modulus, c
