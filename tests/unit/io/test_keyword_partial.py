"""read_deck_partial: the items read before the first error, and that error."""

from __future__ import annotations

from pathlib import Path

import pytest

from hollowbody.errors import DeckError
from hollowbody.io.keyword import Nodes, Part, read_deck, read_deck_partial

DECKS = Path(__file__).parents[2] / "regression" / "decks"


def test_a_deck_that_reads_gives_the_same_deck_and_no_error():
    path = DECKS / "hand_check.k"
    read = read_deck_partial(path)
    assert read.error is None
    assert read.deck == read_deck(path)
    assert read.keywords["PART"] == 3 and read.keywords["NODE"] == 1
    assert "END" not in read.keywords


@pytest.mark.parametrize("bad", ["       3    abc", "         3         1       x.5"])
def test_the_error_is_the_one_read_deck_raises_and_the_items_before_it_are_kept(tmp_path, bad):
    inc = tmp_path / "inc.k"
    node = "             0.0             0.0             0.0\n"
    inc.write_text("*NODE\n       1" + node + "*PART\nplate\n" + bad + "\n")
    deck = tmp_path / "main.k"
    deck.write_text("*KEYWORD\n*PART\ncube\n         1         1         1\n*INCLUDE\ninc.k\n"
                    "*NODE\n       9" + node + "*END\n")
    with pytest.raises(DeckError) as raised:
        read_deck(deck)
    read = read_deck_partial(deck)
    assert str(read.error) == str(raised.value)
    assert read.error.file == str(inc) and read.error.line == 5
    assert [p.pid for p in read.deck.of_type(Part)] == [1]  # the bad *PART adds nothing
    assert [int(n.ids[0]) for n in read.deck.of_type(Nodes)] == [1]  # node 9 comes after
    assert read.keywords == {"KEYWORD": 1, "PART": 2, "INCLUDE": 1, "NODE": 1}
