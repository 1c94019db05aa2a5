"""Verification: a soft tissue block crushed by a heavy rigid plate; no node passes through.

The case reproduces the fat block failure of the block test on a small model:
a 60 x 60 x 30 mm MAT_181 fat block (7.5 mm hexahedra, bottom fixed) struck
by a rigid plate of 4 mm shells (3 mm elements, contact offset 2 mm): a
45 mm punch, or a 75 mm plate that covers the whole top face and the bulging
sides. 50 J crush the block to ~15-20 % of its height, where the fat is
many times stiffer than at rest and the time step falls ~10x, while the
SOFT=1 penalty spring is set from the initial step: a node can then carry
only k (reach + release depth) ~ 10-15 N before it is released, far less than
the crushed fat pushes with. With the contact as it was (release 0.4 sqrt(A)
= 1.2 mm past the mid-surface, inside the shell's own contact thickness, and
no stiffening) the punch went through the whole block (its mid-surface ended
16 mm below the fixed bottom face) and the run still ended "normally".

Tolerances: the total energy stays within 0.95-1.05 of the initial kinetic energy at
every output (measured 1.000-1.004) and ends within 1 % (measured 1.0012-1.0024; the
contact's kinematic step limit sets the step in 2-3 cycles while the plate approaches,
so the step falls before the contact pushes rather than at its first push,
docs/elements.md "Time step"): the central-difference balance with penalty contact has a
transient error of order (omega dt)^2 / 8 of the energy held by the springs (omega dt ~
0.3-0.5 here, up to ~20 % of the energy in the springs at maximum crush). At 30 m/s the
first contact cycles showed a transient up to 1.065 before the kinematic limit (the
kinetic energy at full steps is estimated as v^{n+1/2} + dt/2 a with the plate 1.6 mm
into the contact after one step; now 1.004): there the band applies from 0.25 ms on. The
contact energy never falls below -1 % of the impact energy (a negative value is energy
created by the contact; measured above -0.001 J of 25-50 J). No block node may ever be
beyond the plate's far contact surface (mid-surface + 2 mm, the release depth of these
segments) away from the plate's edge (3 mm).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from contact_decks import PLATE_ID0, soft_block_and_rigid_plate

from hollowbody.api import load_model, run_model
from hollowbody.contact import runtime as contact_runtime
from hollowbody.io.keyword import write_deck

PLATE_T, HEIGHT = 4.0, 30.0
EDGE = 3.0  # mm: nodes closer than this to the plate's edge are not checked


def _run(tmp_path, monkeypatch, size: float, mass: float, speed: float, friction: float = 0.2,
         stiffen: bool = True):
    deck = tmp_path / "block.k"
    write_deck(soft_block_and_rigid_plate(plate_size=size, plate_t=PLATE_T, height=HEIGHT,
                                          plate_mass=mass, speed=speed, friction=friction,
                                          end=5.0), deck)
    model = load_model(deck)
    plate = np.nonzero(model.node_ids >= PLATE_ID0)[0]
    block = np.nonzero(model.node_ids < PLATE_ID0)[0]
    worst = {"beyond": -np.inf, "plate_zmin": np.inf}
    add_forces = contact_runtime.ContactRuntime.add_forces
    inner = size / 2 - EDGE

    def checked(self, x, v, dt, cycle, f):
        if not stiffen and cycle == 0:
            self.set_stiffening(1.0)
        add_forces(self, x, v, dt, cycle, f)
        zp = x[plate, 2].min()
        xb = x[block]
        under = (np.abs(xb[:, 0]) < inner) & (np.abs(xb[:, 1]) < inner)
        worst["beyond"] = max(worst["beyond"], float((xb[under, 2] - zp).max()))
        worst["plate_zmin"] = min(worst["plate_zmin"], float(zp))

    monkeypatch.setattr(contact_runtime.ContactRuntime, "add_forces", checked)
    result = run_model(model, tmp_path / "out", vtk=False)
    glstat = np.genfromtxt(tmp_path / "out" / "glstat.csv", delimiter=",", names=True)
    return result, worst, glstat


# (plate size mm, mass kg, speed mm/ms, friction, time ms from which the energy band
# applies). The 45 mm punch is the hard case (the committed contact let it through
# the whole block); the 75 mm plates cover the top face and the bulging sides.
CASES = [(45.0, 0.25, 20.0, 0.2, 0.0), (75.0, 0.25, 20.0, 0.2, 0.0),
         (75.0, 0.2, 20.0, 0.0, 0.0), (75.0, 0.111, 30.0, 0.2, 0.25)]


@pytest.mark.parametrize("size,mass,speed,friction,settle", CASES)
def test_heavy_plate_does_not_push_soft_block_nodes_through(tmp_path, monkeypatch, size, mass,
                                                            speed, friction, settle):
    result, worst, glstat = _run(tmp_path, monkeypatch, size, mass, speed, friction)
    s = result.summary
    assert result.status == "normal termination"
    assert s["contact_pass_through"] == {"1": {"events": 0, "nodes": 0}}
    # the plate closes at 20-30 mm/ms, faster than half its contact band (2 mm) per
    # element step: the kinematic limit acts, at half the band over the speed at most
    limited = s["contact_step"]["1"]
    assert limited["cycles"] >= 1
    assert limited["dt_min_ms"] <= 0.5 * 0.5 * PLATE_T / speed * (1.0 + 1e-9)
    assert not [w for w in s["warnings"] if w["kind"] == "contact_pass_through"]
    assert worst["beyond"] < 0.5 * PLATE_T  # never past the far contact surface
    # the plate stops above the fixed bottom face (contact offset 2 mm) and rebounds
    assert worst["plate_zmin"] > 0.5 * PLATE_T
    vz = np.genfromtxt(tmp_path / "out" / "nodout.csv", delimiter=",", names=True)["vz_mmms"]
    assert vz[-1] > 0.0
    ratio = glstat["energy_ratio"][glstat["time_ms"] >= settle]
    assert ratio.min() > 0.95 and ratio.max() < 1.05
    assert abs(ratio[-1] - 1.0) < 0.01
    e0 = 0.5 * mass * speed**2
    assert glstat["contact_J"].min() > -0.01 * e0
    if friction == 0.0:
        assert abs(glstat["contact_J"][-1]) < 0.02 * e0


def test_pass_through_without_stiffening_is_reported(tmp_path, monkeypatch):
    # the same crush with the stiffened zone switched off: nodes go through, and
    # the run says so (messages.log, summary.json) instead of ending silently
    result, worst, _ = _run(tmp_path, monkeypatch, 45.0, 0.25, 20.0, stiffen=False)
    s = result.summary
    assert worst["beyond"] > 0.5 * PLATE_T
    assert s["contact_pass_through"]["1"]["events"] > 0
    warned = [w for w in s["warnings"] if w["kind"] == "contact_pass_through"]
    assert warned and warned[0]["contact"] == 1 and warned[0]["node"] > 0
    log = (tmp_path / "out" / "messages.log").read_text()
    assert "pushed through" in log
    assert json.loads((tmp_path / "out" / "summary.json").read_text())[
        "contact_pass_through"]["1"]["nodes"] > 0
