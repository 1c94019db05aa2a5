"""The knee in the pedestrian deck: springs and dampers in place of a spherical joint.

Checks the written deck against :mod:`hollowbody.body.knee` (exact: the values are
written, not computed by the solver), the shear curve's shape, the directions (the
shank's axes at t = 0, also in the tilted walking legs) and that the hollow variant
keeps the knee's elements with ids no new shell takes. The mechanics of the knee
(F / k, M / k) are tested in tests/verification/mechanics/pedestrian/test_knee_shear.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.body.deck import pedestrian_deck
from hollowbody.body.generate import PedestrianOptions, build_deck
from hollowbody.body.knee import (
    AXIAL_STIFFNESS,
    DAMPING_RATIO,
    LCID_SHEAR,
    SHEAR_STIFFNESS,
    SHEAR_STOP,
    STOP_STIFFNESS,
    dampers,
    lower_leg_mass,
    shear_curve,
    shear_force,
)
from hollowbody.body.pedestrian import build_body
from hollowbody.io.keyword import (
    ConstrainedJoint,
    DefineCurve,
    DefineSdOrientation,
    ElementDiscrete,
    JointStiffnessGeneralized,
    MatDamperViscous,
    MatSpringElastic,
    MatSpringNonlinearElastic,
    ShellElements,
    SolidElements,
)


def test_shear_curve_is_linear_to_the_stop_then_stiff() -> None:
    pts = np.array(shear_curve())
    assert np.all(np.diff(pts[:, 0]) > 0.0)
    np.testing.assert_allclose(pts[:, 1], -pts[::-1, 1])  # odd: lateral = medial
    slopes = np.diff(pts[:, 1]) / np.diff(pts[:, 0])
    np.testing.assert_allclose(slopes, [STOP_STIFFNESS, SHEAR_STIFFNESS, SHEAR_STIFFNESS,
                                        STOP_STIFFNESS], rtol=1e-12)
    assert shear_force(SHEAR_STOP) == pytest.approx(2.4)  # kN at 15 mm (Kajzer: 2-3 kN)
    for d in (-30.0, -15.0, -3.0, 0.0, 7.5, 15.0, 20.0, 40.0):  # end slopes beyond it
        assert shear_force(d) == pytest.approx(np.interp(d, pts[:, 0], pts[:, 1])
                                               if abs(d) <= 25.0 else
                                               np.sign(d) * (2.4 + STOP_STIFFNESS
                                                             * (abs(d) - 15.0)), rel=1e-12)


@pytest.mark.parametrize("posture", ["standing", "walking"])
def test_deck_joins_the_knees_with_springs_along_the_shank(posture: str) -> None:
    body = build_body(mesh=50.0, posture=posture)
    deck, info = pedestrian_deck(body)
    heads = {j.heading for j in deck.of_type(ConstrainedJoint)}
    assert not {"knee_l", "knee_r"} & heads and {"hip_l", "ankle_r"} <= heads
    stiff = {j.title: j for j in deck.of_type(JointStiffnessGeneralized)}
    assert stiff["knee_l"].jid == 0 and stiff["knee_r"].jid == 0 and stiff["hip_l"].jid > 0
    vids = {v.vid: np.array([v.xt, v.yt, v.zt]) for v in deck.of_type(DefineSdOrientation)}
    elems = {e.eid: e for e in deck.of_type(ElementDiscrete)}
    parts = info["knee"]["parts"]
    for side in "lr":
        ids = info["knee"]["elements"][f"knee_{side}"]
        frame = body.skeleton.frames[f"shank_{side}"]
        es = [elems[i] for i in ids]
        assert [e.pid for e in es] == [parts["shear"]] * 2 + [parts["axial"]] + [
            parts["shear_damper"]] * 2 + [parts["axial_damper"]]
        for axis, e in enumerate(es):
            np.testing.assert_allclose(vids[e.vid], frame[axis % 3], atol=1e-12)
        assert es[0].n1 == info["history"][f"knee_{side}"]
        assert es[0].n2 == info["history"][f"knee_{side}_tibia"]
    if posture == "walking":  # the forward shank is tilted: its axis is not global z
        assert abs(vids[elems[info["knee"]["elements"]["knee_l"][2]].vid][2]) < 0.99
    mats = {m.mid: m for m in deck.of_type(MatSpringElastic) + deck.of_type(MatDamperViscous)
            + deck.of_type(MatSpringNonlinearElastic)}
    assert mats[1000 + parts["axial"]].k == AXIAL_STIFFNESS
    assert mats[1000 + parts["shear"]].lcd == LCID_SHEAR
    curve = next(c for c in deck.of_type(DefineCurve) if c.lcid == LCID_SHEAR)
    np.testing.assert_array_equal(np.asarray(curve.points, float), shear_curve())
    m = lower_leg_mass(body.skeleton)
    assert m == pytest.approx((0.0433 + 0.0137) * 76.75, rel=1e-3)  # de Leva's shank + foot
    c_s, c_a = dampers(m)
    assert mats[1000 + parts["shear_damper"]].dc == c_s
    assert mats[1000 + parts["axial_damper"]].dc == c_a
    assert c_s == pytest.approx(2.0 * DAMPING_RATIO * np.sqrt(SHEAR_STIFFNESS * m), rel=1e-3)
    # element ids continue after the mesh's
    last = max(int(g.ids.max()) for g in deck.of_type(SolidElements) + deck.of_type(ShellElements))
    assert min(elems) == last + 1


def test_hollow_variant_keeps_the_knee_and_its_ids() -> None:
    deck, info = build_deck(PedestrianOptions(tissue="hollow", mesh=50.0))
    elems = {e.eid for e in deck.of_type(ElementDiscrete)}
    assert elems == {i for ids in info["knee"]["elements"].values() for i in ids}
    shells = np.concatenate([g.ids for g in deck.of_type(ShellElements)])
    solids = np.concatenate([g.ids for g in deck.of_type(SolidElements)])
    assert not elems & set(shells.tolist()) and not elems & set(solids.tolist())
