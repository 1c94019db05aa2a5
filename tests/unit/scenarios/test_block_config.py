"""Block scenario configuration: erosion defaults and the hollow walls' imperfection."""

from __future__ import annotations

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


def test_runs_through_the_base_are_left_out_of_the_wall_time_ratio():
    from hollowbody.report.study import wall_time_ratios

    rows = [{"structure": s, "speed_kmh": v, "status": "normal termination",
             "wall_seconds": w, "outcome": o}
            for s, v, w, o in [("solid", 40.0, 10.0, "stopped"), ("hollow", 40.0, 5.0, "stopped"),
                               ("solid", 100.0, 10.0, "stopped"),
                               ("hollow", 100.0, 5.0, "through the base")]]
    assert wall_time_ratios(rows) == {40.0: 2.0}
