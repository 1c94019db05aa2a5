"""Rigid-body constraint keywords: cards, defaults, options, read -> write -> read."""

from __future__ import annotations

from hollowbody.io.keyword import (
    ConstrainedExtraNodesNode,
    ConstrainedExtraNodesSet,
    ConstrainedNodalRigidBody,
    ConstrainedNodalRigidBodyInertia,
    ConstrainedNodalRigidBodySpc,
    ConstrainedNodalRigidBodySpcInertia,
    ConstrainedRigidBodies,
    ConstrainedRigidBodiesSet,
    deck_lines,
    read_deck_text,
)

TEXT = """\
*KEYWORD
*CONSTRAINED_RIGID_BODIES
$     PIDM      PIDS     IFLAG
         1         2
         2         3         1
*CONSTRAINED_RIGID_BODIES_SET
         1         7
*CONSTRAINED_EXTRA_NODES_NODE
         1        31
         2        32         1
*CONSTRAINED_EXTRA_NODES_SET
1,40
*CONSTRAINED_NODAL_RIGID_BODY
100,0,100
101,0,0,55,2
*CONSTRAINED_NODAL_RIGID_BODY_SPC_TITLE
held body
102,,102
1,4,7
*CONSTRAINED_NODAL_RIGID_BODY_INERTIA
103,0,103
1.0,2.0,3.0,0.5,0,0
10.,0.1,0.,20.,0.,30.
1.0,0.,0.,0.,0.,0.01
*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC
104,0,104
1,7,0
0.,0.,0.,0.25,0,44
1.,0.,0.,1.,0.,1.
*CONSTRAINED_NODAL_RIGID_BODY_INERTIA
105,0,105
0.,0.,0.,0.25,1
1.,0.,0.,2.,0.,3.
0.,0.,0.,0.,0.,0.
0.,1.,0.,-1.,0.,0.
*END
"""


def _items(deck, cls):
    return [it for it in deck.items if type(it) is cls]


def test_cards_and_defaults():
    deck = read_deck_text(TEXT)
    m = _items(deck, ConstrainedRigidBodies)
    assert [(it.pidm, it.pids, it.iflag) for it in m] == [(1, 2, 0), (2, 3, 1)]
    assert _items(deck, ConstrainedRigidBodiesSet)[0].psid == 7
    e = _items(deck, ConstrainedExtraNodesNode)
    assert [(it.pid, it.nid, it.iflag) for it in e] == [(1, 31, 0), (2, 32, 1)]
    assert _items(deck, ConstrainedExtraNodesSet)[0].nsid == 40
    plain = _items(deck, ConstrainedNodalRigidBody)
    assert [(it.pid, it.nsid, it.pnode, it.iprt) for it in plain] == [(100, 100, 0, 0),
                                                                     (101, 0, 55, 2)]
    spc = _items(deck, ConstrainedNodalRigidBodySpc)[0]
    assert (spc.title, spc.pid, spc.cmo, spc.con1, spc.con2) == ("held body", 102, 1, 4, 7)
    ine = _items(deck, ConstrainedNodalRigidBodyInertia)[0]
    assert (ine.xc, ine.yc, ine.zc, ine.tm) == (1.0, 2.0, 3.0, 0.5)
    assert (ine.ixx, ine.ixy, ine.iyy, ine.izz, ine.vtx, ine.vrz) == (10.0, 0.1, 20.0, 30.0,
                                                                      1.0, 0.01)
    both = _items(deck, ConstrainedNodalRigidBodySpcInertia)[0]  # _INERTIA_SPC alias
    assert (both.cmo, both.con1, both.tm, both.nodeid, both.vtx) == (1, 7, 0.25, 44, 0.0)
    local = _items(deck, ConstrainedNodalRigidBodyInertia)[1]  # IRCS = 1: the axes card
    assert (local.ircs, local.yl, local.xlip, local.cid2) == (1, 1.0, -1.0, 0)
    assert ine.ircs == 0 and ine.yl == 0.0  # no axes card without IRCS = 1


def test_read_write_read_is_identity():
    deck = read_deck_text(TEXT)
    again = read_deck_text("\n".join(deck_lines(deck)) + "\n")
    kinds = (ConstrainedRigidBodies, ConstrainedRigidBodiesSet, ConstrainedExtraNodesNode,
             ConstrainedExtraNodesSet, ConstrainedNodalRigidBody, ConstrainedNodalRigidBodySpc,
             ConstrainedNodalRigidBodyInertia, ConstrainedNodalRigidBodySpcInertia)
    for cls in kinds:
        assert _items(deck, cls) == _items(again, cls), cls.__name__
        assert _items(deck, cls), cls.__name__
    assert not deck.unsupported
