"""Leaving arm segments out of the pedestrian deck (the pelvis impact removes the
struck-side forearm and hand): their parts, the nodes only they use and their joints
go; everything else stays as it was."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.body.deck import pedestrian_deck
from hollowbody.body.generate import PedestrianOptions, build_deck
from hollowbody.body.pedestrian import build_body
from hollowbody.build import build_model
from hollowbody.io.keyword import ConstrainedJoint, MatRigid, Nodes, Part, PartInertia
from hollowbody.model.summary import summarize

OMIT = ("forearm_l", "hand_l")


@pytest.fixture(scope="module")
def body():
    return build_body(mesh=50.0)


def _nodes(deck) -> dict[int, np.ndarray]:  # noqa: ANN001
    return {int(i): x for n in deck.of_type(Nodes) for i, x in zip(n.ids, n.xyz)}


def test_omitted_segments_leave_the_deck(body) -> None:
    full, info_full = pedestrian_deck(body)
    cut, info = pedestrian_deck(body, omit=OMIT)
    gone = {p.pid for p in body.mesh.parts if set(p.segment.tolist()) <= set(OMIT)}
    assert info["omitted_parts"] == sorted(gone) and info_full["omitted_parts"] == []
    names = {body.mesh.parts[p - 1].name for p in gone}
    assert names == {"forearm_l bone", "forearm_l proximal epiphysis",
                     "forearm_l distal epiphysis", "forearm_l muscle", "forearm_l skin",
                     "hand_l", "forearm_l proximal epiphysis inertia",
                     "forearm_l distal epiphysis inertia"}
    pids = {p.pid for p in cut.of_type(Part)} | {p.pid for p in cut.of_type(PartInertia)}
    knee = set(info["knee"]["parts"].values())  # the knees' discrete parts, after the mesh's
    assert len(knee) == 4 and min(knee) > max(p.pid for p in body.mesh.parts)
    pids -= knee
    assert not pids & gone and len(pids) == len(body.mesh.parts) - len(gone)
    assert not {1000 + p for p in gone} & {m.mid for m in cut.of_type(MatRigid)}
    heads = {j.heading for j in cut.of_type(ConstrainedJoint)}
    assert {j.heading for j in full.of_type(ConstrainedJoint)} - heads == {"elbow_l",
                                                                          "wrist_l"}
    # nodes: only those of the removed parts are gone, the others keep id and place
    kept, every = _nodes(cut), _nodes(full)
    x = body.mesh.coords()
    used = np.unique(np.concatenate([p.conn.ravel() for p in body.mesh.parts
                                     if p.pid not in gone])) + 1
    for nid in used[::7]:
        np.testing.assert_array_equal(kept[int(nid)], x[nid - 1])
    assert set(every) - set(kept) >= {int(n) + 1 for p in body.mesh.parts if p.pid in gone
                                      for n in np.unique(p.conn)} - set(used.tolist())
    model = build_model(cut)
    assert summarize(model)["problems"] == []
    assert info["history"] == info_full["history"]  # ids as in the whole body


def test_only_arm_segments_can_be_left_out(body) -> None:
    with pytest.raises(ValueError, match="cannot leave out segment 'thigh_l'"):
        pedestrian_deck(body, omit=("thigh_l",))


def test_hollow_variant_without_the_forearm() -> None:
    deck, info = build_deck(PedestrianOptions(tissue="hollow", mesh=50.0), omit=OMIT)
    converted = {p.pid for p in info["conversion"].parts}
    assert converted and not converted & set(info["omitted_parts"])
    assert summarize(build_model(deck))["problems"] == []
