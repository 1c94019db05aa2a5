"""Bad rigid-body input: a DeckError naming the file, the line and the keyword."""

from __future__ import annotations

import re

import pytest

from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.errors import DeckError
from hollowbody.io.keyword import read_deck, write_deck
from hollowbody.testing.rigid_decks import assembly_deck

EXTRA_CARDS = {
    "not_rigid": ("*MAT_ELASTIC\n9,1e-6,0.01,0.3\n*PART\nsoft\n9,1,9\n"
                  "*CONSTRAINED_RIGID_BODIES\n1,9\n",
                  "CONSTRAINED_RIGID_BODIES", "PIDS: part 9 is not rigid"),
    "no_set": ("*CONSTRAINED_NODAL_RIGID_BODY\n200,0,999\n",
               "CONSTRAINED_NODAL_RIGID_BODY", "node set 999 (NSID) is not defined"),
    "two_bodies": ("*SET_NODE_LIST\n300\n1,41\n*CONSTRAINED_NODAL_RIGID_BODY\n300,0,300\n",
                   "CONSTRAINED_NODAL_RIGID_BODY",
                   "node 1 is on nodal rigid body 300 and on rigid body 1 (parts 1 + merged)"),
    "cycle": ("*CONSTRAINED_RIGID_BODIES\n3,1\n", "CONSTRAINED_RIGID_BODIES",
              "constrained to each other in a cycle"),
    "twice": ("*CONSTRAINED_RIGID_BODIES\n1,3\n", "CONSTRAINED_RIGID_BODIES",
              "part 3 is already constrained to part 2"),
    "extra_not_rigid": ("*CONSTRAINED_EXTRA_NODES_NODE\n77,31\n",
                        "CONSTRAINED_EXTRA_NODES_NODE", "PID: part 77 is not a defined part"),
    "motion_on_body": ("*DEFINE_CURVE\n5\n0,1\n1,1\n*BOUNDARY_PRESCRIBED_MOTION_NODE\n"
                       "32,1,0,5\n", "BOUNDARY_PRESCRIBED_MOTION_NODE",
                       "a prescribed motion on node 32, which is on rigid body 1"),
    "motion_on_set": ("*DEFINE_CURVE\n5\n0,1\n1,1\n*SET_NODE_LIST\n600\n41,42\n"
                      "*BOUNDARY_PRESCRIBED_MOTION_SET\n600,3,0,5\n",
                      "BOUNDARY_PRESCRIBED_MOTION_SET",
                      "a prescribed motion on node 41, which is on nodal rigid body 100"),
    "release": ("*CONSTRAINED_NODAL_RIGID_BODY\n400,0,100,0,0,1\n",
                "CONSTRAINED_NODAL_RIGID_BODY", "DRFLAG=1/RRFLAG=0"),
    "no_mass": ("*SET_NODE_LIST\n500\n1\n*CONSTRAINED_NODAL_RIGID_BODY_INERTIA\n500,0,500\n"
                "0,0,0,0\n1,0,0,1,0,1\n", "CONSTRAINED_NODAL_RIGID_BODY_INERTIA",
                "TM=0: the _INERTIA option needs"),
}


def _bad_deck(tmp_path, key):
    path = tmp_path / "bad.k"
    write_deck(assembly_deck(), path)
    text = path.read_text().replace("*END", "")
    cards, _, _ = EXTRA_CARDS[key]
    lines_before = text.count("\n")
    path.write_text(text + cards + "*END\n")
    return path, lines_before


@pytest.mark.parametrize("key", sorted(EXTRA_CARDS))
def test_deck_error_names_file_line_keyword(tmp_path, key):
    path, first_new = _bad_deck(tmp_path, key)
    _, keyword, message = EXTRA_CARDS[key]
    with pytest.raises(DeckError) as err:
        build_model(read_deck(path))
    text = str(err.value)
    m = re.match(rf"{re.escape(str(path))}:(\d+): \*{keyword}: ", text)
    assert m, text
    assert int(m.group(1)) > first_new  # the line of the offending card, in the added text
    assert message in text, text


def test_check_exits_2_with_the_error(tmp_path, capsys):
    path, _ = _bad_deck(tmp_path, "two_bodies")
    assert cli_main(["check", str(path)]) == 2
    assert "a node belongs to one rigid body only" in capsys.readouterr().err
