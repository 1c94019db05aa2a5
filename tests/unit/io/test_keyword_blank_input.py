"""Blank cards, blank lines in bulk blocks, and files that are not keyword decks.

A blank line is a card of default values wherever LS-DYNA reads it so; blank
lines inside a list of rows (*NODE, *ELEMENT_..., *SET_..._LIST) are skipped.
An empty file, a file without a keyword line and a binary file are refused
with one message naming the file.
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    ControlContact,
    InitialVelocityGeneration,
    Nodes,
    SectionShell,
    SetNodeList,
    SolidElements,
    read_deck,
    read_deck_text,
)


def test_blank_required_card_is_a_card_of_defaults():
    """*INITIAL_VELOCITY_GENERATION whose second card (the rotation axis) is blank."""
    deck = read_deck_text("*INITIAL_VELOCITY_GENERATION\n"
                          "         1         2       0.0      -1.0\n"
                          "\n"
                          "*END\n")
    (ivg,) = deck.of_type(InitialVelocityGeneration)
    assert (ivg.id, ivg.styp, ivg.vx) == (1, 2, -1.0)
    assert (ivg.xc, ivg.nx, ivg.phase, ivg.irigid) == (0.0, 0.0, 0, 0)


def test_blank_required_card_at_the_end_of_the_file():
    deck = read_deck_text("*INITIAL_VELOCITY_GENERATION\n         1         2       0.0"
                          "      -1.0\n\n")
    assert len(deck.of_type(InitialVelocityGeneration)) == 1


def test_two_repetitions_each_with_a_blank_second_card():
    deck = read_deck_text("*INITIAL_VELOCITY_GENERATION\n"
                          "         1         2       0.0      -1.0\n\n"
                          "         2         2       0.0       3.0\n\n")
    ivgs = deck.of_type(InitialVelocityGeneration)
    assert [(i.id, i.vx) for i in ivgs] == [(1, -1.0), (2, 3.0)]


def test_blank_required_card_of_a_section_and_of_a_material():
    deck = read_deck_text("*SECTION_SHELL\n         2         2\n\n*MAT_ELASTIC\n\n")
    (sec,) = deck.of_type(SectionShell)
    assert sec.secid == 2 and sec.t1 == 0.0


def test_blank_optional_card_followed_by_another_card():
    deck = read_deck_text("*CONTROL_CONTACT\n\n         0         0         3\n")
    (cc,) = deck.of_type(ControlContact)
    assert cc.slsfac == 0.1 and cc.nsbcs == 3  # card 1 defaults, card 2 read


def test_trailing_blank_lines_are_not_extra_cards():
    deck = read_deck_text("*CONTROL_CONTACT\n       0.2\n\n\n\n*END\n")
    (cc,) = deck.of_type(ControlContact)
    assert cc.slsfac == 0.2 and cc.extra_cards == []


def test_blank_lines_inside_bulk_blocks_are_skipped():
    deck = read_deck_text(
        "*NODE\n"
        "       1             0.0             0.0             0.0\n"
        "\n"
        "       2             1.0             0.0             0.0\n"
        "   \n"
        "*ELEMENT_SOLID\n"
        "       1       1       1       2       2       1       1       2       2       1\n"
        "\n"
        "       2       1       1       2       2       1       1       2       2       1\n"
        "*SET_NODE_LIST\n"
        "         7\n"
        "\n"
        "         1         2\n"
        "*BOUNDARY_SPC_NODE\n"
        "         1         0         1\n"
        "\n"
        "         2         0         1\n")
    (nodes,) = deck.of_type(Nodes)
    assert nodes.ids.tolist() == [1, 2]
    assert np.array_equal(nodes.xyz[:, 0], [0.0, 1.0])
    (solids,) = deck.of_type(SolidElements)
    assert solids.ids.tolist() == [1, 2]
    (s,) = deck.of_type(SetNodeList)
    assert sorted(np.asarray(s.nodes).tolist()) == [1, 2]
    from hollowbody.io.keyword import BoundarySpcNode
    assert [b.nid for b in deck.of_type(BoundarySpcNode)] == [1, 2]


def test_blank_title_card_of_a_part():
    from hollowbody.io.keyword import Part
    deck = read_deck_text("*PART\n\n         1         1         1\n")
    (p,) = deck.of_type(Part)
    assert (p.title, p.pid, p.secid, p.mid) == ("", 1, 1, 1)


@pytest.mark.parametrize("data, words", [
    (b"", "the file is empty"),
    (b"   \n\n$ only a comment\n", "no line starts with '*'"),
    (b"NODE 1 0 0 0\n", "no line starts with '*'"),
    (b"\x7fELF\x02\x01\x01\x00\x00\x00*NODE\n", "binary"),
    (bytes(range(256)) * 8, "binary"),
])
def test_files_that_are_not_keyword_decks(tmp_path, data, words):
    path = tmp_path / "deck.k"
    path.write_bytes(data)
    with pytest.raises(DeckError) as err:
        read_deck(path)
    assert str(err.value).startswith(f"{path}: not a keyword deck")
    assert words in str(err.value)


def test_an_empty_include_file_is_allowed(tmp_path):
    (tmp_path / "empty.k").write_text("")
    path = tmp_path / "deck.k"
    path.write_text("*KEYWORD\n*INCLUDE\nempty.k\n*END\n")
    assert read_deck(path).includes()[0].deck.items == []


def test_a_binary_include_file_is_refused(tmp_path):
    (tmp_path / "bin.k").write_bytes(b"\x00\x01\x02" * 100)
    path = tmp_path / "deck.k"
    path.write_text("*KEYWORD\n*INCLUDE\nbin.k\n*END\n")
    with pytest.raises(DeckError, match="bin.k: not a keyword deck: the file is binary"):
        read_deck(path)
