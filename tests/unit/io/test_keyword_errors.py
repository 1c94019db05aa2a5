"""Malformed decks raise DeckError at the right file and line (library and CLI)."""

from __future__ import annotations

import pytest

from hollowbody.build import build_model
from hollowbody.cli.main import main
from hollowbody.errors import DeckError
from hollowbody.io.keyword import read_deck

# A valid one-hexahedron model; cases below append or replace keywords.
BASE = """\
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
*ELEMENT_SOLID
       1       1       1       2       3       4       5       6       7       8
*PART
cube
         1         1         1
*SECTION_SOLID
         1
*MAT_ELASTIC
         1    1.0e-6       0.1       0.3
*CONTROL_TERMINATION
       1.0
"""  # 21 lines

CASES = {
    "bad node coordinate": (
        BASE.replace("       3             1.0             1.0",
                     "       3             1.0             1.x"),
        "5: *NODE: field Y: '1.x' is not a number"),
    "bad free-format node": (
        BASE + "*NODE\n9,1.0,abc,0.0\n", "23: *NODE: field Y: 'abc' is not a number"),
    "bad element node id": (
        BASE.replace("       1       1       1       2       3       4       5       6       7",
                     "       1       1       1       2       3       4       5       6      7a"),
        "12: *ELEMENT_SOLID: field N7: '7a' is not an integer"),
    "bad card number": (
        BASE.replace("    1.0e-6       0.1", "    1.0e-6      0.1a"),
        "19: *MAT_ELASTIC: field E: '0.1a' is not a number"),
    "missing card": (
        BASE + "*MAT_SIMPLIFIED_RUBBER\n         2    1.0e-6       1.0\n",
        "23: *MAT_SIMPLIFIED_RUBBER: card 2 (SGL, SW, ST, LCID, TENSION, RTYPE, AVGOPT, PR) "
        "is missing"),
    "element with a missing node": (
        BASE + "*ELEMENT_SOLID\n      42       1       1       2       3       4       5"
        "       6       7     999\n",
        "23: *ELEMENT_SOLID: element 42 refers to node 999 which is not defined"),
    "element with a missing part": (
        BASE + "*ELEMENT_SOLID\n       2       5       1       2       3       4       5"
        "       6       7       8\n",
        "23: *ELEMENT_SOLID: element 2 refers to part 5 which is not defined"),
    "part with a missing material": (
        BASE + "*PART\nother\n         2         1         9\n",
        "24: *PART: part 2 refers to material 9 which is not defined"),
    "part with a missing section": (
        BASE + "*PART\nother\n         2         4         1\n",
        "24: *PART: part 2 refers to section 4 which is not defined"),
    "duplicate node": (
        BASE + "*NODE\n       3             5.0             0.0             0.0\n",
        "23: *NODE: node 3 is defined twice (first at {path}:5)"),
    "duplicate element": (
        BASE + "*ELEMENT_SOLID\n       1       1       1       2       3       4       5"
        "       6       7       8\n",
        "23: *ELEMENT_SOLID: element 1 is defined twice (first at {path}:12)"),
    "duplicate part": (
        BASE + "*PART\nagain\n         1         1         1\n",
        "24: *PART: part 1 is defined twice (first at {path}:15)"),
    "duplicate material": (
        BASE + "*MAT_RIGID\n         1    1.0e-6       0.1       0.3\n",
        "23: *MAT_RIGID: material 1 is defined twice (first at {path}:19)"),
    "duplicate section": (
        BASE + "*SECTION_SHELL\n         1\n       1.0\n",
        "23: *SECTION_SHELL: section 1 is defined twice (first at {path}:17)"),
    "duplicate curve": (
        BASE + "*DEFINE_CURVE\n5\n0,0\n1,1\n*DEFINE_CURVE\n5\n0,0\n1,1\n",
        "27: *DEFINE_CURVE: curve 5 is defined twice (first at {path}:23)"),
    "duplicate set": (
        BASE + "*SET_NODE_LIST\n5\n1\n*SET_NODE_LIST_GENERATE\n5\n1,2\n",
        "26: *SET_NODE_LIST_GENERATE: node set 5 is defined twice (first at {path}:23)"),
    "curve abscissa not increasing": (
        BASE + "*DEFINE_CURVE\n5\n0.0,0.0\n1.0,1.0\n1.0,2.0\n",
        "26: *DEFINE_CURVE: curve 5: abscissa 1 does not increase (previous point 1)"),
    "set with a missing node": (
        BASE + "*SET_NODE_LIST\n5\n1,2,3\n4,77\n",
        "25: *SET_NODE_LIST: node set 5 refers to node 77 which is not defined"),
    "set with a missing part": (
        BASE + "*SET_PART_LIST\n5\n1,8\n",
        "24: *SET_PART_LIST: part set 5 refers to part 8 which is not defined"),
    "contact with a missing part set": (
        BASE + "*CONTACT_AUTOMATIC_SINGLE_SURFACE\n         3         0         2\n",
        "23: *CONTACT_AUTOMATIC_SINGLE_SURFACE: contact refers to part set 3 (SSTYP=2) which "
        "is not defined"),
    "contact on a shell element set": (
        BASE + "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE\n         3         1         1"
        "         3\n",
        "23: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE: SSTYP=1 (shell element set) is not "
        "supported (0 segment set, 2 part set, 3 part, 4 node set, 5 all)"),
    "prescribed motion with a missing curve": (
        BASE + "*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,3,0,44\n",
        "23: *BOUNDARY_PRESCRIBED_MOTION_NODE: prescribed motion refers to curve 44 which is "
        "not defined"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_malformed_deck_error_names_file_and_line(case, deck_file):
    text, expected = CASES[case]
    path = deck_file(text)
    with pytest.raises(DeckError) as err:
        build_model(read_deck(path))
    assert str(err.value) == f"{path}:" + expected.format(path=path)


def test_missing_include_names_the_include_card(deck_file):
    deck_file("*NODE\n1,0,0,0\n*INCLUDE\n\nnot_there.k\n", "sub/a.k")
    path = deck_file("*KEYWORD\n*INCLUDE\nsub/a.k\n")
    with pytest.raises(DeckError) as err:
        read_deck(path)
    sub = path.parent / "sub" / "a.k"
    assert str(err.value) == (f"{sub}:5: *INCLUDE: include file "
                              f"'{path.parent / 'sub' / 'not_there.k'}' does not exist")


@pytest.mark.parametrize("case", ["bad node coordinate", "element with a missing node",
                                  "missing card", "duplicate part"])
def test_cli_check_reports_one_line_and_exit_code_2(case, deck_file, capsys):
    path = deck_file(CASES[case][0])
    assert main(["check", str(path)]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in captured.err
    assert lines[0].startswith(f"hollowbody check: error: {path}:")


def test_cli_check_missing_file(tmp_path, capsys):
    assert main(["check", str(tmp_path / "nope.k")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"hollowbody check: error: deck '{tmp_path / 'nope.k'}' does not exist"]
