"""Selective mass scaling (*CONTROL_TIMESTEP DT2MS < 0) and the rotational
inertia of thickening shells (*CONTROL_SHELL ISTUPD 1).

Checks: the added mass against the closed form m ((T / dt_e)^2 - 1) for
elements of equal step; the run's step held at TSSFAC T; energy balance with
the kinetic energy of the added mass counted; ENDMAS ends the run; a
thickened shell's nodal rotational inertia follows m t^2 / 12.
"""

import json
import math

import numpy as np
import pytest
from solver_decks import crushed_strip, cube_and_plate

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.elements.shell_group import ShellGroupRuntime
from hollowbody.io.results.history import read_history
from hollowbody.model.model import HourglassDef, MaterialDef, SectionDef, ShellGroup
from hollowbody.solver.mass_scaling import MassScaling

TSSFAC = 0.9


def _run(deck, path, **kw):
    model = build_model(deck)
    return model, run_model(model, path, vtk=False, **kw)


def _strip_step() -> float:
    """Critical step of the strip's 5 mm squares (E 0.1 GPa, nu 0.3, rho 1e-6)."""
    return 5.0 / math.sqrt(0.1 / (1.0e-6 * (1 - 0.3 ** 2)))


def test_uniform_shells_get_the_closed_form_mass_and_step(tmp_path):
    # no crush: three equal squares, all below the target 2 dt_e: each element's
    # mass x 4 at t = 0, added = 3 x the strip's mass; the step is TSSFAC T
    target = 2.0 * _strip_step()
    model, res = _run(crushed_strip(crush=0.0, end=0.2, dt2ms=-target), tmp_path)
    assert res.status == "normal termination"
    ms = res.summary["mass_scaling"]
    strip_mass = 3 * 25.0 * 1.0 * 1.0e-6
    assert ms["added_mass_kg"] == pytest.approx(3.0 * strip_mass, rel=1e-9)
    assert ms["added_mass_percent"] == pytest.approx(300.0, rel=1e-9)
    assert ms["added_mass_by_part_kg"] == {"8": pytest.approx(3.0 * strip_mass, rel=1e-9)}
    assert res.summary["dt_initial_ms"] == pytest.approx(TSSFAC * target, rel=1e-9)
    dt = read_history(tmp_path / "glstat.csv")["dt [ms]"][1:-1]
    assert np.allclose(dt, TSSFAC * target, rtol=1e-9)


def _with_dt2ms(deck, target: float):
    for item in deck.items:
        if type(item).__name__ == "ControlTimestep":
            item.dt2ms = -target
    return deck


def test_uniform_solids_get_the_closed_form_mass(tmp_path):
    # the plate 50 mm away never touches the cube: only the t = 0 scaling acts
    _, ref = _run(cube_and_plate(e=0.1, speed=3.0, end=0.05, gap=50.0), tmp_path / "ref")
    target = 2.0 * ref.summary["dt_initial_ms"] / TSSFAC  # every hexahedron alike
    model, res = _run(_with_dt2ms(cube_and_plate(e=0.1, speed=3.0, end=0.05, gap=50.0),
                                  target), tmp_path / "ms")
    assert res.status == "normal termination"
    masses = model_part_masses(model)
    cube_mass = sum(m for pid, m in masses.items() if pid != rigid_pid(model))
    assert res.summary["mass_scaling"]["added_mass_kg"] == pytest.approx(3.0 * cube_mass,
                                                                         rel=1e-9)
    assert res.summary["dt_initial_ms"] == pytest.approx(TSSFAC * target, rel=1e-9)


def test_mass_scaled_impact_balances_energy(tmp_path):
    _, ref = _run(cube_and_plate(e=0.1, speed=3.0, end=2.0), tmp_path / "ref")
    target = 2.0 * ref.summary["dt_initial_ms"] / TSSFAC
    _, res = _run(_with_dt2ms(cube_and_plate(e=0.1, speed=3.0, end=2.0), target),
                  tmp_path / "ms")
    assert res.status == "normal termination"
    # tolerance 3 %: the unscaled run stays within 2.0 %, a cube of 4x the density
    # (the same masses and step, no mass scaling) within 2.2 % (penalty contact error
    # grows with the step)
    ratio = read_history(tmp_path / "ms" / "glstat.csv")["energy_ratio"]
    assert np.all(np.abs(ratio - 1.0) < 0.03), ratio.max()
    assert res.cycles < 0.6 * ref.cycles  # the step is at least twice the unscaled one


def model_part_masses(model) -> dict[int, float]:
    from hollowbody.model.mass import lumped_node_mass

    return lumped_node_mass(model)[1]


def rigid_pid(model) -> int:
    return next(pid for pid in model.parts if model.material_of(pid).kind == "rigid")


def test_crushed_strip_keeps_its_step_and_counts_the_added_energy(tmp_path):
    target = 0.5 * _strip_step()
    _, ref = _run(crushed_strip(crush=10.0, end=1.0), tmp_path / "ref")
    dt_ref = read_history(tmp_path / "ref" / "glstat.csv")["dt [ms]"][1:-1]
    assert dt_ref.min() < 0.5 * TSSFAC * target  # without scaling the step collapses
    _, res = _run(crushed_strip(crush=10.0, end=1.0, dt2ms=-target), tmp_path / "ms")
    assert res.status == "normal termination"
    g = read_history(tmp_path / "ms" / "glstat.csv")
    assert g["dt [ms]"][1:-1].min() >= TSSFAC * target * (1 - 1e-12)
    assert res.cycles < ref.cycles
    ms = res.summary["mass_scaling"]
    assert ms["added_mass_kg"] > 0.0 and g["added_mass [kg]"][-1] == pytest.approx(
        ms["added_mass_kg"])
    assert np.all(np.diff(g["added_mass [kg]"]) >= 0.0)  # mass is only ever added
    # the energy balance is as good as the unscaled run's (the added mass's kinetic
    # energy is counted as work of mass scaling)
    ratio_ref = read_history(tmp_path / "ref" / "glstat.csv")["energy_ratio"]
    assert np.abs(g["energy_ratio"] - 1.0).max() <= np.abs(ratio_ref - 1.0).max() + 0.02


def test_endmas_ends_the_run_naming_the_part(tmp_path):
    deck = crushed_strip(crush=10.0, end=1.0, dt2ms=-0.5 * _strip_step())
    for item in deck.items:
        if type(item).__name__ == "ControlTermination":
            item.endmas = 1.0  # 1 % of the strip's mass
    _, res = _run(deck, tmp_path)
    assert res.status == "error termination"
    assert "mass scaling added" in res.reason and "ENDMAS 1 %" in res.reason
    assert "part 8" in res.reason
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["error_part"] == 8 and s["end_time_ms"] < 1.0


def test_thickened_shell_gets_the_rotational_inertia_of_its_thickness():
    x = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], dtype=float)
    g = ShellGroup(pid=3, elem_ids=np.array([1]), conn=np.array([[0, 1, 2, 3]], np.int32),
                   thickness=np.full((1, 4), 1.0))
    mat = MaterialDef(mid=1, kind="elastic", density=1e-6, params={"E": 0.1, "PR": 0.3})
    sec = SectionDef(secid=1, kind="shell", elform=2, params={"NIP": 3})
    rt = ShellGroupRuntime(g, mat, sec, HourglassDef(hgid=0), {}, x, thickness_update=True)
    node_mass = rt.lumped_mass(4)
    inertia = rt.lumped_rotational_inertia(4)
    assert inertia == pytest.approx(node_mass * 100.0 / 4.0)  # A/4 governs at t = 1
    inv_m, inv_i = 1.0 / node_mass, 1.0 / inertia
    ms = MassScaling([rt], 0.0, node_mass, inertia, inv_m, inv_i)
    rt.thickness[:] = 1.0 + 1e-3  # thin: A/4 still governs, nothing changes
    ms.apply(np.zeros((4, 3)), np.zeros((4, 3)))
    assert inertia == pytest.approx(node_mass * 25.0)
    rt.thickness[:] = 30.0  # crushed thick: t^2/12 = 75 > A0/4 = 25
    w = np.tile([0.0, 0.1, 0.0], (4, 1))
    ms.apply(np.zeros((4, 3)), w)
    assert inertia == pytest.approx(node_mass * 75.0, rel=1e-12)
    assert inv_i == pytest.approx(1.0 / inertia, rel=1e-12)
    assert ms.total_added == 0.0  # no mass, only rotary inertia
    assert ms.work == pytest.approx(0.5 * 4 * node_mass[0] * 50.0 * 0.01, rel=1e-12)
