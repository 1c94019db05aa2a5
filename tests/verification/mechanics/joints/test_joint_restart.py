"""Restart: a run with joints (penalty pairs with their frozen stiffness and the
last gaps and forces, joint stiffness friction and angle histories) resumed from a
restart file equals the uninterrupted run, digit for digit (one numba thread; the
histories are compared as text). Also: jntforc.csv is written at *DATABASE_JNTFORC's
interval with the joint's force, the stiffness's angles and moments.
"""

from __future__ import annotations

import csv

import pytest
from joint_decks import curve, gravity, stiffness_pair

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.io.keyword import DatabaseAscii, DefineCurve
from hollowbody.solver.restart import dump_files

HISTORIES = ("glstat.csv", "rbdout.csv", "jntforc.csv")


pytestmark = pytest.mark.usefixtures("one_thread")


def _deck():
    deck = stiffness_pair("GENERALIZED", dof=6, end=12.0, lcidt=10, dlcidt=11, est=500.0,
                          fmt=1.0, moment=[(0.0, 0.0), (4.0, 3.0), (8.0, 3.0), (10.0, -2.0),
                                           (1.0e4, -2.0)])
    curve(deck, 10, lambda q: 5.0 * q)
    deck.add(DefineCurve(lcid=11, points=[[-10.0, -300.0], [10.0, 300.0]]))
    gravity(deck, 0.1)
    deck.add(DatabaseAscii(name="JNTFORC", dt=0.5))
    deck.add(DatabaseAscii(name="GLSTAT", dt=0.5))
    deck.add(DatabaseAscii(name="RBDOUT", dt=0.5))
    return deck


def test_resumed_run_equals_uninterrupted(tmp_path):
    ref = run_model(build_model(_deck()), tmp_path / "ref", vtk=False)
    assert ref.status == "normal termination" and ref.cycles > 200
    out = tmp_path / "resumed"
    run_model(build_model(_deck()), out, vtk=False, dump_cycles=100)
    files = dump_files(out)
    assert len(files) >= 2
    res = run_model(build_model(_deck()), out, vtk=False, restart=files[0], dump_cycles=0)
    assert res.cycles == ref.cycles
    for name in HISTORIES:
        assert (out / name).read_text() == (tmp_path / "ref" / name).read_text(), name
    rows = list(csv.DictReader((out / "jntforc.csv").open()))
    assert len(rows) in (25, 26)  # every 0.5 ms from 0 to 12 ms (and the last state)
    last = rows[-1]
    assert int(last["joint"]) == 1 and int(last["jsid"]) == 1
    # the pivot carries the body's weight (1 kg x 0.1 mm/ms^2 = 0.1 kN, body B pulled up)
    assert float(last["fz [kN]"]) == pytest.approx(0.1, rel=0.02)
    assert float(last["angle2 [rad]"]) > 0.0 and float(last["moment2 [kN*mm]"]) < 0.0
