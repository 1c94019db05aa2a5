"""The solid time-step rule against the exact stability limit of free hexahedral meshes.

The exact limit of the central-difference scheme is ``dt = 2 / omega_max``, omega_max^2
the largest eigenvalue of M^-1 K (lumped mass M; K assembled column by column from
central finite differences of the element group's own force routine about the
undeformed mesh, bulk viscosity off, FB hourglass stiffness QM 0.05 on). The rules
(:mod:`hollowbody.elements.solid_step_factor`): ``engine``, the engine's step
(TSSFAC 0.9 x the restrained-axes factor x L_e / c); ``lone``, the same with the
lone-element factor (a bound for any mesh, the engine's rule before the step's
bulk-viscosity term was made continuous; kept here as the reference).

Long runs: free meshes with random plus node-alternating ("checkerboard") initial
velocities, which excite every mode including the volumetric ones, run 3,000
cycles at the rule's step with the default bulk viscosity (Q1 1.5, Q2 0.06).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import hollowbody.testing.engine as engine_module
from hollowbody.elements.solid_step_factor import (
    restrained_axes,
    volumetric_step_factor,
)
from hollowbody.mesh import block_mesh
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, NodalSPC
from hollowbody.solver.energies import energies
from hollowbody.testing.engine import EngineRun
from hollowbody.testing.models import PartSpec, assemble_model
from hollowbody.tissues import TISSUES

H = 10.0  # mm element size
_MUS = TISSUES["muscle"]
CURVES = {4: Curve(4, _MUS.strain, _MUS.stress)}
MATERIALS = {
    # the block test's muscle: KM 1 GPa, G0 ~ 1.7e-4 GPa (K / G ~ 6,000)
    "rubber": MaterialDef(2, "rubber181", _MUS.density, {"KM": _MUS.bulk_modulus, "MU": 0.0,
                                                         "SGL": 1.0, "SW": 1.0, "ST": 1.0,
                                                         "LCID": 4}),
    "elastic": MaterialDef(1, "elastic", 1e-6, {"E": 0.01, "PR": 0.3}),
}


def make(counts, mat: MaterialDef, v0=None, q1=1.5, q2=0.06):
    """Free block of counts elements of H mm, hourglass IHQ 4 QM 0.05."""
    x0, conn = block_mesh(counts, tuple(H * np.asarray(counts, dtype=float)))
    model = assemble_model([PartSpec(1, x0, conn, kind=mat.kind, params=dict(mat.params),
                                     density=mat.density)])
    model.hourglass[1] = HourglassDef(1, ihq=4, qm=0.05, q1=q1, q2=q2)
    model.parts[1].hgid = 1
    model.curves.update(CURVES)
    if v0 is not None:
        model.node_v0 = np.asarray(v0, dtype=np.float64).copy()
    return model


def use_rule(monkeypatch, rule: str) -> None:
    """Rule "lone": EngineRun's set-up gives every solid group the lone-element factor
    instead of the engine's restrained-axes factor."""
    if rule != "lone":
        return
    original = engine_module.assemble

    def assemble(model):
        asm = original(model)
        for rt in asm.elements:
            mat = model.material_of(rt.pid)
            rt.step_factor = volumetric_step_factor(mat.kind, mat.params, model.curves, 0)
        return asm

    monkeypatch.setattr(engine_module, "assemble", assemble)


def omega_max(run: EngineRun) -> float:
    """Largest circular frequency (1/ms) of the run's free mesh (lumped mass)."""
    (rt,) = run.plan.elements
    saved = {k: np.copy(getattr(rt, k)) for k in rt.STATE_FIELDS}
    x0 = run.state.x.copy()
    n = x0.shape[0]
    k_mat = np.zeros((3 * n, 3 * n))
    du = 1e-6 * H
    for j in range(3 * n):
        for sign in (1.0, -1.0):
            for name, value in saved.items():  # every column from the undeformed state
                if np.ndim(value):
                    getattr(rt, name)[...] = value
                else:
                    setattr(rt, name, float(value))
            u = np.zeros((n, 3))
            u.flat[j] = sign * du
            f = np.zeros((n, 3))
            # v = u over dt = 1 ms: the increment is the displacement u
            rt.add_forces(np.ascontiguousarray(x0 + u), u, 1.0, f)
            k_mat[:, j] -= sign * f.ravel() / (2.0 * du)
    m = np.repeat(run.mass, 3)
    a = 0.5 * (k_mat + k_mat.T) / np.sqrt(np.outer(m, m))
    return math.sqrt(np.linalg.eigvalsh(a).max())


def wave_speed(mat: MaterialDef) -> float:
    """Initial dilatational wave speed (mm/ms) of the material, as the engine uses it."""
    run = EngineRun(make((1, 1, 1), mat, q1=0.0, q2=0.0))
    return float(run.plan.elements[0].wave_speed()[0])


@pytest.mark.parametrize("material", ["rubber", "elastic"])
def test_lone_element_breathing_mode_is_the_analytic_limit(material):
    """A lone cube's highest mode is the breathing mode, w^2 = 12 K / (rho h^2) (K >> G)
    or the uniaxial 4 (K + 4G/3) / (rho h^2), whichever is larger; the finite-difference
    K gets it to 1e-4 (round-off of the 1e-5 mm perturbation is ~1e-8)."""
    mat = MATERIALS[material]
    run = EngineRun(make((1, 1, 1), mat, q1=0.0, q2=0.0))
    c = wave_speed(mat)
    m_mod = mat.density * c * c
    if material == "elastic":
        e, nu = mat.params["E"], mat.params["PR"]
        k = e / (3.0 * (1.0 - 2.0 * nu))
    else:
        k = mat.params["KM"]
    w_exact = math.sqrt(max(12.0 * k, 4.0 * m_mod) / (mat.density * H * H))
    assert omega_max(run) == pytest.approx(w_exact, rel=1e-4)


# (counts, restrained axes k)
MESHES = [((1, 1, 1), 0), ((2, 1, 1), 1), ((2, 2, 1), 2), ((4, 4, 1), 2), ((2, 2, 2), 3),
          ((3, 3, 2), 3)]


@pytest.mark.parametrize("material", ["rubber", "elastic"])
@pytest.mark.parametrize("counts,axes", MESHES)
def test_engine_step_is_below_the_exact_limit(counts, axes, material):
    """The engine's first step uses the restrained-axes factor of the mesh (min_axes = k)
    and keeps omega_max dt / 2 < 1 at TSSFAC 0.9 (measured 0.71-0.96, the largest for
    the elastic blocks at factor 1; the bound 0.97 leaves room for the 1e-4 error of
    omega_max)."""
    mat = MATERIALS[material]
    run = EngineRun(make(counts, mat, q1=0.0, q2=0.0))
    (rt,) = run.plan.elements
    assert restrained_axes([rt.conn])[0].min() == axes
    factor = volumetric_step_factor(mat.kind, mat.params, CURVES, axes)
    assert rt.step_factor == factor
    dt = run.state.dt_next
    assert dt == pytest.approx(0.9 * factor * rt.dt_elem.min(), rel=1e-12)
    assert omega_max(run) * dt / 2.0 < 0.97


@pytest.mark.parametrize("material", ["rubber", "elastic"])
@pytest.mark.parametrize("counts,axes", MESHES)
def test_lone_element_factor_is_a_bound(counts, axes, material):
    """omega_max dt / 2 <= 0.9 with the lone-element factor: exact for the lone element
    (0.9 = TSSFAC, to the 1e-4 error of omega_max) and a bound for the assembled meshes
    (measured 0.58-0.86)."""
    mat = MATERIALS[material]
    run = EngineRun(make(counts, mat, q1=0.0, q2=0.0))
    (rt,) = run.plan.elements
    dt = 0.9 * volumetric_step_factor(mat.kind, mat.params, CURVES, 0) * rt.dt_elem.min()
    assert omega_max(run) * dt / 2.0 < 0.9 + 1e-3


@pytest.mark.parametrize("counts", [(2, 2, 2), (4, 4, 1)])
def test_rubber_needs_the_factor(counts):
    """LS-DYNA's L_e / c with TSSFAC 0.9 is above the exact limit of free rubber meshes
    (measured omega_max * 0.9 L/c / 2 = 1.10 and 1.21): the factor is not a margin."""
    run = EngineRun(make(counts, MATERIALS["rubber"], q1=0.0, q2=0.0))
    (rt,) = run.plan.elements
    rule = 0.9 * rt.dt_elem.min()
    assert omega_max(run) * rule / 2.0 > 1.05


def test_factor_values():
    """The factors the docs quote: LS-DYNA's step for an elastic nu 0.3 block (k = 3)."""
    el, rub = MATERIALS["elastic"], MATERIALS["rubber"]
    assert volumetric_step_factor(el.kind, el.params, CURVES, 3) == 1.0
    assert volumetric_step_factor(el.kind, el.params, CURVES, 0) == pytest.approx(
        math.sqrt((1 - 0.3) / (1 + 0.3)), rel=1e-12)
    assert volumetric_step_factor(rub.kind, rub.params, CURVES, 3) == pytest.approx(
        math.sqrt(1 / 1.5), rel=1e-3)
    assert volumetric_step_factor(rub.kind, rub.params, CURVES, 2) == pytest.approx(
        math.sqrt(3 / 7), rel=1e-3)
    assert volumetric_step_factor(rub.kind, rub.params, CURVES, 0) == pytest.approx(
        1 / math.sqrt(3), rel=1e-3)


def alternating_velocities(counts, amp: float, seed: int) -> np.ndarray:
    """Random (amp mm/ms) plus node-alternating amp (-1)^i per coordinate."""
    x0, _ = block_mesh(counts, tuple(H * np.asarray(counts, dtype=float)))
    rng = np.random.default_rng(seed)
    return rng.normal(scale=amp, size=x0.shape) + amp * (-1.0) ** np.rint(x0 / H)


def watch(run: EngineRun, cycles: int) -> tuple[np.ndarray, np.ndarray]:
    """(half-step kinetic energy, energy ratio) per cycle."""
    e0 = energies(run.plan, run.state)["total"]
    ke, ratio = np.zeros(cycles), np.zeros(cycles)
    for i in range(cycles):
        run.step()
        ke[i] = run.kinetic(run.state.v)
        ratio[i] = energies(run.plan, run.state)["total"] / e0
    return ke, ratio


@pytest.mark.parametrize("rule", ["engine", "lone"])
@pytest.mark.parametrize("material", ["rubber", "elastic"])
@pytest.mark.parametrize("counts", [(1, 1, 1), (2, 2, 1), (2, 2, 2), (4, 4, 4)])
def test_free_block_with_checkerboard_velocities_stays_stable(counts, material, rule,
                                                              monkeypatch):
    """3,000 cycles at the engine's step: no growth of the kinetic energy (an unstable
    mode grows by 10^6 within 4-30 cycles at LS-DYNA's step, factor 1, for every rubber
    mesh here; measured here: the last 10 % at 0.07-0.63 of the first 10 %) and no energy
    gained after the start: the ratio after the first 10 % stays below its maximum in the
    first 10 % (+0.5 %). Its value itself is not a tight check here: for modes near the
    stability limit the full-step velocity estimate of the kinetic energy is off by up
    to (w dt / 2)^2 / (1 - (w dt / 2)^2), so the ratio starts at 1.3-4 and settles at
    0.93-1.14 as the bulk viscosity damps the high modes (bound: within 0.2 of 1)."""
    use_rule(monkeypatch, rule)
    v0 = alternating_velocities(counts, 0.01, seed=7)
    run = EngineRun(make(counts, MATERIALS[material], v0=v0))
    ke, ratio = watch(run, 3000)
    q = ke.size // 10
    assert np.all(np.isfinite(ratio))
    assert ke[-q:].max() <= ke[:q].max()
    assert ratio[q:].max() <= ratio[:q].max() + 0.005
    assert abs(ratio[-1] - 1.0) < 0.2


@pytest.mark.parametrize("rule", ["engine", "lone"])
@pytest.mark.parametrize("material,speed", [("rubber", 10.0), ("elastic", 1.0)])
def test_impacted_block_stays_balanced(material, speed, rule, monkeypatch):
    """A 4 x 4 x 2 block moving at `speed` mm/ms with its bottom face clamped (a wave of
    strain v / c: 1 % for rubber, 0.9 % for the elastic block) for 3,000 cycles at the
    engine's step. The velocity jump at the clamped face is high-frequency content, so
    the ratio starts at 1.10-1.15 (see the test above); no energy is gained after that
    (below its first-10 % maximum) and it settles within 5 % of 1 (measured 1.010-1.039;
    at LS-DYNA's step, factor 1, the rubber block reached 2.8)."""
    counts = (4, 4, 2)
    x0, _ = block_mesh(counts, tuple(H * np.asarray(counts, dtype=float)))
    v0 = np.zeros_like(x0)
    v0[:, 2] = -speed
    bottom = np.nonzero(x0[:, 2] < 1e-9)[0]
    v0[bottom] = 0.0
    model = make(counts, MATERIALS[material], v0=v0)
    model.spcs.append(NodalSPC(nodes=bottom, dofs=np.ones((bottom.size, 6), dtype=bool)))
    use_rule(monkeypatch, rule)
    run = EngineRun(model)
    _, ratio = watch(run, 3000)
    q = ratio.size // 10
    assert ratio[q:].max() <= ratio[:q].max() + 0.005
    assert abs(ratio[-1] - 1.0) < 0.05
