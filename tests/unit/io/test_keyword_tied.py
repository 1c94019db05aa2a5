"""*CONTACT_TIED_...: reading, writing, the round trip, the model and the errors."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    RawKeyword,
    TiedContact,
    UnsupportedKeywordWarning,
    deck_lines,
    read_deck_text,
)

MESH = """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2             1.0             0.0             0.0
       3             1.0             1.0             0.0
       4             0.0             1.0             0.0
       5             0.0             0.0             1.0
       6             1.0             0.0             1.0
       7             1.0             1.0             1.0
       8             0.0             1.0             1.0
       9             0.5             0.5             1.0
*ELEMENT_SOLID
       1       1       1       2       3       4       5       6       7       8
*ELEMENT_SHELL
       2       2       5       6       7       8
*PART
cube
         1         1         1
*PART
lid
         2         2         1
*SECTION_SOLID
         1
*SECTION_SHELL
         2         2             1.0
       1.0       1.0       1.0       1.0
*MAT_ELASTIC
         1    1.0e-6       0.1       0.3
*SET_NODE_LIST
         5
         9
*SET_SEGMENT
         6
         5         6         7         8
*SET_PART_LIST
         3
         1         2
*CONTROL_TERMINATION
       1.0
"""  # 39 lines

TIED = """\
*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_ID
$     CID HEADING
      1001hollow walls -> boundary, part 2
$    SSID      MSID     SSTYP     MSTYP
         5         6         4         0
$      FS        FD        DC        VC       VDC    PENCHK        BT        DT
       0.0       0.0       0.0       0.0       0.0         0       0.0     1e+20
$     SFS       SFM       SST       MST      SFST      SFMT       FSF       VSF
       1.0       1.0       0.0       2.5       1.0       1.0       1.0       1.0
*CONTACT_TIED_NODES_TO_SURFACE_OFFSET
         5         1         4         3
*CONTACT_TIED_SURFACE_TO_SURFACE_CONSTRAINED_OFFSET_TITLE
        12glue
         2         3         3         2
       0.2
       1.0       1.0      -0.5
*CONTACT_TIED_NODES_TO_SURFACE_MPP_ID
        13
         1         0         0
         5         6         4         0
"""


def _read(text: str):
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnsupportedKeywordWarning)
        return read_deck_text(text, "deck.k")


def test_read_all_forms():
    deck = _read(MESH + TIED)
    ties = deck.of_type(TiedContact)
    assert [(t.type, t.offset, t.cid) for t in ties] == [
        ("TIED_SHELL_EDGE_TO_SURFACE", "", 1001), ("TIED_NODES_TO_SURFACE", "OFFSET", None),
        ("TIED_SURFACE_TO_SURFACE", "CONSTRAINED_OFFSET", 12),
        ("TIED_NODES_TO_SURFACE", "", 13)]
    a, b, c, d = ties
    assert a.heading == "hollow walls -> boundary, part 2"  # a comma inside the heading
    assert (a.ssid, a.msid, a.sstyp, a.mstyp, a.mst) == (5, 6, 4, 0, 2.5)
    assert (b.ssid, b.msid, b.sstyp, b.mstyp) == (5, 1, 4, 3)
    assert (c.heading, c.fs, c.sst) == ("glue", 0.2, -0.5)
    assert d.mpp == ["         1         0         0"]
    assert a.source.line == 44 and b.source.line == 50


def test_round_trip_equal_deck_and_text():
    deck = _read(MESH + TIED)
    text = "\n".join(deck_lines(deck)) + "\n"
    back = _read(text)
    assert back == deck
    assert "\n".join(deck_lines(back)) + "\n" == text
    kws = [ln for ln in text.splitlines() if ln.startswith("*CONTACT")]
    assert kws == ["*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_ID",
                   "*CONTACT_TIED_NODES_TO_SURFACE_OFFSET",
                   "*CONTACT_TIED_SURFACE_TO_SURFACE_CONSTRAINED_OFFSET_ID",
                   "*CONTACT_TIED_NODES_TO_SURFACE_MPP_ID"]


def test_model_tied_contacts():
    model = build_model(_read(MESH + TIED))
    assert model.contacts == []
    a, b, c, d = model.tied_contacts
    assert (a.cid, a.kind, a.offset, a.mst) == (1001, "shell_edge_to_surface", False, 2.5)
    assert a.slave.kind == "nodes" and model.node_ids[a.slave.nodes].tolist() == [9]
    assert a.master.kind == "segments" and model.node_ids[a.master.segments].tolist() == \
        [[5, 6, 7, 8]]
    assert (b.cid, b.kind, b.offset, b.master.pids) == (2, "nodes_to_surface", True, [1])
    assert (c.kind, c.slave.pids, c.master.pids, c.offset) == ("surface_to_surface", [2],
                                                              [1, 2], True)
    assert c.sst == -0.5 and c.title == "glue"
    assert d.cid == 13 and model.controls.tiedprj == 0


def test_api_item_writes_what_it_reads():
    item = TiedContact(type="tied_shell_edge_to_surface", cid=5, heading="h", ssid=5, sstyp=4,
                       msid=6, mstyp=0, mst=1.5)
    deck = _read(MESH)
    deck.add(item)
    back = _read("\n".join(deck_lines(deck)) + "\n")
    assert back.of_type(TiedContact) == [item]
    with pytest.raises(ValueError, match="TIED_SHELL"):
        TiedContact(type="TIED_BEAM_TO_SURFACE")
    with pytest.raises(ValueError, match="offset"):
        TiedContact(offset="BEAM_OFFSET")


@pytest.mark.parametrize("keyword", ["CONTACT_TIED_SHELL_EDGE_TO_SURFACE_BEAM_OFFSET",
                                     "CONTACT_TIED_SURFACE_TO_SURFACE_FAILURE"])
def test_other_tied_forms_stay_unsupported(keyword):
    with pytest.warns(UnsupportedKeywordWarning, match=keyword):
        deck = read_deck_text(MESH + f"*{keyword}\n         5         1         4         3\n",
                              "deck.k")
    assert [r.keyword for r in deck.of_type(RawKeyword)] == [keyword]


@pytest.mark.parametrize("card, message", [
    ("         5         1         4         5", "deck.k:41: *CONTACT_TIED_NODES_TO_SURFACE: "
     "MSTYP=5 (all) is not supported for a tied contact"),
    ("         5         1         1         3", "SSTYP=1 (shell element set) is not supported"),
    ("         7         1         4         3", "refers to node set 7 (SSTYP=4) which is not "
     "defined"),
    ("         5         9         4         0", "refers to segment set 9 (MSTYP=0) which is "
     "not defined"),
    ("         5         1         4         3         1", "SBOXID/MBOXID"),
])
def test_errors_name_file_line_and_keyword(card, message):
    with pytest.raises(DeckError) as err:
        build_model(_read(MESH + "*CONTACT_TIED_NODES_TO_SURFACE\n" + card + "\n"))
    assert message in str(err.value)


def test_tiedprj_read_into_controls():
    model = build_model(_read(MESH + TIED + "*CONTROL_CONTACT\n\n0,0,0,0,0,0,0,1\n"))
    assert model.controls.tiedprj == 1
    assert np.all(model.node_sets[5] >= 0)


def test_id_card_headings_with_commas():
    text = ("*KEYWORD\n*CONTACT_TIED_NODES_TO_SURFACE_ID\n,glue, again\n1,2,4,3\n"
            "*CONTACT_TIED_NODES_TO_SURFACE_ID\n         9walls -> boundary, part 2\n1,2,4,3\n"
            "*CONTACT_TIED_NODES_TO_SURFACE_ID\n4,free, format\n1,2,4,3\n")
    ties = _read(text).of_type(TiedContact)
    assert [(t.cid, t.heading) for t in ties] == [(0, "glue, again"),
                                                  (9, "walls -> boundary, part 2"),
                                                  (4, "free, format")]
