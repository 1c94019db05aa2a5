"""Bad load, rigid-wall and *MAT_NULL input: exit 2 with file, line and keyword."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.cli.main import main
from hollowbody.io.keyword import (
    ControlTermination,
    Deck,
    DefineCurve,
    MatElastic,
    Part,
    SectionSolid,
    SetPartList,
    write_deck,
)

GOOD_BODY = "*LOAD_BODY_Z\n         1  0.00981\n"


def _write(tmp_path, tail: str, mat: str | None = None):  # noqa: ANN202
    """A one-hex deck followed by ``mat`` (the part's material, when given) and ``tail``;
    returns (path, line of the first card after the deck)."""
    deck = Deck()
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                  [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)
    deck.add_nodes(np.arange(1, 9), x)
    deck.add_solids(np.array([1]), 1, np.arange(1, 9)[None, :])
    deck.add(Part(pid=1, secid=1, mid=1))
    deck.add(SectionSolid(secid=1))
    if mat is None:
        deck.add(MatElastic(mid=1, ro=1.0e-6, e=0.01, pr=0.3))
    deck.add(DefineCurve(lcid=1, points=[[0.0, 1.0], [10.0, 1.0]]))
    deck.add(SetPartList(sid=1, parts=[1]))
    deck.add(ControlTermination(endtim=0.1))
    path = tmp_path / "deck.k"
    write_deck(deck, path)
    text = path.read_text()
    assert text.rstrip().endswith("*END")
    head = text.rstrip()[:-len("*END")]
    line = head.count("\n") + 2  # the keyword line, then its first card
    if mat is not None:  # the material's card is then the line reported
        head += mat
    path.write_text(head + tail + "*END\n")
    return path, line


CASES = [
    ("LOAD_BODY_Z", "*LOAD_BODY_Z\n         9  0.00981\n", 0, "curve 9 is not defined"),
    ("LOAD_NODE_POINT", "*LOAD_NODE_POINT\n       999         3         1       1.0\n", 0,
     "node 999 which is not defined"),
    ("LOAD_NODE_SET", "*LOAD_NODE_SET\n        99         3         1       1.0\n", 0,
     "node set 99 is not defined"),
    ("LOAD_NODE_POINT", "*LOAD_NODE_POINT\n         1         4         1       1.0\n", 0,
     "follower"),
    ("LOAD_NODE_POINT", "*LOAD_NODE_POINT\n         1         1         1       1.0"
     "         5\n", 0, "local coordinate system"),
    ("LOAD_RIGID_BODY", "*LOAD_RIGID_BODY\n        99         1         1       1.0\n", 0,
     "part 99 is not defined"),
    ("LOAD_RIGID_BODY", "*LOAD_RIGID_BODY\n         1         1         1       1.0\n", 0,
     "not rigid"),
    ("LOAD_BODY_PARTS", "*LOAD_BODY_PARTS\n        99\n" + GOOD_BODY, 0,
     "part set 99 is not defined"),
    ("RIGIDWALL_PLANAR", "*RIGIDWALL_PLANAR\n         0\n       0.0       0.0       1.0"
     "       0.0       0.0       1.0\n", 0, "normal is zero"),
    ("RIGIDWALL_PLANAR", "*RIGIDWALL_PLANAR\n        77\n       0.0       0.0       0.0"
     "       0.0       0.0       1.0\n", 0, "node set 77 is not defined"),
    ("RIGIDWALL_PLANAR_MOVING", "*RIGIDWALL_PLANAR_MOVING\n         0\n       0.0       0.0"
     "       0.0       0.0       0.0       1.0\n       1.0       0.0\n", 0, "_MOVING"),
]


@pytest.mark.parametrize(("keyword", "tail", "offset", "message"), CASES)
def test_bad_load_or_wall_exits_2_naming_file_line_keyword(tmp_path, capsys, keyword, tail,
                                                          offset, message):
    path, line = _write(tmp_path, tail)
    assert main(["check", str(path)]) == 2
    out = capsys.readouterr()
    text = out.out + out.err
    assert f"deck.k:{line + offset}: *{keyword}" in text, text
    assert message in text, text


def test_null_solid_is_rejected_at_its_material(tmp_path, capsys):
    mat = "*MAT_NULL\n         1   1.0e-06       0.0       0.0       0.0       0.0      0.01" \
          "       0.3\n"
    path, line = _write(tmp_path, "", mat=mat)
    assert main(["check", str(path)]) == 2
    out = capsys.readouterr()
    text = out.out + out.err
    assert f"deck.k:{line}: *MAT_NULL" in text, text
    assert "equation of state" in text


def test_good_loads_pass(tmp_path, capsys):
    """The same deck with valid gravity, a nodal force and a floor checks clean."""
    tail = GOOD_BODY + "*LOAD_NODE_POINT\n         1         3         1       1.0\n" \
        "*RIGIDWALL_PLANAR\n         0\n       0.0       0.0      -1.0       0.0       0.0" \
        "       1.0\n"
    path, _ = _write(tmp_path, tail)
    assert main(["check", str(path)]) == 0, capsys.readouterr().out
