"""The pedestrian's joints: spherical joints with generalized rotational stiffness.

Every joint but the knees is a *CONSTRAINED_JOINT_SPHERICAL between the rigid bodies of the
two segments (node pair at the joint centre, each node added to its body by
*CONSTRAINED_EXTRA_NODES_NODE) with a *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED
in the distal segment's frame at the joint (x anterior, y to the body's
left, z along the segment towards the proximal joint): phi about x
(ab/adduction, lateral bending, knee varus/valgus), theta about y
(flexion/extension), psi about z (axial rotation). Per angle: a linear
moment-angle curve (k), a linear damping curve (c) and elastic stops
(stop stiffness ES past the stop angles).

Values (N m/rad = kN mm/rad; damping N m s/rad; stops degrees): stated
engineering choices of the order of the passive joint moments of Riener and
Edrich (J. Biomech. 32:539-544, 1999; hip, knee, ankle: a few N m per 10
degrees in mid-range, rising steeply near the range limits, here the stops)
and of the lateral knee bending of Kajzer et al. (Stapp Car Crash Conf.
1997, 973326: about 100-150 N m at 10-15 degrees of valgus, here 400 N m/rad
up to a 15 degree stop); spine, neck, shoulder, elbow and wrist values are
choices that hold the standing posture under gravity for the 150 ms of an
impact. In the walking posture the flexion of hips, knees, shoulders and
elbows and the hips' axial rotation get a postural tone sized from the
posture's gravity moments (:mod:`hollowbody.body.tone`) in place of the
passive values. The knee is not a spherical joint: its stiffness acts between
femur and tibia ends joined by translational springs, so it bends in
valgus/varus and shears under lateral load (:mod:`hollowbody.body.knee`).
"""

from __future__ import annotations

from dataclasses import dataclass

#: Damping of every rotation (N m s/rad), a choice.
DAMPING = 0.5
#: Stop stiffness (N m/rad), a choice.
STOP_STIFFNESS = 2000.0


@dataclass(frozen=True)
class JointSpec:
    """One joint: name, rigid bodies A (proximal) and B (distal) by name, the centre
    landmark, the frame's segment, stiffness (phi, theta, psi) N m/rad and stops
    (neg, pos) degrees per angle."""

    name: str
    body_a: str
    body_b: str
    centre: str
    frame: str
    k: tuple[float, float, float]
    stops: tuple[tuple[float, float], tuple[float, float], tuple[float, float]]


def joint_specs(tone: dict[str, tuple[float, float, float]] | None = None
                ) -> list[JointSpec]:
    """All joints, proximal to distal (spine and neck first, then each side).

    ``tone``: stiffness (phi, theta, psi) N m/rad by joint name replacing the passive
    values (:func:`hollowbody.body.tone.postural_tone`); default none.
    """
    sp = ((-20.0, 20.0), (-20.0, 20.0), (-20.0, 20.0))
    out = [
        JointSpec("L3-sacrum", "sacrum", "L3", "L3L4", "trunk", (150.0, 150.0, 100.0), sp),
        JointSpec("T12-L3", "L3", "T12", "T12L1", "trunk", (150.0, 150.0, 100.0), sp),
        JointSpec("T8-T12", "T12", "T8", "T9T10", "trunk", (150.0, 150.0, 100.0), sp),
        JointSpec("T1-T8", "T8", "T1", "T4T5", "trunk", (150.0, 150.0, 100.0), sp),
        JointSpec("neck-T1", "T1", "neck", "C7T1", "neck", (50.0, 50.0, 30.0),
                  ((-40.0, 40.0), (-40.0, 40.0), (-45.0, 45.0))),
        JointSpec("head-neck", "neck", "head", "OC", "head", (30.0, 30.0, 20.0),
                  ((-30.0, 30.0), (-30.0, 30.0), (-45.0, 45.0))),
    ]
    for s in ("l", "r"):
        out += [
            JointSpec(f"hip_{s}", "pelvis", f"thigh_{s}_proximal", f"HJC_{s}", f"thigh_{s}",
                      (50.0, 50.0, 20.0), ((-45.0, 45.0), (-20.0, 120.0), (-45.0, 45.0))),
            JointSpec(f"knee_{s}", f"thigh_{s}_distal", f"shank_{s}_proximal", f"KJC_{s}",
                      f"shank_{s}", (400.0, 5.0, 20.0),
                      ((-15.0, 15.0), (-2.0, 140.0), (-30.0, 30.0))),
            JointSpec(f"ankle_{s}", f"shank_{s}_distal", f"foot_{s}", f"AJC_{s}",
                      f"foot_{s}", (30.0, 30.0, 30.0),
                      ((-30.0, 30.0), (-30.0, 30.0), (-30.0, 30.0))),
            JointSpec(f"shoulder_{s}", "T1", f"upper_arm_{s}_proximal", f"SJC_{s}",
                      f"upper_arm_{s}", (10.0, 10.0, 10.0),
                      ((-90.0, 90.0), (-90.0, 90.0), (-90.0, 90.0))),
            JointSpec(f"elbow_{s}", f"upper_arm_{s}_distal", f"forearm_{s}_proximal",
                      f"EJC_{s}", f"forearm_{s}", (20.0, 5.0, 5.0),
                      ((-10.0, 10.0), (-145.0, 5.0), (-80.0, 80.0))),
            JointSpec(f"wrist_{s}", f"forearm_{s}_distal", f"hand_{s}", f"WJC_{s}",
                      f"hand_{s}", (10.0, 10.0, 10.0),
                      ((-60.0, 60.0), (-60.0, 60.0), (-60.0, 60.0))),
        ]
    if tone:
        out = [JointSpec(j.name, j.body_a, j.body_b, j.centre, j.frame,
                         tuple(tone.get(j.name, j.k)), j.stops) for j in out]
    return out


def walking_tone(sk) -> dict[str, tuple[float, float, float]]:  # noqa: ANN001 - Skeleton
    """The postural tone of ``sk`` if it is walking (:mod:`hollowbody.body.tone`), else
    an empty dict (the standing posture is held by the passive joints)."""
    if getattr(sk, "posture", "standing") != "walking":
        return {}
    from hollowbody.body.tone import postural_tone

    return postural_tone(sk, {j.name: j.k for j in joint_specs()})
