"""Whole runs: energy balance, momentum, and every way a run can end.

Tolerances: the energy ratio of an elastic impact stays within 2% (penalty
contact and central differences conserve energy to O(dt^2); measured
deviations are below 1%); rigid-body momentum is exact to round-off.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from solver_decks import crushed_column, crushed_strip, cube_and_plate

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.io.results.history import read_history


def _run(deck, tmp_path, **kw):
    return run_model(build_model(deck), tmp_path, vtk=False, **kw)


def test_elastic_impact_conserves_energy_and_rebounds(tmp_path):
    res = _run(cube_and_plate(e=0.1, speed=3.0, end=4.0), tmp_path)
    assert res.status == "normal termination"
    g = read_history(tmp_path / "glstat.csv")
    ratio = g["energy_ratio"]
    assert np.all(np.abs(ratio - 1.0) < 0.02), ratio.min()
    rb = read_history(tmp_path / "rbdout.csv")
    vz = rb["vz [mm/ms]"]
    assert vz[0] == pytest.approx(-3.0)
    assert vz.max() > 0.5  # the plate bounced back off the elastic cube
    assert res.summary["cycles"] > 0


def test_free_rigid_body_keeps_momentum(tmp_path):
    deck = cube_and_plate(speed=2.0, end=0.5, gap=50.0)  # the plate never reaches the cube
    res = _run(deck, tmp_path)
    assert res.status == "normal termination"
    rb = read_history(tmp_path / "rbdout.csv")
    assert np.allclose(rb["vz [mm/ms]"], -2.0, rtol=0, atol=1e-12)
    assert rb["uz [mm]"][-1] == pytest.approx(-2.0 * 0.5, rel=1e-9)


def test_prescribed_rigid_motion_work_balances_the_energy(tmp_path):
    """A rigid plate driven at constant speed (*BOUNDARY_PRESCRIBED_MOTION_RIGID)
    compresses an elastic cube: the reaction's work enters the external work, so
    the energy ratio stays within 2 % (same tolerance as the free impact) while
    the work done exceeds the plate's initial kinetic energy."""
    from hollowbody.io.keyword import DefineCurve, PrescribedMotionRigid

    deck = cube_and_plate(e=0.1, speed=3.0, end=1.5)
    deck.add(DefineCurve(lcid=9, points=[[0.0, -3.0], [10.0, -3.0]]))
    deck.add(PrescribedMotionRigid(pid=2, dof=3, vad=0, lcid=9))
    res = _run(deck, tmp_path)
    assert res.status == "normal termination"
    g = read_history(tmp_path / "glstat.csv")
    assert g["external_work [J]"][-1] > 1.5 * g["kinetic [J]"][0]
    assert np.all(np.abs(g["energy_ratio"] - 1.0) < 0.02), g["energy_ratio"].max()
    rb = read_history(tmp_path / "rbdout.csv")
    assert np.allclose(rb["vz [mm/ms]"][1:], -3.0)


def test_prescribed_velocity_from_t0_is_an_initial_condition(tmp_path):
    """A plate at rest in the deck, prescribed to move at 3 mm/ms from t = 0: the
    velocity holds from the start (in the initial kinetic energy) instead of a
    jump in the first cycle, whose reaction work M V^2 against a kinetic energy
    of 1/2 M V^2 made the energy ratio 0.5. Ratio within 2 % of 1."""
    from hollowbody.io.keyword import DefineCurve, PrescribedMotionRigid

    deck = cube_and_plate(e=0.1, speed=0.0, end=1.0)
    deck.add(DefineCurve(lcid=9, points=[[0.0, -3.0], [10.0, -3.0]]))
    deck.add(PrescribedMotionRigid(pid=2, dof=3, vad=0, lcid=9))
    assert _run(deck, tmp_path).status == "normal termination"
    g = read_history(tmp_path / "glstat.csv")
    ratio = g["energy_ratio"][1:]
    assert np.all(np.abs(ratio - 1.0) < 0.02), (ratio.min(), ratio.max())


def test_negative_volume_is_an_error_termination_with_outputs_kept(tmp_path):
    """The top element is driven through its own height: it ends with a negative volume,
    or, when each step (which shrinks with the element's volume) leaves some volume, with
    the step collapsed to zero; either names the element and part."""
    res = _run(crushed_column(crush=30.0, end=1.0), tmp_path)
    assert res.status == "error termination"
    assert ("negative volume in solid element" in res.reason
            or "time step collapsed to zero" in res.reason), res.reason
    assert "part 7)" in res.reason
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["status"] == "error termination"
    assert s["error_part"] == 7 and s["error_element"] in (1, 2, 3)
    # the column (15 mm) cannot be crushed by more than its height: t < 15/30 ms
    assert 5.0 / 30.0 <= s["end_time_ms"] <= 15.0 / 30.0
    assert len(read_history(tmp_path / "glstat.csv")["time [ms]"]) > 2
    assert "error termination" in (tmp_path / "messages.log").read_text()


def test_erode_deletes_elements_and_goes_on(tmp_path):
    res = _run(crushed_column(crush=30.0, end=1.0, erode=1, dtmin=0.05), tmp_path)
    assert res.summary["eroded_elements"] >= 1
    assert res.summary["end_time_ms"] > 0.45  # went on past the first deletion
    assert "erosion: solid element" in (tmp_path / "messages.log").read_text()


def test_shell_collapse_is_an_error_termination(tmp_path):
    """A shell strip crushed in its own plane: the first element whose area falls
    below 1 % of its initial area ends the run, named, with its part and time.
    The strip is 15 mm high and crushed at 30 mm/ms, so some element must have
    collapsed before t = 0.5 ms; with the top nodes prescribed, the top element
    alone cannot reach 1 % before its top has moved 0.99 h (t >= 0.165 ms)."""
    res = _run(crushed_strip(crush=30.0, end=1.0), tmp_path)
    assert res.status == "error termination"
    assert "shell element" in res.reason and "collapsed in its plane" in res.reason
    assert "(part 8)" in res.reason
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["error_part"] == 8 and s["error_element"] in (1, 2, 3)
    assert s["end_time_ms"] <= 0.5
    assert len(read_history(tmp_path / "glstat.csv")["time [ms]"]) > 2


def test_erode_deletes_collapsed_shells_and_goes_on(tmp_path):
    res = _run(crushed_strip(crush=30.0, end=1.0, erode=1), tmp_path)
    assert res.summary["eroded_elements"] >= 1
    log = (tmp_path / "messages.log").read_text()
    assert "erosion: shell element" in log and "collapsed in its plane" in log
    assert res.summary["end_time_ms"] == pytest.approx(1.0)


def test_dtmin_ends_the_run(tmp_path):
    deck = crushed_column(crush=30.0, end=1.0, dtmin=0.5)
    res = _run(deck, tmp_path)
    assert res.status == "error termination"
    assert "DTMIN" in res.reason


def test_user_interrupt_keeps_outputs(tmp_path, monkeypatch):
    from hollowbody.solver import explicit

    calls = {"n": 0}
    original = explicit.step

    def interrupted(model, plan, state, dt):
        calls["n"] += 1
        if calls["n"] == 20:
            raise KeyboardInterrupt
        return original(model, plan, state, dt)

    monkeypatch.setattr(explicit, "step", interrupted)
    res = _run(cube_and_plate(end=2.0), tmp_path)
    assert res.status == "user interrupt"
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["status"] == "user interrupt" and s["cycles"] == 19


def test_non_finite_force_names_node_element_and_part(tmp_path, monkeypatch):
    from hollowbody.elements.solid_group import SolidGroupRuntime

    orig = SolidGroupRuntime.add_forces
    calls = {"n": 0}

    def sick(self, x, v, dt, f):
        out = orig(self, x, v, dt, f)
        calls["n"] += 1
        if calls["n"] == 5:  # element 3 of the cube breaks down on the 5th call
            i = 2
            self.stress[i] = np.nan
            f[self.conn[i, 0]] = np.nan
        return out

    monkeypatch.setattr(SolidGroupRuntime, "add_forces", sick)
    model = build_model(cube_and_plate(e=0.1, speed=3.0, end=1.0))
    res = run_model(model, tmp_path, vtk=False)
    assert res.status == "error termination"
    rt_elem = int(model.solid_groups[0].elem_ids[2])
    assert f"in element {rt_elem} (part " in res.reason and "non-finite force at node" in res.reason
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["error_element"] == rt_elem and s["error_node"] > 0
