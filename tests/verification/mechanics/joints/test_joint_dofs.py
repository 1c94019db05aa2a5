"""Each joint type keeps its free degrees of freedom free and its locked ones locked.

A free cube (1 kg, isotropic inertia 100 kg*mm^2, centre on the joint's axis or
point) is joined to a fixed cube; it starts with a unit velocity in one degree of
freedom (1 mm/ms, or 0.05 rad/ms about the centre) and no gravity. A free DOF has
no joint reaction (the pair forces act across the axis, through the axis, or at
the pivot, and the centre is on them), so its velocity is kept: >= 99 % after 800
cycles. A locked DOF's motion is stopped by the penalty springs and their dashpots
(DAMP = 1: 10 % of critical at the stiffest mode; the slowest mode, of the
three-pair joints whose pairs lie in one plane, decays in about 200 steps): all
six velocities <= 1 % of the initial speed after 800 cycles. Conservation laws behind this: the
momentum along a free translation and the angular momentum about a free axis
through the centre are not changed by the joint's forces; everything the joint
absorbs goes to its internal energy (checked: the energy balance holds to 1e-3).
"""

from __future__ import annotations

import numpy as np
import pytest
from joint_decks import Driver, joint_pair

FREE = {"SPHERICAL": {3, 4, 5}, "REVOLUTE": {4}, "CYLINDRICAL": {1, 4},
        "UNIVERSAL": {4, 5}, "TRANSLATIONAL": {1}, "LOCKING": set()}
SPEED, SPIN = 1.0, 0.05


@pytest.mark.parametrize("kind", sorted(FREE))
@pytest.mark.parametrize("dof", range(6))
def test_free_and_locked_dofs(kind, dof):
    v0, w0 = np.zeros(3), np.zeros(3)
    (v0 if dof < 3 else w0)[dof % 3] = SPEED if dof < 3 else SPIN
    run = Driver(joint_pair(kind, v0=v0, w0=w0))
    ke0 = run.body(2).kinetic_energy()
    for _ in range(800):
        run.step()
    b = run.body(2)
    now = np.concatenate([b.vel / SPEED, b.omega / SPIN])
    if dof in FREE[kind]:
        assert now[dof] >= 0.99, f"{kind}: free DOF {dof} slowed to {now[dof]:.4f}"
        others = np.delete(now, dof)
        assert np.abs(others).max() <= 0.01, f"{kind}: DOF {dof} leaked into {others}"
    else:
        assert np.abs(now).max() <= 0.01, f"{kind}: locked DOF {dof} still moves: {now}"
    e = run.energies()
    assert abs(e["total"] - (run.state.e0 + e["external_work"])) <= 1e-3 * ke0
