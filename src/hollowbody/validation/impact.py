"""The lateral hub impacts on the whole body: pelvis, abdomen, thorax, shoulder.

:func:`impact_setup` builds the deck of one case (:mod:`hollowbody.validation.cases`)
at one speed on the open pedestrian (solid or hollow soft tissue, standing,
default stature and mass) or on a user's model (``model`` + its landmark entry):

- the hub (:mod:`hollowbody.validation.impactor`): a rigid shell cylinder,
  150 mm diameter, 60 mm long, flat face toward the body, its axis along the
  travel direction through the case's landmark; the impactor mass exactly
  (*PART_INERTIA); guided (rotations and the translations across its path held,
  *MAT_RIGID CMO = 1), free along its path, starting at the test speed with its
  face ``GAP`` mm from the first skin its face meets;
- *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE: hub = master (part), body = slave
  (part set of the parts it may touch), friction ``FRICTION``, SOFT = 1, contact
  damping ``VDC``;
- outputs: RCFORC, RBDOUT, NODOUT (history nodes: the reference node and the
  node at the hub's face centre, ``Setup.impactor_node``), GLSTAT, MATSUM and
  the pedestrian's JNTFORC / RWFORC every ``OUTPUT_DT`` ms, d3plot every
  ``D3PLOT_DT`` ms; termination at the end time; gravity and the floor of the
  pedestrian deck stay.

Geometry of the pedestrian (x anterior, y to the body's left, z up; struck
side: left, so a pure-lateral hub travels along -y and the oblique one,
30 degrees forward of lateral, along (-sin 30, -cos 30, 0)): thorax at the
xiphoid (XYPH) and abdomen 75 mm below it, axis through the body's vertical
axis; pelvis through the left hip joint centre (the greater trochanter,
approximated at the hip joint centre's height); shoulder through the left
glenohumeral joint centre. Reference nodes (deflection = hub travel minus
theirs): thorax T8, abdomen a node added on the T12 spine body at the impact
height, pelvis the sacrum, shoulder T1.

A user's model: the main deck includes the user's file unchanged (by its
absolute path, never rewritten) and ``impact.k``; the landmark entry gives
``point`` [x, y, z] mm (the hub's axis passes through it), ``direction``
[3] (travel), ``contact_parts`` (part ids the hub may touch),
``reference_node`` and optionally ``gravity`` (default true: gravity
*LOAD_BODY_Z is added unless the model has a *LOAD_BODY of its own).
Units mm, ms, kg, kN; speeds m/s = mm/ms.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

import numpy as np

from hollowbody.errors import UserInputError
from hollowbody.io.keyword import (
    ConstrainedExtraNodesNode,
    Contact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    Deck,
    DefineCurve,
    Include,
    LoadBody,
    SetPartList,
)
from hollowbody.validation import cases
from hollowbody.validation.impactor import (
    HUB_T,
    FreeIds,
    Hub,
    axis_hit,
    first_touch,
    free_ids,
    hub_keywords,
    segment_triangles,
)
from hollowbody.validation.landmarks import entry, field_of, load_landmarks
from hollowbody.validation.setup import Setup, unit

#: Gap (mm) between the hub's face and the first skin it meets, at the start.
GAP = 2.0
#: Hub length (mm) along its axis.
HUB_LENGTH = 60.0
#: Friction of the hub-body contact (static = dynamic), as hollowbody's other
#: tissue-impactor contacts (block, limb bending).
FRICTION = 0.2
#: Viscous damping of the hub-body contact (% of critical, LS-DYNA VDC): damps the
#: penalty springs' chatter between the heavy rigid hub and the light skin nodes (without
#: it the force samples alternate between zero and several times the mean).
VDC = 20.0
#: History output interval (ms; the ratings resample at 0.1 ms) and d3plot interval.
OUTPUT_DT = 0.1
D3PLOT_DT = 2.0
#: DTMIN (a fraction of the first step) with ERODE 1, as the bending set-ups: soft
#: tissue crushed between the hub and the skeleton (the upper arm against the trunk in
#: the shoulder case) is deleted when its step falls below it, instead of ending the run.
DTMIN = 0.05
#: The abdomen's aim below the xiphoid (mm; Viano 1989).
ABDOMEN_BELOW_XYPH = 75.0
#: The pedestrian's parts the hub may touch, by case: prefixes of ``Body.parts`` keys.
CONTACT_REGIONS = {"thorax": ("trunk_",), "abdomen": ("trunk_",),
                   "pelvis": ("trunk_", "thigh_l_"), "shoulder": ("trunk_", "upper_arm_l_")}
#: The pedestrian's reference node (history node name) by case.
REFERENCE = {"thorax": "T8", "abdomen": "T12", "pelvis": "sacrum", "shoulder": "T1"}
#: Segments the pelvis case removes (the paper: struck-side forearm and hand).
PELVIS_OMIT = ("forearm_l", "hand_l")
OUTPUTS = ("GLSTAT", "MATSUM", "RBDOUT", "NODOUT", "RCFORC")
GRAVITY = 9.81e-3  # mm/ms^2


def impact_setup(case: str, speed: float, tissue: str = "solid", mesh: float = 30.0,
                 end_time: float | None = None, model: Path | None = None,
                 landmarks: dict | None = None, landmarks_path: Path | None = None,
                 hollow_options=None) -> Setup:  # noqa: ANN001 - HollowOptions
    """The set-up of impact ``case`` at ``speed`` m/s (see the module docstring).

    tissue ``solid`` or ``hollow`` (the pedestrian's soft tissue; ``mesh`` its
    element size mm; ``hollow_options`` the conversion's), ignored with
    ``model`` (a user's deck; tissue ``user``), which needs the case's
    landmark entry ``landmarks`` (or the whole landmark file's dict, or
    ``landmarks_path`` alone) and ``landmarks_path`` for the messages.
    end_time ms (default: the case's at the nearest test speed). Bad landmark
    input raises UserInputError naming the file, the case and the key.
    """
    c = cases.case(case)
    if c.kind != "impact":
        raise ValueError(f"{case!r} is not an impact case (the impacts: "
                         f"{', '.join(n for n in cases.ORDER if cases.CASES[n].kind == 'impact')})")
    if not speed > 0.0:
        raise ValueError(f"the impact speed must be positive (got {speed:g} m/s)")
    end = float(end_time) if end_time is not None else cases.end_time_of(c, speed)
    if not end > 0.0:
        raise ValueError(f"the end time must be positive (got {end:g} ms)")
    if model is not None:
        return _user_setup(c, float(speed), end, Path(model), landmarks, landmarks_path)
    if tissue not in ("solid", "hollow"):
        raise ValueError(f"tissue must be solid or hollow (got {tissue!r})")
    return _pedestrian_setup(c, float(speed), tissue, float(mesh), end, hollow_options)


def case_direction(c: cases.Case) -> np.ndarray:
    """Travel direction (3,) of a case's hub on the pedestrian: from the body's left,
    ``oblique_deg`` forward of pure lateral (from the left-front)."""
    a = np.radians(c.oblique_deg)
    return np.array([-np.sin(a), -np.cos(a), 0.0]) + 0.0  # no -0.0


def case_landmark(name: str, skeleton) -> np.ndarray:  # noqa: ANN001 - Skeleton
    """The point (3,) mm the hub's axis passes through on the pedestrian."""
    if name == "thorax":
        return skeleton.point("XYPH").copy()
    if name == "abdomen":
        return skeleton.point("XYPH") - np.array([0.0, 0.0, ABDOMEN_BELOW_XYPH])
    if name == "pelvis":
        return skeleton.point("HJC_l").copy()
    if name == "shoulder":
        return skeleton.point("SJC_l").copy()
    raise ValueError(f"no pedestrian landmark for case {name!r}")


# ---------------------------------------------------------------------------
# the open pedestrian


def _pedestrian_setup(c: cases.Case, speed: float, tissue: str, mesh: float, end: float,
                      hollow_options) -> Setup:  # noqa: ANN001
    from hollowbody.body.deck import comment, pedestrian_deck
    from hollowbody.body.generate import PedestrianOptions, build_deck
    from hollowbody.body.pedestrian import rigid_bodies
    from hollowbody.build import build_model

    omit = PELVIS_OMIT if c.name == "pelvis" else ()
    opts = PedestrianOptions(tissue=tissue, mesh=mesh, end_time=end, picture=False)
    deck, info = build_deck(opts, hollow_options, omit=omit)
    body = info["body"]
    sk = body.skeleton
    gone = set(info["omitted_parts"])
    slave = sorted(p.pid for k, p in body.parts.items()
                   if k.startswith(CONTACT_REGIONS[c.name]) and p.pid not in gone)
    point = case_landmark(c.name, sk)
    d = case_direction(c)
    _set_outputs(deck, end)
    ids = free_ids(deck)
    test = Deck()
    notes = [f"the subject stands (standing pedestrian, {sk.stature:g} mm, {sk.mass:g} kg, "
             f"{mesh:g} mm soft-tissue mesh; {tissue} soft tissue); the tests' subjects were "
             "seated cadavers; gravity on, the feet on the floor (rigid wall, friction 0.6), "
             "the body otherwise free",
             f"erosion on (ERODE 1, DTMIN {DTMIN:g}): elements crushed until their step is "
             f"{100 * DTMIN:g} % of the first are deleted (summary.json counts them)"]
    rb = rigid_bodies(body)
    history = dict(info["history"])
    if c.name == "abdomen":  # a reference node on the T12 spine body at the impact height
        z12 = sk.point("T12L1")[2], sk.point("T9T10")[2]
        spine = body.mesh.coords()[np.unique(body.parts["trunk_spine_T12"].conn)]
        at = np.array([spine[:, 0].mean(), 0.0, float(np.clip(point[2], *z12))])
        history["T12"] = ids.node
        test.add_nodes(np.array([ids.node]), at[None, :])
        test.add(ConstrainedExtraNodesNode(pid=rb["T12"], nid=ids.node))
        test.add(DatabaseHistoryNode(ids=[ids.node]))
        notes.append(f"reference node {ids.node}: added on the T12 spine body (part "
                     f"{rb['T12']}) at the impact height, {at.round(1).tolist()} mm")
    if c.name == "pelvis":
        removed = _removed_mass(pedestrian_deck(body)[0], sorted(gone))
        elbow = sk.point("EJC_l")
        nid = ids.node + 1
        test.add_nodes(np.array([nid]), elbow[None, :])
        test.add(ConstrainedExtraNodesNode(pid=rb["upper_arm_l_distal"], nid=nid))
        test.add_masses(np.array([ids.element]), np.array([nid]), removed)
        notes.append(f"left forearm and hand removed (parts {sorted(gone)}, with the elbow "
                     f"and wrist joints), as the paper does; their mass {removed:.4f} kg is a "
                     f"point mass (*ELEMENT_MASS) at the elbow centre, node {nid} on the upper "
                     f"arm's distal rigid end (part {rb['upper_arm_l_distal']}); total mass "
                     "unchanged")
    ref = history[REFERENCE[c.name]]
    ids = dataclasses.replace(ids, node=ids.node + 10, element=ids.element + 10)
    body_model = build_model(deck)
    hub, touch, axis_gap, hit = _place_hub(test, ids, body_model, slave, point, d, c,
                                           speed)
    test.add(SetPartList(sid=ids.set, parts=slave, title="body parts the hub may touch"))
    test.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=ids.contact,
                     heading="hub-body", ssid=ids.set, sstyp=2, msid=hub.pid, mstyp=3,
                     fs=FRICTION, fd=FRICTION, vdc=VDC, soft=1))
    test.add(DatabaseHistoryNode(ids=[hub.centre_node]))
    notes += _hub_notes(c, hub, touch, axis_gap, hit, point, slave, d)
    if c.name in ("thorax", "abdomen"):
        arms = sorted(p.pid for k, p in body.parts.items()
                      if k.startswith(("upper_arm_", "forearm_", "hand_")))
        notes.append("the arms hang at the sides: their parts "
                     f"({arms[0]}-{arms[-1]}) are left out of the hub contact (the hub's path "
                     "crosses the left arm; in the tests the hub struck the chest or abdominal "
                     "wall directly)")
    if c.name == "pelvis":
        notes.append("greater trochanter approximated: the axis passes through the left hip "
                     "joint centre (the model has no trochanter); the slave parts are the "
                     "trunk and the left thigh")
    if c.name == "shoulder":
        notes.append("the axis passes through the left glenohumeral joint centre; the model "
                     "has no clavicle, scapula or deltoid (the joint is on T1) and the arm's "
                     "flesh stops 12 mm below the joint centre: the hub first meets the upper "
                     "arm's lateral skin, below its axis")
    if tissue == "hollow":
        conv = info["conversion"]
        hollow = sorted(p.pid for p in conv.parts) if conv is not None else []
        notes.append(f"hollow variant: converted parts keep their ids, so their shells "
                     f"(parts {sorted(set(hollow) & set(slave))}) are in the slave set")
    test.items.insert(0, comment([f"hollowbody validate: {c.name}, {speed:g} m/s "
                                  f"({c.source.split(',')[0]})", f"hub part {hub.pid}, "
                                  f"contact {ids.contact}, reference node {ref}"]))
    deck.add_include("impact.k", test)
    deck.title = f"hollowbody validate {c.name} {speed:g} m/s: open pedestrian, {tissue}"
    return Setup(case=c.name, speed=speed, tissue=tissue, deck=deck, end_time=end,
                 impactor_pid=hub.pid, impactor_mass=c.impactor_mass,
                 contact_id=ids.contact, direction=tuple(float(v) for v in d),
                 impact_point=tuple(float(v) for v in hit), contact_time=GAP / speed,
                 impactor_node=hub.centre_node, reference_node=int(ref), notes=notes)


def _set_outputs(deck: Deck, end: float) -> None:
    """The pedestrian main deck's termination and output intervals for the test."""
    for t in deck.of_type(ControlTermination):
        t.endtim, t.dtmin = end, DTMIN
    for ts in deck.of_type(ControlTimestep):
        ts.erode = 1
    names = set()
    for a in deck.of_type(DatabaseAscii):
        a.dt = OUTPUT_DT
        names.add(a.name.upper())
    for name in OUTPUTS:
        if name not in names:
            deck.add(DatabaseAscii(name=name, dt=OUTPUT_DT))
    for b in deck.of_type(DatabaseBinaryD3plot):
        b.dt = D3PLOT_DT


def _removed_mass(full: Deck, pids: list[int]) -> float:
    """Mass (kg) of parts ``pids`` as the solver counts it in the deck ``full``."""
    from hollowbody.build import build_model
    from hollowbody.model.mass import lumped_node_mass

    m = build_model(full)
    _, part_mass = lumped_node_mass(m)
    return float(sum(m.part_inertia[p].tm if p in m.part_inertia else part_mass.get(p, 0.0)
                     for p in pids))


def _place_hub(test: Deck, ids: FreeIds, body_model, slave: list[int], point: np.ndarray,  # noqa: ANN001
               d: np.ndarray, c: cases.Case, speed: float
               ) -> tuple[Hub, np.ndarray, float | None, np.ndarray]:
    """Put the hub on the axis through ``point`` with its face GAP before the first
    skin its face meets; (hub, touched point, axis hit distance from the face or None,
    impact point)."""
    from hollowbody.contact.surface import build_surface
    from hollowbody.model.model import SurfaceRef

    surf = build_surface(SurfaceRef("parts", pids=list(slave)), body_model)
    tris = segment_triangles(surf.seg, body_model.node_x0)
    radius = 0.5 * c.impactor_diameter
    ft = first_touch(tris, point, d, radius)
    if ft is None:
        raise UserInputError(f"the hub's path (axis through {np.round(point, 1).tolist()} "
                             f"mm along {np.round(d, 4).tolist()}) misses the body parts "
                             f"{slave}")
    w_touch, touch = ft
    face = point + (w_touch - GAP) * d
    hub = hub_keywords(test, ids, face, d, speed, c.impactor_mass, c.impactor_diameter,
                       HUB_LENGTH, title=f"hub {c.impactor_diameter:g} mm, "
                       f"{c.impactor_mass:g} kg")
    w_axis = axis_hit(tris, point, d)
    hit = point + w_axis * d if w_axis is not None else touch
    return hub, touch, (None if w_axis is None else w_axis - (w_touch - GAP)), hit


def _hub_notes(c: cases.Case, hub: Hub, touch: np.ndarray, axis_gap: float | None,
               hit: np.ndarray, point: np.ndarray, slave: list[int], d: np.ndarray
               ) -> list[str]:
    """What the hub, its start and its contact are, in words."""
    axes = "".join("xyz"[k] for k in hub.held)
    guided = (f"rotations and the {axes} translation{'s' if len(axes) > 1 else ''} held"
              if axes else "rotations held")
    off = float(np.linalg.norm((touch - point) - ((touch - point) @ d) * d))
    out = [f"hub: rigid shell cylinder {c.impactor_diameter:g} mm x {HUB_LENGTH:g} mm "
           f"({HUB_T:g} mm shells), {c.impactor_mass:g} kg (*PART_INERTIA), travelling along "
           f"{np.round(d, 4).tolist()}; guided ({guided}: *MAT_RIGID CMO=1 CON1/CON2), free "
           "along its path with its initial speed, as the tests' pendulum / ram",
           f"the face starts {GAP:g} mm from the first skin it meets ({off:.1f} mm off the "
           f"axis, at {np.round(touch, 1).tolist()} mm); contact_time = gap / speed (the "
           f"contact surfaces, half the hub's {HUB_T:g} mm shell and half the skin's "
           "thickness, meet a little earlier)"]
    if axis_gap is None:
        out.append("the axis itself meets none of the slave parts: the impact point is the "
                   "first touched point")
    else:
        out.append(f"the axis meets the skin {axis_gap:.1f} mm ahead of the face, at "
                   f"{np.round(hit, 1).tolist()} mm (the impact point)")
    out.append(f"contact: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE, hub part {hub.pid} master, "
               f"slave part set of parts {slave}; friction {FRICTION:g} (as hollowbody's "
               f"other tissue-impactor contacts), SOFT=1, viscous damping VDC={VDC:g} % of "
               "critical (damps the contact's chatter between the heavy hub and the light "
               "skin nodes)")
    return out


# ---------------------------------------------------------------------------
# a user's model


def _user_setup(c: cases.Case, speed: float, end: float, model: Path, landmarks: dict | None,
                landmarks_path: Path | None) -> Setup:
    from hollowbody.body.deck import comment
    from hollowbody.build import build_model
    from hollowbody.io.keyword import read_deck

    where = landmarks_path if landmarks_path is not None else Path("landmarks")
    if landmarks is None:
        if landmarks_path is None:
            raise UserInputError(f"--model {model} needs a landmark file (--landmarks)")
        landmarks = load_landmarks(landmarks_path)
    e = _entry_of(landmarks, c.name, where)
    point = np.array(field_of(e, "point", c.name, where, "point"))
    raw = field_of(e, "direction", c.name, where, "point")
    if not np.linalg.norm(raw) > 0.0:
        raise UserInputError(f"{where}: {c.name}.direction must not be the zero vector")
    d = unit(raw)
    slave = field_of(e, "contact_parts", c.name, where, "ids")
    ref = field_of(e, "reference_node", c.name, where, "id")
    gravity = e.get("gravity", True)
    if not isinstance(gravity, bool):
        raise UserInputError(f"{where}: {c.name}.gravity must be true or false "
                             f"(got {gravity!r})")
    path = model.resolve()
    if not path.is_file():
        raise UserInputError(f"{model}: cannot read the model deck (no such file)")
    user = read_deck(str(path))
    body_model = build_model(user)
    missing = [p for p in slave if p not in body_model.parts]
    if missing:
        raise UserInputError(f"{where}: {c.name}.contact_parts: part(s) {missing} are not in "
                             f"{model}")
    if ref not in set(body_model.node_ids.tolist()):
        raise UserInputError(f"{where}: {c.name}.reference_node: node {ref} is not in {model}")
    ids = free_ids(user)
    test = Deck()
    try:
        hub, touch, axis_gap, hit = _place_hub(test, ids, body_model, slave, point, d, c,
                                               speed)
    except UserInputError as err:
        raise UserInputError(f"{where}: {c.name}.point/direction: {err}") from None
    test.add(SetPartList(sid=ids.set, parts=slave, title="body parts the hub may touch"))
    test.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=ids.contact,
                     heading="hub-body", ssid=ids.set, sstyp=2, msid=hub.pid, mstyp=3,
                     fs=FRICTION, fd=FRICTION, vdc=VDC, soft=1))
    test.add(DatabaseHistoryNode(ids=[ref, hub.centre_node]))
    notes = [f"user model {model}: included unchanged; landmarks from {where}"]
    notes += _hub_notes(c, hub, touch, axis_gap, hit, point, slave, d)
    own_gravity = bool(user.of_type(LoadBody))
    if gravity and not own_gravity:
        test.add(DefineCurve(lcid=ids.curve, points=[[0.0, 1.0], [1.0e6, 1.0]],
                             title="gravity"))
        test.add(LoadBody(axis="Z", lcid=ids.curve, sf=GRAVITY))
        notes.append("gravity added (*LOAD_BODY_Z 9.81e-3 mm/ms^2, z up)")
    elif own_gravity:
        notes.append("the model's own *LOAD_BODY is kept" + ("" if gravity else
                     " (gravity: false cannot remove it without rewriting the model)"))
    else:
        notes.append("no gravity (gravity: false)")
    notes.append("the body is as the model has it (posture, supports, floor); the test's "
                 "termination and outputs follow the model's include and replace its own")
    test.items.insert(0, comment([f"hollowbody validate: {c.name}, {speed:g} m/s",
                                  f"hub part {hub.pid}, contact {ids.contact}, reference "
                                  f"node {ref}"]))
    main = Deck()
    main.title = f"hollowbody validate {c.name} {speed:g} m/s: {model.name}"
    main.add(Include(filename=str(path), deck=user, external=True))
    main.add_include("impact.k", test)
    main.add(ControlTermination(endtim=end))
    for name in OUTPUTS:
        main.add(DatabaseAscii(name=name, dt=OUTPUT_DT))
    main.add(DatabaseBinaryD3plot(dt=D3PLOT_DT))
    return Setup(case=c.name, speed=speed, tissue="user", deck=main, end_time=end,
                 impactor_pid=hub.pid, impactor_mass=c.impactor_mass,
                 contact_id=ids.contact, direction=tuple(float(v) for v in d),
                 impact_point=tuple(float(v) for v in hit), contact_time=GAP / speed,
                 impactor_node=hub.centre_node, reference_node=int(ref), notes=notes)


def _entry_of(landmarks: dict[str, Any], case: str, where: Path) -> dict[str, Any]:
    """The case's entry: ``landmarks`` itself when it is one, else its ``case`` entry."""
    if "point" in landmarks or not any(isinstance(v, dict) for v in landmarks.values()):
        return landmarks
    return entry(landmarks, case, where)
