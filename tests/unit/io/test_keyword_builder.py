"""Deck -> Model: indices, groups, defaults, sets, conditions, contacts, controls."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    Contact,
    Deck,
    InitialVelocityGeneration,
    MatElastic,
    MatRigid,
    Part,
    SectionShell,
    SectionSolid,
    read_deck_text,
)
from hollowbody.model.model import MATERIAL_PARAMS

# Two unit cubes (parts 1 and 2, ids not contiguous), one shell (part 3).
MESH = """\
*NODE
      11             0.0             0.0             0.0
      12             1.0             0.0             0.0
      13             1.0             1.0             0.0
      14             0.0             1.0             0.0
      15             0.0             0.0             1.0
      16             1.0             0.0             1.0
      17             1.0             1.0             1.0
      18             0.0             1.0             1.0
      26             2.0             0.0             1.0
      27             2.0             1.0             1.0
      22             2.0             0.0             0.0
      23             2.0             1.0             0.0
*ELEMENT_SOLID
     100       2      12      22      23      13      16      26      27      17
     101       1      11      12      13      14      15      16      17      18
     102       2      12      22      23      13      16      26      27      17
*ELEMENT_SHELL
     200       3      15      16      17      18
     201       3      16      26      27
*PART
left
1,1,1
*PART
right
2,1,2
*PART
skin
3,2,3
*SECTION_SOLID
1
*SECTION_SHELL
2,0,,
2.0
*MAT_ELASTIC
1,1.0e-6,0.1,0.3
*MAT_RIGID
2,7.85e-6,210.,0.3
*MAT_PLASTIC_KINEMATIC
3,1.0e-6,0.1,0.3,0.004
*CONTROL_TERMINATION
1.0
"""


def model_of(extra: str = "", mesh: str = MESH):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return build_model(read_deck_text(mesh + extra))


def test_nodes_and_element_groups():
    m = model_of()
    assert m.node_ids.tolist() == [11, 12, 13, 14, 15, 16, 17, 18, 26, 27, 22, 23]
    assert m.node_x0.shape == (12, 3) and m.node_x0.dtype == np.float64
    assert [g.pid for g in m.solid_groups] == [1, 2]
    g2 = m.solid_groups[1]
    assert g2.elem_ids.tolist() == [100, 102] and g2.conn.dtype == np.int32
    assert m.node_ids[g2.conn[0]].tolist() == [12, 22, 23, 13, 16, 26, 27, 17]
    sh = m.shell_groups[0]
    assert m.node_ids[sh.conn].tolist() == [[15, 16, 17, 18], [16, 26, 27, 27]]
    assert sh.thickness.tolist() == [[2.0] * 4] * 2
    assert m.node_v0.shape == (12, 3) and not m.node_v0.any()


def test_materials_sections_hourglass_defaults():
    m = model_of("*MAT_SIMPLIFIED_RUBBER\n4,1e-6,0.001\n,,,10\n*DEFINE_CURVE\n10\n0,0\n1,1\n"
                 "*HOURGLASS\n5,0,0.0\n*HOURGLASS\n6,4,0.05,,1.2,0.1\n"
                 "*CONTROL_HOURGLASS\n2,0.07\n*CONTROL_BULK_VISCOSITY\n1.4,0.05\n")
    for mat in m.materials.values():
        assert tuple(mat.params) == MATERIAL_PARAMS[mat.kind]
    assert m.materials[2].kind == "rigid" and m.materials[2].keyword == "MAT_RIGID"
    r = m.materials[4].params
    assert (r["MU"], r["SGL"], r["SW"], r["ST"], r["LCID"], r["KM"]) == \
        (0.1, 1.0, 1.0, 1.0, 10.0, 0.001)
    assert m.materials[3].params["SIGY"] == 0.004
    sh = m.sections[2]
    assert (sh.kind, sh.elform, sh.params["NIP"], sh.params["T4"], sh.params["SHRF"]) == \
        ("shell", 2, 2.0, 2.0, 1.0)
    assert (m.sections[1].kind, m.sections[1].elform) == ("solid", 1)
    h5, h6, hc = m.hourglass[5], m.hourglass[6], m.controls.hourglass
    assert (hc.ihq, hc.qm, hc.q1, hc.q2) == (2, 0.07, 1.4, 0.05)
    assert (h5.ihq, h5.qm, h5.q1, h5.q2) == (2, 0.1, 1.4, 0.05)
    assert (h6.ihq, h6.qm, h6.q1, h6.q2) == (4, 0.05, 1.2, 0.1)


def test_element_thickness_overrides_section():
    row = "     200       3      15      16      17      18\n"
    mesh = MESH.replace("*ELEMENT_SHELL\n" + row,
                        "*ELEMENT_SHELL_THICKNESS\n" + row +
                        "             1.0             1.0             0.0             0.0\n"
                        "*ELEMENT_SHELL\n")
    sh = model_of(mesh=mesh).shell_groups[0]
    assert sh.elem_ids.tolist() == [200, 201]
    assert sh.thickness.tolist() == [[1.0, 1.0, 2.0, 2.0], [2.0] * 4]


def test_curves_scale_and_offsets():
    m = model_of("*DEFINE_CURVE_TITLE\nc\n7,0,2.0,3.0,1.0,-1.0\n0,1\n1,2\n")
    c = m.curves[7]
    assert c.x.tolist() == [2.0, 4.0] and c.y.tolist() == [0.0, 3.0] and c.title == "c"
    assert c(3.0) == 1.5


def test_sets_resolve_to_indices():
    m = model_of("*SET_NODE_LIST\n1\n11,12,26\n*SET_NODE_LIST_GENERATE\n2\n20,30\n"
                 "*SET_PART_LIST\n3\n2,1\n*SET_PART_LIST_GENERATE\n4\n2,9\n"
                 "*SET_SEGMENT\n5\n11,12,13,14\n15,16,17\n")
    assert m.node_ids[m.node_sets[1]].tolist() == [11, 12, 26]
    assert sorted(m.node_ids[m.node_sets[2]].tolist()) == [22, 23, 26, 27]
    assert m.part_sets == {3: [2, 1], 4: [2, 3]}
    seg = m.segment_sets[5]
    assert seg.dtype == np.int32 and m.node_ids[seg].tolist() == [[11, 12, 13, 14],
                                                                  [15, 16, 17, 17]]


def test_spcs_from_boundary_cards_and_node_constraints():
    mesh = MESH.replace("      22             2.0             0.0             0.0",
                        "      22             2.0             0.0             0.0       3       7")
    m = model_of("*SET_NODE_LIST\n1\n11,12\n*BOUNDARY_SPC_SET\n1,0,1,1,1\n"
                 "*BOUNDARY_SPC_NODE\n13,0,1\n14,0,0,0,0,1\n", mesh=mesh)
    by_node = {}
    for spc in m.spcs:
        for node, dofs in zip(spc.nodes.tolist(), spc.dofs.tolist()):
            by_node[int(m.node_ids[node])] = dofs
    assert by_node[22] == [False, False, True, True, True, True]
    assert by_node[11] == by_node[12] == [True, True, True, False, False, False]
    assert by_node[13] == [True, False, False, False, False, False]
    assert by_node[14] == [False, False, False, True, False, False]
    with pytest.raises(DeckError, match="local coordinate systems"):
        model_of("*BOUNDARY_SPC_NODE\n13,5,1\n")


def test_prescribed_motion():
    m = model_of("*DEFINE_CURVE\n9\n0,1\n10,1\n*BOUNDARY_PRESCRIBED_MOTION_RIGID\n2,3,0,9,-2.0\n"
                 "*SET_NODE_LIST\n1\n11\n*BOUNDARY_PRESCRIBED_MOTION_SET\n1,1,2,9,,,5.0\n")
    rigid, nodes = m.prescribed
    assert (rigid.target, rigid.pid, rigid.dof, rigid.sf, rigid.death) == ("rigid", 2, 3, -2.0,
                                                                           1e28)
    assert (nodes.target, nodes.vad, nodes.death, nodes.nodes.tolist()) == ("nodes", 2, 5.0, [0])
    with pytest.raises(DeckError, match="part 1 is not rigid"):
        model_of("*DEFINE_CURVE\n9\n0,1\n10,1\n*BOUNDARY_PRESCRIBED_MOTION_RIGID\n1,3,0,9\n")
    with pytest.raises(DeckError, match="DOF=4 is not supported"):
        model_of("*DEFINE_CURVE\n9\n0,1\n10,1\n*BOUNDARY_PRESCRIBED_MOTION_NODE\n11,4,0,9\n")


def test_initial_velocity_generation_by_part_set_and_rotation():
    m = model_of("*INITIAL_VELOCITY_GENERATION\n2,2,0,0,0,-11.0\n0,0,0,0,0,0\n")
    moving = np.flatnonzero(m.node_v0[:, 2])
    assert sorted(m.node_ids[moving].tolist()) == [12, 13, 16, 17, 22, 23, 26, 27]  # rigid part
    assert np.all(m.node_v0[moving] == [0.0, 0.0, -11.0])
    m = model_of("*SET_PART_LIST\n5\n1\n"
                 "*INITIAL_VELOCITY_GENERATION\n5,1,0.5,1.0,0,0\n0.0,0.0,0.0,0.0,0.0,2.0\n")
    k = int(np.flatnonzero(m.node_ids == 13)[0])  # x = (1, 1, 0)
    np.testing.assert_allclose(m.node_v0[k], [1.0 - 0.5, 0.5, 0.0])  # v + w x r
    np.testing.assert_allclose(m.node_w0[k], [0.0, 0.0, 0.5])
    assert not m.node_v0[m.node_ids == 22].any()
    m = model_of("*INITIAL_VELOCITY_GENERATION\n0,2,0,0,3.0\n0,0,0,0,0,0\n")
    assert np.all(m.node_v0[:, 1] == 3.0)


def test_initial_velocity_node_set_exempt_and_order():
    m = model_of("*SET_NODE_LIST\n1\n11,12\n*SET_NODE_LIST\n2\n12\n"
                 "*INITIAL_VELOCITY\n1,2\n5.0\n7.0\n*INITIAL_VELOCITY_NODE\n11,0,1.0\n"
                 "*SET_NODE_LIST\n3\n14\n*INITIAL_VELOCITY_GENERATION\n3,3,0,0,0,9.0\n0,0,0\n")
    v = dict(zip(m.node_ids.tolist(), m.node_v0.tolist()))
    assert v[11] == [0.0, 1.0, 0.0] and v[12] == [7.0, 0.0, 0.0] and v[14] == [0.0, 0.0, 9.0]
    assert v[13] == [0.0, 0.0, 0.0]


def test_part_inertia():
    m = model_of("*PART_INERTIA\nimpactor\n9,1,2\n1.0,2.0,3.0,5.0,0,17\n"
                 "10.,1.,2.,20.,3.,30.\n0.,0.,-11.1,0.,0.,0.5\n")
    pi = m.part_inertia[9]
    assert pi.xc.tolist() == [1.0, 1.0, 1.0]  # from NODEID 17
    assert pi.tm == 5.0 and pi.v0.tolist() == [0, 0, -11.1] and pi.w0.tolist() == [0, 0, 0.5]
    assert pi.inertia.tolist() == [[10, 1, 2], [1, 20, 3], [2, 3, 30]]
    assert m.parts[9].mid == 2


def test_contacts_surfaces_and_defaults():
    m = model_of("*SET_PART_LIST\n1\n1,2\n*SET_NODE_LIST\n2\n11,12\n"
                 "*SET_SEGMENT\n3\n11,12,13,14\n"
                 "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID\n7,impact\n2,1,3,2\n0.2,0.1,0.5,,20\n"
                 "*CONTACT_AUTOMATIC_NODES_TO_SURFACE\n2,3,4,0\n"
                 "*CONTACT_AUTOMATIC_SINGLE_SURFACE\n0\n\n0,0\n2\n"
                 "*CONTACT_AUTOMATIC_SINGLE_SURFACE\n0,0,5\n")
    a, b, c, d = m.contacts
    assert (a.cid, a.kind, a.title, a.fs, a.fd, a.dc, a.vdc) == \
        (7, "surface_to_surface", "impact", 0.2, 0.1, 0.5, 20.0)
    assert (a.slave.kind, a.slave.pids, a.master.kind, a.master.pids) == \
        ("parts", [2], "parts", [1, 2])
    assert (b.cid, b.kind, b.slave.kind, b.master.kind) == (2, "nodes_to_surface", "nodes",
                                                            "segments")
    assert b.master.segments.tolist() == [[0, 1, 2, 3]]
    assert (c.kind, c.slave.kind, c.master, c.soft, c.sofscl, c.sfs, c.sfm) == \
        ("single_surface", "all", None, 1, 0.1, 1.0, 1.0)
    assert d.slave.kind == "all"


def test_controls_and_outputs():
    m = model_of("*CONTROL_TIMESTEP\n0.0,0.0,0,0.0,0.0,0,1\n*CONTROL_CONTACT\n0.0\n0,0,0\n"
                 "*DATABASE_GLSTAT\n0.1\n*DATABASE_MATSUM\n0.2\n*DATABASE_ELOUT\n0.3\n"
                 "*DATABASE_BINARY_D3PLOT\n0.5\n*DATABASE_HISTORY_NODE\n13,11\n"
                 "*SET_NODE_LIST\n1\n26,27\n*DATABASE_HISTORY_NODE_SET\n1\n")
    c = m.controls
    assert (c.end_time, c.tssfac, c.erode, c.slsfac, c.contact_sort_interval) == \
        (1.0, 0.9, 1, 0.1, 100)
    assert m.output.intervals == {"glstat": 0.1, "matsum": 0.2}
    assert m.output.d3plot_dt == 0.5
    assert m.node_ids[m.output.history_nodes].tolist() == [13, 11, 26, 27]


def test_unsupported_keywords_are_listed():
    m = model_of("*SECTION_SPH\n9\n*CONTROL_ENERGY\n2\n")
    assert [u[0] for u in m.unsupported] == ["SECTION_SPH", "CONTROL_ENERGY"]
    assert m.unsupported[0][1:] == ("<text>", MESH.count("\n") + 1)


def test_building_from_an_api_deck():
    deck = Deck()
    deck.title = "api"
    deck.add_nodes([1, 2, 3, 4], [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 0, 1]])
    deck.add_solids([1], 1, [[1, 2, 3, 4]])
    deck.add_shells([2], 2, [[1, 2, 3]], thickness=0.5)
    deck.add_masses([3], [4], 1.5)
    deck.add(Part(pid=1, secid=1, mid=1))
    deck.add(Part(pid=2, secid=2, mid=2))
    deck.add(SectionSolid(secid=1))
    deck.add(SectionShell(secid=2, t1=1.0))
    deck.add(MatElastic(mid=1, ro=1e-6, e=0.1, pr=0.3))
    deck.add(MatRigid(mid=2, ro=1e-6, e=0.1, pr=0.3))
    deck.add(InitialVelocityGeneration(id=2, styp=2, vx=1.0))
    deck.add(Contact(type="AUTOMATIC_SINGLE_SURFACE"))
    m = build_model(deck)
    assert m.title == "api" and m.solid_groups[0].conn.tolist() == [[0, 1, 2, 3, 3, 3, 3, 3]]
    assert m.shell_groups[0].thickness.tolist() == [[0.5] * 4]
    assert m.node_extra_mass.tolist() == [0, 0, 0, 1.5]
    assert m.node_v0[:, 0].tolist() == [1.0, 1.0, 1.0, 0.0]
    assert m.contacts[0].slave.kind == "all"
