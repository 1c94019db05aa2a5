"""The lateral hub impacts' set-ups (pelvis, abdomen, thorax, shoulder) on the open
pedestrian and on a user's model: what the built Model holds (hub mass from its
rigid-body table, initial velocity, hub geometry and gap against an independent ray
cast, the contact's sides, the outputs, the pelvis case's removed forearm and kept
mass), the deck as written, bad landmark input, and one short run.

Coarse 50 mm mesh throughout (fast). Tolerances: masses 1e-6 relative (the
*PART_INERTIA mass and the element masses are exact; 1e-6 covers summation order),
positions 1 mm for the axis through the landmark (the hub's nodes are placed exactly;
1 mm is what matters for the test), the gap +-0.5 mm (a 0.5 mm ray grid over the face)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from hollowbody.body.deck import pedestrian_deck
from hollowbody.body.pedestrian import build_body
from hollowbody.build import build_model
from hollowbody.contact.surface import build_surface
from hollowbody.errors import UserInputError
from hollowbody.io.keyword import ConstrainedJoint, Include, read_deck, write_deck
from hollowbody.model.mass import lumped_node_mass, part_nodes
from hollowbody.model.rigid_bodies import rigid_body_defs
from hollowbody.model.summary import summarize
from hollowbody.solver.preflight import first_time_step
from hollowbody.validation import cases
from hollowbody.validation.impact import GAP, impact_setup

MESH = 50.0
IMPACTS = ("thorax", "abdomen", "pelvis", "shoulder")
SPEED = {"thorax": 4.4, "abdomen": 4.8, "pelvis": 5.2, "shoulder": 4.4}


@pytest.fixture(scope="module")
def body():
    return build_body(mesh=MESH)


@pytest.fixture(scope="module")
def built():
    """case -> (setup, model) at the coarse mesh, solid."""
    out = {}
    for c in IMPACTS:
        s = impact_setup(c, SPEED[c], mesh=MESH)
        out[c] = (s, build_model(s.deck))
    return out


def _expected_direction(case: str) -> np.ndarray:
    a = np.radians({"thorax": 30.0, "abdomen": 30.0, "pelvis": 0.0, "shoulder": 0.0}[case])
    return np.array([-np.sin(a), -np.cos(a), 0.0])  # from the body's left (+y), forward


def _landmark(case: str, body) -> np.ndarray:  # noqa: ANN001
    sk = body.skeleton
    return {"thorax": sk.point("XYPH"), "abdomen": sk.point("XYPH") - [0.0, 0.0, 75.0],
            "pelvis": sk.point("HJC_l"), "shoulder": sk.point("SJC_l")}[case]


def _hub_xyz(model, pid: int) -> np.ndarray:  # noqa: ANN001
    return model.node_x0[part_nodes(model, pid)]


def _contact(model, cid: int):  # noqa: ANN001, ANN202
    (c,) = [c for c in model.contacts if c.cid == cid]
    return c


def _rays_first_hit(origins: np.ndarray, d: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """Distance along d from each origin (k, 3) to the first triangle (t, 3, 3) it
    crosses going downstream (Moller-Trumbore, written here independently); +inf on a
    miss. Hits behind the origin count too (negative): they would be penetrations."""
    out = np.full(origins.shape[0], np.inf)
    e1, e2 = tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    p = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, p)
    ok = np.abs(det) > 1e-12
    e1, e2, p, det, v0 = e1[ok], e2[ok], p[ok], det[ok], tris[ok, 0]
    for s in range(0, origins.shape[0], 500):
        o = origins[s:s + 500]
        tv = o[:, None, :] - v0[None]
        u = np.einsum("kij,ij->ki", tv, p) / det
        q = np.cross(tv, e1[None])
        v = np.einsum("kij,j->ki", q, d) / det
        t = np.einsum("kij,ij->ki", q, e2) / det
        hit = (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9)
        out[s:s + 500] = np.where(hit, t, np.inf).min(axis=1)
    return out


def _face_samples(centre: np.ndarray, d: np.ndarray, radius: float, step: float,
                  rim_step: float) -> np.ndarray:
    """Points on the disc (centre, normal d, radius) on rings ``step`` apart, ``step``
    apart along each ring; the rim ``rim_step`` apart."""
    up = np.array([0.0, 0.0, 1.0]) - d[2] * d
    up /= np.linalg.norm(up)
    side = np.cross(up, d)
    pts = [centre[None, :]]
    for r in np.append(np.arange(step, radius, step), radius):
        n = max(8, int(np.ceil(2 * np.pi * r / (step if r < radius else rim_step))))
        a = 2 * np.pi * np.arange(n) / n
        pts.append(centre + r * (np.cos(a)[:, None] * side + np.sin(a)[:, None] * up))
    return np.vstack(pts)


# ---------------------------------------------------------------------------
# the open pedestrian


@pytest.mark.parametrize("case", IMPACTS)
def test_deck_builds_and_takes_a_step(built, case: str) -> None:
    s, model = built[case]
    summ = summarize(model)
    assert summ["problems"] == [] and summ["unsupported"] == []
    assert s.deck.unsupported == []
    step = first_time_step(model)
    assert 1e-4 < step["run_dt"] < 1e-2  # ms: the body's own step, not set by the hub
    assert model.controls.end_time == s.end_time == cases.end_time_of(cases.case(case),
                                                                       SPEED[case])


@pytest.mark.parametrize("case", IMPACTS)
def test_hub_mass_is_the_impactor_mass(built, case: str) -> None:
    """From the run's own rigid-body table (the solver's definition of the body)."""
    s, model = built[case]
    (row,) = [r for r in summarize(model)["rigid_bodies"] if r["pid"] == s.impactor_pid]
    assert row["mass_kg"] == pytest.approx(cases.case(case).impactor_mass, rel=1e-6)
    assert s.impactor_mass == cases.case(case).impactor_mass


@pytest.mark.parametrize("case", IMPACTS)
def test_hub_initial_velocity_and_guidance(built, case: str) -> None:
    s, model = built[case]
    node_mass, _ = lumped_node_mass(model)
    (hub,) = [b for b in rigid_body_defs(model, node_mass) if b.pid == s.impactor_pid]
    d = _expected_direction(case)
    np.testing.assert_allclose(s.direction, d, atol=1e-12)
    np.testing.assert_allclose(hub.vel, SPEED[case] * d, atol=1e-9)
    assert np.linalg.norm(hub.vel) == pytest.approx(SPEED[case], rel=1e-12)
    np.testing.assert_allclose(hub.omega, 0.0, atol=1e-12)
    assert hub.fixed_rot.all()  # guided: no rotation
    held = [k for k in range(3) if hub.fixed_trans[k]]
    assert held == ([2] if case in ("thorax", "abdomen") else [0, 2])  # free along its path
    # the body starts at rest
    body_nodes = np.setdiff1d(np.arange(model.n_nodes), hub.nodes)
    assert not np.any(model.node_v0[body_nodes])


@pytest.mark.parametrize("case", IMPACTS)
def test_hub_geometry_and_axis_through_the_landmark(built, body, case: str) -> None:
    s, model = built[case]
    x = _hub_xyz(model, s.impactor_pid)
    d = np.asarray(s.direction)
    w = x @ d
    face, back = x[np.isclose(w, w.max(), atol=1e-6)], x[np.isclose(w, w.min(), atol=1e-6)]
    assert w.max() - w.min() == pytest.approx(60.0, abs=1e-6)
    c_face, c_back = face.mean(axis=0), back.mean(axis=0)
    axis = (c_face - c_back) / np.linalg.norm(c_face - c_back)
    assert axis @ d == pytest.approx(1.0, abs=1e-9)  # axis along the travel, face first
    r = face - c_face
    assert np.linalg.norm(r, axis=1).max() == pytest.approx(75.0, abs=1e-6)  # 150 mm face
    lm = _landmark(case, body)
    off = (lm - c_face) - ((lm - c_face) @ axis) * axis
    assert np.linalg.norm(off) < 1.0
    k = int(np.flatnonzero(model.node_ids == s.impactor_node)[0])  # history node on the axis
    np.testing.assert_allclose(model.node_x0[k], c_face, atol=1e-6)
    assert k in model.output.history_nodes
    ip = np.asarray(s.impact_point)
    off_ip = (ip - c_face) - ((ip - c_face) @ axis) * axis
    assert np.linalg.norm(off_ip) < 1.0  # the impact point is on the axis too
    assert (ip - c_face) @ axis >= GAP - 0.5


@pytest.mark.parametrize("case", IMPACTS)
def test_face_starts_the_gap_from_the_skin(built, case: str) -> None:
    """An independent ray cast from the face (rays 2 mm apart, 0.5 mm on the rim, and
    through every surface vertex in the hub's footprint, where the distance along the
    travel is smallest on a facet) to the contact's slave surface: the nearest skin
    along the travel is GAP mm away (+-0.5 mm) and nothing of the slave surface lies
    behind the face within the hub's footprint."""
    s, model = built[case]
    c = _contact(model, s.contact_id)
    surf = build_surface(c.slave, model)
    seg = surf.seg
    tris = np.concatenate([model.node_x0[seg[:, [0, 1, 2]]],
                           model.node_x0[seg[seg[:, 3] != seg[:, 2]][:, [0, 2, 3]]]])
    x = _hub_xyz(model, s.impactor_pid)
    d = np.asarray(s.direction)
    w = x @ d
    centre = x[np.isclose(w, w.max(), atol=1e-6)].mean(axis=0)
    rel = tris.reshape(-1, 3) - centre
    perp = np.linalg.norm(rel - np.outer(rel @ d, d), axis=1).reshape(-1, 3)
    tris = tris[(perp < 75.0 + 2 * MESH).any(axis=1)]
    pts = _face_samples(centre, d, 75.0, 2.0, 0.5)
    v = np.unique(tris.reshape(-1, 3), axis=0) - centre
    v = v - np.outer(v @ d, d)  # vertices projected onto the face's plane
    pts = np.vstack([pts, centre + v[np.linalg.norm(v, axis=1) <= 75.0]])
    t = _rays_first_hit(pts - 200.0 * d, d, tris) - 200.0  # also what lies behind the face
    assert np.isfinite(t).any()
    assert t.min() == pytest.approx(GAP, abs=0.5)
    assert s.contact_time == pytest.approx(GAP / SPEED[case], rel=1e-12)


def test_pelvis_forearm_and_hand_removed_mass_kept(built, body) -> None:
    s, model = built["pelvis"]
    titles = {p.title for p in model.parts.values()}
    assert not any(t.startswith(("forearm_l", "hand_l")) for t in titles)
    assert any(t.startswith("forearm_r") for t in titles)  # the other arm stays
    heads = {j.heading for j in s.deck.of_type(ConstrainedJoint)}
    assert "elbow_l" not in heads and "wrist_l" not in heads and "elbow_r" in heads
    assert "shoulder_l" in heads
    full = summarize(build_model(pedestrian_deck(body)[0]))["mass_kg"]
    total = summarize(model)["mass_kg"]
    assert total - cases.case("pelvis").impactor_mass == pytest.approx(full, rel=1e-6)
    # the removed mass is one point mass at the elbow centre, on the upper arm's rigid end
    k = np.flatnonzero(model.node_extra_mass)
    assert k.size == 1
    np.testing.assert_allclose(model.node_x0[k[0]], body.skeleton.point("EJC_l"), atol=1e-6)
    fore = sum(seg.mass for name, seg in body.skeleton.segments.items()
               if name in ("forearm", "hand"))
    assert model.node_extra_mass[k[0]] == pytest.approx(fore, rel=0.01)  # de Leva's
    node_mass, _ = lumped_node_mass(model)
    distal = body.parts["upper_arm_l_distal"].pid
    (rb,) = [b for b in rigid_body_defs(model, node_mass) if b.pid == distal]
    assert k[0] in rb.nodes


@pytest.mark.parametrize("case, must, never", [
    ("thorax", ("trunk",), ("upper_arm", "forearm", "hand", "thigh")),
    ("abdomen", ("trunk",), ("upper_arm", "forearm", "hand", "thigh")),
    ("pelvis", ("trunk", "thigh_l"), ("upper_arm", "forearm", "hand", "thigh_r")),
    ("shoulder", ("trunk", "upper_arm_l"), ("forearm", "hand", "upper_arm_r", "thigh")),
])
def test_contact_sides(built, body, case: str, must: tuple, never: tuple) -> None:
    """Hub = master (its part), body = slave part set; thorax and abdomen without the
    arms; friction, SOFT and damping as stated."""
    s, model = built[case]
    c = _contact(model, s.contact_id)
    assert c.kind == "surface_to_surface"
    assert c.master.kind == "parts" and list(c.master.pids) == [s.impactor_pid]
    assert c.slave.kind == "parts"
    keys = {p.pid: k for k, p in body.parts.items()}
    slave = {keys[p] for p in c.slave.pids}
    for prefix in must:
        want = {k for k in body.parts if k.startswith(prefix)}
        assert want <= slave, prefix
    assert not any(k.startswith(never) for k in slave)
    assert c.fs == c.fd == 0.2 and c.soft == 1 and c.vdc == 20.0


@pytest.mark.parametrize("case, ref", [("thorax", "T8"), ("pelvis", "sacrum"),
                                       ("shoulder", "T1"), ("abdomen", "T12")])
def test_outputs_and_reference_node(built, body, case: str, ref: str) -> None:
    s, model = built[case]
    for name in ("rcforc", "rbdout", "nodout", "glstat", "matsum"):
        assert model.output.intervals[name] == pytest.approx(0.1)
    assert model.output.d3plot_dt == pytest.approx(2.0)
    idx = int(np.flatnonzero(model.node_ids == s.reference_node)[0])
    assert idx in model.output.history_nodes
    node_mass, _ = lumped_node_mass(model)
    zone = body.parts[f"trunk_spine_{ref}" if ref != "sacrum" else "trunk_pelvis"].pid
    owner = [b.pid for b in rigid_body_defs(model, node_mass) if idx in b.nodes]
    assert owner == [zone]  # a node of that spine body (the sacrum is merged to the pelvis)
    if case == "abdomen":  # at the impact height
        assert model.node_x0[idx, 2] == pytest.approx(_landmark(case, body)[2], abs=1e-6)


def test_written_deck_passes_check(built, tmp_path) -> None:
    from hollowbody.cli.main import main

    s, model = built["shoulder"]
    files = write_deck(s.deck, tmp_path / "deck.k", flatten=False)
    assert "impact.k" in [f.name for f in files]
    assert main(["check", str(tmp_path / "deck.k")]) == 0
    again = build_model(read_deck(tmp_path / "deck.k"))
    assert summarize(again)["mass_kg"] == pytest.approx(summarize(model)["mass_kg"], rel=1e-6)
    json.dumps(s.to_json())  # the record is plain JSON


def test_hollow_variant_puts_the_hollow_shells_in_the_slave_set() -> None:
    s = impact_setup("thorax", 4.4, tissue="hollow", mesh=MESH)
    model = build_model(s.deck)
    (row,) = [r for r in summarize(model)["rigid_bodies"] if r["pid"] == s.impactor_pid]
    assert row["mass_kg"] == pytest.approx(23.4, rel=1e-6)
    c = _contact(model, s.contact_id)
    fat = [p for p, d in model.parts.items() if d.title.startswith("subcutaneous fat")]
    assert fat and set(fat) <= set(c.slave.pids)
    shells = {g.pid for g in model.shell_groups}
    solids = {g.pid for g in model.solid_groups}
    assert set(fat) <= shells and not set(fat) & solids  # converted: shells only
    assert s.tissue == "hollow"


# ---------------------------------------------------------------------------
# a user's model


@pytest.fixture()
def user_model(tmp_path, body):
    """A small pedestrian deck (with includes) in tmp_path and its landmark file."""
    deck, info = pedestrian_deck(body)
    path = tmp_path / "user" / "ped.k"
    files = write_deck(deck, path, flatten=False)
    before = {f: f.read_bytes() for f in files}
    trunk = sorted(p.pid for k, p in body.parts.items() if k.startswith("trunk_"))
    lm = {"thorax": {"point": body.skeleton.point("XYPH").tolist(),
                     "direction": [-0.5, -np.sqrt(3.0) / 2.0, 0.0],
                     "contact_parts": trunk, "reference_node": info["history"]["T8"]}}
    lm_path = tmp_path / "landmarks.json"
    lm_path.write_text(json.dumps(lm))
    return path, lm_path, lm, before


def test_user_model_is_included_unchanged(user_model, built, tmp_path) -> None:
    path, lm_path, lm, before = user_model
    s = impact_setup("thorax", 4.4, model=path, landmarks_path=lm_path)
    assert s.tissue == "user"
    inc = [it for it in s.deck.items if isinstance(it, Include)]
    assert inc[0].external and inc[0].filename == str(path.resolve())
    files = write_deck(s.deck, tmp_path / "run" / "deck.k", flatten=False)
    assert sorted(f.name for f in files) == ["deck.k", "impact.k"]
    assert {f: f.read_bytes() for f in before} == before  # the user's files untouched
    # the written deck includes the user's file by its absolute path (read back: a path
    # longer than a card is written over continuation lines)
    written = [it for it in read_deck(tmp_path / "run" / "deck.k").items
               if isinstance(it, Include)]
    assert str(path.resolve()) in [str(Path(it.filename)) for it in written]
    model = build_model(read_deck(tmp_path / "run" / "deck.k"))
    (row,) = [r for r in summarize(model)["rigid_bodies"] if r["pid"] == s.impactor_pid]
    assert row["mass_kg"] == pytest.approx(23.4, rel=1e-6)
    user = build_model(read_deck(path))
    assert s.impactor_pid not in user.parts and s.contact_id not in {c.cid for c in
                                                                      user.contacts}
    assert model.node_ids.max() > user.node_ids.max()
    assert len([ld for ld in model.loads if "LOAD_BODY" in str(ld.source)]) <= 1
    idx = int(np.flatnonzero(model.node_ids == s.reference_node)[0])
    assert idx in model.output.history_nodes
    assert model.output.intervals["rcforc"] == pytest.approx(0.1)
    assert model.controls.end_time == pytest.approx(60.0)
    # the same body and landmark as the generated set-up: the same hub and point
    ped, _ = built["thorax"]
    np.testing.assert_allclose(s.impact_point, ped.impact_point, atol=1e-6)
    # the case's dict given directly works the same
    s2 = impact_setup("thorax", 4.4, model=path, landmarks=lm["thorax"],
                      landmarks_path=lm_path)
    np.testing.assert_allclose(s2.impact_point, s.impact_point, atol=1e-9)


@pytest.mark.parametrize("change, key", [
    (lambda e: e.pop("reference_node"), "thorax.reference_node"),
    (lambda e: e.update(contact_parts=[1, 999]), "thorax.contact_parts"),
    (lambda e: e.update(reference_node=987654), "thorax.reference_node"),
    (lambda e: e.update(direction=[0, 0, 0]), "thorax.direction"),
    (lambda e: e.update(point=[5000.0, 0.0, 0.0], direction=[0.0, 0.0, -1.0]),
     "thorax.point/direction"),
    (lambda e: e.update(gravity="yes"), "thorax.gravity"),
    (lambda e: e.update(point=[0, 1]), "thorax.point"),
])
def test_bad_landmarks_name_file_case_and_key(user_model, change, key: str) -> None:
    path, lm_path, lm, _ = user_model
    change(lm["thorax"])
    lm_path.write_text(json.dumps(lm))
    with pytest.raises(UserInputError) as err:
        impact_setup("thorax", 4.4, model=path, landmarks_path=lm_path)
    assert str(lm_path) in str(err.value) and key in str(err.value)


def test_missing_case_entry_names_the_file(user_model) -> None:
    path, lm_path, lm, _ = user_model
    lm_path.write_text(json.dumps({"pelvis": lm["thorax"]}))
    with pytest.raises(UserInputError, match="thorax") as err:
        impact_setup("thorax", 4.4, model=path, landmarks_path=lm_path)
    assert str(lm_path) in str(err.value)


def test_not_an_impact_case() -> None:
    with pytest.raises(ValueError, match="not an impact case"):
        impact_setup("leg-bending", 1.5)


# ---------------------------------------------------------------------------
# a short run


def test_short_thorax_run_force_rises_energy_holds(tmp_path) -> None:
    """Thorax, 50 mm mesh, to 3 ms after the face reaches the skin: no force before the
    contact surfaces meet, then the body pushes back and the hub slows; energy within
    2 % (gravity and contact included)."""
    from hollowbody.api import run_deck
    from hollowbody.io.results.history import read_history

    s0 = impact_setup("thorax", 4.4, mesh=MESH)
    end = s0.contact_time + 3.0
    s = impact_setup("thorax", 4.4, mesh=MESH, end_time=end)
    write_deck(s.deck, tmp_path / "deck.k", flatten=False)
    res = run_deck(tmp_path / "deck.k", tmp_path / "run", quiet=True, vtk=False)
    assert res.status == "normal termination"
    assert abs(res.summary["energy_ratio"] - 1.0) < 0.02
    rc = read_history(tmp_path / "run" / "rcforc.csv")
    sel = rc["contact"] == s.contact_id
    t = rc["time [ms]"][sel]
    d = np.asarray(s.direction)
    f = np.column_stack([rc[f"master_f{c} [kN]"][sel] for c in "xyz"]) @ (-d)
    # the contact surfaces (half the 1 mm hub shell, half the 1 mm skin) meet after
    # (GAP - 1 mm) of travel: nothing before
    assert np.all(f[t < 0.9 * (GAP - 1.0) / 4.4] == 0.0)
    assert f.max() > 0.1  # kN: the body pushes back on the hub
    rb = read_history(tmp_path / "run" / "rbdout.csv")
    hub = rb["part"] == s.impactor_pid
    v = np.column_stack([rb[f"v{c} [mm/ms]"][hub] for c in "xyz"]) @ d
    assert v[0] == pytest.approx(4.4, rel=1e-6)  # rbdout.csv: 9 digits
    assert 0.0 < v[-1] < 4.4 - 0.05  # slowed by the body
    # the runner's signals: the face node travels with the hub; the body pushes back
    from hollowbody.validation.signals import read_signals

    sig = read_signals(tmp_path / "run", s)
    assert sig.force_raw.max() > 0.1
    u_rb = np.column_stack([rb[f"u{c} [mm]"][hub] for c in "xyz"]) @ d
    assert sig.deflection.max() == pytest.approx(
        u_rb.max() - GAP, abs=1.0)  # the spine barely moves in 3 ms
