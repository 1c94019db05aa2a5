"""*SECTION_BEAM, *ELEMENT_BEAM, *INTEGRATION_BEAM: read, write, read back, build;
bad input is a DeckError naming file, line and keyword."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.errors import DeckError
from hollowbody.io.keyword import ElementBeam, IntegrationBeam, SectionBeam, read_deck, write_deck
from hollowbody.model.summary import summarize
from hollowbody.testing.beams import cantilever_deck

DECK = """\
*KEYWORD
*NODE
       1             0.0             0.0             0.0
       2            10.0             0.0             0.0
       3            20.0             0.0             0.0
       4             0.0             5.0             0.0
*PART
resultant
         1         1         1
*PART
integrated
         2         2         1
*SECTION_BEAM_TITLE
resultant section
         1         2
      25.0     52.08     52.08     88.02     20.83
*SECTION_BEAM
         2         1     0.833        -7         0       0.0    1.0E-6
       5.0       5.0       4.0       4.0
*INTEGRATION_BEAM
         7         2       1.0         0
      -0.5       0.0       0.5         0
       0.5       0.0       0.5         0
*MAT_ELASTIC
         1   7.85E-6     200.0       0.3
*ELEMENT_BEAM
       1       1       1       2       4
       2       2       2       3
*END
"""


def _write(tmp_path: Path, text: str, name: str = "beam.k") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def test_cards_and_defaults(tmp_path):
    deck = read_deck(_write(tmp_path, DECK))
    s1, s2 = deck.of_type(SectionBeam)
    assert (s1.secid, s1.elform, s1.a, s1.iss, s1.itt, s1.j, s1.sa) == \
        (1, 2, 25.0, 52.08, 52.08, 88.02, 20.83)
    assert s1.title == "resultant section" and s1.shrf == 1.0 and s1.qr == 2
    assert (s2.elform, s2.shrf, s2.qr, s2.nsm, s2.ts1, s2.tt2) == (1, 0.833, -7, 1e-6, 5.0, 4.0)
    (el,) = deck.of_type(ElementBeam)
    assert el.ids.tolist() == [1, 2] and el.pids.tolist() == [1, 2]
    assert el.conn.tolist() == [[1, 2, 4], [2, 3, 0]]
    assert el.local.tolist() == [2, 2] and not el.releases.any()
    assert el.row_lines.tolist() == [27, 28]
    (rule,) = deck.of_type(IntegrationBeam)
    assert rule.irid == 7 and rule.points == [[-0.5, 0.0, 0.5, 0.0], [0.5, 0.0, 0.5, 0.0]]


def test_round_trip_and_model(tmp_path):
    first = read_deck(_write(tmp_path, DECK))
    out = tmp_path / "out.k"
    write_deck(first, out)
    second = read_deck(out)
    assert first == second
    m1, m2 = build_model(first), build_model(second)
    assert [g.pid for g in m1.beam_groups] == [1, 2]
    for g1, g2 in zip(m1.beam_groups, m2.beam_groups):
        assert np.array_equal(g1.conn, g2.conn) and np.array_equal(g1.elem_ids, g2.elem_ids)
    assert m1.beam_groups[0].conn.tolist() == [[0, 1, 3]]
    assert m1.beam_groups[1].conn.tolist() == [[1, 2, -1]]
    assert m1.beam_groups[1].rule.shape == (2, 3)
    assert m1.sections[2].kind == "beam" and m1.sections[2].params["RA"] == 1.0
    assert dataclasses.asdict(m1.sections[1])["params"] == m2.sections[1].params


def test_check_counts_beams_and_mass(tmp_path):
    model = build_model(read_deck(_write(tmp_path, DECK)))
    s = summarize(model)
    assert s["elements"]["beams"] == 2
    by_pid = {p["pid"]: p["mass_kg"] for p in s["parts"]}
    # rho A L (+ NSM L for part 2: 1e-6 kg/mm over 10 mm)
    assert by_pid[1] == pytest.approx(7.85e-6 * 25.0 * 10.0)
    assert by_pid[2] == pytest.approx(7.85e-6 * 20.0 * 10.0 + 1e-5)


def test_cantilever_deck_round_trips(tmp_path):
    for kw in ({"elform": 2}, {"elform": 1, "tube": (10.0, 8.0), "qr": 3},
               {"elform": 1, "gauss_rule": (2, 4), "sigy": 0.2}):
        first = read_deck(_write(tmp_path, cantilever_deck(n=3, **kw)))
        write_deck(first, tmp_path / "o.k")
        assert read_deck(tmp_path / "o.k") == first


BAD = [
    # (what to replace, by what, expected message part, keyword)
    ("       2       2       2       3\n", "       2       2       2      99\n",
     "node 99 which is not defined", "ELEMENT_BEAM"),
    ("       1       1       1       2       4\n", "       1       1       1       2       3\n",
     "collinear", "ELEMENT_BEAM"),
    ("       1       1       1       2       4\n",
     "       1       1       1       2       4       1\n", "release codes", "ELEMENT_BEAM"),
    ("         1         2\n      25.0", "         1         3\n      25.0",
     "ELFORM 3 is not supported", "SECTION_BEAM"),
    ("      25.0     52.08", "       0.0     52.08", "needs A, ISS, ITT and J", "SECTION_BEAM"),
    ("        -7         0", "        -8         0", "IRID 8", "SECTION_BEAM"),
    ("         7         2       1.0         0\n      -0.5       0.0       0.5         0\n"
     "       0.5       0.0       0.5         0\n",
     "         7         0       0.0         3\n       1.0       1.0       0.1       0.1\n",
     "standard sections", "INTEGRATION_BEAM"),
    ("       5.0       5.0       4.0       4.0", "       0.0       5.0       4.0       4.0",
     "TS1, TT1 > 0", "SECTION_BEAM"),
]


@pytest.mark.parametrize("old, new, message, keyword", BAD)
def test_bad_input_names_file_line_keyword(tmp_path, old, new, message, keyword):
    assert old in DECK
    path = _write(tmp_path, DECK.replace(old, new, 1))
    with pytest.raises(DeckError) as err:
        build_model(read_deck(path))
    e = err.value
    assert message in str(e)
    assert e.file and Path(e.file).name == "beam.k" and e.line > 0
    assert e.keyword and keyword in e.keyword
    line = path.read_text().splitlines()[e.line - 1]
    assert line.strip()  # the line named is a card of the deck
    if keyword == "ELEMENT_BEAM":  # the element's own row
        assert line.split()[0] == new.split()[0]


def test_missing_section_card(tmp_path):
    """The resultant card missing (the next keyword follows), or no section at all."""
    text = DECK.replace("      25.0     52.08     52.08     88.02     20.83\n", "")
    with pytest.raises(DeckError) as err:
        build_model(read_deck(_write(tmp_path, text)))
    assert "(A, ISS, ITT, J, SA, IST) is missing" in str(err.value)
    assert err.value.line == 15 and "SECTION_BEAM" in err.value.keyword
    text = DECK.replace("*SECTION_BEAM_TITLE\nresultant section\n         1         2\n"
                        "      25.0     52.08     52.08     88.02     20.83\n", "")
    with pytest.raises(DeckError) as err:
        build_model(read_deck(_write(tmp_path, text)))
    assert "section 1 which is not defined" in str(err.value) and err.value.line == 9


def test_part_without_beam_section(tmp_path):
    text = DECK.replace("*PART\nresultant\n         1         1         1",
                        "*PART\nresultant\n         1         9         1") + ""
    text = text.replace("*MAT_ELASTIC", "*SECTION_SHELL\n         9\n       1.0\n*MAT_ELASTIC")
    with pytest.raises(DeckError) as err:
        build_model(read_deck(_write(tmp_path, text)))
    assert "not a *SECTION_BEAM" in str(err.value)


def test_cli_exit_code_two_without_traceback(tmp_path, capsys):
    from hollowbody.cli.main import main as cli_main

    path = _write(tmp_path, DECK.replace("       2       2       2       3\n",
                                         "       2       2       2      99\n"))
    assert cli_main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    assert "beam.k:28" in err and "ELEMENT_BEAM" in err and "Traceback" not in err


def test_runtime_masses_match_the_lumped_masses(tmp_path):
    """The run's nodal masses (model.mass) and the beam runtimes' own masses agree
    (NSM included, a user rule included), and the rotational inertia is
    m_node max(L^2 / 4, (ISS + ITT) / A) per node."""
    from hollowbody.elements.beam_group import beam_runtimes
    from hollowbody.model.mass import lumped_node_mass

    model = build_model(read_deck(_write(tmp_path, DECK)))
    node_mass, _ = lumped_node_mass(model)
    rts = beam_runtimes(model, model.node_x0)
    n = model.n_nodes
    total = sum(rt.lumped_mass(n) for rt in rts)
    assert np.allclose(total, node_mass, rtol=1e-12)
    rt = rts[0]  # resultant part: A 25, ISS = ITT = 52.08, L = 10
    j = rt.lumped_rotational_inertia(n)
    m_node = 0.5 * 7.85e-6 * 25.0 * 10.0
    assert j[0] == pytest.approx(m_node * max(10.0 ** 2 / 4.0, 2 * 52.08 / 25.0))
