"""*MAT_NULL shells: contact skins with mass and no stiffness.

A rigid cube (10 mm, 1 g) falls at 1 mm/ms onto an elastic cube standing on a fixed
base; the only contact is between a *MAT_NULL shell skin and the elastic cube, the
skin being on the rigid cube's bottom face (its nodes are the cube's) or on the
elastic cube's top face.
"""

from __future__ import annotations

import numpy as np
import pytest
from loads_decks import Run, add_block, base_deck

from hollowbody.errors import UserInputError
from hollowbody.io.keyword import (
    BoundarySpcSet,
    Contact,
    InitialVelocityGeneration,
    MatNull,
    Part,
    SetNodeList,
)

RO_NULL, T_NULL = 2.0e-6, 1.0  # kg/mm^3, mm (the 100 mm^2 skin weighs 0.2 g)


def _face_quads(ids: np.ndarray, layer: int) -> np.ndarray:
    """The 2 x 2 quads (node ids) of horizontal node layer ``layer`` of a 2x2x2 cube."""
    p = np.array([i + 3 * j for j in range(2) for i in range(2)]) + 9 * layer
    return ids[np.column_stack([p, p + 1, p + 4, p + 3])]


def _deck(skin: str | None, contact: bool = True, ym: float = 0.05) -> object:
    deck = base_deck(1.5, g=None)
    lower = add_block(deck, pid=1, size=10.0, h=5.0, e=0.05)
    upper = add_block(deck, pid=2, size=10.0, h=5.0, z0=10.5, first_node=1001,
                      first_elem=1001, rigid=True, e=0.05)
    deck.add(SetNodeList(sid=1, nodes=lower[:9].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    deck.add(InitialVelocityGeneration(id=2, styp=2, vz=-1.0))
    if skin is not None:
        quads = _face_quads(upper, 0) if skin == "rigid" else _face_quads(lower, 2)
        deck.add_shells(5001 + np.arange(4), 3, quads)
        deck.add(Part(pid=3, secid=900, mid=3, title="null skin"))
        deck.add(MatNull(mid=3, ro=RO_NULL, ym=ym, pr=0.3))
        if contact:
            other = 1 if skin == "rigid" else 2
            deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=1, ssid=3, sstyp=3,
                             msid=other, mstyp=3, soft=0))
    return deck


@pytest.mark.parametrize("skin", ["rigid", "solid"])
def test_null_skin_adds_mass_keeps_the_step_and_contacts(skin):
    """The skin's mass rho A t = 2e-6 * 100 * 1 = 2e-4 kg is added (to the rigid body,
    or to the elastic cube's top nodes) to round-off; the first step is the same with
    and without the skin (it sets none); the contact through the skin stops the rigid
    cube: it rebounds (vz > 0 at 1.5 ms) and never passes the elastic cube's top by
    more than the skin's half thickness plus 0.5 mm, while without the contact it
    passes through."""
    bare = Run(_deck(None))
    run = Run(_deck(skin))
    added = RO_NULL * 100.0 * T_NULL
    assert abs(run.plan.node_mass.sum() - bare.plan.node_mass.sum() - added) < 1e-12
    if skin == "rigid":
        assert abs(run.plan.bodies[0].mass - bare.plan.bodies[0].mass - added) < 1e-12
    assert run.state.dt_next == bare.state.dt_next
    assert not any(rt.pid == 3 for rt in run.plan.elements)
    low = np.inf

    def every(r: Run) -> None:
        nonlocal low
        low = min(low, r.plan.bodies[0].xc[2] - 5.0)

    run.run_to(1.5, every=every)
    assert run.plan.bodies[0].vel[2] > 0.0
    assert low > 10.0 - 0.5 * T_NULL - 0.5 - 1e-9, low
    free = Run(_deck(skin, contact=False))
    free.run_to(1.5)
    assert free.plan.bodies[0].vel[2] == pytest.approx(-1.0)


def test_null_skin_without_ym_in_a_contact_is_rejected():
    with pytest.raises(UserInputError, match="YM"):
        Run(_deck("rigid", ym=0.0))
