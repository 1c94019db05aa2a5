"""Discrete-element keywords: cards, LS-DYNA defaults, read -> write -> read."""

from __future__ import annotations

import warnings

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    DefineSdOrientation,
    ElementDiscrete,
    MatDamperViscous,
    MatSpringElastic,
    MatSpringGeneralNonlinear,
    MatSpringNonlinearElastic,
    SectionDiscrete,
    read_deck,
    write_deck,
)

DECK = """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2            10.0             0.0             0.0
*ELEMENT_MASS
       1       2             0.5
*SECTION_DISCRETE_TITLE
springs
         1         0       0.0       0.0       0.0      25.0
       0.0       0.0
*SECTION_DISCRETE
         2         1

*PART
s01
         1         1         1
*PART
s02
         2         1         2
*PART
s04
         3         1         3
*PART
s06
         4         1         4
*MAT_SPRING_ELASTIC_TITLE
linear
         1      2.5
*MAT_S02
         2      0.01
*MAT_SPRING_NONLINEAR_ELASTIC
         3         7
*MAT_SPRING_GENERAL_NONLINEAR
         4         7         8       1.0       2.0      -3.0
*DEFINE_CURVE
         7
                -1.0                -2.0
                 0.0                 0.0
                 1.0                 2.0
*DEFINE_CURVE
         8
                -1.0               -10.0
                 1.0                10.0
*DEFINE_SD_ORIENTATION
         3         0       0.0       0.0       2.0
*ELEMENT_DISCRETE
$    EID     PID      N1      N2     VID               S      PF          OFFSET
       1       1       1       2
       2       2       1       2       0             2.0       1            0.25
       3       3       1       2       3
       4       4       2       0       3             0.0
*END
"""


def _read(tmp_path, text):
    p = tmp_path / "d.k"
    p.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # every keyword is known
        return read_deck(p)


def test_cards_and_defaults(tmp_path):
    deck = _read(tmp_path, DECK)
    sec = deck.of_type(SectionDiscrete)
    assert [(s.secid, s.dro, s.fd, s.title) for s in sec] == [(1, 0, 25.0, "springs"),
                                                               (2, 1, 0.0, "")]
    el = deck.of_type(ElementDiscrete)
    assert [(e.eid, e.pid, e.n1, e.n2, e.vid, e.s, e.pf, e.offset) for e in el] == [
        (1, 1, 1, 2, 0, 1.0, 0, 0.0), (2, 2, 1, 2, 0, 2.0, 1, 0.25),
        (3, 3, 1, 2, 3, 1.0, 0, 0.0), (4, 4, 2, 0, 3, 0.0, 0, 0.0)]
    assert deck.of_type(MatSpringElastic)[0].k == 2.5
    assert deck.of_type(MatSpringElastic)[0].title == "linear"
    assert deck.of_type(MatDamperViscous)[0].dc == 0.01
    assert deck.of_type(MatSpringNonlinearElastic)[0].lcd == 7
    g = deck.of_type(MatSpringGeneralNonlinear)[0]
    assert (g.lcdl, g.lcdu, g.beta, g.tyi, g.cyi) == (7, 8, 1.0, 2.0, -3.0)
    o = deck.of_type(DefineSdOrientation)[0]
    assert (o.vid, o.iop, o.zt) == (3, 0, 2.0)


def test_round_trip_and_model(tmp_path):
    first = _read(tmp_path, DECK)
    out = tmp_path / "out.k"
    write_deck(first, out)
    second = read_deck(out)
    assert first == second
    a, b = build_model(first), build_model(second)
    assert len(a.discrete_groups) == 4
    for ga, gb in zip(a.discrete_groups, b.discrete_groups):
        assert ga.kind == gb.kind and ga.pid == gb.pid
        for name in ("elem_ids", "n1", "n2", "scale", "offset", "print_flag", "fixed_axis",
                     "axis"):
            assert (getattr(ga, name) == getattr(gb, name)).all(), name
    g = {g.pid: g for g in a.discrete_groups}
    assert g[2].scale[0] == 2.0 and g[2].offset[0] == 0.25 and g[2].print_flag[0] == 1
    assert g[4].scale[0] == 1.0  # S = 0 means 1
    assert g[4].n2[0] == -1 and g[4].fixed_axis[0] and list(g[4].axis[0]) == [0, 0, 1.0]
    assert g[1].failure_deflection == 25.0
    assert a.sections[1].kind == "discrete"
