"""`hollowbody check`'s summary lists loads, rigid walls and joints of the example decks."""

from __future__ import annotations

from pathlib import Path

from hollowbody.api import load_model
from hollowbody.model.summary import summarize

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def test_loads_and_walls_listed() -> None:
    s = summarize(load_model(EXAMPLES / "loads" / "block_drop.k"))
    assert s["loads"] == [{"kind": "LOAD_BODY_Z", "curve": 1, "sf": 0.00981,
                           "target": "all parts"}]
    (wall,) = s["rigid_walls"]
    assert wall["normal"] == [0.0, 0.0, 1.0] and wall["nodes"] == 200
    assert s["joints"] == [] and s["can_run"]


def test_joints_listed() -> None:
    s = summarize(load_model(EXAMPLES / "joints" / "double_pendulum.k"))
    assert [j["type"] for j in s["joints"]] == ["REVOLUTE", "REVOLUTE"]
    assert [j["parts"] for j in s["joints"]] == [[1, 2], [2, 3]]
    assert s["loads"][0]["kind"] == "LOAD_BODY_Z"
