"""Restart of a rigid assembly: the resumed run equals the straight one.

The free-flying assembly (merged parts, extra nodes, a nodal rigid body) runs
straight with a restart file every 300 cycles; a second run resumes from the
second file (cycle 600) into the same folder. Every array a body carries from
one cycle to the next (centre, rotation, the rotation of the last velocity
update, velocities, resultants) is in RigidBody.STATE_FIELDS and saved exactly,
and on one thread the arithmetic is the same, so the histories (rbdout, glstat)
must be equal as text.
"""

from __future__ import annotations

import pytest

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.solver.restart import dump_files
from hollowbody.testing.rigid_decks import assembly_deck

pytestmark = pytest.mark.usefixtures("one_thread")


def _deck():
    return assembly_deck(end=20.0, rbdout_dt=0.1)


def test_resumed_run_equals_straight_run(tmp_path):
    straight, resumed = tmp_path / "straight", tmp_path / "resumed"
    ref = run_model(build_model(_deck()), straight, vtk=False)
    assert ref.status == "normal termination" and ref.cycles > 1000
    res = run_model(build_model(_deck()), resumed, vtk=False, dump_cycles=300)
    files = dump_files(resumed)
    assert len(files) == 3
    res2 = run_model(build_model(_deck()), resumed, vtk=False, restart=files[1],
                     dump_cycles=0)
    assert res2.cycles == ref.cycles == res.cycles
    for name in ("rbdout.csv", "glstat.csv"):
        assert (resumed / name).read_text() == (straight / name).read_text(), name
    assert (straight / "rbdout.csv").read_text().count("\n") > 300  # both bodies, 200 rows
