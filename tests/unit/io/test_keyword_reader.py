"""Reading keyword cards: every supported keyword, fixed and free format, defaults."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    BoundarySpcNode,
    BoundarySpcSet,
    Contact,
    ControlBulkViscosity,
    ControlContact,
    ControlHourglass,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    DatabaseHistoryNodeSet,
    DefineCurve,
    Hourglass,
    Include,
    InitialVelocity,
    InitialVelocityGeneration,
    InitialVelocityNode,
    MassElements,
    MatElastic,
    MatPiecewiseLinearPlasticity,
    MatPlasticKinematic,
    MatRigid,
    MatSimplifiedRubber,
    Nodes,
    Part,
    PartInertia,
    PrescribedMotionNode,
    PrescribedMotionRigid,
    PrescribedMotionSet,
    RawKeyword,
    SectionShell,
    SectionSolid,
    SetNodeList,
    SetNodeListGenerate,
    SetPartList,
    SetPartListGenerate,
    SetSegment,
    ShellElements,
    SolidElements,
    UnsupportedKeywordWarning,
    read_deck,
    read_deck_text,
)


def one(text: str, cls: type):
    """The single item of class ``cls`` read from ``text``."""
    items = read_deck_text(text).of_type(cls)
    assert len(items) == 1, items
    return items[0]


# ---------------------------------------------------------------------------
# Mesh


def test_node_fixed_free_and_comments():
    d = read_deck_text(
        "*NODE\n"
        "$#   nid               x               y               z      tc      rc\n"
        "       1             1.5            -2.0          3.0e+1\n"
        "$ comment inside the block\n"
        "2,4.0,,6.0\n"
        "       3      1.0000D+00             0.0             0.0       7       0\n")
    n = d.of_type(Nodes)[0]
    np.testing.assert_array_equal(n.ids, [1, 2, 3])
    np.testing.assert_array_equal(n.xyz, [[1.5, -2.0, 30.0], [4.0, 0.0, 6.0], [1.0, 0, 0]])
    np.testing.assert_array_equal(n.tc, [0, 0, 7])
    np.testing.assert_array_equal(n.row_lines, [3, 5, 6])
    assert n.source.line == 3


def test_node_long_formats():
    line = f"{12345678901:>20d}{1.25:>20}{-2.5:>20}{3.0:>20}"
    for head in ("*NODE +", "*NODE+"):
        n = one(f"{head}\n{line}\n", Nodes)
        assert n.ids[0] == 12345678901 and n.xyz[0].tolist() == [1.25, -2.5, 3.0]
    n = one(f"*KEYWORD long=y\n*NODE\n{line}\n", Nodes)
    assert n.ids[0] == 12345678901
    n = one(f"*NODE %\n{1234567890:>10d}{1.0:>16}{2.0:>16}{3.0:>16}\n", Nodes)
    assert n.ids[0] == 1234567890 and n.xyz[0].tolist() == [1.0, 2.0, 3.0]


def test_node_crlf_and_left_justified_ids():
    d = read_deck_text("*NODE\r\n1       1.0             2.0             3.0\r\n"
                       "      -2             0.0             0.0             0.0\r\n")
    n = d.of_type(Nodes)[0]
    assert n.ids.tolist() == [1, -2] and n.xyz[0].tolist() == [1.0, 2.0, 3.0]


def test_solid_one_card_two_card_and_degenerate_forms():
    d = read_deck_text(
        "*ELEMENT_SOLID\n"
        "       1       7       1       2       3       4       5       6       7       8\n"
        "       2       7       1       2       3       4       5       5       6       6\n"
        "       3       7       1       2       3       4       0       0       0       0\n"
        "*ELEMENT_SOLID\n"
        "       4       8\n"
        "       1       2       3       4\n"
        "       5       8\n"
        "       1       2       3       4       5       6       7       8\n")
    a, b = d.of_type(SolidElements)
    assert a.ids.tolist() == [1, 2, 3] and a.pids.tolist() == [7, 7, 7]
    assert a.conn[1].tolist() == [1, 2, 3, 4, 5, 5, 6, 6]
    assert a.conn[2].tolist() == [1, 2, 3, 4, 4, 4, 4, 4]
    assert b.ids.tolist() == [4, 5] and b.conn[0].tolist() == [1, 2, 3, 4, 4, 4, 4, 4]
    assert b.row_lines.tolist() == [6, 8]


def test_shell_plain_thickness_and_triangles():
    s = one("*ELEMENT_SHELL\n1,3,1,2,3,4\n2,3,4,5,6\n", ShellElements)
    assert s.conn.tolist() == [[1, 2, 3, 4], [4, 5, 6, 6]] and s.thickness is None
    s = one("*ELEMENT_SHELL_THICKNESS\n"
            "       1       3       1       2       3       4\n"
            "             1.5             1.5             2.0             2.0            30.0\n",
            ShellElements)
    assert s.thickness.tolist() == [[1.5, 1.5, 2.0, 2.0]] and s.beta.tolist() == [30.0]
    assert s.option == "THICKNESS"


def test_element_mass():
    m = one("*ELEMENT_MASS\n       1      10             2.5\n"
            "       2      11          0.0001       5\n", MassElements)
    assert m.nids.tolist() == [10, 11] and m.mass.tolist() == [2.5, 1e-4]
    assert m.pids.tolist() == [0, 5]


# ---------------------------------------------------------------------------
# Parts, sections, materials


def test_parts_repeat_and_inertia():
    d = read_deck_text("*PART\nfirst, with comma\n1,2,3\n\n4,5,6,0,7\n")
    p1, p2 = d.of_type(Part)
    assert (p1.title, p1.pid, p1.secid, p1.mid) == ("first, with comma", 1, 2, 3)
    assert (p2.title, p2.pid, p2.hgid) == ("", 4, 7)
    assert p1.source.line == 3
    pi = one("*PART_INERTIA\nimpactor\n9,1,1\n1.0,2.0,3.0,5.0,0,0\n"
             "10.,0.,0.,20.,0.,30.\n0.,0.,-11.1,0.,0.,0.\n", PartInertia)
    assert (pi.pid, pi.xc, pi.zc, pi.tm, pi.ixx, pi.iyy, pi.izz, pi.vtz) == \
        (9, 1.0, 3.0, 5.0, 10.0, 20.0, 30.0, -11.1)


def test_sections_defaults_and_title():
    s = one("*SECTION_SOLID_TITLE\nsoft tissue\n         1\n", SectionSolid)
    assert (s.secid, s.elform, s.title) == (1, 1, "soft tissue")
    sh = one("*SECTION_SHELL\n2\n1.5\n", SectionShell)
    assert (sh.elform, sh.nip, sh.shrf, sh.t1, sh.t2) == (2, 2, 1.0, 1.5, 0.0)
    sh = one("*SECTION_SHELL\n3,2,,10,,,1\n1.0\n0,45,90,0,45,90,0,45\n-45,90\n", SectionShell)
    assert sh.angles == [0, 45, 90, 0, 45, 90, 0, 45, -45, 90]


def test_hourglass_blank_q1_q2_stay_blank():
    h = one("*HOURGLASS\n         3         4      0.05\n", Hourglass)
    assert (h.hgid, h.ihq, h.qm, h.q1, h.q2) == (3, 4, 0.05, None, None)


def test_materials():
    e = one("*MAT_001_TITLE\nsteel\n1,7.85e-6,210.,0.3\n", MatElastic)
    assert (e.mid, e.ro, e.e, e.pr, e.title) == (1, 7.85e-6, 210.0, 0.3, "steel")
    r = one("*MAT_RIGID\n2,7.85e-6,210.,0.3\n1.0,4.0,7.0\n", MatRigid)
    assert (r.cmo, r.con1, r.con2) == (1.0, 4.0, 7.0)
    r = one("*MAT_020\n2,7.85e-6,210.,0.3\n", MatRigid)
    assert r.cmo == 0.0
    k = one("*MAT_PLASTIC_KINEMATIC\n3,1e-6,0.1,0.3,0.004,0.001\n", MatPlasticKinematic)
    assert (k.sigy, k.etan, k.beta) == (0.004, 0.001, 0.0)
    p = one("*MAT_PIECEWISE_LINEAR_PLASTICITY\n4,1e-6,0.1,0.3,0.004\n0,0,12\n",
            MatPiecewiseLinearPlasticity)
    assert (p.lcss, p.fail) == (12, 1.0e21)


@pytest.mark.parametrize("name", ["MAT_SIMPLIFIED_RUBBER", "MAT_SIMPLIFIED_RUBBER/FOAM",
                                  "MAT_181", "mat_simplified_rubber/foam"])
def test_mat181_layout_and_blank_defaults(name):
    text = (f"*{name}\n"
            "$#     mid        ro        km        mu         g      sigf       ref     prten\n"
            "         5    1.0e-6       1.0\n"
            "$#     sgl        sw        st    lc/tbid   tension     rtype    avgopt        pr\n"
            "                                      10\n")
    m = one(text, MatSimplifiedRubber)
    assert (m.mid, m.ro, m.km, m.mu) == (5, 1.0e-6, 1.0, 0.1)
    assert (m.sgl, m.sw, m.st, m.lcid, m.tension) == (1.0, 1.0, 1.0, 10, -1.0)


def test_mat181_keeps_extra_cards():
    m = one("*MAT_181\n5,1e-6,1.0\n2.,3.,4.,10\n0,1.0,,,1.0\n0.01,100.\n", MatSimplifiedRubber)
    assert (m.sgl, m.sw, m.st, m.visco) == (2.0, 3.0, 4.0, 1.0)
    assert m.extra_cards == ["0.01,100."]


# ---------------------------------------------------------------------------
# Curves and sets


def test_define_curve_title_scale_and_points():
    c = one("*DEFINE_CURVE_TITLE\nmuscle\n"
            "        10         0       2.0       0.5\n"
            "               -0.5               -1.0\n"
            "                 0.0                 0.0\n\n"
            "1.0,2.0\n", DefineCurve)
    assert (c.lcid, c.sfa, c.sfo, c.title) == (10, 2.0, 0.5, "muscle")
    assert c.points.tolist() == [[-0.5, -1.0], [0.0, 0.0], [1.0, 2.0]]


def test_sets():
    s = one("*SET_NODE_LIST_TITLE\nbottom\n1\n1,2,3,4,5,6,7,8\n9\n", SetNodeList)
    assert (s.sid, s.title, s.nodes.tolist()) == (1, "bottom", list(range(1, 10)))
    assert one("*SET_NODE\n2\n5,6\n", SetNodeList).nodes.tolist() == [5, 6]
    g = one("*SET_NODE_LIST_GENERATE\n3\n1,4,10,12\n", SetNodeListGenerate)
    assert g.expand().tolist() == [1, 2, 3, 4, 10, 11, 12]
    p = one("*SET_PART_LIST\n4\n1,2\n", SetPartList)
    assert p.parts.tolist() == [1, 2]
    assert one("*SET_PART_LIST_GENERATE\n5\n1,3\n", SetPartListGenerate).expand().tolist() == \
        [1, 2, 3]
    seg = one("*SET_SEGMENT\n6\n1,2,3,4\n5,6,7\n", SetSegment)
    assert seg.segments.tolist() == [[1, 2, 3, 4], [5, 6, 7, 7]]


# ---------------------------------------------------------------------------
# Boundary and initial conditions


def test_spc_node_set_and_id_option():
    d = read_deck_text("*BOUNDARY_SPC_NODE\n1,0,1,1,1\n2,0,0,0,1,1,1,1\n"
                       "*BOUNDARY_SPC_SET_ID\n        77fixed bottom\n3,0,1,1,1\n")
    a, b = d.of_type(BoundarySpcNode)
    assert a.dofs() == [True, True, True, False, False, False]
    assert b.dofs() == [False, False, True, True, True, True]
    s = d.of_type(BoundarySpcSet)[0]
    assert (s.nsid, s.bid, s.heading) == (3, 77, "fixed bottom")


def test_prescribed_motion_variants_and_defaults():
    d = read_deck_text("*BOUNDARY_PRESCRIBED_MOTION_NODE\n1,3,2,5\n"
                       "*BOUNDARY_PRESCRIBED_MOTION_SET\n2,1,0,5,-1.0\n"
                       "*BOUNDARY_PRESCRIBED_MOTION_RIGID\n3,7,0,5,2.0,0,10.0,1.0\n")
    n = d.of_type(PrescribedMotionNode)[0]
    assert (n.nid, n.dof, n.vad, n.lcid, n.sf, n.death, n.birth) == (1, 3, 2, 5, 1.0, 1e28, 0.0)
    assert d.of_type(PrescribedMotionSet)[0].sf == -1.0
    r = d.of_type(PrescribedMotionRigid)[0]
    assert (r.pid, r.dof, r.death, r.birth) == (3, 7, 10.0, 1.0)


def test_initial_velocities():
    g = one("*INITIAL_VELOCITY_GENERATION\n2,2,0.1,0,0,-11.1\n0,0,45,0,1,0\n",
            InitialVelocityGeneration)
    assert (g.id, g.styp, g.omega, g.vz, g.zc, g.ny) == (2, 2, 0.1, -11.1, 45.0, 1.0)
    n = one("*INITIAL_VELOCITY_NODE\n5,1.0,2.0,3.0\n", InitialVelocityNode)
    assert (n.nid, n.vx, n.vz, n.vxr) == (5, 1.0, 3.0, 0.0)
    v = one("*INITIAL_VELOCITY\n1,2\n1.,0.,0.\n0.,2.,0.\n", InitialVelocity)
    assert (v.nsid, v.nsidex, v.vx, v.vye) == (1, 2, 1.0, 2.0)
    v = one("*INITIAL_VELOCITY\n1\n1.,0.,0.\n", InitialVelocity)
    assert v.vye == 0.0


# ---------------------------------------------------------------------------
# Contacts, controls, databases


def test_contact_cards_id_mpp_and_card_a():
    c = one("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_MPP_ID\n"
            "         3impactor-tissue\n"
            "         0       200\n"
            "&                   1\n"
            "         1         2         3         2\n"
            "       0.2       0.1\n"
            "       1.0       1.0       0.5\n"
            "         1       0.2\n", Contact)
    assert (c.type, c.cid, c.heading) == ("AUTOMATIC_SURFACE_TO_SURFACE", 3, "impactor-tissue")
    assert len(c.mpp) == 2
    assert (c.ssid, c.msid, c.sstyp, c.mstyp, c.fs, c.fd, c.sst) == (1, 2, 3, 2, 0.2, 0.1, 0.5)
    assert (c.soft, c.sofscl) == (1, 0.2)
    c = one("*CONTACT_AUTOMATIC_SINGLE_SURFACE\n1,0,2\n", Contact)
    assert (c.cid, c.soft, c.sfs, c.dt) == (None, None, 1.0, 1e20)
    c = one("*CONTACT_AUTOMATIC_NODES_TO_SURFACE_TITLE\n5,nodes\n4,1,4,3\n", Contact)
    assert (c.cid, c.heading, c.sstyp) == (5, "nodes", 4)


def test_controls_and_databases_defaults():
    d = read_deck_text("*CONTROL_TERMINATION\n20.0\n*CONTROL_TIMESTEP\n\n"
                       "*CONTROL_HOURGLASS\n4\n*CONTROL_CONTACT\n0.2\n0,0,50\n"
                       "*CONTROL_BULK_VISCOSITY\n*DATABASE_GLSTAT\n0.1\n*DATABASE_NODOUT\n0.2\n"
                       "*DATABASE_BINARY_D3PLOT\n1.0\n*DATABASE_HISTORY_NODE\n1,2\n"
                       "*DATABASE_HISTORY_NODE_SET\n3\n")
    assert d.of_type(ControlTermination)[0].endtim == 20.0
    assert d.of_type(ControlTimestep)[0].tssfac == 0.9
    h = d.of_type(ControlHourglass)[0]
    assert (h.ihq, h.qh) == (4, 0.1)
    cc = d.of_type(ControlContact)[0]
    assert (cc.slsfac, cc.nsbcs) == (0.2, 50)
    assert d.of_type(ControlBulkViscosity)[0].q1 == 1.5
    assert [(x.name, x.dt) for x in d.of_type(DatabaseAscii)] == [("GLSTAT", 0.1),
                                                                   ("NODOUT", 0.2)]
    assert d.of_type(DatabaseBinaryD3plot)[0].dt == 1.0
    assert d.of_type(DatabaseHistoryNode)[0].ids.tolist() == [1, 2]
    assert d.of_type(DatabaseHistoryNodeSet)[0].ids.tolist() == [3]


# ---------------------------------------------------------------------------
# File structure


def test_keyword_names_are_case_insensitive():
    d = read_deck_text("*part\nx\n1,1,1\n*Mat_Elastic\n1,1e-6,1.,0.3\n")
    assert d.of_type(Part)[0].pid == 1 and d.of_type(MatElastic)[0].e == 1.0


def test_end_stops_reading_the_file(deck_file):
    path = deck_file("*KEYWORD\n*PART\np\n1,1,1\n*END\n*PART\nq\n2,1,1\n")
    assert [p.pid for p in read_deck(path).of_type(Part)] == [1]


def test_nested_includes_relative_to_the_including_file(deck_file):
    deck_file("*NODE\n1,0,0,0\n*INCLUDE\nsub/elements.k\n*END\n", "mesh/nodes.k")
    deck_file("*ELEMENT_SOLID\n1,1,1,1,1,1,1,1,1,1\n", "mesh/sub/elements.k")
    main = deck_file("*KEYWORD\n*INCLUDE\nmesh/nodes.k\n*PART\np\n1,1,1\n")
    deck = read_deck(main)
    inc = deck.items[0]
    assert isinstance(inc, Include) and inc.filename == "mesh/nodes.k"
    nested = inc.deck.includes()[0]
    assert nested.filename == "sub/elements.k"
    assert nested.deck.path.endswith("mesh/sub/elements.k")
    assert [type(i).__name__ for i in deck.iter_items()] == ["Nodes", "SolidElements", "Part"]
    assert deck.of_type(SolidElements)[0].source.file.endswith("mesh/sub/elements.k")


def test_include_path_folders(deck_file):
    deck_file("*NODE\n1,0,0,0\n", "lib/nodes.k")
    main = deck_file("*INCLUDE_PATH\nlib\n*INCLUDE\nnodes.k\n")
    assert read_deck(main).of_type(Nodes)[0].ids.tolist() == [1]


def test_unknown_keywords_warn_once_and_are_kept(deck_file):
    path = deck_file("*KEYWORD\n*SECTION_SPH\n1,1.2\n*SECTION_SPH\n2,1.2\n*EOS_GRUNEISEN\n"
                     "1\n*COMMENT\nanything\n")
    with pytest.warns(UnsupportedKeywordWarning) as record:
        deck = read_deck(path)
    messages = [str(w.message) for w in record]
    assert len(messages) == 2
    assert messages[0].startswith(f"{path}:2: *SECTION_SPH:")
    assert deck.unsupported == [("SECTION_SPH", str(path), 2), ("SECTION_SPH", str(path), 4),
                                ("EOS_GRUNEISEN", str(path), 6)]
    raw = deck.of_type(RawKeyword)
    assert raw[0].lines == ["1,1.2"] and not raw[-1].unsupported


def test_strict_makes_the_first_unknown_keyword_an_error(deck_file):
    path = deck_file("*KEYWORD\n*PART\np\n1,1,1\n*SECTION_SPH\n1\n")
    with pytest.raises(DeckError) as err:
        read_deck(path, strict=True)
    assert str(err.value) == f"{path}:5: *SECTION_SPH: keyword not supported (strict mode)"


def test_options_the_class_does_not_know_are_unknown_keywords():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = read_deck_text("*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_TIEBREAK\n1,2,3,3\n"
                           "*ELEMENT_SHELL_OFFSET\n1,1,1,2,3,4\n*DEFINE_CURVE_SMOOTH\n1\n")
    assert [u[0] for u in d.unsupported] == ["CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_TIEBREAK",
                                             "ELEMENT_SHELL_OFFSET", "DEFINE_CURVE_SMOOTH"]


def test_free_format_rows_of_equal_length():
    d = read_deck_text("*NODE\n1,1.0,2.0,3.0\n2,4.0,5.0,6.0\n*ELEMENT_SOLID\n"
                       "1,1,1,2,3,4,5,6,7,8\n2,1,2,3,4,5,6,7,8,9\n")
    assert d.of_type(Nodes)[0].xyz.tolist() == [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]
    assert d.of_type(SolidElements)[0].conn[1].tolist() == [2, 3, 4, 5, 6, 7, 8, 9]
