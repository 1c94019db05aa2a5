"""The three-point bending set-ups (thigh, leg) cut from the open pedestrian.

What the set-up must be, checked on the built Model (coarse 50 mm mesh, fast):
the deck builds and writes as valid input; it holds the segment's parts only;
the supports hold exactly the stated degrees of freedom; the impactor is
driven at the speed along the direction, its axis's path through mid-span,
its face the stated gap from the skin; span and load point agree with the
geometry; a user's deck of the segment gives the same test; bad landmark
input is a UserInputError naming the file, the case and the key. One short
run (thigh, solid, 50 mm mesh, 6 ms past contact) checks the physics.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from hollowbody.body.anatomy import JOINT_GAP
from hollowbody.body.pedestrian import build_body
from hollowbody.build import build_model
from hollowbody.errors import UserInputError
from hollowbody.io.keyword import DatabaseHistoryNode, Part, read_deck, write_deck
from hollowbody.model.mass import lumped_node_mass
from hollowbody.model.rigid_bodies import rigid_body_defs
from hollowbody.model.summary import summarize, unsupported_entries
from hollowbody.solver.preflight import first_time_step
from hollowbody.validation.bending import GAP, IMPACTOR_T, bending_setup
from hollowbody.validation.cases import CASES
from hollowbody.validation.segment import cut_segment

MESH = 50.0  # mm: the coarsest pedestrian mesh (fast)
#: ms of the short run past first contact: the flesh (assumed-strain hourglass control,
#: its physical softness) takes most of the first 10 mm of travel before the bone bends.
RUN_MS = 16.0
SEGMENT = {"thigh-bending": "thigh", "leg-bending": "shank"}


@pytest.fixture(scope="module")
def body():
    return build_body(mesh=MESH)


@pytest.fixture(scope="module")
def built():
    """(setup, model) by (case, tissue); the hollow thigh is converted once."""
    out = {}
    for case, tissue in (("thigh-bending", "solid"), ("leg-bending", "solid"),
                         ("thigh-bending", "hollow")):
        s = bending_setup(case, tissue=tissue, mesh=MESH)
        out[case, tissue] = (s, build_model(s.deck))
    return out


VARIANTS = [("thigh-bending", "solid"), ("leg-bending", "solid"), ("thigh-bending", "hollow")]


def _bodies(m):
    return {b.pid: b for b in rigid_body_defs(m, lumped_node_mass(m)[0])}


def _pids(body, case):
    s = SEGMENT[case]
    return {r: body.parts[f"{s}_l_{r}"].pid for r in ("bone", "proximal", "distal", "muscle",
                                                      "skin")}


@pytest.mark.parametrize("case, tissue", VARIANTS)
def test_deck_builds_and_writes_as_valid_input(built, tmp_path, case, tissue) -> None:
    """The written deck (main file + includes) reads back and builds with no unsupported
    keyword, a positive first step, and the histories at 0.1 ms."""
    s, _ = built[case, tissue]
    files = write_deck(s.deck, tmp_path / "deck.k", flatten=False)
    assert {f.name for f in files} == {"deck.k", "segment.k", "impactor.k"}
    m = build_model(read_deck(tmp_path / "deck.k"))
    assert unsupported_entries(m) == []
    assert first_time_step(m)["run_dt"] > 0.0
    for name in ("glstat", "matsum", "rcforc", "nodout"):
        assert m.output.intervals[name] == pytest.approx(0.1)
    assert "*DATABASE_RBDOUT" in (tmp_path / "deck.k").read_text()
    assert s.tissue == tissue and s.reference_node is None
    assert s.end_time == CASES[case].end_time[1.5]


@pytest.mark.parametrize("case, tissue", VARIANTS)
def test_only_the_segment_is_kept(built, body, case, tissue) -> None:
    """Parts: the segment's bone, epiphyses (with their inertia carriers), muscle and
    skin and the impactor; no joint, load, floor or SPC; the segment's mass is de
    Leva's (the pedestrian sizes each segment to it; 0.1 %: the solver's element
    volumes differ from the generator's by 0.03 % here; the hollow conversion keeps
    the mass within 0.5 %)."""
    s, m = built[case, tissue]
    pids = _pids(body, case)
    carriers = {body.carriers[pids[r]] for r in ("proximal", "distal")}
    assert set(m.parts) == set(pids.values()) | carriers | {s.impactor_pid}
    name = f"{SEGMENT[case]}_l"
    titles = {p.pid: p.title for p in s.deck.of_type(Part)}
    assert all(titles[p].startswith(name) for p in pids.values())
    assert not (m.joints or m.loads or m.rigid_walls or m.spcs or m.extra_nodes)
    seg_mass = summarize(m)["mass_kg"] - s.impactor_mass
    target = body.skeleton.segments[SEGMENT[case]].mass
    assert seg_mass == pytest.approx(target, rel=0.005 if tissue == "hollow" else 1e-3)
    used = np.unique(np.concatenate([g.conn.ravel() for g in m.solid_groups + m.shell_groups]))
    assert used.size == m.n_nodes  # no node left over from the body


@pytest.mark.parametrize("case, tissue", VARIANTS)
def test_supports_hold_exactly_the_stated_dofs(built, body, case, tissue) -> None:
    """Rigid-body constraints as the solver reads them: proximal epiphysis x, y, z and
    the spin about the limb's axis (z) held; distal epiphysis x, y held (a roller along
    the limb); the impactor's x, z and rotations held (y is driven)."""
    s, m = built[case, tissue]
    pids = _pids(body, case)
    rb = _bodies(m)
    prox, dist, imp = rb[pids["proximal"]], rb[pids["distal"]], rb[s.impactor_pid]
    assert prox.fixed_trans.tolist() == [True, True, True]
    assert prox.fixed_rot.tolist() == [False, False, True]
    assert dist.fixed_trans.tolist() == [True, True, False]
    assert dist.fixed_rot.tolist() == [False, False, False]
    axis = (dist.centre - prox.centre) / np.linalg.norm(dist.centre - prox.centre)
    assert abs(abs(axis[2]) - 1.0) < 1e-5  # the free translation is along the limb
    assert imp.fixed_trans.tolist() == [True, False, True]
    assert imp.fixed_rot.tolist() == [True, True, True]
    assert set(rb) == {pids["proximal"], pids["distal"], s.impactor_pid}


@pytest.mark.parametrize("speed", [1.5, 3.0])
def test_impactor_is_driven_at_the_speed(speed) -> None:
    """Velocity prescribed on the impactor's rigid body (VAD 0) = speed x direction over
    the whole run; -y is lateral to medial on the left leg; contact time = gap / speed;
    the impactor's mass as the solver counts it; one contact, impactor = master."""
    s = bending_setup("thigh-bending", speed=speed, mesh=MESH)
    m = build_model(s.deck)
    assert s.direction == (0.0, -1.0, 0.0)
    for t in (0.0, 0.5 * s.end_time, s.end_time):
        v = np.zeros(3)
        for p in m.prescribed:
            assert p.target == "rigid" and p.pid == s.impactor_pid and p.vad == 0
            v[p.dof - 1] += p.sf * m.curves[p.lcid](t)
        assert v == pytest.approx(speed * np.array(s.direction), abs=1e-12)
    assert s.contact_time == pytest.approx(GAP / speed)
    assert _bodies(m)[s.impactor_pid].mass == pytest.approx(s.impactor_mass, rel=1e-9)
    (c,) = m.contacts
    assert c.cid == s.contact_id and c.kind == "surface_to_surface"
    assert c.master.pids == [s.impactor_pid]
    assert c.slave.pids == [p for p in m.parts if "skin" in m.parts[p].title]


@pytest.mark.parametrize("case, tissue", VARIANTS)
def test_impactor_aims_at_mid_span_with_the_gap(built, body, case, tissue) -> None:
    """The impactor's nodes lie on a cylinder about x of mid-surface radius 25 - t/2 (the
    contact face's diameter is the case's 50 mm); its axis's path along the travel passes
    within 1 mm of the mid-span point (between the supports' centres) and it is centred
    on it; the skin's contact surface (sampled on a 0.1 mm grid, independent of the
    set-up's sampling) is GAP mm from the face (-0.05 mm: a 50 mm quad's curvature
    between samples; the face's facets lie at most 0.1 mm inside the circle)."""
    s, m = built[case, tissue]
    pids = _pids(body, case)
    g = next(g for g in m.shell_groups if g.pid == s.impactor_pid)
    xi = m.node_x0[np.unique(g.conn)]
    c = xi.mean(axis=0)
    a = np.linalg.svd(xi - c)[2][0]
    assert abs(abs(a[0]) - 1.0) < 1e-12
    rel = xi - c
    radius = np.linalg.norm(rel - np.outer(rel @ a, a), axis=1)
    face = 0.5 * CASES[case].impactor_diameter
    assert radius == pytest.approx(np.full(radius.size, face - 0.5 * IMPACTOR_T), abs=1e-9)
    rb = _bodies(m)
    mid = 0.5 * (rb[pids["proximal"]].centre + rb[pids["distal"]].centre)
    d = np.array(s.direction)
    normal = np.cross(a, d)
    assert abs((mid - c) @ normal) < 1.0
    assert abs((mid - c) @ a) < 1.0
    skin = next(g for g in m.shell_groups if g.pid == pids["skin"])
    p = m.node_x0[skin.conn]
    r = np.linspace(0.0, 1.0, 501)
    u, v = (x.ravel() for x in np.meshgrid(r, r))
    w = np.column_stack([(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v])
    near = np.abs((p.mean(axis=1) - c) @ normal) < 80.0
    q = np.einsum("mk,skc->smc", w, p[near]).reshape(-1, 3) - c
    clearance = np.linalg.norm(q - np.outer(q @ a, a), axis=1).min() - face - 0.5
    assert GAP - 0.05 < clearance <= GAP + 1e-6


@pytest.mark.parametrize("case, tissue", VARIANTS)
def test_span_and_load_point_follow_the_geometry(built, body, case, tissue) -> None:
    """span = distance between the epiphyses' centres of mass (where the supports hold;
    each inside its end row); load_a = load_b = span / 2 (the load's line passes through
    mid-span); the impact point is on the skin, lateral of mid-span, in the loading plane."""
    s, m = built[case, tissue]
    pids = _pids(body, case)
    rb = _bodies(m)
    p0, p1 = rb[pids["proximal"]].centre, rb[pids["distal"]].centre
    assert s.span == pytest.approx(np.linalg.norm(p1 - p0), abs=1e-9)
    assert s.load_a == pytest.approx(0.5 * s.span, abs=1e-6)
    assert s.load_a + s.load_b == pytest.approx(s.span, abs=1e-9)
    x = body.mesh.coords()
    for end, c in (("proximal", p0), ("distal", p1)):
        z = x[np.unique(body.parts[f"{SEGMENT[case]}_l_{end}"].conn)][:, 2]
        assert z.min() < c[2] < z.max()
    seg = cut_segment(body, SEGMENT[case])
    assert s.span < np.linalg.norm(seg.distal_joint - seg.proximal_joint) - 2.0 * JOINT_GAP
    mid = 0.5 * (p0 + p1)
    pt = np.array(s.impact_point)
    assert pt[[0, 2]] == pytest.approx(mid[[0, 2]], abs=1e-6)
    assert pt[1] > mid[1] + 20.0
    skin = next(g for g in m.shell_groups if g.pid == pids["skin"])
    q = m.node_x0[skin.conn]
    ok = False
    for tri in ((0, 1, 2), (0, 2, 3), (0, 1, 3), (1, 2, 3)):
        t = q[:, tri]
        n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        n /= np.linalg.norm(n, axis=1)[:, None]
        on_plane = np.abs(np.einsum("ij,ij->i", pt - t[:, 0], n)) < 1e-6
        inside = np.all(t.min(axis=1) - 1e-6 <= pt, axis=1) & np.all(
            t.max(axis=1) + 1e-6 >= pt, axis=1)
        ok |= bool((on_plane & inside).any())
    assert ok


# ---------------------------------------------------------------------------
# a user's model of the segment


def _user_files(tmp_path, body, case="thigh-bending", **entry):
    """The pedestrian's cut segment as a user's deck (epiphyses not held) and a
    landmark file; ``entry`` overrides the default entry (None removes a key)."""
    seg = cut_segment(body, SEGMENT[case])
    deck = tmp_path / "segment_model.k"
    write_deck(seg.deck, deck)
    ref = bending_setup(case, mesh=MESH)
    e = {"proximal_part": seg.pids["proximal"], "distal_part": seg.pids["distal"],
         "point": list(ref.impact_point), "direction": [0, -1, 0],
         "contact_parts": [seg.pids["skin"]]}
    e.update(entry)
    e = {k: seg.pids[v] if isinstance(v, str) and v in seg.pids and k.endswith("_part")
         else v for k, v in e.items() if v is not None}
    lm = tmp_path / "landmarks.json"
    lm.write_text(json.dumps({case: e}))
    return deck, lm, ref, seg


def test_user_model_gives_the_same_test(tmp_path, body) -> None:
    """The user's copy of the segment, included unchanged, with its epiphyses held by zero
    prescribed velocities: same span, load point and impactor position as the
    pedestrian's set-up; proximal x, y, z and spin about z, distal x, y held."""
    deck, lm, ref, seg = _user_files(tmp_path, body)
    s = bending_setup("thigh-bending", model=deck, landmarks_path=lm)
    assert s.tissue == "user"
    files = write_deck(s.deck, tmp_path / "out" / "deck.k", flatten=False)
    assert (tmp_path / "out" / "model" / "segment_model.k") in files
    m = build_model(read_deck(tmp_path / "out" / "deck.k"))
    assert unsupported_entries(m) == [] and first_time_step(m)["run_dt"] > 0.0
    # the same up to the written deck's coordinate digits
    assert s.span == pytest.approx(ref.span, abs=1e-4)
    assert s.load_a == pytest.approx(ref.load_a, abs=1e-4)
    held = {}
    for p in m.prescribed:
        if p.pid != s.impactor_pid:
            assert p.vad == 0 and m.curves[p.lcid](0.0) == 0.0
            assert m.curves[p.lcid](s.end_time) == 0.0
            held.setdefault(p.pid, set()).add(p.dof)
    assert held == {seg.pids["proximal"]: {1, 2, 3, 7}, seg.pids["distal"]: {1, 2}}
    mr = build_model(ref.deck)
    xi = [mm.node_x0[np.unique(next(g for g in mm.shell_groups
                                   if g.pid == r.impactor_pid).conn)].mean(axis=0)
          for mm, r in ((m, s), (mr, ref))]
    assert xi[0] == pytest.approx(xi[1], abs=1e-4)


def test_user_node_supports_are_spcs(tmp_path, body) -> None:
    """Node supports: *BOUNDARY_SPC_SET on the given nodes, x, y, z proximal and the two
    directions normal to the limb (x, y) distal; several contact parts: a part set."""
    seg = cut_segment(body, "thigh")
    x = body.mesh.coords()
    ring = [np.unique(body.parts[f"thigh_l_{e}"].conn) for e in ("proximal", "distal")]
    ends = [r[np.isclose(x[r, 2], x[r, 2].max() if i == 0 else x[r, 2].min())] + 1
            for i, r in enumerate(ring)]
    deck, lm, ref, _ = _user_files(tmp_path, body, proximal_part=None, distal_part=None,
                                   proximal_nodes=ends[0].tolist(),
                                   distal_nodes=ends[1].tolist(),
                                   contact_parts=[seg.pids["skin"], seg.pids["muscle"]])
    s = bending_setup("thigh-bending", model=deck, landmarks_path=lm)
    m = build_model(s.deck)
    (c,) = m.contacts
    assert sorted(c.slave.pids) == sorted([seg.pids["skin"], seg.pids["muscle"]])
    dofs = sorted(tuple(int(v) for v in spc.dofs[0, :3]) for spc in m.spcs)
    assert dofs == [(1, 1, 0), (1, 1, 1)]
    assert s.span == pytest.approx(np.ptp(x[np.concatenate(ends) - 1][:, 2]), abs=1e-6)
    assert seg.pids["proximal"] not in {p.pid for p in m.prescribed}


BAD = [
    ({"proximal_part": 999}, "proximal_part", "not in"),
    ({"proximal_part": "muscle"}, "proximal_part", "not rigid"),  # the segment's muscle
    ({"proximal_nodes": [1, 2]}, "proximal_nodes", "give one of"),
    ({"distal_part": None}, "distal_nodes", "neither"),
    ({"distal_part": None, "distal_nodes": [10**8]}, "distal_nodes", "not in"),
    ({"contact_parts": [999]}, "contact_parts", "not in"),
    ({"contact_parts": "skin"}, "contact_parts", "positive integer"),
    ({"point": [0, 1]}, "point", "three numbers"),
    ({"point": [0, 170, 2000]}, "point", "not between the supports"),
    ({"point": [0, 170, 2000], "direction": [0, 0, -1]}, "direction", "out of the plane"),
    ({"direction": [0, 0, 0]}, "direction", "zero vector"),
    ({"point": [500, 170, 700]}, "point", "misses"),
    ({"point": [0, 250, 700]}, "point", "from the contact parts' surface"),
    ({"axis": [0, -2, 0]}, "axis", "parallel"),
]


@pytest.mark.parametrize("override, key, words", BAD)
def test_bad_landmarks_name_file_case_and_key(tmp_path, body, override, key, words) -> None:
    deck, lm, _, _ = _user_files(tmp_path, body, **override)
    with pytest.raises(UserInputError) as exc:
        bending_setup("thigh-bending", model=deck, landmarks_path=lm)
    msg = str(exc.value)
    assert str(lm) in msg and "thigh-bending" in msg and key in msg and words in msg, msg


def test_tilted_limb_and_missing_entries_are_user_errors(tmp_path, body) -> None:
    """A limb whose axis is not a global axis (node supports on opposite sides of the
    end rings: 4 deg) cannot have a roller in global axes; a case without an entry, a
    missing deck and a missing landmark file are named."""
    x = body.mesh.coords()
    ring = [np.unique(body.parts[f"thigh_l_{e}"].conn) for e in ("proximal", "distal")]
    top = ring[0][np.argmax(x[ring[0], 2] + 1e-3 * x[ring[0], 1])]
    bottom = ring[1][np.argmin(x[ring[1], 2] + 1e-3 * x[ring[1], 1])]
    deck, lm, _, _ = _user_files(tmp_path, body, proximal_part=None, distal_part=None,
                                 proximal_nodes=[int(top) + 1], distal_nodes=[int(bottom) + 1])
    with pytest.raises(UserInputError, match=r"thigh-bending\.distal_nodes.*deg from the "
                                             r"global z axis"):
        bending_setup("thigh-bending", model=deck, landmarks_path=lm)
    with pytest.raises(UserInputError, match="no entry for case 'leg-bending'"):
        bending_setup("leg-bending", model=deck, landmarks_path=lm)
    with pytest.raises(UserInputError, match="no such deck"):
        bending_setup("thigh-bending", model=tmp_path / "none.k", landmarks_path=lm)
    with pytest.raises(UserInputError, match="cannot read the landmark file"):
        bending_setup("thigh-bending", model=deck, landmarks_path=tmp_path / "none.json")


def test_other_cases_and_options_are_refused() -> None:
    with pytest.raises(ValueError, match="not a bending case"):
        bending_setup("thorax")
    with pytest.raises(ValueError, match="tissue"):
        bending_setup("leg-bending", tissue="foam", mesh=MESH)
    with pytest.raises(ValueError, match="speed"):
        bending_setup("leg-bending", speed=0.0, mesh=MESH)


def test_history_node_is_the_bone_at_mid_span(built, body) -> None:
    """The history node is a bone node at mid-span (within one 50 mm row) on the medial
    side (the far side from the impactor)."""
    s, m = built["thigh-bending", "solid"]
    (nid,) = [int(n) for h in s.deck.of_type(DatabaseHistoryNode) for n in h.ids]
    bone = _pids(body, "thigh-bending")["bone"]
    g = next(g for g in m.shell_groups if g.pid == bone)
    idx = int(np.flatnonzero(m.node_ids == nid)[0])
    assert idx in set(g.conn.ravel().tolist())
    xb = m.node_x0[np.unique(g.conn)]
    assert m.node_x0[idx, 1] == pytest.approx(xb[:, 1].min(), abs=1e-6)
    assert abs(m.node_x0[idx, 2] - s.impact_point[2]) <= 0.5 * MESH


# ---------------------------------------------------------------------------
# a short run


def _bone_section_inertia(m, bone_pid: int, z: float, thickness: float) -> float:
    """Second moment of area (mm^4) about x of the bone's shell section at the station
    nearest ``z``: each facet between neighbouring nodes of the ring as a strip of the
    shell's thickness (membrane t L (y1^2 + y1 y2 + y2^2) / 3 about the ring's centre,
    plus its own plate bending t^3 L / 12 weighted by its x-extent)."""
    g = next(g for g in m.shell_groups if g.pid == bone_pid)
    x = m.node_x0[np.unique(g.conn)]
    zs = np.unique(np.round(x[:, 2], 6))
    ring = x[np.isclose(x[:, 2], zs[np.argmin(np.abs(zs - z))])]
    c = ring.mean(axis=0)
    ring = ring[np.argsort(np.arctan2(ring[:, 1] - c[1], ring[:, 0] - c[0]))]
    inertia = 0.0
    for p, q in zip(ring, np.roll(ring, -1, axis=0)):
        length = float(np.linalg.norm(q - p))
        y1, y2 = p[1] - c[1], q[1] - c[1]
        cos_x = abs(q[0] - p[0]) / length
        inertia += thickness * length * (y1 * y1 + y1 * y2 + y2 * y2) / 3.0
        inertia += thickness ** 3 * length / 12.0 * cos_x ** 2
    return inertia


def test_short_run_thigh(tmp_path, body) -> None:
    """Thigh, solid, 50 mm mesh, 6 ms past contact (9 mm of impactor travel):

    - normal termination, energy ratio within 2 % (the prescribed motion's work enters it);
    - no work before the face reaches the skin's contact surface (contact time - 0.05 ms),
      and the force rises: the mean force over the last 2 ms (from the impactor's work)
      exceeds that over the first 2 ms after contact; the master-side rcforc resultant on
      -direction (what the runner reads) averages within 25 % of it (instantaneous
      samples of a chattering skin contact);
    - supports: the proximal epiphysis does not move, the distal one only along z;
      the impactor moves at the speed along -y;
    - the bone bends as a simply supported beam of the span: its strain energy over its
      mid-span deflection, 2 U / delta^2, is 48 E I / L^3 (I of the mesh's 12-sided shell
      section) within -10 %/+15 % once the bone has deflected more than 2 mm (48 for a
      point load, 49.2 for a uniform load, 48.7 for the sine shape; dynamics add energy
      in higher modes, shear deflection takes 3 %; measured 0.97-1.04 at 30 and 50 mm
      meshes, either hourglass control; 0.99 here, at 2.4 mm);
    - the impactor's secant stiffness in the elastic start, 2 (W - kinetic energy of the
      limb) / travel^2, lies below the bone alone's 48 E I / L^3 (the soft tissue under the
      impactor is a spring in series with the bone; the flesh's own bending stiffness,
      E I about 5 % of the bone's with the muscle's initial modulus, is within the
      margin; 0.76 with the former IHQ 4 control) and above 5 % of it (the physically soft
      flesh of the assumed-strain control IHQ 6 measures 10 % over 24 mm of travel; a
      contact that does not load the limb, 0).
    """
    from hollowbody.api import run_deck
    from hollowbody.body.materials import MATERIALS
    from hollowbody.io.results.history import read_history

    probe = bending_setup("thigh-bending", mesh=MESH)
    s = bending_setup("thigh-bending", mesh=MESH, end_time=probe.contact_time + RUN_MS)
    write_deck(s.deck, tmp_path / "deck.k", flatten=False)
    res = run_deck(tmp_path / "deck.k", tmp_path / "run", quiet=True, vtk=False)
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert res.status == "normal termination", summary.get("reason")
    assert abs(summary["energy_ratio"] - 1.0) < 0.02
    run = tmp_path / "run"
    gl = read_history(run / "glstat.csv")
    t, work = gl["time [ms]"], gl["external_work [J]"]
    t0, v, d = s.contact_time, s.speed, np.array(s.direction)
    assert np.all(np.abs(work[t < t0 - 0.05]) < 1e-9)

    def w_at(tt: float) -> float:
        return float(np.interp(tt, t, work))

    early = w_at(t0 + 2.0) / (2.0 * v)
    late = (w_at(s.end_time) - w_at(s.end_time - 2.0)) / (2.0 * v)
    assert late > early > 0.0
    rc = read_history(run / "rcforc.csv")
    sel = (rc["contact"] == s.contact_id) & (rc["time [ms]"] >= s.end_time - 2.0)
    f = np.column_stack([rc[f"master_f{c} [kN]"][sel] for c in "xyz"]) @ (-d)
    assert f.mean() == pytest.approx(late, rel=0.25)
    pids = _pids(body, "thigh-bending")
    rb = read_history(run / "rbdout.csv")
    u = {p: np.column_stack([rb[f"u{c} [mm]"][rb["part"] == p] for c in "xyz"])
         for p in (pids["proximal"], pids["distal"], s.impactor_pid)}
    assert np.abs(u[pids["proximal"]]).max() < 1e-9
    assert np.abs(u[pids["distal"]][:, :2]).max() < 1e-9
    tb = rb["time [ms]"][rb["part"] == s.impactor_pid]
    assert u[s.impactor_pid] == pytest.approx(np.outer(v * tb, d), abs=1e-6)
    # the bone as a beam
    m = build_model(s.deck)
    span = s.span
    inertia = _bone_section_inertia(m, pids["bone"], s.impact_point[2],
                                    body.parts["thigh_l_bone"].thickness)
    k_beam = 48.0 * MATERIALS["cortical"].e * inertia / span ** 3
    ms = read_history(run / "matsum.csv")
    last = ms["time [ms]"] == ms["time [ms]"].max()
    bone = last & (ms["part"] == pids["bone"])
    energy = float(ms["internal [J]"][bone][0] + ms["hourglass [J]"][bone][0])
    nod = read_history(run / "nodout.csv")
    nid = int(next(iter(s.deck.of_type(DatabaseHistoryNode))).ids[0])
    k = nod["node"] == nid
    delta = float(np.column_stack([nod[f"u{c} [mm]"][k] for c in "xyz"])[-1] @ d)
    assert delta > 2.0
    assert 0.9 < 2.0 * energy / delta ** 2 / k_beam < 1.15
    limb_ke = float(ms["kinetic [J]"][last & (ms["part"] != s.impactor_pid)].sum())
    travel = v * (s.end_time - t0)
    k_impactor = 2.0 * (w_at(s.end_time) - limb_ke) / travel ** 2
    assert 0.05 < k_impactor / k_beam < 1.0
