"""The limb segment demonstrator and its three-point bending set-up (solid and hollow)."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
from hollowbody.model.summary import summarize
from hollowbody.scenarios.limb import (
    PID_BONE,
    PID_IMPACTOR,
    PID_MUSCLE,
    PID_SKIN,
    limb_deck,
    run_three_point_bending,
    three_point_bending_deck,
)

SMALL = {"length": 150.0, "n_theta": 12, "n_radial": 2, "axial": 15.0}


def test_limb_deck_parts_and_shared_nodes():
    deck = limb_deck("thigh")
    model = build_model(deck)
    kinds = {pid: model.material_of(pid).kind for pid in model.parts}
    assert kinds == {PID_BONE: "plastic003", PID_MUSCLE: "rubber181", PID_SKIN: "elastic"}
    muscle = next(g for g in model.solid_groups if g.pid == PID_MUSCLE)
    bone = next(g for g in model.shell_groups if g.pid == PID_BONE)
    skin = next(g for g in model.shell_groups if g.pid == PID_SKIN)
    assert set(np.unique(bone.conn)) <= set(np.unique(muscle.conn))
    assert set(np.unique(skin.conn)) <= set(np.unique(muscle.conn))
    r = np.hypot(model.node_x0[:, 0], model.node_x0[:, 1])
    assert r.max() == pytest.approx(75.0) and r.min() == pytest.approx(11.5)
    # muscle mass ~ pi (75^2 - 11.5^2) 400 mm^3 x 1e-6 kg/mm^3 (polygon: a bit less)
    part = {p["pid"]: p["mass_kg"] for p in summarize(model)["parts"]}
    assert part[PID_MUSCLE] == pytest.approx(np.pi * (75**2 - 11.5**2) * 400e-6, rel=0.03)


@pytest.mark.parametrize("structure", ["solid", "hollow"])
def test_three_point_bending_deck(structure):
    limb = limb_deck("leg", **SMALL)
    if structure == "hollow":
        limb, _ = hollowize(limb, Selection(parts=[PID_MUSCLE]), HollowOptions())
    deck, setup = three_point_bending_deck(limb, end_time=5.0)
    model = build_model(deck)
    s = summarize(model)
    assert not s["problems"]
    assert setup.span == pytest.approx(150.0)
    imp = next(g for g in model.shell_groups if g.pid == PID_IMPACTOR)
    skin = next(g for g in model.shell_groups if g.pid == PID_SKIN)
    gap = model.node_x0[np.unique(imp.conn), 1].min() - model.node_x0[np.unique(skin.conn),
                                                                      1].max()
    assert 1.0 < gap < 1.5  # contact offsets (0.5 + 0.5 mm) plus 0.1 mm
    assert model.prescribed[0].target == "rigid" and model.prescribed[0].dof == 2
    assert len(model.spcs) == 2
    if structure == "hollow":
        assert PID_MUSCLE in {g.pid for g in model.shell_groups}
    else:  # the solid muscle's control is the block test's (the assumed-strain form)
        hg = model.hourglass_of(PID_MUSCLE)
        assert (hg.ihq, hg.qm) == (6, pytest.approx(1.0))


def test_runner_runs_or_skips(tmp_path):
    """Runs both structures for a few cycles; skips when deformable shells cannot run yet."""
    runs = run_three_point_bending(tmp_path, segment="leg", end_time=0.05,
                                   hollow_options=HollowOptions(self_contact=False),
                                   limb_kwargs=SMALL)
    assert set(runs) == {"solid", "hollow"}
    assert (tmp_path / "bending.png").exists() and (tmp_path / "bending.csv").exists()
    if any(r.status.startswith("skipped") for r in runs.values()):
        pytest.skip("deformable shells are not available in this version: "
                    + next(r.status for r in runs.values() if r.status.startswith("skipped")))
    for r in runs.values():
        assert r.status == "normal termination", r.status
        assert r.cycles > 0 and r.deflection.size > 0
        assert r.deflection.max() == pytest.approx(0.05 * 1.5, rel=0.05)


def test_hollowized_limb_deck_rereads_and_runs_with_its_tie(tmp_path):
    """The converted deck holds no unsupported keyword; its tie is built and run."""
    import warnings

    from hollowbody.api import run_model
    from hollowbody.io.keyword import UnsupportedKeywordWarning, read_deck, write_deck

    limb, report = hollowize(limb_deck("leg", **SMALL), Selection(parts=[PID_MUSCLE]),
                             HollowOptions(self_contact=False))
    deck, _ = three_point_bending_deck(limb, end_time=0.01)
    write_deck(deck, tmp_path / "deck.k")
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnsupportedKeywordWarning)
        back = read_deck(tmp_path / "deck.k", strict=True)
    model = build_model(back)
    assert not model.unsupported
    (tie,) = model.tied_contacts
    assert tie.kind == "shell_edge_to_surface" and tie.slave.kind == "nodes"
    res = run_model(model, tmp_path / "run", vtk=False)
    assert res.status == "normal termination" and res.cycles > 3
    log = (tmp_path / "run" / "messages.log").read_text()
    n_tied = report.parts[0].tied_nodes
    assert f"{n_tied} slave nodes tied" in log and "not tied" not in log
    assert "unsupported" not in log.lower()
