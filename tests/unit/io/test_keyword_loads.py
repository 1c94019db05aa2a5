"""Load, rigid-wall and *MAT_NULL keywords: fields, defaults, round trip."""

from __future__ import annotations

import numpy as np

from hollowbody.io.keyword import (
    DatabaseAscii,
    LoadBody,
    LoadBodyParts,
    LoadNodePoint,
    LoadNodeSet,
    LoadRigidBody,
    MatNull,
    RigidwallPlanar,
    deck_lines,
    read_deck_text,
)

TEXT = """\
*KEYWORD
*LOAD_BODY_Y
7,0.00981,8,1.0,2.0,3.0
*LOAD_BODY_Z
7
*LOAD_BODY_PARTS
4
*LOAD_NODE_POINT
$ nid dof lcid sf
11,3,7,-2.5
12,5,7
*LOAD_NODE_SET
2,1,7,0.5
*LOAD_RIGID_BODY
3,7,7,1.5
*RIGIDWALL_PLANAR_ID
9,floor
2,5,0,0.1,1.0,
0.0,0.0,-1.0,0.0,0.0,1.0,0.2
*RIGIDWALL_PLANAR
0
1.0,0.0,0.0,2.0,0.0,0.0
*MAT_NULL_TITLE
skin
5,1.0e-6,0.0,0.0,0.0,0.0,0.05,0.3
*DATABASE_RWFORC
0.1
*END
"""


def _items(deck, cls):  # noqa: ANN001, ANN202
    return [it for it in deck.iter_items() if isinstance(it, cls)]


def test_fields_and_defaults():
    deck = read_deck_text(TEXT)
    y, z = _items(deck, LoadBody)
    assert (y.axis, y.lcid, y.sf, y.lciddr, y.xc, y.yc, y.zc) == ("Y", 7, 0.00981, 8, 1.0,
                                                                 2.0, 3.0)
    assert (z.axis, z.lcid, z.sf) == ("Z", 7, 1.0)  # SF default 1
    assert _items(deck, LoadBodyParts)[0].psid == 4
    p1, p2 = _items(deck, LoadNodePoint)
    assert (p1.nid, p1.dof, p1.lcid, p1.sf) == (11, 3, 7, -2.5)
    assert (p2.nid, p2.dof, p2.sf) == (12, 5, 1.0)
    s = _items(deck, LoadNodeSet)[0]
    assert (s.nsid, s.dof, s.sf) == (2, 1, 0.5)
    r = _items(deck, LoadRigidBody)[0]
    assert (r.pid, r.dof, r.sf) == (3, 7, 1.5)
    w1, w2 = _items(deck, RigidwallPlanar)
    assert (w1.rwid, w1.heading, w1.nsid, w1.nsidex, w1.offset, w1.birth) == \
        (9, "floor", 2, 5, 0.1, 1.0)
    assert (w1.death, w1.rwksf, w1.zt, w1.zh, w1.fric) == (1.0e20, 1.0, -1.0, 1.0, 0.2)
    assert w2.rwid is None and w2.xh == 2.0 and w2.variants == ()
    m = _items(deck, MatNull)[0]
    assert (m.mid, m.ro, m.ym, m.pr, m.title) == (5, 1.0e-6, 0.05, 0.3, "skin")
    assert any(d.name == "RWFORC" and d.dt == 0.1 for d in _items(deck, DatabaseAscii))


def test_round_trip():
    deck = read_deck_text(TEXT)
    again = read_deck_text("\n".join(deck_lines(deck)) + "\n")
    for cls in (LoadBody, LoadBodyParts, LoadNodePoint, LoadNodeSet, LoadRigidBody,
                RigidwallPlanar, MatNull):
        a, b = _items(deck, cls), _items(again, cls)
        assert len(a) == len(b) > 0
        for x, y in zip(a, b):
            fields = [f for f in vars(x) if f not in ("source", "extra_cards")]
            assert all(np.all(getattr(x, f) == getattr(y, f)) for f in fields), cls


def test_unsupported_rigidwall_options_are_read_and_named():
    text = "*KEYWORD\n*RIGIDWALL_PLANAR_MOVING_FORCES\n0\n0,0,0,0,0,1\n1.0,0.0\n*END\n"
    w = _items(read_deck_text(text), RigidwallPlanar)[0]
    assert w.variants == ("MOVING", "FORCES")
