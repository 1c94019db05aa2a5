"""The hand-written decks of this folder read, build and check as expected."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.cli.main import main
from hollowbody.io.keyword import Include, read_deck

HERE = Path(__file__).resolve().parent
DECKS = sorted(p for p in HERE.rglob("*.k") if "mesh" not in p.parts)


@pytest.mark.parametrize("path", DECKS, ids=[p.name for p in DECKS])
def test_deck_reads_builds_and_can_run(path, capsys):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = build_model(read_deck(path))
    assert model.n_nodes > 0
    assert main(["check", str(path)]) == 0
    capsys.readouterr()


def test_block_with_nested_includes():
    deck = read_deck(HERE / "block" / "main.k")
    inc = deck.items[1]
    assert isinstance(inc, Include) and inc.filename == "mesh/nodes.k"
    assert isinstance(inc.deck.items[-1], Include) and inc.deck.items[-1].filename == "elements.k"
    m = build_model(deck)
    assert m.title == "block with includes"
    assert m.solid_groups[0].elem_ids.tolist() == [1]
    np.testing.assert_array_equal(m.node_v0, np.tile([0.0, 0.0, -5.0], (8, 1)))
    assert sorted(m.node_ids[m.spcs[0].nodes].tolist()) == [1, 2, 3, 4]
    assert m.materials[1].title == "tissue"
