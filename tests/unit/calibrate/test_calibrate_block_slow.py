"""A real (tiny) calibration with the block test: coarse mesh, 2 x 2 population/generations.

Skips while the hollow block is not available (block_impact raises ValueError).
"""

from __future__ import annotations

import json

import pytest

import hollowbody.cli.main as cli_main


def _hollow_available(tmp_path) -> bool:
    from hollowbody.scenarios.block import BlockConfig, block_impact

    try:
        block_impact(BlockConfig(structure="hollow", mesh=30.0, elements_per_edge=1,
                                 end_time=0.05), tmp_path / "probe", vtk=False, quiet=True)
    except ValueError:
        return False
    return True


@pytest.mark.slow
def test_tiny_real_calibration(tmp_path, monkeypatch):
    if not _hollow_available(tmp_path):
        pytest.skip("the hollow block is not available yet (block_impact raised ValueError)")
    if "calibrate" not in cli_main.SUBCOMMANDS:
        monkeypatch.setattr(cli_main, "SUBCOMMANDS", cli_main.SUBCOMMANDS + ("calibrate",))
    out = tmp_path / "cal"
    code = cli_main.main(["calibrate", "--tissue", "muscle", "--mesh", "30", "--end-time", "6",
                          "--population", "2", "--generations", "2", "--workers", "1",
                          "--quiet", "--out", str(out)])
    assert code == 0
    data = json.loads((out / "calibration.json").read_text())
    assert data["status"] == "complete" and data["best_parameters"] is not None
    assert len(data["evaluations"]) >= 2
    for name in ("convergence.png", "overlay.png", "table1.md", "table1.csv",
                 "best_hollow/deck.k", "reference/40kmh/deck.k"):
        assert (out / name).exists(), name
    assert "*MAT_PLASTIC_KINEMATIC" in (out / "best_hollow" / "deck.k").read_text()
