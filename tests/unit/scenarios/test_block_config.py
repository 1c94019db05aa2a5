"""Block scenario configuration: erosion defaults and the hollow walls' imperfection."""

from __future__ import annotations

import pytest

from hollowbody.model.builder import build_model
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
