"""Fully integrated, selectively reduced hexahedron (*SECTION_SOLID ELFORM 2).

Verified against exact properties and solutions (docs/elements.md, "Fully
integrated hexahedron"):

* a distorted element has exactly six zero-energy modes (rigid motion), where the
  one-point element without hourglass control has eighteen;
* patch test: a distorted mesh under uniform deformation (elastic and MAT_181)
  has the one-point element's uniform stress in every element and no force on
  its interior nodes;
* a cantilever under an end load deflects as Euler-Bernoulli, nearly
  incompressible too (no volumetric locking);
* a rigid rotation of a pre-stressed element rotates its stress, with
  self-equilibrated forces;
* free vibration on the engine's cycle and step conserves energy (elastic and
  MAT_181), the energy is the scheme's own work of the element forces, and
  there is no hourglass energy;
* a deck with ELFORM 2 runs as such (ELFORM -1 / -2 with a warning), through
  ``check`` and ``run``, and its restart gives the uninterrupted run.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from hollowbody.cli.main import main as cli_main
from hollowbody.elements.hex8_full_kernels import gauss_gradients
from hollowbody.elements.hex8_kinematics import hex8_gradients
from hollowbody.elements.solid_group import SolidGroupRuntime
from hollowbody.mesh import block_mesh, distort
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, SolidGroup
from hollowbody.testing.engine import EngineRun
from hollowbody.testing.models import PartSpec, assemble_model
from hollowbody.testing.solids import energy_history, initial_velocity, rot_axis, stiffness

E_MOD = 0.2  # GPa
MUSCLE_STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                          0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                       0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])
RUBBER = MaterialDef(2, "rubber181", 1e-6, {"KM": 0.005, "MU": 0.0, "SGL": 1.0, "SW": 1.0,
                                            "ST": 1.0, "LCID": 4})
RUBBER_CURVES = {4: Curve(4, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}
#: MAT_181 with damping (MU) and the frictional spring (G, SIGF): per-point history
RUBBER_FRICTION = MaterialDef(3, "rubber181", 1e-6, {"KM": 0.005, "MU": 0.2, "G": 1e-4,
                                                     "SIGF": 1e-5, "SGL": 1.0, "SW": 1.0,
                                                     "ST": 1.0, "LCID": 4})
DECKS = Path(__file__).resolve().parents[2] / "regression" / "decks"


def elastic(nu: float) -> MaterialDef:
    return MaterialDef(1, "elastic", 1e-6, {"E": E_MOD, "PR": nu})


def runtime(x0, conn, mat, elform=2, curves=None):
    g = SolidGroup(1, np.arange(len(conn)), conn)
    hg = HourglassDef(0, ihq=1, qm=0.0, q1=0.0, q2=0.0)  # no hourglass control at all
    return SolidGroupRuntime(g, mat, hg, curves or {}, x0, elform=elform)


def test_gauss_point_gradients_sum_to_the_element_volume_and_its_gradients():
    """The 2-point rule integrates the trilinear element exactly: sum_g J_g = V and
    sum_g J_g B_g = V b (b the uniform gradients); a linear field's gradient is exact
    at every point."""
    x0, conn = block_mesh((1, 1, 1), (3.0, 2.0, 1.5))
    x0 = distort(x0, 0.25, seed=11)
    b0g, jac = gauss_gradients(conn, x0)
    b, vol = hex8_gradients(conn, x0)
    assert jac.sum() == pytest.approx(vol[0], rel=1e-13)
    np.testing.assert_allclose((jac[0][:, None, None] * b0g).sum(axis=0), vol[0] * b[0],
                               atol=1e-13 * vol[0] * np.abs(b).max())
    a = np.random.default_rng(2).normal(size=(3, 3))
    u = x0 @ a.T
    for p in range(8):
        np.testing.assert_allclose(u[conn[0]].T @ b0g[p], a, atol=1e-13)


@pytest.mark.parametrize("nu", [0.3, 0.4999])
def test_only_rigid_modes_have_zero_energy(nu):
    """Eigenvalues of K of a distorted element without hourglass control: ELFORM 2 has six
    zeros (rigid motion); the one-point element has eighteen (rigid + 12 hourglass).
    "Zero": below 1e-7 of the largest; the finite-difference stiffness leaves up to 4e-9
    in the zero modes, the softest ELFORM 2 mode is 8e-6 at nu = 0.4999 (K / G = 5000),
    1.6e-2 at nu = 0.3."""
    x0, conn = block_mesh((1, 1, 1), (2.0, 1.5, 1.0))
    x0 = distort(x0, 0.2, seed=3)
    zero = {}
    for elform in (1, 2):
        ev = np.linalg.eigvalsh(stiffness(runtime(x0, conn, elastic(nu), elform), x0))
        zero[elform] = int((np.abs(ev) < 1e-7 * ev[-1]).sum())
    assert zero == {1: 18, 2: 6}


@pytest.mark.parametrize("law", ["elastic", "rubber", "rubber-friction"])
def test_patch_uniform_deformation_of_a_distorted_mesh(law):
    """2 x 2 x 2 distorted mesh, affine motion (stretch, shear, rotation) over 30 steps:
    every element's stress is the one-point element's (exact for uniform F) to 1e-9
    (with MAT_181's frictional stress, point by point), and the force on the interior
    node vanishes (1e-9 of the largest nodal force; not with MAT_181's damping, whose
    viscosity is proportional to the element's size, as LS-DYNA defines it)."""
    x0, conn = block_mesh((2, 2, 2), (4.0, 3.0, 2.0))
    x0 = distort(x0, 0.25, seed=4)
    mat, curves = {"elastic": (elastic(0.3), {}), "rubber": (RUBBER, RUBBER_CURVES),
                   "rubber-friction": (RUBBER_FRICTION, RUBBER_CURVES)}[law]
    full = runtime(x0, conn, mat, 2, curves)
    one = runtime(x0, conn, mat, 1, curves)
    grad = np.array([[-0.4, 0.3, 0.1], [0.2, 0.1, -0.5], [0.0, 0.6, 0.2]])  # 1/ms
    dt = 2e-3
    x = x0.copy()
    f = np.zeros_like(x)
    for _ in range(30):
        v = x @ grad.T + np.array([0.1, 0.0, -0.2])
        x = x + dt * v
        f[:] = 0.0
        full.add_forces(x, v, dt, f)
        one.add_forces(x, v, dt, np.zeros_like(x))
    smax = np.abs(one.stress).max()
    assert smax > 0.0
    np.testing.assert_allclose(full.stress, one.stress, atol=1e-9 * smax)
    np.testing.assert_allclose(full.stress_gp, np.repeat(one.stress, 8, axis=0),
                               atol=1e-9 * smax)
    if law == "rubber-friction":  # the frictional stress of every point is the element's
        fmax = np.abs(one._fric).max()
        assert fmax > 0.0
        np.testing.assert_allclose(full._fric, np.repeat(one._fric, 8, axis=0),
                                   atol=1e-9 * fmax)
        return  # MAT_181's damping scales with the element's size: not a uniform stress
    inner = np.nonzero(np.bincount(conn.ravel()) == 8)[0]
    assert inner.size == 1  # the centre node of the 2 x 2 x 2 mesh
    assert np.abs(f[inner]).max() < 1e-9 * np.abs(f).max()


def cantilever_tip_ratio(nu: float, n: int, m: int) -> float:
    """Static tip deflection / Euler-Bernoulli P L^3 / (3 E I) of an n x m x m cantilever
    (L = 10 mm, 1 x 1 mm section, root nodes fixed, end load over the tip nodes)."""
    length, h = 10.0, 1.0
    x0, conn = block_mesh((n, m, m), (length, h, h))
    k = stiffness(runtime(x0, conn, elastic(nu)), x0)
    free = np.ones(x0.shape, dtype=bool)
    free[x0[:, 0] < 1e-9] = False
    free = free.ravel()
    p = 1e-4  # kN
    tip = x0[:, 0] > length - 1e-9
    load = np.zeros(x0.shape)
    load[tip, 1] = p / tip.sum()
    u = np.zeros(x0.size)
    u[free] = np.linalg.solve(k[np.ix_(free, free)], load.ravel()[free])
    eb = p * length**3 / (3.0 * E_MOD * h**4 / 12.0)
    return float(u.reshape(-1, 3)[tip, 1].mean() / eb)


@pytest.mark.parametrize("nu", [0.3, 0.4999])
def test_cantilever_tip_deflection_converges_to_euler_bernoulli(nu):
    """Tip deflection / Euler-Bernoulli of the cantilever, refined through the thickness:

    ======  ========  =========  =========
    nu      10x1x1    20x2x2     40x4x4
    ======  ========  =========  =========
    0.3     1.21      0.983      0.993
    0.4999  1.39      0.953      0.982
    ======  ========  =========  =========

    One element through the thickness is too soft: its pressure is constant over the
    section, so the bending strain's volumetric part goes unresisted; the 2 x 2 x 2
    deviatoric part is stiffened by parasitic shear (LS-DYNA's ELFORM 2 is known to
    be too stiff in bending at large aspect ratios). A fully integrated pressure would
    lock at nu = 0.4999 (tip ratio of order 1e-2). Asserted: 20 x 2 x 2 within 5 % (the
    mesh error), 40 x 4 x 4 within 2 % and closer than 20 x 2 x 2 (what is left is the
    clamped root, +2 % stiffer when nearly incompressible, and Timoshenko's shear
    deflection, +0.8 % at nu = 0.3, neither in the reference).
    """
    coarse = cantilever_tip_ratio(nu, 20, 2)
    fine = cantilever_tip_ratio(nu, 40, 4)
    assert coarse == pytest.approx(1.0, abs=0.05)
    assert fine == pytest.approx(1.0, abs=0.02)
    assert abs(fine - 1.0) < abs(coarse - 1.0)


def test_rigid_rotation_of_a_prestressed_element_rotates_its_stress():
    """Pre-stress at every point, then a rigid rotation by 90 degrees about a skew axis in
    90 steps: the points' stresses come out rotated (1e-12), the nodal forces have no
    resultant and no moment."""
    x0, conn = block_mesh((1, 1, 1), (2.0, 1.0, 1.5))
    x0 = distort(x0, 0.15, seed=2)
    rt = runtime(x0, conn, elastic(0.3))
    sig0 = np.array([0.3, -0.1, 0.2, 0.05, -0.02, 0.04]) * 1e-3
    rt.stress_gp[:] = sig0
    axis = np.array([1.0, 2.0, -0.5])
    n, dt = 90, 1e-3
    r_step = rot_axis(axis, 0.5 * math.pi / n)
    x = x0.copy()
    centre = x.mean(axis=0)
    f = np.zeros_like(x)
    for _ in range(n):
        x_new = centre + (x - centre) @ r_step.T
        v = (x_new - x) / dt
        x = x_new
        f[:] = 0.0
        rt.add_forces(x, v, dt, f)
    r = rot_axis(axis, 0.5 * math.pi)
    s = sig0
    m = np.array([[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]])
    mr = r @ m @ r.T
    expected = np.array([mr[0, 0], mr[1, 1], mr[2, 2], mr[0, 1], mr[1, 2], mr[2, 0]])
    np.testing.assert_allclose(rt.stress_gp, np.tile(expected, (8, 1)),
                               atol=1e-12 * np.abs(s).max())
    np.testing.assert_allclose(rt.stress[0], expected, atol=1e-12 * np.abs(s).max())
    fmax = np.abs(f).max()
    assert fmax > 0.0
    np.testing.assert_allclose(f.sum(axis=0), 0.0, atol=1e-12 * fmax)
    moment = np.cross(x - centre, f).sum(axis=0)
    np.testing.assert_allclose(moment, 0.0, atol=1e-12 * fmax * np.abs(x - centre).max())


def make(x0, conn, mat: MaterialDef, curves=None, v0=None):
    """A one-part Model of ELFORM 2 hexahedra, no hourglass card, no bulk viscosity."""
    model = assemble_model([PartSpec(1, x0, conn, kind=mat.kind, params=dict(mat.params),
                                     density=mat.density)])
    model.sections[1].elform = 2
    model.hourglass[1] = HourglassDef(1, ihq=1, qm=0.1, q1=0.0, q2=0.0)
    model.parts[1].hgid = 1
    model.curves.update(curves or {})
    if v0 is not None:
        model.node_v0 = np.asarray(v0, dtype=np.float64).copy()
    return model


@pytest.mark.parametrize("law", ["elastic", "rubber"])
def test_free_vibration_on_the_engine_step_conserves_energy(law):
    """Free distorted block, random-free smooth initial velocities (rubber: 20x, large
    strains and rotations), 4,000 cycles at the engine's own step (with the one-point
    element's volumetric step factor): kinetic + internal energy within 1 % of the
    initial kinetic energy (the scheme's second-order error; an unstable step grows
    without bound), and energy through the material."""
    if law == "elastic":
        x0, conn = block_mesh((3, 3, 6), (6.0, 6.0, 12.0))
        x0 = distort(x0, 0.2, seed=2)
        mat, curves, v0 = MaterialDef(1, "elastic", 1e-6, {"E": 0.01, "PR": 0.3}), {}, None
        v0 = initial_velocity(x0)
    else:
        x0, conn = block_mesh((2, 2, 4), (6.0, 6.0, 12.0))
        mat, curves = RUBBER, RUBBER_CURVES
        v0 = 20.0 * initial_velocity(x0)
    loop = EngineRun(make(x0, conn, mat, curves, v0=v0))
    (rt,) = loop.plan.elements
    assert rt.elform == 2
    e0 = loop.kinetic(v0)
    energies, ie_max, _ = energy_history(loop, rt, 4000)
    assert ie_max > 0.1 * e0
    assert np.abs(energies - e0).max() < 0.01 * e0


def test_energy_is_the_central_difference_work_of_the_element_forces():
    """With a constant step the scheme conserves KE(v^{N+1/2}) - dt/2 f^N.v^{N+1/2} + W^N
    exactly (W the element energies); random velocities, MAT_181 with damping and
    friction, bulk viscosity on."""
    x0, conn = block_mesh((3, 3, 3), (3.0, 3.0, 3.0))
    x0 = distort(x0, 0.2, seed=6)
    mat = MaterialDef(2, "rubber181", 1e-6, {"KM": 0.005, "MU": 0.2, "G": 1e-4, "SIGF": 1e-5,
                                             "SGL": 1.0, "SW": 1.0, "ST": 1.0, "LCID": 4})
    v0 = np.random.default_rng(3).normal(scale=0.2, size=x0.shape)

    def model(v=None):
        m = make(x0, conn, mat, RUBBER_CURVES, v0=v)
        m.hourglass[1].q1, m.hourglass[1].q2 = 1.5, 0.06
        return m

    at_rest = EngineRun(model())
    dt = 0.5 * at_rest.state.dt_next / at_rest.plan.tssfac
    loop = EngineRun(model(v0), dt=dt)
    (rt,) = loop.plan.elements
    s = loop.state

    def invariant():
        v = s.v + (0.5 * dt if s.cycle == 0 else dt) * s.f * s.inv_m[:, None]
        return (loop.kinetic(v) - 0.5 * dt * float((s.f * v).sum()) + rt.internal_energy
                + rt.hourglass_energy)

    i0 = invariant()
    values = []
    for _ in range(300):
        loop.step()
        values.append(invariant())
    assert rt.internal_energy > 0.0
    np.testing.assert_allclose(values, i0, rtol=1e-9)


def deck(tmp_path: Path, elform: int) -> Path:
    """The hand-check deck with its solid section set to ``elform`` and an hourglass
    velocity field on its two hexahedra."""
    text = (DECKS / "hand_check.k").read_text()
    old = "*SECTION_SOLID\n         1         1\n"
    assert old in text
    text = text.replace(old, f"*SECTION_SOLID\n         1{elform:10d}\n", 1)
    pattern = (1, -1, 1, -1, 1, -1, 1, -1)  # xi * eta at the nodes N1..N8
    lines = [f"{n:10d}{0.0:10.3f}{0.0:10.3f}{0.5 * h:10.3f}"
             for first in (1, 11) for n, h in zip(range(first, first + 8), pattern)]
    text = text.replace("*END", "*INITIAL_VELOCITY_NODE\n" + "\n".join(lines) + "\n*END")
    path = tmp_path / f"elform{elform}.k"
    path.write_text(text)
    return path


def test_deck_with_elform_2_is_checked_and_run(tmp_path, capsys):
    """An hourglass velocity field that the one-point element only holds by its hourglass
    control: with ELFORM 2 the element's own stress holds it (energy through the
    elements, balanced)."""
    path = deck(tmp_path, 2)
    assert cli_main(["check", str(path), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["can_run"], s["problems"]
    assert not [w for w in s["warnings"] if "ELFORM" in w]
    out = tmp_path / "run"
    assert cli_main(["run", str(path), "--out", str(out), "--quiet", "--no-vtk",
                     "--end-time", "0.5"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "normal termination"
    assert summary["energy_ratio"] == pytest.approx(1.0, abs=0.02)
    e = summary["energies_J"]
    assert e["internal"] > 0.1 * (e["kinetic"] + e["internal"])


@pytest.mark.parametrize(("elform", "runs_as"), [(-1, 2), (-2, 2), (13, 1)])
def test_other_elforms_warn_and_say_how_they_run(elform, runs_as, tmp_path, capsys):
    assert cli_main(["check", str(deck(tmp_path, elform)), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["can_run"]
    assert [w for w in s["warnings"] if f"ELFORM {elform}" in w and f"ELFORM {runs_as}" in w]


def test_restart_of_an_elform_2_run_equals_the_uninterrupted_run(tmp_path):
    """Dumps every 100 cycles; resumed from the first, the run writes the same energy
    history to the last digit (the points' stresses and history are saved state)."""
    path = deck(tmp_path, 2)
    out = tmp_path / "run"
    args = ["--out", str(out), "--quiet", "--no-vtk", "--end-time", "0.5"]
    assert cli_main(["run", str(path), *args, "--dump-cycles", "100"]) == 0
    first = (out / "glstat.csv").read_text()
    assert cli_main(["run", str(path), *args, "--restart", str(out / "d3dump01"),
                     "--dump-cycles", "0"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["resumed_from"]["cycle"] == 100
    assert (out / "glstat.csv").read_text() == first


def reference_stiffness(x: np.ndarray, g_mod: float, k_mod: float) -> np.ndarray:
    """Small-strain K (24, 24) of the selectively reduced element, written independently:
    sum_g J_g B_g^T D_dev B_g + V K bbar bbar^T (Voigt, engineering shear), with the
    shape-function derivatives at the 2 x 2 x 2 points from scratch; x (8, 3) in the
    element's node order."""
    xi = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                   [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
    d_dev = np.diag([2.0, 2.0, 2.0, 1.0, 1.0, 1.0]) * g_mod
    m = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    d_dev -= 2.0 * g_mod / 3.0 * np.outer(m, m)
    k_dev = np.zeros((24, 24))
    vbar = np.zeros(24)
    vol = 0.0
    for pt in xi / math.sqrt(3.0):
        dn = np.empty((8, 3))
        for a in range(8):
            f = 1.0 + xi[a] * pt
            dn[a] = 0.125 * xi[a] * np.array([f[1] * f[2], f[0] * f[2], f[0] * f[1]])
        jac = x.T @ dn  # dx_i / dxi_k
        det = np.linalg.det(jac)
        b = dn @ np.linalg.inv(jac)  # dN_a / dx_j
        bm = np.zeros((6, 24))
        for a in range(8):
            bx, by, bz = b[a]
            c = 3 * a
            bm[0, c], bm[1, c + 1], bm[2, c + 2] = bx, by, bz
            bm[3, c], bm[3, c + 1] = by, bx
            bm[4, c + 1], bm[4, c + 2] = bz, by
            bm[5, c], bm[5, c + 2] = bz, bx
        k_dev += det * bm.T @ d_dev @ bm
        vbar += det * b.ravel()
        vol += det
    return k_dev + k_mod / vol * np.outer(vbar, vbar)


@pytest.mark.parametrize("nu", [0.3, 0.4999])
def test_linear_stiffness_of_a_distorted_element_is_the_selectively_reduced_one(nu):
    """The element's small-strain stiffness (finite differences of its forces) equals an
    independent reference of the selectively reduced element: deviatoric part at the
    eight points weighted by J_g, pressure with the element's mean gradients (1e-6: the
    geometric non-linearity of the finite differences)."""
    x0, conn = block_mesh((1, 1, 1), (2.0, 1.5, 1.0))
    x0 = distort(x0, 0.25, seed=7)
    k = stiffness(runtime(x0, conn, elastic(nu)), x0)
    g_mod = E_MOD / (2.0 * (1.0 + nu))
    k_mod = E_MOD / (3.0 * (1.0 - 2.0 * nu))
    order = np.ravel(3 * conn[0][:, None] + np.arange(3))  # element dofs in k's numbering
    ref = reference_stiffness(x0[conn[0]], g_mod, k_mod)
    np.testing.assert_allclose(k[np.ix_(order, order)], ref, atol=1e-6 * np.abs(ref).max())


def test_erosion_clears_the_points_of_the_eroded_element():
    """Erosion of an ELFORM 2 element: its points' stresses and history are zeroed, its
    step is infinite, the other element keeps all of its own."""
    x0, conn = block_mesh((2, 1, 1), (2.0, 1.0, 1.0))
    rt = runtime(x0, conn, RUBBER_FRICTION, 2, RUBBER_CURVES)
    rng = np.random.default_rng(9)
    v = rng.normal(scale=0.5, size=x0.shape)
    x = x0.copy()
    for _ in range(5):
        x = x + 1e-3 * v
        rt.add_forces(x, v, 1e-3, np.zeros_like(x))
    kept = rt._fric[8:].copy()
    assert np.abs(kept).max() > 0.0 and np.abs(rt._fric[:8]).max() > 0.0
    rt.erode(np.array([0]))
    assert not rt.alive[0] and rt.alive[1]
    assert np.all(rt.stress_gp[:8] == 0.0) and np.all(rt._fric[:8] == 0.0)
    np.testing.assert_array_equal(rt._fric[8:], kept)
    assert rt.dt_elem[0] == np.inf and np.isfinite(rt.dt_elem[1])


def test_an_inverted_point_counts_as_a_negative_volume():
    """A corner pushed inwards until the Gauss point next to it inverts while the element's
    volume is still positive: the element reports a volume <= 0 (so the run ends, or
    erosion deletes it), gives no force, and is named as the first negative one."""
    x0, conn = block_mesh((1, 1, 1), (1.0, 1.0, 1.0))
    corner = int(np.argmax(x0.sum(axis=1)))  # the node at (1, 1, 1)
    x = x0.copy()
    x[corner] = (0.02, 0.02, 0.02)
    b0g, jac = gauss_gradients(conn, x)
    _, vol = hex8_gradients(conn, x)
    assert vol[0] > 0.0 and jac.min() <= 0.0  # the case is what it claims
    rt = runtime(x0, conn, elastic(0.3))
    f = np.zeros_like(x)
    _, _, neg = rt.add_forces(x, (x - x0) / 1e-3, 1e-3, f)
    assert neg == 0
    assert rt.volume[0] <= 0.0
    assert np.all(f == 0.0)


def test_an_element_inverted_at_a_point_from_the_start_is_refused():
    x0, conn = block_mesh((1, 1, 1), (1.0, 1.0, 1.0))
    corner = int(np.argmax(x0.sum(axis=1)))
    x0 = x0.copy()
    x0[corner] = (0.02, 0.02, 0.02)
    from hollowbody.errors import DeckError

    with pytest.raises(DeckError, match="Gauss point"):
        runtime(x0, conn, elastic(0.3))
    runtime(x0, conn, elastic(0.3), elform=1)  # the one-point element only needs V > 0


def test_a_restart_file_of_another_elform_is_refused(tmp_path, capsys):
    """The model's fingerprint holds its fully integrated sections: a dump written with
    ELFORM 1 is not resumed by the same deck with ELFORM 2 (its state has other shapes)."""
    one, two = deck(tmp_path, 1), deck(tmp_path, 2)
    out = tmp_path / "run"
    assert cli_main(["run", str(one), "--out", str(out), "--quiet", "--no-vtk",
                     "--end-time", "0.25", "--dump-at-end"]) == 0
    code = cli_main(["run", str(two), "--out", str(out), "--quiet", "--no-vtk",
                     "--end-time", "0.5", "--restart"])
    assert code == 2
    assert "another model" in capsys.readouterr().err
