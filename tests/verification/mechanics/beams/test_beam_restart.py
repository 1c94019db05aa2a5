"""Restart: a run resumed from a snapshot of its State equals the straight run.

A plastic ELFORM 1 cantilever under a tip load (and an elastic ELFORM 2 one)
runs 300 cycles, its State is saved (:func:`hollowbody.solver.state.snapshot`,
what a restart file holds), the run goes on 300 cycles; a fresh run of the
same deck gets the snapshot restored and runs the same 300 cycles. Positions,
velocities, rotations and every STATE_FIELDS array of the beams must be
identical (bit for bit: the same arithmetic in the same order).
"""

from __future__ import annotations

import numpy as np
import pytest
from beam_runs import add_load, engine

from hollowbody.solver.state import restore, snapshot


def _run(tmp_path, elform):  # noqa: ANN001
    run = engine(tmp_path, n=6, elform=elform, sigy=0.25 if elform == 1 else 0.0,
                 etan=2.0)
    add_load(run, 6, force=lambda t: np.array([0.0, 0.02 * t, -0.3 * t]),
             moment=lambda t: np.array([2.0 * t, 0.0, 0.0]))
    return run


@pytest.mark.parametrize("elform", [1, 2])
def test_resumed_run_equals_straight_run(tmp_path, elform):
    a = _run(tmp_path, elform)
    for _ in range(300):
        a.step()
    snap = snapshot(a.state)
    for _ in range(300):
        a.step()
    b = _run(tmp_path, elform)
    restore(b.state, snap)
    for _ in range(300):
        b.step()
    assert b.state.t == a.state.t
    for name in ("x", "v", "w", "f", "mom"):
        assert np.array_equal(getattr(a.state, name), getattr(b.state, name)), name
    ra, rb = a.plan.elements[0], b.plan.elements[0]
    assert ra.plastic_strain.max() > 0.0 or elform == 2  # the plastic case yielded
    for name in type(ra).STATE_FIELDS:
        va, vb = getattr(ra, name), getattr(rb, name)
        if isinstance(va, np.ndarray):
            assert np.array_equal(va, vb), name
        else:
            assert va == vb, name
