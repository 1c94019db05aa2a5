"""Regression: the hand-kept deck of this folder (muscle and fat on a bone plate, includes,
a part set, an initial velocity, a history node inside the muscle, a *SET_SOLID kept as
text) converts as it did when this test was written."""

from __future__ import annotations

import hashlib
import json
import warnings
from pathlib import Path

import numpy as np
import pytest

import hollowbody.cli.main as cli_main
from hollowbody.build import build_model
from hollowbody.io.keyword import read_deck

HERE = Path(__file__).resolve().parent
DECK = HERE / "deck" / "main.k"


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    out = tmp_path_factory.mktemp("regression") / "new.k"
    before = {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in HERE.rglob("*.k")}
    subcommands = cli_main.SUBCOMMANDS
    if "hollowize" not in subcommands:
        cli_main.SUBCOMMANDS = subcommands + ("hollowize",)
    try:
        code = cli_main.main(["hollowize", str(DECK), "--out", str(out), "--part-set", "1"])
    finally:
        cli_main.SUBCOMMANDS = subcommands
    after = {p: hashlib.sha256(p.read_bytes()).hexdigest() for p in HERE.rglob("*.k")}
    report = json.loads(out.with_name("new_report.json").read_text())
    return {"code": code, "out": out, "report": report, "unchanged": before == after}


def test_converts_both_tissue_parts(result):
    assert result["code"] == 0 and result["unchanged"]
    parts = {p["pid"]: p for p in result["report"]["parts"]}
    assert sorted(parts) == [10, 11]
    for p in parts.values():
        assert p["solids_removed"]["hexahedra"] == 144
        assert p["boundary_shells"] == {"quads": 180, "triangles": 0}
        assert p["wall_shells"] == {"quads": 104, "triangles": 0}
        assert p["within_tolerance"]
        assert p["coverage"]["fraction"] == 1.0
        assert p["smallest_shell"]["length_mm"] == pytest.approx(7.5, rel=1e-6)
    assert parts[10]["material"]["E_MPa"] == 100.0 and parts[11]["material"]["E_MPa"] == 50.0
    assert parts[10]["nodes_kept"] == 1  # the history node inside the muscle
    w = " ".join(result["report"]["warnings"])
    assert "658" in w and "*SET_SOLID" in w and "part set 1" in w


def test_files_and_unchanged_include(result):
    out = result["out"]
    names = sorted(Path(f).name for f in result["report"]["files"])
    assert names == ["new.k", "props_hollow.k", "tissue_hollow.k"]
    text = out.read_text()
    assert "model/bone.k" in text and "tissue_hollow.k" in text
    assert "*SET_SOLID\n$     SID\n         1\n$    EID1      EID2\n      7001      8001\n" in text


def test_converted_deck_builds_with_the_same_mass(result):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m0 = build_model(read_deck(DECK))
        m1 = build_model(read_deck(result["out"]))
    from hollowbody.model.mass import lumped_node_mass

    assert lumped_node_mass(m1)[0].sum() == pytest.approx(lumped_node_mass(m0)[0].sum(),
                                                          rel=1e-5)
    assert not m1.solid_groups
    # the plate still shares its nodes with the (now hollow) muscle
    plate = next(g for g in m1.shell_groups if g.pid == 20)
    muscle = next(g for g in m1.shell_groups if g.pid == 10)
    assert set(np.unique(plate.conn)) <= set(np.unique(muscle.conn))
    assert np.abs(m1.node_v0[np.unique(muscle.conn), 2] + 1.0).max() < 1e-12
