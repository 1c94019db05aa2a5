"""Dynamic three-point bending of the thigh and the leg (Kerrigan et al. 2004).

The tests (:data:`hollowbody.validation.cases.KERRIGAN`): a whole thigh or leg
lying on two supports at its ends, struck lateral-to-medial by a cylindrical
ram at a constant 1.5 m/s. The paper loads at mid-span; so does this set-up.

:func:`bending_setup` builds the test on

- the open pedestrian (``tissue`` ``solid`` or ``hollow``): the left thigh or
  left shank is cut from the standing body (:mod:`hollowbody.validation.segment`:
  long-bone shell tube, its two rigid end rows (epiphyses), muscle, skin);
  the hollow variant converts the segment's muscle afterwards
  (:func:`hollowbody.hollow.convert.hollowize`, 30 mm cells, 1.5 mm walls, no
  self-contact, as ``hollowbody pedestrian --tissue hollow``). The
  epiphyses are the supports: *MAT_RIGID CMO = 1, the proximal one pinned
  (CON1 = 7: x, y, z held; CON2 = 3: the spin about the limb's axis held, the
  bending rotations free), the distal one a roller (CON1 = 4: x and y held,
  free along the limb's axis z; rotations free). No gravity, no floor, no
  joints;
- a user's deck of the segment alone (``model`` + landmark entry, tissue
  ``user``): the deck is included unchanged; the supports are its rigid end
  parts (zero prescribed velocities of the same degrees of freedom) or node
  sets (*BOUNDARY_SPC_SET) named in the landmark file.

The impactor is a rigid shell cylinder (diameter ``Case.impactor_diameter`` at
its contact face, axis normal to the limb and to the travel: x for the
pedestrian) driven at constant ``speed`` along ``direction`` (-y, lateral to
medial on the left leg) by *BOUNDARY_PRESCRIBED_MOTION_RIGID (VAD = 0), its
other translations and its rotations held (*MAT_RIGID CON1/CON2). It starts
:data:`GAP` mm (between the contact surfaces) from the skin, its axis's path
through the load point. Contact *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE,
impactor = master, skin = slave (SOFT = 1, friction :data:`FRICTION`).

Landmark entry of a user's model (JSON, mm; ``docs/validation.md``)::

    {"thigh-bending": {"proximal_part": 16, "distal_part": 17,
                       "point": [0, 188, 710], "direction": [0, -1, 0],
                       "contact_parts": [19]}}

``proximal_part`` / ``distal_part``: rigid parts held at their centres of mass,
or ``proximal_nodes`` / ``distal_nodes``: node ids (held by SPCs, in global
axes: the limb's axis must be a global axis within :data:`AXIS_TOLERANCE_DEG`);
``point``: the load point on the skin; ``direction``: the impactor's travel;
``contact_parts``: the parts it strikes; optional ``axis``: the impactor's
axis (default: normal to the travel and to the limb).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    Contact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    Deck,
    DefineCurve,
    MatRigid,
    Part,
    PrescribedMotionRigid,
    SectionShell,
    SetPartList,
)
from hollowbody.model.model import Model
from hollowbody.validation import cylinder as cyl
from hollowbody.validation.cases import case as case_of
from hollowbody.validation.cases import end_time_of
from hollowbody.validation.setup import Setup, unit

#: Segment of the pedestrian each case cuts (left side: struck laterally along -y).
SEGMENTS = {"thigh-bending": "thigh", "leg-bending": "shank"}
SIDE = "l"
#: Travel of the impactor on the pedestrian: lateral to medial of the left leg.
DIRECTION = (0.0, -1.0, 0.0)
GAP = 2.0  # mm between the impactor's and the skin's contact surfaces at t = 0
FRICTION = 0.2  # impactor-skin, static and dynamic
IMPACTOR_T = 1.0  # mm, shell thickness of the rigid cylinder
IMPACTOR_MASS = 5.0  # kg (driven: any value)
OUTPUT_DT = 0.1  # ms, the histories (the ratings resample at 0.1 ms)
#: *CONTROL_TERMINATION DTMIN with ERODE 1 (as the hollow block: docs/block.md).
DTMIN = 0.05
#: LS-DYNA *MAT_RIGID CON1 / CON2 codes of the supports (global axes).
PROXIMAL_CON = (7, 3)
DISTAL_CON = (4, 0)
#: Largest angle (deg) between a user's limb axis and a global axis for a roller in
#: global axes.
AXIS_TOLERANCE_DEG = 1.0
#: CON codes by the set of held global axes.
CON_CODE = {(): 0, (0,): 1, (1,): 2, (2,): 3, (0, 1): 4, (1, 2): 5, (0, 2): 6, (0, 1, 2): 7}


@dataclass
class Test:
    """What the test needs of a segment model: support points (3,) mm (where the
    supports hold it), slave parts, load point (3,) mm on the skin, travel direction
    (3,), impactor axis (3,) or None, history node ids, and the segment deck's built
    model (kept to avoid building it twice)."""

    proximal: np.ndarray
    distal: np.ndarray
    contact_parts: list[int]
    point: np.ndarray
    direction: np.ndarray
    axis: np.ndarray | None = None
    history: list[int] = field(default_factory=list)
    model: Model | None = None

    @property
    def span(self) -> float:
        return float(np.linalg.norm(self.distal - self.proximal))

    @property
    def limb_axis(self) -> np.ndarray:
        """Unit vector from the proximal to the distal support."""
        return (self.distal - self.proximal) / self.span

    @property
    def load_a(self) -> float:
        """Distance (mm) along the limb from the proximal support to where the load's
        line (through ``point`` along ``direction``) passes the limb's axis (closest
        approach of the two lines)."""
        u, d = self.limb_axis, unit(self.direction)
        w = self.proximal - self.point
        b = float(u @ d)
        return float((b * (d @ w) - (u @ w)) / (1.0 - b * b))


def bending_setup(case: str, speed: float = 1.5, tissue: str = "solid", mesh: float = 30.0,
                  end_time: float | None = None, model: Path | None = None,
                  landmarks: dict | None = None, landmarks_path: Path | None = None,
                  hollow_options=None) -> Setup:  # noqa: ANN001 - HollowOptions
    """The three-point bending test ``case`` (``thigh-bending``, ``leg-bending``).

    speed m/s (= mm/ms); tissue ``solid`` / ``hollow`` (the pedestrian's segment,
    soft-tissue element size ``mesh`` mm) or, with ``model`` (a deck of the segment
    alone), the user's model located by ``landmarks`` (the landmark file's
    entries by case, read from ``landmarks_path`` when not given; errors name
    that file). end_time ms (default: the case's). ``hollow_options``: a
    :class:`~hollowbody.hollow.convert.HollowOptions` for the hollow variant.
    """
    c = case_of(case)
    if c.kind != "bending" or case not in SEGMENTS:
        raise ValueError(f"{case!r} is not a bending case (those are: {', '.join(SEGMENTS)})")
    if not speed > 0.0:
        raise ValueError(f"the speed must be positive (got {speed:g} m/s)")
    end = float(end_time) if end_time is not None else end_time_of(c, speed)
    if not end > 0.0:
        raise ValueError(f"the end time must be positive (got {end:g} ms)")
    if model is not None:
        from hollowbody.validation.bending_user import user_segment

        parts_deck, test, supports, notes = user_segment(case, Path(model), landmarks,
                                                         landmarks_path)
        tissue = "user"
    else:
        if tissue not in ("solid", "hollow"):
            raise ValueError(f"tissue must be solid or hollow (got {tissue!r})")
        if not 10.0 <= mesh <= 50.0:
            raise ValueError(f"mesh must be between 10 and 50 mm (got {mesh:g})")
        parts_deck, test, notes = _pedestrian_segment(case, tissue, mesh, hollow_options)
        supports = None
    return _assemble(c, speed, tissue, end, parts_deck, test, supports, notes)


# ---------------------------------------------------------------------------
# the pedestrian's segment


def _pedestrian_segment(case: str, tissue: str, mesh: float, hollow_options
                        ) -> tuple[Deck, Test, list[str]]:  # noqa: ANN001
    from hollowbody.body.generate import hollow_parts
    from hollowbody.body.pedestrian import build_body
    from hollowbody.validation.segment import cut_segment

    body = build_body(mesh=mesh)
    seg = cut_segment(body, SEGMENTS[case], SIDE)
    hold_epiphyses(seg.deck, seg.pids["proximal"], seg.pids["distal"])
    deck = seg.deck
    notes = [f"segment: the left {SEGMENTS[case]} ({seg.name}) of the open pedestrian "
             f"(standing, {body.skeleton.stature:g} mm, {body.skeleton.mass:g} kg, "
             f"{mesh:g} mm soft-tissue mesh): bone shell tube, its two rigid epiphyses, "
             "muscle and skin only, cut at the flesh's ends 12 mm short of the joint "
             "centres; no joints, no gravity (the tests' specimens lay horizontal on their "
             "supports; the model's limb stands along z), no floor"]
    if tissue == "hollow":
        from hollowbody.hollow.convert import HollowOptions, Selection, hollowize

        pids = [p for p in hollow_parts(body) if p in seg.pids.values()]
        deck, rep = hollowize(deck, Selection(parts=pids),
                              hollow_options or HollowOptions(self_contact=False))
        o = rep.options
        notes.append(f"hollow: muscle part(s) {pids} converted after the cut (cell "
                     f"{o.get('cell', '?')} mm, walls {o.get('thickness', '?')} mm, "
                     f"self-contact {o.get('self_contact', '?')}); mass kept")
        notes += [f"hollow conversion: {w}" for w in rep.warnings]
    m = build_model(deck)
    centres = rigid_centres(m)
    prox, dist = centres[seg.pids["proximal"]], centres[seg.pids["distal"]]
    d = np.asarray(DIRECTION)
    mid = 0.5 * (prox + dist)
    skin = cyl.surface_of(m, [seg.pids["skin"]])
    point = cyl.ray_hit(skin, mid, -d)
    if point is None:
        raise RuntimeError(f"no skin lateral of the mid-span point {mid.round(1)}")
    test = Test(prox, dist, [seg.pids["skin"]], point, d, model=m)
    test.history = [_medial_bone_node(m, seg.pids["bone"], mid, d)]
    joints = float(np.linalg.norm(seg.distal_joint - seg.proximal_joint))
    notes += [
        "supports: the rigid epiphyses (no potting cups), held at their centres of mass by "
        "*MAT_RIGID CMO=1: proximal pinned (CON1=7 x, y, z; CON2=3: the spin about the "
        "limb's axis held, bending rotations free), distal a roller (CON1=4 x, y; free "
        "along the limb, rotations free); no axial preload",
        f"span {test.span:.1f} mm between the epiphyses' centres of mass (joint centres "
        f"{joints:.1f} mm apart); load at mid-span, on the skin at {np.round(point, 1).tolist()}",
        "impactor-skin contact only (hollow: the converted muscle's boundary shells lie on "
        "the skin's nodes and are left out, so both variants have one contact surface)",
        "deflection = impactor travel from first contact (includes the soft tissue's "
        "compression, as the tests' ram displacement); bone mid-span: history node "
        f"{test.history[0]} (medial side of the bone)",
        "bone: *MAT_PLASTIC_KINEMATIC without failure strain: it yields and hardens, it "
        "does not fracture (the tests end at fracture)",
    ]
    return deck, test, notes


def hold_epiphyses(deck: Deck, proximal: int, distal: int) -> None:
    """Set *MAT_RIGID CMO = 1, CON1/CON2 of the epiphyses' materials in ``deck``:
    :data:`PROXIMAL_CON` on part ``proximal``, :data:`DISTAL_CON` on ``distal``."""
    parts = {p.pid: p for p in deck.of_type(Part)}
    mats = {m.mid: m for m in deck.of_type(MatRigid)}
    for pid, (c1, c2) in ((proximal, PROXIMAL_CON), (distal, DISTAL_CON)):
        mat = mats.get(parts[pid].mid)
        if mat is None:
            raise ValueError(f"part {pid} is not rigid")
        mat.cmo, mat.con1, mat.con2 = 1.0, float(c1), float(c2)


def rigid_centres(m: Model) -> dict[int, np.ndarray]:
    """Centre of mass (3,) mm of each rigid body of ``m`` by lead part id (where the
    solver holds a body's constrained translations)."""
    from hollowbody.model.mass import lumped_node_mass
    from hollowbody.model.rigid_bodies import rigid_body_defs

    node_mass, _ = lumped_node_mass(m)
    return {b.pid: np.asarray(b.centre, float) for b in rigid_body_defs(m, node_mass)}


def _medial_bone_node(m: Model, pid: int, mid: np.ndarray, d: np.ndarray) -> int:
    """Id of the bone node nearest to mid-span on the far side from the impactor."""
    idx = np.unique(np.concatenate([g.conn.ravel() for g in m.shell_groups if g.pid == pid]))
    x = m.node_x0[idx]
    r = float(((x - mid) @ d).max())
    k = int(np.argmin(np.linalg.norm(x - (mid + r * d), axis=1)))
    return int(m.node_ids[idx[k]])


# ---------------------------------------------------------------------------
# the test around a segment deck


def _assemble(c, speed: float, tissue: str, end: float, parts_deck: Deck,  # noqa: ANN001
              test: Test, supports, notes: list[str]) -> Setup:  # noqa: ANN001
    """Main deck: the include of ``parts_deck``, the impactor, its motion and contact,
    the supports (``supports(ids, first free curve id)`` -> keyword items, or None when
    the parts deck holds them), control and outputs (after the includes: they win
    over any the included deck has, in LS-DYNA as in hollowbody)."""
    from hollowbody.hollow.deck_edit import IdAllocator

    d = unit(test.direction)
    axis = test.axis if test.axis is not None else np.cross(d, test.limb_axis)
    f = cyl.frame(d, axis)
    m = test.model if test.model is not None else build_model(parts_deck)
    skin = cyl.surface_of(m, test.contact_parts)
    radius = 0.5 * c.impactor_diameter  # of the contact face
    # length: the contact parts' extent along the axis either side of the load point
    half = float(np.abs((skin.x[np.unique(skin.seg)] - test.point) @ f[0]).max()) + 20.0
    # start clear of the whole surface behind the load point, then find the first touch
    behind = float(((test.point - skin.x[np.unique(skin.seg)]) @ d).max(initial=0.0))
    start = test.point - d * (radius + behind + 10.0)
    travel, touch = cyl.first_contact_travel(skin, start, d, f[0], radius, half)
    centre = start + (travel - GAP) * d
    ids = IdAllocator(parts_deck)
    pid = _next_id(list(m.parts))
    lc = _next_id(list(m.curves) + [cv.lcid for cv in parts_deck.of_type(DefineCurve)])
    nodes, quads = cyl.cylinder_mesh(centre, f[0], radius - 0.5 * IMPACTOR_T, 2.0 * half)
    area = float(cyl.quad_areas(nodes, quads).sum())
    rho = IMPACTOR_MASS / (area * IMPACTOR_T)
    main = Deck()
    main.title = (f"hollowbody validate {c.name}: three-point bending at {speed:g} m/s, "
                  f"{tissue}")
    n0, e0 = ids.take("node", nodes.shape[0]), ids.take("element", quads.shape[0])
    imp = Deck()
    imp.add_nodes(n0 + np.arange(nodes.shape[0]), nodes)
    imp.add_shells(e0 + np.arange(quads.shape[0]), pid, n0 + quads)
    secid, mid = ids.take("section"), ids.take("material")
    imp.add(Part(pid=pid, secid=secid, mid=mid,
                 title=f"impactor: rigid cylinder {c.impactor_diameter:g} mm"))
    imp.add(SectionShell(secid=secid, elform=2, t1=IMPACTOR_T, t2=IMPACTOR_T, t3=IMPACTOR_T,
                         t4=IMPACTOR_T))
    zero = tuple(i for i in range(3) if d[i] == 0.0)
    imp.add(MatRigid(mid=mid, ro=rho, e=210.0, pr=0.3, cmo=1.0, con1=float(CON_CODE[zero]),
                     con2=7.0, title="impactor (driven)"))
    imp.add(DefineCurve(lcid=lc, points=[[0.0, 1.0], [max(10.0 * end, 1.0e3), 1.0]],
                        title="impactor speed: constant"))
    for i in range(3):
        if d[i] != 0.0:
            imp.add(PrescribedMotionRigid(pid=pid, dof=i + 1, vad=0, lcid=lc,
                                          sf=float(speed * d[i])))
    cid = ids.take("contact")
    if len(test.contact_parts) == 1:
        ssid, sstyp = test.contact_parts[0], 3
    else:
        ssid, sstyp = ids.take("part_set"), 2
        imp.add(SetPartList(sid=ssid, parts=test.contact_parts, title="struck parts"))
    imp.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=cid, heading="impactor-skin",
                    ssid=ssid, sstyp=sstyp, msid=pid, mstyp=3, fs=FRICTION, fd=FRICTION,
                    soft=1))
    for it in supports(ids, lc + 1) if supports is not None else []:
        imp.add(it)
    main.add_include(_include_name(parts_deck), parts_deck)
    main.add_include("impactor.k", imp)
    _controls(main, parts_deck, end, notes)
    for name in ("GLSTAT", "MATSUM", "RCFORC", "RBDOUT", "NODOUT"):
        main.add(DatabaseAscii(name=name, dt=OUTPUT_DT))
    main.add(DatabaseBinaryD3plot(dt=end / 15.0))
    if test.history:
        main.add(DatabaseHistoryNode(ids=list(test.history)))
    gap_axis = float((test.point - centre) @ d) - radius
    notes.append(f"impactor: axis {np.round(f[0], 4).tolist()}, {2.0 * half:.0f} mm long, "
                 f"{IMPACTOR_MASS:g} kg; face {GAP:g} mm from the skin's contact surface "
                 f"(first touch at {np.round(touch, 1).tolist()}; {gap_axis:.2f} mm from the "
                 f"load point along the travel); friction {FRICTION:g}")
    return Setup(case=c.name, speed=float(speed), tissue=tissue, deck=main, end_time=end,
                 impactor_pid=pid, impactor_mass=IMPACTOR_MASS, contact_id=cid,
                 direction=tuple(float(v) for v in d),
                 impact_point=tuple(float(v) for v in test.point),
                 contact_time=GAP / float(speed), reference_node=None, span=test.span,
                 load_a=test.load_a, load_b=test.span - test.load_a, notes=notes)


def _controls(main: Deck, parts_deck: Deck, end: float, notes: list[str]) -> None:
    """*CONTROL_TERMINATION (ENDTIM ``end``; DTMIN :data:`DTMIN`) and *CONTROL_TIMESTEP
    (TSSFAC 0.9, ERODE 1); a user's deck keeps its own *CONTROL_TIMESTEP (mass scaling,
    step factor) and its termination's other fields."""
    own_t = parts_deck.of_type(ControlTermination)
    own_s = parts_deck.of_type(ControlTimestep)
    if own_t:
        t = dataclasses.replace(own_t[-1], endtim=end)
        notes.append(f"the model's *CONTROL_TERMINATION kept but ENDTIM = {end:g} ms")
    else:
        t = ControlTermination(endtim=end, dtmin=DTMIN)
    main.add(t)
    if own_s:
        notes.append("the model's *CONTROL_TIMESTEP kept (ERODE "
                     f"{int(own_s[-1].erode)}, DT2MS {own_s[-1].dt2ms:g})")
    else:
        main.add(ControlTimestep(tssfac=0.9, erode=1))
        notes.append(f"erosion on (ERODE 1, DTMIN {DTMIN:g}): elements crushed until their "
                     f"step is {100 * DTMIN:g} % of the initial one (hollow walls under the "
                     "impactor) are deleted instead of ending the run; summary.json counts them")


def _next_id(used: list[int]) -> int:
    """The next multiple of 1000 above ``used``, plus one (1001 for none)."""
    return (max(used, default=0) // 1000 + 1) * 1000 + 1


def _include_name(parts_deck: Deck) -> str:
    """``segment.k`` (the pedestrian's), or ``model/<name>`` (a user's deck, copied there
    when the main deck is written with its includes)."""
    return "segment.k" if parts_deck.path is None else f"model/{Path(parts_deck.path).name}"
