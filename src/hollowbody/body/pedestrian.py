"""The open pedestrian model: the body's parts, masses and joints assembled.

:func:`build_body` makes the meshes of :mod:`hollowbody.body.anatomy` in the
posture of a :class:`~hollowbody.body.skeleton.Skeleton`, sizes the flesh of
each segment so it carries most of de Leva's segment mass, and gives the rigid
pieces of the segment the rest (the epiphyses of a limb segment; spine zones
of a trunk third; pelvis and sacrum of the lower trunk), so every segment's
mass is de Leva's. Head (with neck), hands and feet are rigid shells whose
mass, centre of mass and inertia are de Leva's (*PART_INERTIA).

:mod:`hollowbody.body.deck` turns the result into a keyword deck;
:mod:`hollowbody.body.joints` lists the joints. Units mm, kg, kg*mm^2.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.body import anatomy as an
from hollowbody.body.anthropometry import DEFAULT_MASS, DEFAULT_STATURE
from hollowbody.body.materials import MATERIALS
from hollowbody.body.skeleton import Skeleton, standing, walking
from hollowbody.body.tube import _signed_volume

#: Share of each limb segment's mass carried by the flesh (bone, muscle, skin); the
#: two epiphyses carry the rest (bone ends, joint capsules, missing flesh). The
#: shares put the segment's transverse moments of inertia near de Leva's (the mass
#: at the ends weighs with the square of the half-length; docs/pedestrian.md).
FLESH_SHARE = {"thigh": 0.88, "shank": 0.98, "upper_arm": 0.98, "forearm": 0.95}
#: Neck share of de Leva's head-and-neck mass (VIVA+ 50M: neck 1.16 kg of 5.58 kg).
NECK_SHARE = 1.16 / (1.16 + 4.42)
#: Rigid parts that carry the rest of a trunk third: part key -> share.
TRUNK_FILL = {"upper_trunk": {"spine_T1": 0.3, "spine_T8": 0.7},
              "middle_trunk": {"spine_T12": 0.5, "spine_L3": 0.5},
              "lower_trunk": {"pelvis": 0.7, "spine_sacrum": 0.3}}
LIMBS = ("thigh", "shank", "upper_arm", "forearm")
#: Gap (mm) between the hanging arm and the trunk and thigh (a choice).
ARM_CLEARANCE = 12.0


@dataclass
class Body:
    """The assembled body: mesh, skeleton, parts by key, rigid densities by pid
    (kg/mm^3), the flesh scale of each segment, and the inertia carriers merged into
    rigid parts (rigid pid -> carrier pid; :mod:`hollowbody.body.inertia_fit`)."""

    mesh: an.BodyMesh
    skeleton: Skeleton
    parts: dict[str, an.PartMesh]
    rigid_density: dict[int, float] = field(default_factory=dict)
    scales: dict[str, float] = field(default_factory=dict)
    mesh_size: float = 25.0
    carriers: dict[int, int] = field(default_factory=dict)


def element_masses(x: np.ndarray, part: an.PartMesh, density: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(masses (e,) kg, centroids (e, 3) mm) of a part's elements at ``density`` kg/mm^3."""
    p = x[part.conn]
    if part.kind == "solid":
        vol = _signed_volume(x, part.conn)
    else:
        vol = 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]),
                                   axis=1) * part.thickness
    return vol * density, p.mean(axis=1)


def part_density(body: Body, part: an.PartMesh) -> float:
    """Density kg/mm^3 of a part (rigid parts: their fill density)."""
    if part.rigid:
        return body.rigid_density.get(part.pid, 1.0e-9)
    return MATERIALS[part.material].density


def segment_masses(body: Body, rigid: bool = True) -> dict[str, float]:
    """Model mass (kg) per segment label; rigid parts with *PART_INERTIA count their
    TM; ``rigid=False``: deformable parts only."""
    x = body.mesh.coords()
    out: dict[str, float] = {}
    for p in body.mesh.parts:
        if p.rigid and not rigid:
            continue
        if p.inertia is not None:
            out[p.segment[0]] = out.get(p.segment[0], 0.0) + p.inertia[0]
            continue
        m, _ = element_masses(x, p, part_density(body, p))
        for s in np.unique(p.segment):
            out[s] = out.get(s, 0.0) + float(m[p.segment == s].sum())
    return out


def build_body(stature: float = DEFAULT_STATURE, mass: float = DEFAULT_MASS,
               mesh: float = 25.0, posture: str = "standing", struck: str = "l",
               scales: dict[str, float] | None = None, skeleton: Skeleton | None = None,
               fit: bool = True) -> Body:
    """The body of ``stature`` mm and ``mass`` kg, soft-tissue element size ``mesh`` mm.

    ``posture``: ``standing`` or ``walking`` (struck side ``struck`` forward);
    ``scales``: flesh scale by segment (default: sized so the flesh carries
    :data:`FLESH_SHARE` of the segment mass). The shoulder joint centres are
    placed where the hanging arms clear the trunk and thighs by
    :data:`ARM_CLEARANCE` (at least Winter's half shoulder width);
    ``skeleton`` overrides the posture; ``fit``: the fill masses of the trunk thirds'
    and limb segments' rigid parts move into inertia carriers that fit the segment
    inertias to de Leva's (:func:`hollowbody.body.inertia_fit.fit_inertias`; False: the
    fill stays on the rigid shells). Raises ValueError for a non-positive
    size, stature or mass or an unknown posture.
    """
    if not mesh > 0.0:
        raise ValueError(f"the element size must be positive (got {mesh:g} mm)")
    if posture not in ("standing", "walking"):
        raise ValueError(f"posture must be standing or walking (got {posture!r})")
    if skeleton is not None:
        sk = skeleton
    else:
        if scales is None:
            base = standing(stature, mass)
            scales = flesh_scales(stature, mass, mesh, base)
        half = shoulder_half_width(standing(stature, mass), scales)
        sk = (standing(stature, mass, half) if posture == "standing"
              else walking(stature, mass, struck, shoulder_half_width=half))
    if scales is None:
        scales = flesh_scales(stature, mass, mesh, sk)
    body = an.BodyMesh()
    parts: dict[str, an.PartMesh] = {}
    for key, p in an.trunk(body, sk, mesh, scales["trunk"]).items():
        parts[f"trunk_{key}"] = p
    for side in ("l", "r"):
        for s in LIMBS:
            for key, p in an.limb(body, sk, s, side, mesh, scales[s]).items():
                parts[f"{s}_{side}_{key}"] = p
    _extremities(body, sk, parts, mesh)
    out = Body(body, sk, parts, {}, dict(scales), mesh)
    _fill_rigid(out)
    if fit:
        from hollowbody.body.inertia_fit import fit_inertias
        from hollowbody.body.mass_report import _frame, targets

        t = targets(out)
        labels = [k for k in t if not k.startswith(("head", "hand", "foot"))]
        fit_inertias(out, {k: t[k]["inertia"] for k in labels},
                     {k: _frame(out, k) for k in labels})
    return out


def flesh_scales(stature: float, mass: float, mesh: float, sk: Skeleton) -> dict[str, float]:
    """Flesh scale per limb segment so the flesh carries :data:`FLESH_SHARE` of its mass."""
    first = build_body(stature, mass, mesh, scales={s: 1.0 for s in LIMBS + ("trunk",)},
                       skeleton=sk, fit=False)
    flesh = segment_masses(first, rigid=False)
    scales = {s: float(np.sqrt(sk.segments[s].mass * FLESH_SHARE[s] / flesh[f"{s}_l"]))
              for s in LIMBS}
    scales["trunk"] = 1.0
    return scales


def shoulder_half_width(sk: Skeleton, scales: dict[str, float]) -> float:
    """Lateral position (mm) of the shoulder joint centres: the hanging upper arm clears the
    trunk, and the wrist end of the forearm and the hand clear the thigh's top, by
    :data:`ARM_CLEARANCE`; at least Winter's half shoulder width 0.1295 H."""
    h = sk.stature
    sh = an.LIMB_SHAPES
    trunk = max(an.TRUNK_SHAPE["a"]) * h * scales["trunk"]
    arm = max(sh["upper_arm"]["a"], sh["upper_arm"]["b"]) * h * scales["upper_arm"]
    thigh = (sk.point("HJC_l")[1] + (sh["thigh"]["offset"] + sh["thigh"]["a"]) * h
             * scales["thigh"])
    fore = (max(sh["forearm"]["a"], sh["forearm"]["b"]) * sh["forearm"]["taper"] * h
            * scales["forearm"])  # the wrist end is beside the thigh's top
    hand = 0.017 * h
    return float(max(0.1295 * h, trunk + arm + ARM_CLEARANCE,
                     thigh + max(fore, hand) + ARM_CLEARANCE))


def _extremities(body: an.BodyMesh, sk: Skeleton, parts: dict[str, an.PartMesh],
                 mesh: float) -> None:
    """Head, neck, hands and feet: rigid shells with de Leva's mass and inertia."""
    h = sk.stature
    seg = sk.segments
    n = max(2, int(round(120.0 / mesh)))
    # head and neck: de Leva's head (VERT-CERV) split into a neck cylinder and the head
    hd = seg["head"]
    vert, cerv = sk.point("VERT"), sk.point("CERV")
    com_t = vert + (cerv - vert) * hd.com / hd.length
    i_t = np.diag(np.array(hd.inertia))  # de Leva's, about the segment axes
    semi = np.array([0.056, 0.044, 0.066]) * h  # head half length, breadth, height
    centre = vert - np.array([0.0, 0.0, semi[2]])
    rn = 0.030 * h
    top = centre[2] - semi[2] * np.sqrt(1.0 - (rn / semi[1]) ** 2) - 4.0
    bottom = sk.point("C7T1")[2] + an.JOINT_GAP
    m_n = NECK_SHARE * hd.mass
    c_n = np.array([0.0, 0.0, 0.5 * (top + bottom)])
    ln = top - bottom
    i_n = m_n * np.diag([(3 * rn**2 + ln**2) / 12.0, (3 * rn**2 + ln**2) / 12.0,
                         rn**2 / 2.0])
    m_h = hd.mass - m_n
    c_h = (hd.mass * com_t - m_n * c_n) / m_h
    i_h = i_t - (i_n + m_n * _shift(c_n - com_t)) - m_h * _shift(c_h - com_t)
    if np.any(np.linalg.eigvalsh(i_h) <= 0.0):
        raise ValueError("head inertia not positive after taking out the neck")
    parts["head"] = an.rigid_shell(body, "head", "head_neck", "head", "ellipsoid", centre,
                                   semi, np.eye(3), n, m_h, c_h, i_h)
    parts["neck"] = an.rigid_shell(body, "neck", "head_neck", "head", "ellipsoid",
                                   np.array([0.0, 0.0, 0.5 * (top + bottom)]),
                                   np.array([rn, rn, 0.5 * ln]), np.eye(3), max(2, n // 2),
                                   m_n, c_n, i_n)
    for side in ("l", "r"):
        # hand: a box from the wrist along the forearm axis (palm medial), de Leva mass
        fr = sk.frames[f"hand_{side}"]
        w, m3 = sk.point(f"WJC_{side}"), sk.point(f"MET3_{side}")
        hl = 0.108 * h  # hand length (Winter)
        semi = np.array([0.027 * h, 0.017 * h, 0.5 * (hl - an.JOINT_GAP)])
        c = w - fr[2] * (an.JOINT_GAP + semi[2])
        sg = seg["hand"]
        com = w + (m3 - w) * sg.com / sg.length
        parts[f"hand_{side}"] = an.rigid_shell(
            body, f"hand_{side}", f"arm_{side}", f"hand_{side}", "box", c, semi, fr,
            max(2, n // 2), sg.mass, com, fr.T @ np.diag(sg.inertia) @ fr)
        # foot: a box from heel to toe tip, floor to just below the ankle gap
        heel, ttip, ajc = (sk.point(f"{k}_{side}") for k in ("HEEL", "TTIP", "AJC"))
        ff = sk.frames[f"foot_{side}"]
        length = float(np.linalg.norm(ttip - heel))
        height = float(ajc[2] - heel[2]) - 0.5 * an.JOINT_GAP
        semi = np.array([0.5 * length, 0.5 * 0.055 * h, 0.5 * height])
        c = heel + ff[0] * semi[0] + ff[2] * semi[2]
        sg = seg["foot"]
        com = heel + ff[0] * (sg.com / sg.length) * length + ff[2] * semi[2]
        inertia = np.diag([sg.inertia[2], sg.inertia[1], sg.inertia[0]])
        parts[f"foot_{side}"] = an.rigid_shell(
            body, f"foot_{side}", f"leg_{side}", f"foot_{side}", "box", c, semi, ff,
            max(2, n // 2), sg.mass, com, ff.T @ inertia @ ff)


def _shift(d: np.ndarray) -> np.ndarray:
    """Parallel-axis term |d|^2 I - d d^T (mm^2) for a unit mass at offset d."""
    return float(d @ d) * np.eye(3) - np.outer(d, d)


def _fill_rigid(body: Body) -> None:
    """Rigid part densities so each segment's mass is de Leva's."""
    x = body.mesh.coords()
    flesh = segment_masses(body, rigid=False)
    sk = body.skeleton
    fills: dict[str, dict[str, float]] = dict(TRUNK_FILL)
    for side in ("l", "r"):
        for s in LIMBS:
            fills[f"{s}_{side}"] = {f"{s}_{side}_proximal": 0.5, f"{s}_{side}_distal": 0.5}
    for label, shares in fills.items():
        target = sk.segments[label.rsplit("_", 1)[0] if label[-2:] in ("_l", "_r")
                             else label].mass
        rest = target - flesh.get(label, 0.0)
        if rest <= 0.0:
            raise ValueError(f"{label}: the flesh ({flesh[label]:.3f} kg) is heavier than "
                             f"the segment ({target:.3f} kg); use a smaller flesh scale")
        for key, share in shares.items():
            part = body.parts[f"trunk_{key}" if not key.startswith(LIMBS) else key]
            m_unit, _ = element_masses(x, part, 1.0)
            body.rigid_density[part.pid] = share * rest / float(m_unit.sum())


def rigid_bodies(body: Body) -> dict[str, int]:
    """Rigid body (joint side) name -> pid of the part that represents it."""
    p = body.parts
    out = {"pelvis": p["trunk_pelvis"].pid, "head": p["head"].pid, "neck": p["neck"].pid}
    for z in ("T1", "T8", "T12", "L3"):
        out[z] = p[f"trunk_spine_{z}"].pid
    out["sacrum"] = out["pelvis"]  # merged into the pelvis (*CONSTRAINED_RIGID_BODIES)
    out["sacrum_part"] = p["trunk_spine_sacrum"].pid
    for side in ("l", "r"):
        for s in LIMBS:
            out[f"{s}_{side}_proximal"] = p[f"{s}_{side}_proximal"].pid
            out[f"{s}_{side}_distal"] = p[f"{s}_{side}_distal"].pid
        out[f"hand_{side}"] = p[f"hand_{side}"].pid
        out[f"foot_{side}"] = p[f"foot_{side}"].pid
    return out
