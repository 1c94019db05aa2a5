"""Three-point bending on a user's own segment model: its landmark entry, checked.

:func:`user_segment` reads the user's deck of the segment alone (included
unchanged by the set-up), checks the landmark entry of the case against the
built model (ids that exist, rigid support parts, a limb axis along a global
axis, a travel normal to it, a load point between the supports) and returns
what :mod:`hollowbody.validation.bending` needs. Every error is a
:class:`~hollowbody.errors.UserInputError` naming the landmark file, the case
and the key. Units mm.

Supports (global axes; the limb's axis from the proximal to the distal support
must be a global axis within ``AXIS_TOLERANCE_DEG``):

- ``proximal_part`` / ``distal_part``: a rigid part (*MAT_RIGID) held at its
  body's centre of mass by zero prescribed velocities
  (*BOUNDARY_PRESCRIBED_MOTION_RIGID, VAD = 0, a zero curve): proximal x, y, z and
  the rotation about the limb's axis, distal the two directions normal to the axis;
- ``proximal_nodes`` / ``distal_nodes``: node ids held by *BOUNDARY_SPC_SET in
  the same translations (no rotational DOF: a ring of held nodes also holds the
  end's rotation, closer to a clamp than a pin; give one node, or a rigid part).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from hollowbody.build import build_model
from hollowbody.errors import UserInputError
from hollowbody.io.keyword import (
    BoundarySpcSet,
    Deck,
    DefineCurve,
    KeywordItem,
    PrescribedMotionRigid,
    SetNodeList,
    read_deck,
)
from hollowbody.model.model import Model
from hollowbody.validation import cylinder as cyl
from hollowbody.validation.bending import AXIS_TOLERANCE_DEG, Test, rigid_centres
from hollowbody.validation.landmarks import entry, field_of, load_landmarks

#: Largest angle (deg) between the travel and the plane normal to the limb's axis.
DIRECTION_TOLERANCE_DEG = 10.0
#: Largest distance (mm) from the landmark ``point`` to the struck surface along the travel.
POINT_TOLERANCE = 20.0
Supports = Callable[[Any, int], list[KeywordItem]]


def user_segment(case: str, model_path: Path, landmarks: dict | None,
                 landmarks_path: Path | None) -> tuple[Deck, Test, Supports, list[str]]:
    """(the user's deck, the test's geometry, a maker of the support keywords
    ``(IdAllocator, first free curve id) -> items``, notes) for ``case``."""
    where = landmarks_path if landmarks_path is not None else "<landmarks>"
    if landmarks is None:
        if landmarks_path is None:
            raise UserInputError(f"{case}: a user's model needs a landmark file (--landmarks)")
        landmarks = load_landmarks(landmarks_path)
    e = entry(landmarks, case, where)
    if not model_path.is_file():
        raise UserInputError(f"{model_path}: no such deck file")
    deck = read_deck(model_path)
    m = build_model(deck)

    def bad(key: str, msg: str) -> UserInputError:
        return UserInputError(f"{where}: {case}.{key}: {msg}")

    ends = {}
    for end in ("proximal", "distal"):
        given = [k for k in (f"{end}_part", f"{end}_nodes") if k in e]
        if len(given) != 1:
            raise UserInputError(f"{where}: {case}: give one of {end}_part (a rigid part id) "
                                 f"or {end}_nodes (node ids) (got {given or 'neither'})")
        key = given[0]
        if key.endswith("_part"):
            ends[end] = (key, _rigid_end(m, field_of(e, key, case, where, "id"), model_path,
                                         lambda msg, k=key: bad(k, msg)))
        else:
            ends[end] = (key, _node_end(m, field_of(e, key, case, where, "ids"), model_path,
                                        lambda msg, k=key: bad(k, msg)))
    (pkey, (prox, pref)), (dkey, (dist, dref)) = ends["proximal"], ends["distal"]
    point = np.asarray(field_of(e, "point", case, where, "point"))
    d = np.asarray(field_of(e, "direction", case, where, "point"))
    if not np.linalg.norm(d) > 0.0:
        raise bad("direction", "must not be the zero vector")
    d = d / np.linalg.norm(d)
    d[np.abs(d) < 1e-9] = 0.0
    d = d / np.linalg.norm(d)
    parts = field_of(e, "contact_parts", case, where, "ids")
    missing = [p for p in parts if p not in m.parts]
    if missing:
        raise bad("contact_parts", f"part(s) {missing} are not in {model_path}")
    span = float(np.linalg.norm(dist - prox))
    if not span > 1.0:
        raise bad(dkey, f"the supports are {span:.3g} mm apart (proximal at "
                  f"{np.round(prox, 1).tolist()}, distal at {np.round(dist, 1).tolist()})")
    u = (dist - prox) / span
    k = int(np.argmax(np.abs(u)))
    off = float(np.degrees(np.arccos(min(1.0, abs(u[k])))))
    if off > AXIS_TOLERANCE_DEG:
        raise bad(dkey, f"the limb's axis (proximal -> distal support, "
                  f"{np.round(u, 3).tolist()}) is {off:.1f} deg from the global {'xyz'[k]} "
                  "axis: the roller is held in global axes; rotate the model so the limb lies "
                  f"along x, y or z (within {AXIS_TOLERANCE_DEG:g} deg)")
    tilt = float(np.degrees(np.arcsin(min(1.0, abs(float(d @ u))))))
    if tilt > DIRECTION_TOLERANCE_DEG:
        raise bad("direction", f"{np.round(d, 3).tolist()} is {tilt:.1f} deg out of the plane "
                  f"normal to the limb's axis (at most {DIRECTION_TOLERANCE_DEG:g})")
    axis = None
    if "axis" in e:
        axis = np.asarray(field_of(e, "axis", case, where, "point"))
        if np.linalg.norm(np.cross(axis, d)) < 1e-6 * max(np.linalg.norm(axis), 1e-300):
            raise bad("axis", "must be a non-zero vector not parallel to the direction")
    test = Test(prox, dist, parts, point, d, axis, model=m)
    if not 0.0 < test.load_a < span:
        raise bad("point", f"{point.tolist()} is not between the supports (at "
                  f"{test.load_a:.1f} mm along a {span:.1f} mm span)")
    surface = cyl.surface_of(m, parts)
    hit = cyl.ray_hit(surface, point + d * 1.0e4, -d)  # the outermost crossing of the line
    if hit is None:
        raise bad("point", f"the line through {point.tolist()} along the direction "
                  f"{d.round(3).tolist()} misses the contact parts {parts}")
    off = float(np.linalg.norm(hit - point))
    if off > POINT_TOLERANCE:
        raise bad("point", f"{point.tolist()} is {off:.1f} mm from the contact parts' "
                  f"surface along the direction (at {np.round(hit, 1).tolist()}); give the "
                  "load point on the skin")

    def supports(ids: Any, lcid: int) -> list[KeywordItem]:  # noqa: ANN401 - IdAllocator
        out: list[KeywordItem] = []
        normal = [i for i in range(3) if i != k]
        for end, trans, rot in (("proximal", [0, 1, 2], [k]), ("distal", normal, [])):
            key, (_, ref) = ends[end]
            if key.endswith("_part"):
                if not any(isinstance(it, DefineCurve) and it.lcid == lcid for it in out):
                    out.append(DefineCurve(lcid=lcid, points=[[0.0, 0.0], [1.0e6, 0.0]],
                                           title="support: zero velocity"))
                out += [PrescribedMotionRigid(pid=ref, dof=i + 1, vad=0, lcid=lcid, sf=1.0)
                        for i in trans]
                out += [PrescribedMotionRigid(pid=ref, dof=i + 5, vad=0, lcid=lcid, sf=1.0)
                        for i in rot]
            else:
                sid = ids.take("node_set")
                held = [1 if i in trans else 0 for i in range(3)]
                out.append(SetNodeList(sid=sid, nodes=np.asarray(ref), title=key))
                out.append(BoundarySpcSet(nsid=sid, dofx=held[0], dofy=held[1],
                                          dofz=held[2]))
        return out

    notes = [f"user model {model_path} (included unchanged), landmarks {where}",
             f"supports: {pkey} {_describe(pref)} pinned at {np.round(prox, 1).tolist()} "
             f"(x, y, z{'; spin about the limb axis held' if pkey.endswith('_part') else ''}),"
             f" {dkey} {_describe(dref)} a roller at {np.round(dist, 1).tolist()} (free along "
             f"{'xyz'[k]}); span {span:.1f} mm, load point {test.load_a:.1f} mm from the "
             "proximal support"]
    if pkey.endswith("_nodes") or dkey.endswith("_nodes"):
        notes.append("node supports hold each node's translations: a ring of nodes also holds "
                     "the end's rotation (closer to a clamp than a pin)")
    return deck, test, supports, notes


def _describe(ref: int | np.ndarray) -> str:
    return f"part {ref}" if isinstance(ref, int) else f"{len(ref)} node(s)"


def _rigid_end(m: Model, pid: int, model_path: Path,
               bad: Callable[[str], UserInputError]) -> tuple[np.ndarray, int]:
    """(centre of mass (3,) mm of the rigid body of part ``pid``, pid)."""
    from hollowbody.model.rigid_bodies import lead_of

    if pid not in m.parts:
        raise bad(f"part {pid} is not in {model_path}")
    if m.material_of(pid).kind != "rigid":
        raise bad(f"part {pid} is not rigid (*MAT_RIGID); a support part is a rigid end "
                  "of the bone (or give node ids instead)")
    return rigid_centres(m)[lead_of(m)[pid]], pid


def _node_end(m: Model, nids: list[int], model_path: Path,
              bad: Callable[[str], UserInputError]) -> tuple[np.ndarray, np.ndarray]:
    """(centroid (3,) mm of the nodes, their ids)."""
    ids = np.asarray(nids, dtype=np.int64)
    known = np.isin(ids, m.node_ids)
    if not known.all():
        raise bad(f"node(s) {ids[~known][:5].tolist()} are not in {model_path}")
    order = np.argsort(m.node_ids)
    idx = order[np.searchsorted(m.node_ids[order], ids)]
    return m.node_x0[idx].mean(axis=0), ids
