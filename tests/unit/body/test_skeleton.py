"""The body plan: joint centres of the standing and walking postures."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.body.skeleton import ANKLE_HEIGHT, SEGMENT_AXES, standing, walking

PAIRS = [("HJC", "KJC", "thigh"), ("KJC", "AJC", "shank"), ("SJC", "EJC", "upper_arm"),
         ("EJC", "WJC", "forearm"), ("WJC", "MET3", "hand")]


def test_standing_chain_reaches_the_stature() -> None:
    """The vertex is at the stature, the ankle at 0.039 H, and every limb segment is de
    Leva's length times the one chain factor (to 1e-9 mm: exact arithmetic)."""
    sk = standing(1753.0, 76.75)
    assert sk.point("VERT")[2] == pytest.approx(1753.0, abs=1e-9)
    assert sk.point("AJC_l")[2] == pytest.approx(ANKLE_HEIGHT * 1753.0, abs=1e-9)
    assert 0.95 < sk.chain_scale < 1.0  # de Leva's lengths add up to 2 % more than H
    for a, b, seg in PAIRS:
        for s in "lr":
            d = np.linalg.norm(sk.point(f"{a}_{s}") - sk.point(f"{b}_{s}"))
            assert d == pytest.approx(sk.segments[seg].length * sk.chain_scale, abs=1e-9)
    assert sk.point("MIDH")[2] == pytest.approx(sk.point("HJC_l")[2])


def test_sides_mirror_and_spine_levels_are_ordered() -> None:
    sk = standing()
    for k in ("HJC", "KJC", "AJC", "SJC", "EJC", "WJC", "HEEL", "TTIP"):
        left, right = sk.point(f"{k}_l"), sk.point(f"{k}_r")
        assert left == pytest.approx(right * np.array([1.0, -1.0, 1.0]))
        assert left[1] > 0.0
    z = [sk.point(k)[2] for k in ("MIDH", "L5S1", "L3L4", "T12L1", "T9T10", "T4T5", "C7T1",
                                  "OC", "VERT")]
    assert np.all(np.diff(z) > 0.0)


def test_scaling_with_stature_is_proportional() -> None:
    """All choices are fractions of the stature: at twice the stature every landmark is
    twice as far from the origin (the floor at the mid-plane)."""
    a, b = standing(1700.0, 70.0), standing(3400.0, 70.0)
    for k, p in a.points.items():
        assert b.points[k] == pytest.approx(2.0 * p, abs=1e-9)


@pytest.mark.parametrize("struck", ["l", "r"])
def test_walking_keeps_lengths_feet_flat(struck: str) -> None:
    """Rotations about joint centres keep every segment's length (1e-9 mm); both feet are
    flat on the floor (heel and toe at z = 0), the ankles at one height, the struck
    leg's knee in front and the other behind; frames stay orthonormal."""
    st, wk = standing(), walking(struck=struck)
    other = "r" if struck == "l" else "l"
    for a, b, _ in PAIRS:
        for s in "lr":
            d0 = np.linalg.norm(st.point(f"{a}_{s}") - st.point(f"{b}_{s}"))
            d1 = np.linalg.norm(wk.point(f"{a}_{s}") - wk.point(f"{b}_{s}"))
            assert d1 == pytest.approx(d0, abs=1e-9)
    for s in "lr":
        assert wk.point(f"HEEL_{s}")[2] == pytest.approx(0.0, abs=1e-9)
        assert wk.point(f"TTIP_{s}")[2] == pytest.approx(0.0, abs=1e-9)
    assert wk.point("AJC_l")[2] == pytest.approx(wk.point("AJC_r")[2], abs=1e-6)
    assert wk.point(f"KJC_{struck}")[0] > 50.0 > -50.0 > wk.point(f"KJC_{other}")[0]
    assert wk.point("WJC_l")[0] > 100.0  # arms forward
    for name, fr in wk.frames.items():
        assert fr @ fr.T == pytest.approx(np.eye(3), abs=1e-12), name
    for seg, (a, b) in SEGMENT_AXES.items():  # frame z runs from the distal to the proximal
        for s in "lr":
            axis = wk.point(f"{a}_{s}") - wk.point(f"{b}_{s}")
            assert wk.frames[f"{seg}_{s}"][2] == pytest.approx(axis / np.linalg.norm(axis))


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="positive"):
        standing(-1.0, 70.0)
    with pytest.raises(ValueError, match="struck"):
        walking(struck="x")
