"""Block scenario configuration: erosion defaults and the hollow walls' imperfection."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.scenarios.block import BlockConfig, build_block_deck


@pytest.mark.parametrize("structure, erode, expected", [
    ("solid", None, False), ("hollow", None, True), ("hollow", False, False),
    ("solid", True, True)])
def test_erosion_defaults_to_on_for_hollow_only(structure, erode, expected):
    cfg = BlockConfig(structure=structure, erode=erode, mesh=30.0)
    assert cfg.erodes is expected
    model = build_model(build_block_deck(cfg))
    assert bool(model.controls.erode) is expected


def test_hollow_walls_carry_the_default_imperfection():
    flat = build_model(build_block_deck(BlockConfig(structure="hollow", imperfection=0.0)))
    bent = build_model(build_block_deck(BlockConfig(structure="hollow")))
    d = abs(bent.node_x0 - flat.node_x0).max()
    assert d == pytest.approx(0.1 * 1.5, rel=1e-9)  # 0.1 x wall thickness at panel centres


def test_impact_outcome_by_impactor_travel():
    from hollowbody.scenarios.block import impact_outcome

    assert impact_outcome(40.0) == "stopped"
    assert impact_outcome(80.9) == "stopped"  # below 90 % of the 90 mm height
    assert impact_outcome(81.0) == "reached the base"
    assert impact_outcome(95.0) == "reached the base"
    assert impact_outcome(95.1) == "through the base"
    assert impact_outcome(None) is None and impact_outcome(float("nan")) is None
    # a run that ended (error termination) while the impactor still pressed in
    assert impact_outcome(60.0, advancing=True) == "ended before it stopped"
    assert impact_outcome(85.0, advancing=True) == "reached the base"


def test_still_advancing_reads_the_end_of_the_travel():
    from types import SimpleNamespace

    from hollowbody.scenarios.block import still_advancing

    def c(d):
        return SimpleNamespace(displacement=np.array(d, dtype=float))

    assert still_advancing(c([0.0, 10.0, 20.0]))
    assert not still_advancing(c([0.0, 20.0, 19.0]))  # rebounding: it was stopped
    assert not still_advancing(c([0.0, 20.0, 20.0]))  # at rest
    assert not still_advancing(c([5.0]))


def test_runs_through_the_base_are_left_out_of_the_wall_time_ratio():
    from hollowbody.report.study import wall_time_ratios

    rows = [{"structure": s, "speed_kmh": v, "status": "normal termination",
             "wall_seconds": w, "outcome": o}
            for s, v, w, o in [("solid", 40.0, 10.0, "stopped"), ("hollow", 40.0, 5.0, "stopped"),
                               ("solid", 100.0, 10.0, "stopped"),
                               ("hollow", 100.0, 5.0, "through the base")]]
    assert wall_time_ratios(rows) == {40.0: 2.0}


def test_every_node_of_the_hollow_blocks_bottom_walls_is_fixed():
    """The bottom walls are offset out of their plane like every panel (up to 0.15 mm
    either side): all their nodes rest on the fixed base, none of the walls above it
    (the first row of the vertical walls is 7.5 mm up). With ``z <= 0`` the panels
    offset upwards were free (162 of the 625 nodes)."""
    model = build_model(build_block_deck(BlockConfig(structure="hollow")))
    z = model.node_x0[:, 2]
    fixed = np.zeros(z.shape[0], dtype=bool)
    for spc in model.spcs:
        fixed[spc.nodes[spc.dofs.all(axis=1)]] = True
    block = z < 90.0 + 1.0  # the impactor starts above the block
    bottom = block & (np.abs(z) <= 0.15 + 1e-9)
    assert bottom.sum() == 625  # (6 x 4 + 1)^2 nodes of the bottom walls
    assert np.array_equal(fixed & block, bottom)
    assert (z[bottom] > 1e-9).sum() == 162  # those left free before


def test_solid_block_fixes_its_bottom_face_only():
    model = build_model(build_block_deck(BlockConfig(structure="solid", mesh=30.0)))
    z = model.node_x0[:, 2]
    fixed = np.zeros(z.shape[0], dtype=bool)
    for spc in model.spcs:
        fixed[spc.nodes[spc.dofs.all(axis=1)]] = True
    assert np.array_equal(fixed & (z < 91.0), np.abs(z) < 1e-9)


def test_wall_hourglass_option_sets_the_walls_hourglass():
    """--wall-hourglass 4: the three wall parts get *HOURGLASS IHQ 4 QM 0.1; by default the
    walls carry none (LS-DYNA's default viscous form); bad values are refused."""
    from hollowbody.scenarios.block import PID_WALLS

    plain_model = build_model(build_block_deck(BlockConfig(structure="hollow")))
    assert all(plain_model.parts[p].hgid == 0 for p in PID_WALLS)
    model = build_model(build_block_deck(BlockConfig(structure="hollow", wall_hourglass_ihq=4)))
    for p in PID_WALLS:
        hg = model.hourglass_of(p)
        assert hg.ihq == 4 and hg.qm == pytest.approx(0.1)
    with pytest.raises(ValueError, match="wall hourglass"):
        BlockConfig(structure="hollow", wall_hourglass_ihq=7)


def test_solid_block_element_formulation():
    """--elform 2 writes ELFORM 2 into the deck's solid section, the default stays 1, and
    anything else is refused."""
    for elform in (1, 2):
        model = build_model(build_block_deck(BlockConfig(mesh=30.0, elform=elform)))
        assert [s.elform for s in model.sections.values() if s.kind == "solid"] == [elform]
    with pytest.raises(ValueError, match="ELFORM must be 1 or 2"):
        BlockConfig(elform=3)
    with pytest.raises(ValueError, match="hollow block has no solid elements"):
        BlockConfig(structure="hollow", elform=2)


def test_solid_block_hourglass_control():
    """The solid block's deck carries *HOURGLASS IHQ 6 QM 1 by default (the assumed-strain
    form, docs/block.md) and what --solid-hourglass gives (QM 0.1 by default for other
    forms); IHQ outside 1-7 or a negative QM is refused."""
    def control(cfg):
        hg = build_model(build_block_deck(cfg)).hourglass_of(1)
        return hg.ihq, hg.qm

    assert control(BlockConfig(mesh=30.0)) == (6, pytest.approx(1.0))
    assert control(BlockConfig(mesh=30.0, hourglass_ihq=4, hourglass_qh=0.05)) == (
        4, pytest.approx(0.05))
    for bad in (dict(hourglass_ihq=0), dict(hourglass_ihq=8), dict(hourglass_qh=-1.0)):
        with pytest.raises(ValueError, match="solid hourglass IHQ must be 1-7"):
            BlockConfig(**bad)


@pytest.mark.parametrize("argv, expected", [
    ([], (6, 1.0)), (["--solid-hourglass", "4"], (4, 0.1)),
    (["--solid-hourglass", "4", "--solid-hourglass-qm", "0.05"], (4, 0.05)),
    (["--solid-hourglass", "7"], (7, 1.0)), (["--solid-hourglass-qm", "0.5"], (6, 0.5)),
])
def test_block_cli_solid_hourglass(tmp_path, argv, expected):
    from hollowbody.cli.main import main
    from hollowbody.io.keyword import read_deck

    out = tmp_path / "b"
    assert main(["block", "--mesh", "30", "--dry-run", "--out", str(out), *argv]) == 0
    hg = build_model(read_deck(out / "deck.k")).hourglass_of(1)
    assert (hg.ihq, hg.qm) == (expected[0], pytest.approx(expected[1]))


def test_block_cli_refuses_an_unknown_elform(capsys):
    from hollowbody.cli.main import main

    with pytest.raises(SystemExit) as exc:
        main(["block", "--elform", "3", "--dry-run"])
    assert exc.value.code == 2
    assert "--elform" in capsys.readouterr().err


def test_block_compare_dry_run_with_elform_2_keeps_it_for_the_solid_only(tmp_path):
    from hollowbody.cli.main import main
    from hollowbody.io.keyword import read_deck

    out = tmp_path / "cmp"
    assert main(["block", "--compare", "--elform", "2", "--mesh", "30", "--dry-run",
                 "--out", str(out)]) == 0
    solid = build_model(read_deck(out / "solid" / "deck.k"))
    assert [s.elform for s in solid.sections.values() if s.kind == "solid"] == [2]
    hollow = build_model(read_deck(out / "hollow" / "deck.k"))
    assert not hollow.solid_groups
