"""Joints, joint stiffnesses and coordinate systems: cards, defaults, round trip, the
Model records, ``check``'s report, and bad input (DeckError naming file, line and
keyword; exit 2 from the CLI)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.cli.main import main
from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    ConstrainedJoint,
    DefineCoordinateNodes,
    DefineCoordinateSystem,
    JointStiffnessGeneralized,
    deck_lines,
    read_deck,
    read_deck_text,
)
from hollowbody.model.joints import axes_from_points
from hollowbody.solver.setup import assemble


def _cube(first: int, corner) -> list[str]:  # noqa: ANN001
    c = np.asarray(corner, float)
    unit = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1],
                     [1, 1, 1], [0, 1, 1]], float)
    return [f"{first + k},{p[0]},{p[1]},{p[2]}" for k, p in enumerate(c + 10.0 * unit)]


#: ground cube (part 1, fixed rigid, nodes 101-108), body cube (part 2, rigid, 201-208)
#: sharing the face x = 0, a deformable cube (part 3, 301-308) below with node 305 at
#: the origin; node 102 = 201 = 305 = (0,0,0), 103 = 204 = (0,10,0), 106 = 205 = (0,0,10).
BASE = "\n".join([
    "*KEYWORD", "*CONTROL_TERMINATION", "1.0", "*NODE",
    *_cube(101, (-10, 0, 0)), *_cube(201, (0, 0, 0)), *_cube(301, (0, 0, -10)),
    "*ELEMENT_SOLID", "1,1,101,102,103,104,105,106,107,108",
    "2,2,201,202,203,204,205,206,207,208", "3,3,301,302,303,304,305,306,307,308",
    "*PART", "ground", "1,1,1", "*PART", "body", "2,1,2", "*PART", "soft", "3,1,3",
    "*SECTION_SOLID", "1", "*MAT_RIGID", "1,1e-6,0.03,0.3", "1.0,7,7",
    "*MAT_RIGID", "2,1e-6,0.03,0.3", "*MAT_ELASTIC", "3,1e-6,0.03,0.3",
    "*DEFINE_COORDINATE_SYSTEM", "1,0,0,0,1,0,0", "0,1,0",
    "*DEFINE_CURVE", "7", "-1.0,-1.0", "1.0,1.0",
]) + "\n"


def _deck(tmp_path, text: str):  # noqa: ANN001, ANN202
    path = tmp_path / "joint.k"
    path.write_text(BASE + text + "*END\n")
    return path


def _line_of(path, needle: str) -> int:  # noqa: ANN001
    lines = path.read_text().splitlines()
    return max(k for k, t in enumerate(lines) if t.startswith(needle)) + 1


def test_joint_cards_defaults_and_round_trip():
    text = ("*KEYWORD\n*CONSTRAINED_JOINT_REVOLUTE_ID\n        12hinge\n1,2,3,4\n"
            "*CONSTRAINED_JOINT_SPHERICAL\n5,6\n7,8,0,0,0,0,2.0,0.005\n"
            "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n1,10,20,4,0,12\n0,0,5\n"
            "0,0,0,0,100.,3.\n0,0,0,0,-30,30\n"
            "*DEFINE_COORDINATE_NODES_TITLE\nknee\n3,1,2,3,1,Z\n*END\n")
    deck = read_deck_text(text)
    joints = [i for i in deck.iter_items() if isinstance(i, ConstrainedJoint)]
    assert [(j.kind, j.jid, j.heading) for j in joints] == [
        ("REVOLUTE", 12, "hinge"), ("SPHERICAL", None, ""), ("SPHERICAL", None, "")]
    assert (joints[0].rps, joints[0].damp) == (1.0, 1.0)
    assert (joints[2].rps, joints[2].damp) == (2.0, 0.005)
    st = next(i for i in deck.iter_items() if isinstance(i, JointStiffnessGeneralized))
    assert (st.jsid, st.pida, st.pidb, st.cida, st.cidb, st.jid, st.lcidps) == \
        (1, 10, 20, 4, 0, 12, 5)
    assert (st.esps, st.fmps, st.nsaps, st.psaps) == (100.0, 3.0, -30.0, 30.0)
    cn = next(i for i in deck.iter_items() if isinstance(i, DefineCoordinateNodes))
    assert (cn.cid, cn.flag, cn.dir, cn.title) == (3, 1, "Z", "knee")
    again = read_deck_text("\n".join(deck_lines(deck)) + "\n")
    assert list(again.iter_items()) == list(deck.iter_items())


def test_coordinate_systems_axes():
    # DIR = X: x along N1->N2, N3 in the x-y plane; DIR = Z: z along N1->N2, N3 in z-x
    e = axes_from_points(np.zeros(3), np.array([2.0, 0, 0]), np.array([1.0, 1.0, 0]), 0)
    assert np.allclose(e, np.eye(3))
    e = axes_from_points(np.zeros(3), np.array([0, 0, 3.0]), np.array([1.0, 0, 1.0]), 2)
    assert np.allclose(e, np.eye(3))
    e = axes_from_points(np.zeros(3), np.array([0, 1.0, 0]), np.array([0, 1.0, 1.0]), 1)
    assert np.allclose(e, np.eye(3))
    with pytest.raises(ValueError):
        axes_from_points(np.zeros(3), np.array([1.0, 0, 0]), np.array([2.0, 0, 0]), 0)


def test_model_records(tmp_path):
    path = _deck(tmp_path, "*DEFINE_COORDINATE_NODES\n2,102,202,204,1,X\n"
                 "*CONSTRAINED_JOINT_CYLINDRICAL_ID\n5\n102,201,103,204,0,0,0.,0.\n"
                 "*CONSTRAINED_JOINT_STIFFNESS_FLEXION-TORSION\n3,1,2,2,1,5\n7,0,7\n"
                 "0,0,10.,2.\n45.,30.,-30.\n*DATABASE_JNTFORC\n0.25\n")
    model = build_model(read_deck(path))
    (j,) = model.joints
    assert (j.jid, j.kind, j.rps, j.damp) == (5, "CYLINDRICAL", 1.0, 1.0)
    assert model.node_ids[j.nodes].tolist() == [102, 201, 103, 204]
    cs = model.coordinate_systems[2]
    assert cs.follow and np.allclose(cs.axes, np.eye(3))
    (st,) = model.joint_stiffness
    assert (st.kind, st.cida, st.cidb, st.jid) == ("FLEXION-TORSION", 2, 1, 5)
    assert np.allclose(st.pos_stop, np.radians([45.0, np.nan, 30.0]), equal_nan=True)
    assert np.allclose(st.neg_stop, [np.nan, np.nan, -np.radians(30.0)], equal_nan=True)
    assert model.output.intervals["jntforc"] == 0.25


def test_check_reports_joints(tmp_path, capsys):
    path = _deck(tmp_path, "*CONSTRAINED_JOINT_SPHERICAL\n102,201\n"
                 "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n4,1,2,1\n7\n")
    assert main(["check", str(path), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["joints"] == [{"jid": 1, "type": "SPHERICAL", "nodes": [102, 201],
                            "parts": [1, 2]}]
    assert s["joint_stiffness"] == [{"jsid": 4, "type": "GENERALIZED", "parts": [1, 2],
                                     "cid": [1, 1], "jid": 0}]
    assert main(["check", str(path)]) == 0
    out = capsys.readouterr().out
    assert "joint 1: SPHERICAL, nodes 102, 201, rigid parts 1 / 2" in out


BAD = {
    "not on a rigid body": ("*CONSTRAINED_JOINT_SPHERICAL\n102,305\n",
                            "node 305 (N2) is not on a rigid body", "CONSTRAINED_JOINT_SPHERICAL"),
    "not coincident": ("*CONSTRAINED_JOINT_SPHERICAL\n102,202\n",
                       "are 10 mm apart; they must coincide", "CONSTRAINED_JOINT_SPHERICAL"),
    "same body": ("*CONSTRAINED_JOINT_SPHERICAL\n201,201\n",
                  "are both on rigid part 2", "CONSTRAINED_JOINT_SPHERICAL"),
    "missing node": ("*CONSTRAINED_JOINT_REVOLUTE\n102,201\n", "N3 is required",
                     "CONSTRAINED_JOINT_REVOLUTE"),
    "undefined node": ("*CONSTRAINED_JOINT_SPHERICAL\n102,999\n", "node 999 which is not",
                       "CONSTRAINED_JOINT_SPHERICAL"),
    "arms not perpendicular": ("*CONSTRAINED_JOINT_UNIVERSAL\n102,201,103,204\n",
                               "must be perpendicular", "CONSTRAINED_JOINT_UNIVERSAL"),
    "curve": ("*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n4,1,2,1\n99\n",
              "LCIDPH=99: curve 99 is not defined", "CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"),
    "coordinate system": ("*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n4,1,2,5\n",
                          "CIDA=5: coordinate system not defined",
                          "CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"),
    "not a rigid body": ("*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n4,1,3,1\n",
                         "PIDB=3 is not a rigid body", "CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"),
    "collinear nodes": ("*DEFINE_COORDINATE_NODES\n2,102,103,103\n",
                        "do not define axes", "DEFINE_COORDINATE_NODES"),
    "joint not defined": ("*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n4,1,2,1,0,8\n",
                          "JID=8: joint not defined", "CONSTRAINED_JOINT_STIFFNESS_GENERALIZED"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_is_a_deck_error_at_its_card(tmp_path, case, capsys):
    text, message, keyword = BAD[case]
    path = _deck(tmp_path, text)
    with pytest.raises(DeckError) as err:
        assemble(build_model(read_deck(path)))
    exc = err.value
    assert message in exc.message
    assert exc.file == str(path) and exc.keyword.lstrip("*") == keyword
    assert exc.line == _line_of(path, text.splitlines()[1].split(",")[0] + ",")
    assert main(["run", str(path), "--out", str(tmp_path / "out")]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_joint_stiffness_keywords_in_a_deck_written_back(tmp_path):
    deck = read_deck(_deck(tmp_path, "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED\n4,1,2,1\n"))
    text = "\n".join(deck_lines(deck))
    assert "*CONSTRAINED_JOINT_STIFFNESS_GENERALIZED" in text
    assert any(isinstance(i, DefineCoordinateSystem) for i in deck.iter_items())
