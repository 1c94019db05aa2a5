"""End to end: how a block run reports the way it ended.

A hollow block that cannot absorb the impact reports that the impactor reached the
base (summary.json ``impact_outcome``), and its fixed bottom walls hold.

Hollow muscle at 100 km/h (1,929 J; the walls absorbed about 700 J at 70 km/h before
the base) to 5 ms: the impactor crosses the block's 90 mm in 3.2 ms at its initial
speed, so it must reach the base within the run. Bounds: the travel between 81 mm
(90 % of the height, the ``reached the base`` limit) and 95 mm (beyond, nodes of the
fixed base were pushed through the impactor's surface); the energy ratio within 1 %
of 1 (a conservation law; measured 1.0022 over 20 ms).

A solid block whose element collapses under the impactor keeps the energies of its
last balanced record (below).
"""

from __future__ import annotations

import json

import pytest

from hollowbody.scenarios.block import REACHED_BASE, BlockConfig, block_impact


@pytest.mark.slow
def test_fast_hollow_impact_reports_reaching_the_base(tmp_path):
    res = block_impact(BlockConfig(structure="hollow", speed_kmh=100.0, end_time=5.0),
                       tmp_path, vtk=False)
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["status"] == "normal termination"
    assert 81.0 <= res.curve.max_displacement <= 95.0
    assert s["impact_outcome"] == REACHED_BASE == res.summary["impact_outcome"]
    assert s["eroded_elements"] > 0
    assert abs(s["energy_ratio"] - 1.0) < 0.01


def test_solid_block_that_inverts_keeps_its_balanced_energies(tmp_path):
    """Solid muscle at 100 km/h with the block's default hourglass control: an element
    under the impactor inverts (negative volume, measured at 3.88 ms, 89.8 mm) and its
    collapse blows up the failing cycle's energies (ratio 4.9e26). The summary keeps
    the last balanced record (within 1 % of 1: a conservation law up to the collapse)
    and grades the run on it, naming the failing cycle."""
    block_impact(BlockConfig(speed_kmh=100.0, end_time=5.0), tmp_path, vtk=False)
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["status"] == "error termination" and "negative volume" in s["reason"]
    before = s["energies_before_error_J"]
    assert abs(before["energy_ratio"] - 1.0) < 0.01
    assert 0.0 < before["time_ms"] <= s["end_time_ms"]
    indicators = {r["indicator"] for r in s["quality_reasons"]}
    assert "failing_cycle" in indicators and "energy_ratio" not in indicators
