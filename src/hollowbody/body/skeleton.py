"""The body plan: joint centres and segment frames of the standing pedestrian.

Global frame: x anterior, y to the body's left, z up; the floor is z = 0 and
the body stands on it, feet flat. Units mm.

Vertical chain (standing, all landmarks of one body side on one vertical
line; the trunk's landmarks on the body's vertical axis x = y = 0):

    floor -> AJC (ankle height) -> KJC (+ shank) -> HJC = MIDH (+ thigh)
          -> OMPH (+ lower trunk) -> XYPH (+ middle trunk) -> CERV (+ upper trunk)
          -> VERT (+ head and neck) = stature.

Lengths are de Leva's (:mod:`hollowbody.body.anthropometry`) scaled with
stature. De Leva's lengths and the ankle height add up to 2 % more than the
stature (his sample's segment lengths are means of separate measurements and
the trunk's landmarks are not on one vertical): every length of the chain is
multiplied by one factor ``chain_scale`` (0.98 at the default) so that the
vertex is at the stature; the report states it.

Choices where de Leva gives no number (each a stated engineering choice,
scaled with stature; H = stature):

- ankle joint centre height 0.039 H (the ankle height of Drillis and Contini's
  proportions, as reproduced in Winter, Biomechanics and Motor Control of
  Human Movement, 4th ed., 2009, Fig. 4.1);
- hip joint centres 0.052 H either side of the mid-plane (182 mm apart at
  1,753 mm; a choice in the range of adult male hip-joint-centre spacings of
  gait laboratories, narrow enough for two thighs of the right mass to clear
  each other);
- shoulder joint centres at height 0.80 H (Winter's shoulder height 0.818 H
  less 0.018 H from the acromion to the joint centre, a choice) and laterally
  where the hanging arm clears the torso (computed by :mod:`pedestrian`, close
  to Winter's half shoulder width 0.1295 H);
- heel 0.22 of the foot length behind the ankle centre, foot length 0.152 H
  (Winter), so de Leva's HEEL-TTIP foot length is used for the mass only;
- spine zone boundaries and neck: the C7/T1 joint at CERV; occipital condyles
  (head-neck joint) 0.42 of the head length above CERV; T4/T5 at 0.35 of the
  upper trunk below CERV; T9/T10 at XYPH; T12/L1 half-way down the middle
  trunk; L3/L4 at OMPH; L5/S1 at 0.35 of the lower trunk above MIDH
  (anatomical levels assigned to de Leva's landmarks, choices).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.body.anthropometry import DEFAULT_MASS, DEFAULT_STATURE, Segment, segments

ANKLE_HEIGHT = 0.039
HIP_HALF_WIDTH = 0.052
SHOULDER_HEIGHT = 0.80
FOOT_LENGTH = 0.152
HEEL_BEHIND_ANKLE = 0.22
NECK_OC = 0.42
T4_T5 = 0.35
T12_L1 = 0.5
L5_S1 = 0.35

#: Spine zones (rigid bodies) from the top down: name, upper boundary, lower boundary.
SPINE_ZONES = (("T1", "C7T1", "T4T5"), ("T8", "T4T5", "T9T10"), ("T12", "T9T10", "T12L1"),
               ("L3", "T12L1", "L3L4"), ("sacrum", "L3L4", "MIDH"))


@dataclass
class Skeleton:
    """Landmarks and joint centres (name -> (3,) mm) of one posture; sides suffixed
    ``_l`` (y > 0) and ``_r``; frames: segment name -> (3, 3) rows = local x, y, z
    (z from the distal to the proximal joint, x anterior); ``segments``: de Leva's
    scaled segments; chain_scale: the factor on the vertical chain's lengths;
    posture: ``standing`` or ``walking``."""

    stature: float
    mass: float
    points: dict[str, np.ndarray]
    frames: dict[str, np.ndarray]
    segments: dict[str, Segment]
    chain_scale: float
    shoulder_half_width: float = 0.0
    notes: list[str] = field(default_factory=list)
    posture: str = "standing"

    def point(self, name: str) -> np.ndarray:
        """The landmark ``name`` (KeyError naming the known ones otherwise)."""
        try:
            return self.points[name]
        except KeyError:
            raise KeyError(f"no landmark {name!r}; known: {sorted(self.points)}") from None

    def length(self, segment: str) -> float:
        """Modelled length (mm) of a segment: de Leva's scaled by ``chain_scale``."""
        return self.segments[segment].length * self.chain_scale


def standing(stature: float = DEFAULT_STATURE, mass: float = DEFAULT_MASS,
             shoulder_half_width: float | None = None) -> Skeleton:
    """The standing posture of a body of ``stature`` mm and ``mass`` kg.

    ``shoulder_half_width`` (mm): lateral position of the shoulder joint
    centres (default: Winter's half shoulder width 0.1295 H).
    Raises ValueError for a non-positive stature or mass.
    """
    seg = segments(stature, mass)
    h = stature
    za = ANKLE_HEIGHT * h
    chain = ("shank", "thigh", "lower_trunk", "middle_trunk", "upper_trunk", "head")
    scale = (h - za) / sum(seg[s].length for s in chain)

    def ln(name: str) -> float:
        return seg[name].length * scale

    zk = za + ln("shank")
    zh = zk + ln("thigh")
    zo = zh + ln("lower_trunk")
    zx = zo + ln("middle_trunk")
    zc = zx + ln("upper_trunk")
    p: dict[str, np.ndarray] = {}

    def put(name: str, x: float, y: float, z: float) -> None:
        p[name] = np.array([x, y, z], dtype=float)

    put("MIDH", 0.0, 0.0, zh)
    put("OMPH", 0.0, 0.0, zo)
    put("XYPH", 0.0, 0.0, zx)
    put("CERV", 0.0, 0.0, zc)
    put("VERT", 0.0, 0.0, h)
    put("C7T1", 0.0, 0.0, zc)
    put("OC", 0.0, 0.0, zc + NECK_OC * ln("head"))
    put("T4T5", 0.0, 0.0, zc - T4_T5 * ln("upper_trunk"))
    put("T9T10", 0.0, 0.0, zx)
    put("T12L1", 0.0, 0.0, zx - T12_L1 * ln("middle_trunk"))
    put("L3L4", 0.0, 0.0, zo)
    put("L5S1", 0.0, 0.0, zh + L5_S1 * ln("lower_trunk"))
    ys = shoulder_half_width if shoulder_half_width is not None else 0.1295 * h
    zs = SHOULDER_HEIGHT * h
    foot = FOOT_LENGTH * h
    for side, sgn in (("l", 1.0), ("r", -1.0)):
        yh = sgn * HIP_HALF_WIDTH * h
        put(f"HJC_{side}", 0.0, yh, zh)
        put(f"KJC_{side}", 0.0, yh, zk)
        put(f"AJC_{side}", 0.0, yh, za)
        put(f"HEEL_{side}", -HEEL_BEHIND_ANKLE * foot, yh, 0.0)
        put(f"TTIP_{side}", (1.0 - HEEL_BEHIND_ANKLE) * foot, yh, 0.0)
        y = sgn * ys
        put(f"SJC_{side}", 0.0, y, zs)
        put(f"EJC_{side}", 0.0, y, zs - ln("upper_arm"))
        put(f"WJC_{side}", 0.0, y, zs - ln("upper_arm") - ln("forearm"))
        put(f"MET3_{side}", 0.0, y, zs - ln("upper_arm") - ln("forearm") - ln("hand"))
    sk = Skeleton(stature, mass, p, {}, seg, scale, ys)
    sk.frames = segment_frames(sk)
    sk.notes.append(f"vertical chain lengths x {scale:.4f} so that the vertex is at the "
                    f"stature ({h:g} mm)")
    return sk


#: Segment -> (proximal joint, distal joint) whose line is the segment's long axis.
SEGMENT_AXES = {
    "thigh": ("HJC", "KJC"), "shank": ("KJC", "AJC"), "upper_arm": ("SJC", "EJC"),
    "forearm": ("EJC", "WJC"), "hand": ("WJC", "MET3"),
}


def frame_from_axis(down: np.ndarray, forward: np.ndarray | None = None) -> np.ndarray:
    """(3, 3) rows x, y, z: z = -down (unit, distal to proximal), x = ``forward`` (default
    global x) made perpendicular to z, y = z cross x."""
    forward = np.array([1.0, 0.0, 0.0]) if forward is None else np.asarray(forward, float)
    z = -np.asarray(down, float) / np.linalg.norm(down)
    x = forward - np.dot(forward, z) * z
    if np.linalg.norm(x) < 1e-9:
        x = np.array([0.0, 0.0, 1.0]) - z[2] * z
    x /= np.linalg.norm(x)
    return np.vstack([x, np.cross(z, x), z])


def segment_frames(sk: Skeleton) -> dict[str, np.ndarray]:
    """Frames of the limb segments (both sides) and of the trunk, neck, head, feet."""
    out = {}
    for name, (a, b) in SEGMENT_AXES.items():
        for side in ("l", "r"):
            pa, pb = sk.points[f"{a}_{side}"], sk.points[f"{b}_{side}"]
            out[f"{name}_{side}"] = frame_from_axis(pb - pa)
    for side in ("l", "r"):
        out[f"foot_{side}"] = np.eye(3)
    for name in ("trunk", "neck", "head"):
        out[name] = np.eye(3)
    return out


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """(3, 3) rotation matrix by ``angle`` rad about the unit ``axis`` (right hand)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


#: Segments distal to each joint (rotating a joint moves these with it).
DISTAL = {
    "HJC": ("thigh", "shank", "foot"), "KJC": ("shank", "foot"), "AJC": ("foot",),
    "SJC": ("upper_arm", "forearm", "hand"), "EJC": ("forearm", "hand"), "WJC": ("hand",),
}
#: Landmarks that move with each segment.
SEGMENT_POINTS = {"thigh": ("KJC",), "shank": ("AJC",), "foot": ("HEEL", "TTIP"),
                  "upper_arm": ("EJC",), "forearm": ("WJC",), "hand": ("MET3",)}
#: Walking posture (degrees, flexion forward positive): struck-side leg forward, the
#: other leg back, feet flat; arms forward, elbows bent (choices close to the
#: mid-stance gait posture of pedestrian impact tests).
WALKING = {"hip_forward": 20.0, "knee_forward": 5.0, "hip_back": 15.0,
           "shoulder": 20.0, "elbow": 70.0}


def rotate_joint(sk: Skeleton, joint: str, side: str, axis: np.ndarray, angle: float) -> None:
    """Rotate the segments distal to ``joint`` of ``side`` by ``angle`` rad about ``axis``
    through the joint centre (landmarks and frames, in place)."""
    r = rotation(axis, angle)
    c = sk.points[f"{joint}_{side}"].copy()
    for seg in DISTAL[joint]:
        for name in SEGMENT_POINTS[seg]:
            key = f"{name}_{side}"
            sk.points[key] = c + r @ (sk.points[key] - c)
        key = f"{seg}_{side}"
        sk.frames[key] = sk.frames[key] @ r.T


def walking(stature: float = DEFAULT_STATURE, mass: float = DEFAULT_MASS, struck: str = "l",
            angles: dict[str, float] | None = None,
            shoulder_half_width: float | None = None) -> Skeleton:
    """The walking posture: the struck-side (``l`` or ``r``) leg forward, the other back
    with its knee bent so both ankles are at one height, feet flat on the floor, both arms
    forward with bent elbows (``angles`` in degrees override :data:`WALKING`)."""
    if struck not in ("l", "r"):
        raise ValueError(f"struck side must be 'l' or 'r' (got {struck!r})")
    a = dict(WALKING, **(angles or {}))
    sk = standing(stature, mass, shoulder_half_width)
    sk.posture = "walking"
    y = np.array([0.0, 1.0, 0.0])
    other = "r" if struck == "l" else "l"
    lt, ls = sk.length("thigh"), sk.length("shank")
    af, kf, ab = (np.radians(a[k]) for k in ("hip_forward", "knee_forward", "hip_back"))
    drop = lt * np.cos(af) + ls * np.cos(af - kf)
    c = np.clip((drop - lt * np.cos(ab)) / ls, -1.0, 1.0)
    kb = float(np.arccos(c)) - ab  # rear knee flexion
    # forward flexion turns the distal end to +x: a negative rotation about +y
    rotate_joint(sk, "HJC", struck, y, -af)
    rotate_joint(sk, "KJC", struck, y, kf)
    rotate_joint(sk, "AJC", struck, y, af - kf)
    rotate_joint(sk, "HJC", other, y, ab)
    rotate_joint(sk, "KJC", other, y, kb)
    rotate_joint(sk, "AJC", other, y, -(ab + kb))
    for side in ("l", "r"):
        rotate_joint(sk, "SJC", side, y, -np.radians(a["shoulder"]))
        rotate_joint(sk, "EJC", side, y, -np.radians(a["elbow"]))
    # lower the body so the feet stand on the floor
    dz = min(sk.points[f"HEEL_{s}"][2] for s in ("l", "r"))
    for k in sk.points:
        sk.points[k] = sk.points[k] - np.array([0.0, 0.0, dz])
    sk.notes.append(f"walking: struck side {struck} forward (hip {a['hip_forward']:g}, knee "
                    f"{a['knee_forward']:g} deg), other leg back (hip {a['hip_back']:g}, knee "
                    f"{np.degrees(kb):.1f} deg), arms forward (shoulder {a['shoulder']:g}, "
                    f"elbow {a['elbow']:g} deg); body lowered {dz:.1f} mm")
    return sk
