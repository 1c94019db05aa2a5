"""The walking pedestrian's postural tone: the gravity moments it is sized from against
hand calculations, the static rotation it allows, its scaling, and where the deck
uses it (walking only, not with --no-tone)."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.body.deck import pedestrian_deck
from hollowbody.body.joints import joint_specs, walking_tone
from hollowbody.body.pedestrian import build_body
from hollowbody.body.skeleton import WALKING, standing, walking
from hollowbody.body.tone import THETA_ALLOW, TONE_MARGIN, G, gravity_loads
from hollowbody.io.keyword import DefineCurve, JointStiffnessGeneralized


def _leg(sk, side):  # noqa: ANN001, ANN202
    h, k, a = (sk.point(f"{j}_{side}")[[0, 2]] for j in ("HJC", "KJC", "AJC"))
    return np.linalg.norm(h - k), np.linalg.norm(k - a), h, k, a


def test_knee_moment_is_the_leg_load_times_the_knee_offset() -> None:
    """A leg pinned at hip and ankle is a two-force member: the knee moment is F times
    the knee's distance from the hip-ankle chord, d = L1 L2 sin(q) / L (q the knee
    flexion, L the chord), and the geometric stiffness F L1 L2 / L is the derivative
    of F d(q) at q = 0 (at the posture's 5 degrees the derivative is smaller by cos q
    and a sin^2 q term: 1 %). The two legs' vertical loads carry the weight above the
    shanks, their horizontal loads cancel (1e-9)."""
    sk = walking()
    loads = gravity_loads(sk)
    seg = sk.segments
    w = G * (sk.mass - 2.0 * (seg["shank"].mass + seg["foot"].mass))
    vert, horiz = 0.0, 0.0
    for side in "lr":
        l1, l2, h, k, a = _leg(sk, side)
        chord = np.linalg.norm(h - a)
        cq = np.dot(h - k, k - a) / (l1 * l2)  # cosine of the knee flexion
        q = np.arccos(np.clip(cq, -1.0, 1.0))
        d = l1 * l2 * np.sin(q) / chord
        ld = loads[f"knee_{side}"]
        assert ld["d"] == pytest.approx(d, rel=1e-9)
        assert ld["M"] == pytest.approx(ld["F"] * d / 1000.0, rel=1e-9)

        def moment(qq: float, f: float = ld["F"], a: float = l1, b: float = l2) -> float:
            return f * a * b * np.sin(qq) / np.sqrt(a**2 + b**2 + 2 * a * b
                                                    * np.cos(qq)) / 1000.0

        slope = (moment(q + 1e-6) - moment(q - 1e-6)) / 2e-6
        assert ld["k_geo"] == pytest.approx(slope, rel=0.01)
        u = (h - a) / chord
        vert += ld["F"] * u[1]
        horiz += ld["F"] * u[0]
    assert vert == pytest.approx(w, rel=1e-9)
    assert horiz == pytest.approx(0.0, abs=1e-9 * w)


def test_arm_moments_match_a_hand_calculation() -> None:
    """Shoulder flexed 20 degrees, elbow 70 (forearm and hand horizontal): the moment
    about the shoulder is g sum m_i x_i with the lever arms of de Leva's centres of
    mass along the arm's segments (1e-9)."""
    sk = walking()
    seg = sk.segments
    s, e = np.radians(WALKING["shoulder"]), np.radians(WALKING["shoulder"] + WALKING["elbow"])
    lu, lf, lh = (sk.length(n) for n in ("upper_arm", "forearm", "hand"))
    cu, cf, ch = (seg[n].com / seg[n].length for n in ("upper_arm", "forearm", "hand"))
    xe = lu * np.sin(s)
    shoulder = G * (seg["upper_arm"].mass * cu * xe + seg["forearm"].mass
                    * (xe + cf * lf * np.sin(e)) + seg["hand"].mass
                    * (xe + (lf + ch * lh) * np.sin(e))) / 1000.0
    elbow = G * (seg["forearm"].mass * cf * lf + seg["hand"].mass * (lf + ch * lh)) / 1000.0
    loads = gravity_loads(sk)
    for side in "lr":
        assert loads[f"shoulder_{side}"]["M"] == pytest.approx(shoulder, rel=1e-9)
        assert loads[f"elbow_{side}"]["M"] == pytest.approx(elbow, rel=1e-9)


def test_standing_posture_loads_nothing() -> None:
    """Standing: knees on the chords, the head-arms-trunk above the hips, no yaw couple:
    no moments (1e-9 N m), the legs share the weight equally; and no tone."""
    sk = standing()
    for name, ld in gravity_loads(sk).items():
        if not name.startswith(("shoulder", "elbow")):
            assert ld["M"] == pytest.approx(0.0, abs=1e-9), name
    loads = gravity_loads(sk)
    assert loads["knee_l"]["F"] == pytest.approx(loads["knee_r"]["F"], rel=1e-9)
    assert walking_tone(sk) == {}


def test_tone_bounds_the_static_rotation() -> None:
    """Every loaded angle's tone exceeds its geometric stiffness (stable) and leaves a
    static rotation M / (k - k_geo) of at most THETA_ALLOW / TONE_MARGIN (plus the
    rounding of k to 1 N m/rad), the legs' axial rotations (hip, knee and ankle in
    series) a third of it each; the other angles keep the passive values."""
    sk = walking()
    tone = walking_tone(sk)
    passive = {j.name: j.k for j in joint_specs()}
    idx = {"": 1, "psi": 2}
    for key, ld in gravity_loads(sk).items():
        name, _, angle = key.partition(".")
        k = tone[name][idx[angle]]
        assert k > ld["k_geo"], key
        allow = THETA_ALLOW / TONE_MARGIN / ld.get("series", 1.0)
        assert ld["M"] / (k - ld["k_geo"]) <= allow * 1.01, key
    for name, k in tone.items():
        assert k[0] == passive[name][0]
        if name.startswith(("shoulder", "elbow")):
            assert k[2] == passive[name][2]
        if name.startswith("ankle"):
            assert k[1] == passive[name][1]
    assert set(tone) == {f"{j}_{s}" for j in ("hip", "knee", "ankle", "shoulder", "elbow")
                         for s in "lr"}


def test_tone_scales_with_weight_times_stature() -> None:
    """Moments and geometric stiffnesses of a posture scale with m g H, so the tone does
    (rounding to 1 N m/rad: 1 %)."""
    a, b = walking(), walking(1900.0, 95.0)
    ta, tb = walking_tone(a), walking_tone(b)
    ratio = 95.0 * 1900.0 / (76.75 * 1753.0)
    for name in ("knee_l", "hip_r", "shoulder_l", "elbow_r"):
        assert tb[name][1] / ta[name][1] == pytest.approx(ratio, rel=0.01), name
    for name in ("hip_l", "knee_r", "ankle_l"):
        assert tb[name][2] / ta[name][2] == pytest.approx(ratio, rel=0.01)


def _knee_flexion_slope(deck, name: str) -> float:  # noqa: ANN001
    curves = {c.lcid: c for c in deck.of_type(DefineCurve)}
    jsg = [j for j in deck.of_type(JointStiffnessGeneralized) if j.title == name][0]
    pts = np.asarray(curves[jsg.lcidt].points, float)
    return float((pts[-1, 1] - pts[0, 1]) / (pts[-1, 0] - pts[0, 0]))


def test_deck_uses_the_tone_when_walking_only() -> None:
    """The deck's knee flexion curve: the tone's slope walking, the passive 5 N m/rad
    standing or walking without tone."""
    walk = build_body(mesh=50.0, posture="walking")
    stand = build_body(mesh=50.0)
    tone = walking_tone(walk.skeleton)
    assert _knee_flexion_slope(pedestrian_deck(walk)[0], "knee_r") == pytest.approx(
        tone["knee_r"][1])
    assert _knee_flexion_slope(pedestrian_deck(walk, tone=False)[0], "knee_r") == 5.0
    assert _knee_flexion_slope(pedestrian_deck(stand)[0], "knee_r") == 5.0
