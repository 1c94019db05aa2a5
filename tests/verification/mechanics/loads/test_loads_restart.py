"""Restart with gravity, loads and a rigid wall: a run resumed from a restart file
writes the same histories as the uninterrupted run, digit for digit (one thread)."""

from __future__ import annotations

import pytest
from loads_decks import G, add_block, base_deck

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.io.keyword import (
    DatabaseAscii,
    DefineCurve,
    LoadNodePoint,
    LoadRigidBody,
    RigidwallPlanar,
)
from hollowbody.solver.restart import dump_files

HISTORIES = ("glstat.csv", "rbdout.csv", "rwforc.csv", "matsum.csv")


pytestmark = pytest.mark.usefixtures("one_thread")


def _deck():
    deck = base_deck(12.0, g=30.0 * G)
    add_block(deck, pid=1, size=10.0, h=5.0, z0=0.5, e=0.05)
    add_block(deck, pid=2, size=10.0, h=5.0, z0=0.8, x0=30.0, first_node=1001,
              first_elem=1001, rigid=True, e=0.05)
    deck.add(DefineCurve(lcid=2, points=[[0.0, 0.0], [12.0, 1.0]]))
    deck.add(LoadNodePoint(nid=27, dof=1, lcid=2, sf=1.0e-5))
    deck.add(LoadRigidBody(pid=2, dof=1, lcid=2, sf=2.0e-5))
    deck.add(RigidwallPlanar(xt=0.0, yt=0.0, zt=0.0, xh=0.0, yh=0.0, zh=1.0, fric=0.3))
    for name in ("GLSTAT", "RBDOUT", "RWFORC", "MATSUM"):
        deck.add(DatabaseAscii(name=name, dt=0.1))
    return deck


def test_resumed_run_equals_the_straight_run(tmp_path):
    ref = tmp_path / "straight"
    res = run_model(build_model(_deck()), ref, vtk=False)
    assert res.status == "normal termination" and res.cycles > 200
    rw = (ref / "rwforc.csv").read_text().splitlines()
    assert len(rw) > 100  # the wall's history is written, and the wall carries the bodies
    assert float(rw[-1].split(",")[2]) > 0.0
    out = tmp_path / "resumed"
    run_model(build_model(_deck()), out, vtk=False, dump_cycles=100)
    files = dump_files(out)
    assert len(files) >= 2
    res2 = run_model(build_model(_deck()), out, vtk=False, restart=files[1], dump_cycles=0)
    assert res2.cycles == res.cycles
    for name in HISTORIES:
        assert (ref / name).read_text() == (out / name).read_text(), name
