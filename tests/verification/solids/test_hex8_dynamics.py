"""Dynamic verification of the hexahedron on the engine's own cycle.

Each case is a Model run cycle by cycle with :class:`hollowbody.testing.engine.EngineRun`
(the engine's plan, State and ``step``: its central differences, constraints and
time-step rule):

* dilatational wave speed in a laterally confined column;
* energy conservation of elastic (and hyperelastic rubber) free vibration;
* hourglass work is non-negative in the viscous form;
* internal + hourglass energy is the scheme's own work of the element forces.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.mesh import block_mesh, distort
from hollowbody.model.model import (
    Curve,
    HourglassDef,
    MaterialDef,
    NodalSPC,
    PrescribedMotion,
)
from hollowbody.testing.engine import EngineRun
from hollowbody.testing.models import PartSpec, assemble_model
from hollowbody.testing.solids import energy_history, initial_velocity

MUSCLE_STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                          0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                       0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])


def make(x0, conn, mat: MaterialDef, curves=None, v0=None, **hg):
    """A one-part Model of hexahedra (part 1, hourglass card 1 with ``hg``)."""
    model = assemble_model([PartSpec(1, x0, conn, kind=mat.kind, params=dict(mat.params),
                                     density=mat.density)])
    model.hourglass[1] = HourglassDef(1, **hg)
    model.parts[1].hgid = 1
    model.curves.update(curves or {})
    if v0 is not None:
        model.node_v0 = np.asarray(v0, dtype=np.float64).copy()
    return model


def group(run: EngineRun):
    """The run's element-group runtime (one part)."""
    (rt,) = run.plan.elements
    return rt


def discrete_invariant(run: EngineRun, dt: float) -> float:
    """Exactly conserved by the scheme for a constant step and no constraints:
    KE(v^{N+1/2}) - dt/2 f^N . v^{N+1/2} + (work of the element forces up to t^N)."""
    s, rt = run.state, group(run)
    # v^{N+1/2} of the next cycle (the first cycle's step is dt/2, from v^0)
    v = s.v + (0.5 * dt if s.cycle == 0 else dt) * s.f * s.inv_m[:, None]
    return (run.kinetic(v) - 0.5 * dt * float((s.f * v).sum())
            + rt.internal_energy + rt.hourglass_energy)


def test_dilatational_wave_speed_in_confined_column():
    n, h = 200, 1.0
    x0, conn = block_mesh((1, 1, n), (h, h, n * h))
    e_mod, nu, rho = 0.2, 0.3, 1e-6
    model = make(x0, conn, MaterialDef(1, "elastic", rho, {"E": e_mod, "PR": nu}),
                 qm=0.1, q1=0.0, q2=0.0)
    c = math.sqrt(e_mod * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) / rho)
    v_in = 0.01  # mm/ms, pushed in at z = 0
    bottom = np.nonzero(x0[:, 2] < 1e-9)[0]
    # lateral confinement (uniaxial strain): x and y held everywhere
    model.spcs.append(NodalSPC(nodes=np.arange(x0.shape[0]),
                               dofs=np.tile([True, True, False, False, False, False],
                                             (x0.shape[0], 1))))
    model.curves[9] = Curve(9, np.array([0.0, 1e3]), np.array([v_in, v_in]))
    model.prescribed.append(PrescribedMotion(target="nodes", dof=3, vad=0, lcid=9,
                                             nodes=bottom))
    loop = EngineRun(model)
    stations = {50: None, 150: None}
    node_at = {k: np.nonzero(np.abs(x0[:, 2] - k * h) < 1e-9)[0] for k in stations}
    while any(t is None for t in stations.values()) and loop.t < 2 * n * h / c:
        v_full = loop.step()
        for k in stations:
            if stations[k] is None and v_full[node_at[k], 2].mean() >= 0.5 * v_in:
                stations[k] = loop.t
    # speed from the difference of arrival times (start-up transient cancels)
    c_num = (150 - 50) * h / (stations[150] - stations[50])
    assert c_num == pytest.approx(c, rel=0.02)
    # half-amplitude arrival of a step front in a lumped-mass chain: within 2 elements
    assert abs(stations[150] - 150 * h / c) < 2.0 * h / c


@pytest.mark.parametrize("ihq", [4, 0])
def test_elastic_free_vibration_conserves_energy(ihq):
    x0, conn = block_mesh((3, 3, 6), (6.0, 6.0, 12.0))
    x0 = distort(x0, 0.2, seed=2)
    qm = 0.05 if ihq == 4 else 0.0
    v0 = initial_velocity(x0)
    loop = EngineRun(make(x0, conn, MaterialDef(1, "elastic", 1e-6, {"E": 0.01, "PR": 0.3}),
                          v0=v0, ihq=max(ihq, 1), qm=qm, q1=0.0, q2=0.0))
    rt = group(loop)
    e0 = loop.kinetic(v0)
    # several periods of the lowest modes (the engine's step is the volumetric factor
    # sqrt((1 - nu) / (1 + nu)) = 0.73 of TSSFAC L/c: 4,100 cycles)
    energies, ie_max, _ = energy_history(loop, rt, 4100)
    assert ie_max > 0.1 * e0  # energy really went through the springs
    assert np.abs(energies - e0).max() < 0.01 * e0


def test_rubber_free_vibration_conserves_energy():
    x0, conn = block_mesh((2, 2, 4), (6.0, 6.0, 12.0))
    mat = MaterialDef(2, "rubber181", 1e-6, {"KM": 0.005, "MU": 0.0, "SGL": 1.0, "SW": 1.0,
                                             "ST": 1.0, "LCID": 4})
    curves = {4: Curve(4, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}
    v0 = 20.0 * initial_velocity(x0)  # large strains and rotations
    # nearly incompressible (KM / G0 = 30) on a coarse free mesh: the exact stability
    # limit is about 0.83 L/c (see docs/elements.md); the engine's step rule (volumetric
    # factor 0.58 x TSSFAC 0.9) stays below it
    loop = EngineRun(make(x0, conn, mat, curves, v0=v0, ihq=4, qm=0.05, q1=0.0, q2=0.0))
    rt = group(loop)
    e0 = loop.kinetic(v0)
    energies, ie_max, _ = energy_history(loop, rt, 4000)
    assert ie_max > 0.1 * e0  # energy really went through the material
    assert np.abs(energies - e0).max() < 0.01 * e0


def test_mu_damping_dissipates():
    x0, conn = block_mesh((2, 2, 4), (6.0, 6.0, 12.0))
    curves = {4: Curve(4, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}
    mat = MaterialDef(2, "rubber181", 1e-6, {"KM": 0.005, "MU": 0.3, "SGL": 1.0, "SW": 1.0,
                                             "ST": 1.0, "LCID": 4})
    v0 = 20.0 * initial_velocity(x0)
    loop = EngineRun(make(x0, conn, mat, curves, v0=v0, ihq=4, qm=0.05, q1=0.0, q2=0.0))
    rt = group(loop)
    e0 = loop.kinetic(v0)
    for _ in range(4000):
        v_full = loop.step()
    total = loop.kinetic(v_full) + rt.internal_energy + rt.hourglass_energy
    # internal energy includes the dissipated work, so the balance still holds ...
    assert total == pytest.approx(e0, rel=0.01)
    # ... while the mechanical energy left is clearly smaller than without damping
    assert loop.kinetic(v_full) < 0.9 * e0


def test_viscous_hourglass_energy_non_negative():
    x0, conn = block_mesh((3, 3, 3), (3.0, 3.0, 3.0))
    x0 = distort(x0, 0.2, seed=5)
    rng = np.random.default_rng(1)
    v0 = rng.normal(scale=0.05, size=x0.shape)  # excites hourglass modes
    loop = EngineRun(make(x0, conn, MaterialDef(1, "elastic", 1e-6, {"E": 0.01, "PR": 0.3}),
                          v0=v0, ihq=2, qm=0.1))
    rt = group(loop)
    history = []
    for _ in range(300):
        loop.step()
        history.append(rt.hourglass_energy)
    history = np.array(history)
    assert history[-1] > 0.1 * loop.kinetic(v0)
    assert np.all(history >= 0.0)


@pytest.mark.parametrize("case", ["elastic-viscous", "elastic-stiffness", "elastic-assumed-strain",
                                  "rubber", "rubber-assumed-strain"])
def test_energy_accounting_matches_central_difference_work(case):
    """Internal + hourglass energy is the scheme's own work of the element forces.

    With a constant step the scheme conserves KE(v^{N+1/2}) - dt/2 f^N.v^{N+1/2} + W^N
    exactly; random velocities, bulk viscosity, hourglass control and damping all on.
    """
    x0, conn = block_mesh((3, 3, 3), (3.0, 3.0, 3.0))
    x0 = distort(x0, 0.2, seed=6)
    if case.startswith("rubber"):
        mat = MaterialDef(2, "rubber181", 1e-6, {"KM": 0.005, "MU": 0.2, "G": 1e-4,
                                                 "SIGF": 1e-5, "SGL": 1.0, "SW": 1.0,
                                                 "ST": 1.0, "LCID": 4})
        curves = {4: Curve(4, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}
        hg = {"ihq": 6, "qm": 1.0} if case.endswith("assumed-strain") else {"ihq": 1, "qm": 0.1}
    else:
        mat = MaterialDef(1, "elastic", 1e-6, {"E": 0.01, "PR": 0.3})
        ihq = {"elastic-viscous": 2, "elastic-stiffness": 5, "elastic-assumed-strain": 6}[case]
        curves, hg = {}, {"ihq": ihq, "qm": 1.0 if ihq == 6 else 0.1}
    rng = np.random.default_rng(3)
    v0 = rng.normal(scale=0.2, size=x0.shape)
    # the step: half the critical step at rest (a constant step, the invariant is exact)
    at_rest = EngineRun(make(x0, conn, mat, curves, **hg))
    dt = 0.5 * at_rest.state.dt_next / at_rest.plan.tssfac
    loop = EngineRun(make(x0, conn, mat, curves, v0=v0, **hg), dt=dt)
    rt = group(loop)
    i0 = discrete_invariant(loop, dt)
    inv = []
    for _ in range(400):
        loop.step()
        inv.append(discrete_invariant(loop, dt))
    assert rt.internal_energy > 0.0 and rt.hourglass_energy > 0.0
    np.testing.assert_allclose(inv, i0, rtol=1e-9)
