"""Postural tone of the walking pedestrian: the flexion stiffness that holds the posture.

A living pedestrian holds a walking posture by muscle activity; a passive
joint (a few N m/rad) does not. In mid-stance the knees are flexed and the
body weight acts across them: a leg whose hip and ankle are (nearly) pins is
a two-force member, the load F along the hip-ankle chord, so the knee carries
the moment F d (d: the knee's distance from the chord) and, as the knee
flexes further, the moment grows with the geometric (buckling) stiffness
F L1 L2 / L (thigh L1, shank L2, chord L). A knee flexion stiffness below that
gives way under the body weight whatever its damping. The same holds for the
head-arms-trunk over the hips (weight W at height h above the hips:
geometric stiffness W h) and, without the geometric term (a pendulum is
stable), for the forward-held arms at shoulders and elbows. The legs' loads
also have horizontal components, backwards at the forward leg's hip and
forwards at the rear leg's, F_x at +-w (half the hip distance): a couple
2 F_x w about the vertical that turns the pelvis (yaw) against the hips'
axial rotation (psi); a run with flexion tone alone showed it: the pelvis
turned 2.2 degrees in 55 ms; with the hips' axial rotation toned, the knees'
and ankles' (20 and 30 N m/rad) let it turn on (the yaw goes down each leg
through hip, knee and ankle in series, so each of the three gets the tone for
a third of the allowed rotation).

The tone here is a stiffness sized from these static moments of the
generated posture:

    k = TONE_MARGIN * (k_geo + M_g / THETA_ALLOW)

(flexion; for the legs' axial rotation M_g is half the yaw couple, k_geo 0,
and the allowed rotation is shared by hip, knee and ankle)
so that the static rotation under gravity, M_g / (k - k_geo), is below
THETA_ALLOW / TONE_MARGIN (1.3 degrees), and the stiffness is never below the
passive joint's. At the default body the knees get about 390 N m/rad, the hips
360 N m/rad in flexion, hips, knees and ankles 1230 N m/rad in axial
rotation; the flexion values are of the order of the
knee's quasi-stiffness in the stance phase of walking (Shamaei, Sawicki and
Dollar, PLoS ONE 8(3):e59993, 2013: the knee moment-angle relation in
weight acceptance is nearly linear; its slope follows from a knee extensor
moment of 0.5-1 N m/kg over a flexion excursion of 10-20 degrees, i.e. a few
hundred N m/rad for a 77 kg adult). The standing
posture needs none: its knees rest on their extension stops and the load
line passes close to the hip, knee and ankle centres (quiet standing holds the
knee with little muscle activity). Units: N, m, N m, N m/rad (= kN mm/rad).
"""

from __future__ import annotations

import numpy as np

from hollowbody.body.skeleton import Skeleton

G = 9.81  # m/s^2
#: Allowed static flexion under gravity before the margin (rad), a choice.
THETA_ALLOW = np.radians(2.0)
#: Margin on the required stiffness, a choice.
TONE_MARGIN = 1.5
#: Segments of head, arms and trunk (HAT), carried by the hips.
HAT = ("head", "upper_trunk", "middle_trunk", "lower_trunk")
ARM = ("upper_arm", "forearm", "hand")
#: Segment -> (proximal, distal) landmarks of de Leva's centre of mass line.
_COM_LINE = {"head": ("VERT", "CERV"), "upper_trunk": ("CERV", "XYPH"),
             "middle_trunk": ("XYPH", "OMPH"), "lower_trunk": ("OMPH", "MIDH"),
             "upper_arm": ("SJC", "EJC"), "forearm": ("EJC", "WJC"), "hand": ("WJC", "MET3")}


def _com(sk: Skeleton, name: str, side: str = "") -> tuple[float, np.ndarray]:
    """(mass kg, centre of mass (3,) mm) of de Leva's segment ``name`` in the posture."""
    seg = sk.segments[name]
    a, b = _COM_LINE[name]
    sfx = f"_{side}" if side else ""
    pa, pb = sk.point(a + sfx), sk.point(b + sfx)
    return seg.mass, pa + (pb - pa) * seg.com / seg.length


def _lump(items: list[tuple[float, np.ndarray]]) -> tuple[float, np.ndarray]:
    m = sum(i[0] for i in items)
    return m, sum(i[0] * i[1] for i in items) / m


def gravity_loads(sk: Skeleton) -> dict[str, dict[str, float]]:
    """Static gravity moment ``M`` (N m) and geometric stiffness ``k_geo`` (N m/rad) of the
    flexion of each hip, knee, shoulder and elbow (names as in
    :func:`hollowbody.body.joints.joint_specs`) and of the axial rotation of hips, knees
    and ankles (names ``hip_l.psi`` etc.; ``series``: the three joints of a leg share
    the pelvis's yaw) in the posture of ``sk``; knees also the leg load ``F`` (N, along
    the hip-ankle chord) and the knee's distance ``d`` (mm) from the chord.

    Knees: both legs are two-force members from the ankles to the common hip
    (sagittal plane): F_f e_f + F_r e_r = W z with W the weight of all but the
    shanks and feet. Hips: the head, trunk and arms (HAT) over both hips, half
    each. Arms: the segments distal to the joint, horizontal lever arms.
    """
    out: dict[str, dict[str, float]] = {}
    seg = sk.segments
    # hips: HAT over the hip axis
    hat = [_com(sk, s) for s in HAT] + [_com(sk, s, side) for side in "lr" for s in ARM]
    m_hat, c_hat = _lump(hat)
    hip = 0.5 * (sk.point("HJC_l") + sk.point("HJC_r"))
    for side in "lr":
        out[f"hip_{side}"] = {"M": 0.5 * G * m_hat * abs(float(c_hat[0] - hip[0])) / 1000.0,
                              "k_geo": 0.5 * G * m_hat * float(c_hat[2] - hip[2]) / 1000.0}
    # knees: two-force legs meeting at the hip
    w = G * (sk.mass - 2.0 * (seg["shank"].mass + seg["foot"].mass))
    e = {}
    for side in "lr":
        d = sk.point(f"HJC_{side}") - sk.point(f"AJC_{side}")
        e[side] = d[[0, 2]] / np.linalg.norm(d[[0, 2]])
    # least squares: parallel legs (standing) share the load equally
    f = np.linalg.lstsq(np.column_stack([e["l"], e["r"]]), [0.0, w], rcond=None)[0]
    w_half = 0.5 * abs(float(sk.point("HJC_l")[1] - sk.point("HJC_r")[1]))
    yaw = abs(float(f[0] * e["l"][0] - f[1] * e["r"][0])) * w_half / 1000.0
    for side in "lr":  # each leg's half, through hip, knee and ankle in series
        for joint in ("hip", "knee", "ankle"):
            out[f"{joint}_{side}.psi"] = {"M": 0.5 * yaw, "k_geo": 0.0, "series": 3.0}
    for side, fs in zip("lr", f):
        h, k, a = (sk.point(f"{j}_{side}")[[0, 2]] for j in ("HJC", "KJC", "AJC"))
        chord = float(np.linalg.norm(h - a))
        u = (h - a) / chord
        dist = abs(float((k - a)[0] * u[1] - (k - a)[1] * u[0]))
        l1, l2 = float(np.linalg.norm(h - k)), float(np.linalg.norm(k - a))
        out[f"knee_{side}"] = {"M": float(fs) * dist / 1000.0,
                               "k_geo": max(0.0, float(fs)) * l1 * l2 / chord / 1000.0,
                               "F": float(fs), "d": dist}
    # arms: distal segments about shoulder and elbow (a hanging pendulum is stable)
    for side in "lr":
        for joint, centre, segs in (("shoulder", "SJC", ARM), ("elbow", "EJC", ARM[1:])):
            c = sk.point(f"{centre}_{side}")
            m = sum(G * mm * float(np.linalg.norm((p - c)[:2]))
                    for mm, p in (_com(sk, s, side) for s in segs))
            out[f"{joint}_{side}"] = {"M": m / 1000.0, "k_geo": 0.0}
    return out


ANGLES = {"phi": 0, "theta": 1, "psi": 2}


def postural_tone(sk: Skeleton, passive: dict[str, tuple[float, float, float]]
                  ) -> dict[str, tuple[float, float, float]]:
    """Stiffness (phi, theta, psi) N m/rad per joint name that holds the posture of
    ``sk``: TONE_MARGIN * (k_geo + M / THETA_ALLOW) for the loaded angles (flexion
    theta; ``name.psi``: axial rotation; THETA_ALLOW divided among joints in
    ``series``), at least the passive joint's
    (``passive[name]``); the other angles keep the passive values."""
    out: dict[str, list[float]] = {}
    for key, ld in gravity_loads(sk).items():
        name, _, angle = key.partition(".")
        i = ANGLES[angle or "theta"]
        k = out.setdefault(name, list(passive[name]))
        allow = THETA_ALLOW / ld.get("series", 1.0)
        k[i] = float(max(passive[name][i], round(TONE_MARGIN * (ld["k_geo"]
                                                                  + ld["M"] / allow))))
    return {n: (k[0], k[1], k[2]) for n, k in out.items()}
