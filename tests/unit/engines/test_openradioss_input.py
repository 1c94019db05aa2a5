"""What OpenRadioss gets from a hollowbody deck (the rewritten keyword deck and the
engine file) and the reading of its engine listing.

The listings below are SYNTHETIC, in the layout of OpenRadioss's engine listing
(ROOT_0001.out: the cycle table in the engine's fixed format, its stop messages
and the termination lines); they test the parser, not the engine. The engine file's keywords and cards are those of
OpenRadioss's engine input reference (/RUN, /TFILE, /ANIM/DT, /PRINT,
/DT/Eltyp/STOP).
"""

# The synthetic listings keep the engines' line widths (over 100 characters).
# ruff: noqa: E501

from __future__ import annotations

import math
from pathlib import Path

import pytest

from hollowbody.engines.lsdyna_ascii import GLSTAT_ORDER
from hollowbody.engines.lsdyna_status import ERROR, NORMAL, UNKNOWN
from hollowbody.engines.radioss_deck import (
    EngineSettings,
    engine_file_text,
    engine_settings,
    merge_engine_files,
    rewrite_for_openradioss,
)
from hollowbody.engines.radioss_listing import parse_listing, read_listing
from hollowbody.io.keyword import read_deck, write_deck
from hollowbody.testing.decks import box_deck

BLOCK = Path(__file__).parents[2] / "regression" / "decks" / "block" / "main.k"

LISTING = """\
 OpenRadioss Engine 2026.08.21

   CYCLE    TIME      TIME-STEP  ELEMENT          ERROR  I-ENERGY    K-ENERGY T  K-ENERGY R  EXT-WORK     MAS.ERR     TOTAL MASS  MASS ADDED
       0  0.000      0.1000E-03 BRICK         12   0.0%  0.000       12.50      0.000       0.000       0.000      0.1000E-01  0.000
     100  0.1000E-01 0.9900E-04 BRICK         12  -0.1%  0.5000      12.00      0.000      0.1000E-01  0.000      0.1000E-01 0.2000E-05
"""


def test_listing_normal_termination_and_glstat_rows():
    lst = parse_listing(LISTING + "\n\n\n     NORMAL TERMINATION      \n"
                        "     TOTAL NUMBER OF CYCLES  :     101\n")
    assert (lst.status, lst.reason) == (NORMAL, "normal termination")
    assert lst.version == "OpenRadioss Engine 2026.08.21"
    assert lst.cycles == 101 and lst.end_time_ms == pytest.approx(0.01)
    assert lst.dt_element == ("BRICK", 12)
    r0, r1 = (dict(zip(GLSTAT_ORDER, r)) for r in lst.rows)
    assert r1["cycle"] == 100 and r1["dt [ms]"] == pytest.approx(9.9e-5)
    assert r1["kinetic [J]"] == 12.0 and r1["internal [J]"] == 0.5
    assert r1["external_work [J]"] == 0.01 and r1["total [J]"] == 12.5
    # hollowbody's ratio: total / (initial total + external work) = 12.5 / 12.51
    assert r1["energy_ratio"] == pytest.approx(12.5 / 12.51, rel=1e-12)
    assert r0["energy_ratio"] == 1.0
    assert math.isnan(r1["hourglass [J]"]) and math.isnan(r1["contact [J]"])
    assert r1["added_mass [kg]"] == 2.0e-6 and r0["added_mass [kg]"] == 0.0


def test_listing_error_termination_on_negative_volume():
    # an eroded element (WARNING / DELETE) does not end the run
    eroded = " ** WARNING ZERO OR NEGATIVE VOLUME : DELETE 3D-ELEMENT ID: 77\n"
    lst = parse_listing(LISTING + eroded + "\n ** STOP: ZERO OR NEGATIVE VOLUME FOR 3D-ELEMENT "
                        "ID=345\n\n\n\n     ERROR TERMINATION\n")
    assert lst.status == ERROR
    assert lst.where == {"element": 345, "time_ms": 0.01, "cycle": 100}
    assert lst.reason == "negative volume in solid element 345 near t=0.01 ms"
    # the id on the next line (tetrahedra, integration points)
    lst = parse_listing(LISTING + " ** STOP: ZERO OR NEGATIVE VOLUME\n"
                        "           FOR 4 NODES TETRAHEDRON ID=9, INTEGRATION POINT=1\n"
                        "     ERROR TERMINATION\n")
    assert lst.status == ERROR and lst.where["element"] == 9
    assert parse_listing(LISTING + eroded + "     NORMAL TERMINATION\n").where == {}


def test_listing_missing_or_unfinished(tmp_path):
    assert read_listing(tmp_path / "none_0001.out").status == UNKNOWN
    assert parse_listing(LISTING).status == UNKNOWN


def _box_with(tmp_path, extra: str) -> Path:
    deck = tmp_path / "box.k"
    write_deck(box_deck(h=30.0), deck)
    text = deck.read_text().replace("*END", extra + "*END")
    deck.write_text(text)
    return deck


def test_rewrite_inlines_includes_and_drops_control_contact(tmp_path):
    starter, notes = rewrite_for_openradioss(BLOCK, tmp_path / "main.k")
    assert starter == tmp_path / "main_0000.rad"
    out = tmp_path / "main.k"
    text = out.read_text()
    assert "*INCLUDE" not in text and "*NODE" in text and "*ELEMENT_SOLID" in text
    assert any("include" in n for n in notes)
    assert read_deck(out) is not None  # the written deck reads back
    deck = _box_with(tmp_path, "*CONTROL_CONTACT\n       0.1\n")
    _, notes = rewrite_for_openradioss(deck, tmp_path / "box2.k")
    assert "*CONTROL_CONTACT" not in (tmp_path / "box2.k").read_text()
    assert any("*CONTROL_CONTACT" in n for n in notes)


def test_engine_settings_and_file_text(tmp_path):
    deck = _box_with(tmp_path, "*CONTROL_TIMESTEP\n       0.0      0.67\n"
                               "*DATABASE_GLSTAT\n     0.001\n"
                               "*DATABASE_BINARY_D3PLOT\n      0.05\n")
    parsed = read_deck(deck)
    s = engine_settings(parsed)
    assert s == EngineSettings(end_time=1.0, history_dt=0.001, anim_dt=0.05, tssfac=0.67)
    body = engine_file_text("box", s, "box.k").splitlines()
    assert body[1:3] == ["/RUN/box/1", f"{1.0:20.6g}"]
    assert body[3:5] == ["/TFILE", f"{0.001:20.6g}"]
    assert body[5:7] == ["/ANIM/DT", f"{0.0:20.6g}{0.05:20.6g}"]
    assert "/TH/TITLE" in body and "/PRINT/-100" in body
    assert not any(b.startswith("/DT/") for b in body)


def test_dtmin_becomes_an_absolute_minimum_step(tmp_path):
    deck = box_deck(h=30.0)
    from hollowbody.io.keyword import ControlTermination

    deck.of_type(ControlTermination)[0].dtmin = 0.1
    s = engine_settings(deck, dt0=2.0e-4)
    assert s.dtmin_abs == pytest.approx(2.0e-5)
    body = engine_file_text("box", s).splitlines()
    i = body.index("/DT/BRICK/STOP")
    assert body[i + 1] == f"{0.9:20.6g}{2.0e-5:20.6g}"
    assert body[body.index("/DT/SHELL/STOP") + 1] == body[i + 1]
    # without the initial step there is no minimum
    assert engine_settings(deck).dtmin_abs == 0.0
    # ERODE = 1: the element whose step falls below DTMIN is deleted, the run goes on
    from hollowbody.io.keyword import ControlTimestep

    deck.add(ControlTimestep(tssfac=0.9, erode=1))
    body = engine_file_text("box", engine_settings(deck, dt0=2.0e-4)).splitlines()
    assert "/DT/BRICK/DEL" in body and "/DT/SHELL/DEL" in body
    assert "/DT/BRICK/STOP" not in body
    # defaults when the deck asks for no output: end / 500 and end / 20
    assert (s.history_dt, s.anim_dt) == (1.0 / 500, 1.0 / 20)


def test_engine_file_merged_with_the_starters():
    # a synthetic engine file as the starter writes it from a deck's controls
    generated = ("#RADIOSS ENGINE\n/RUN/box/1\n                 2.0\n/ANIM/DT\n 0.0 0.5\n"
                 "/DT/NODA/CST/0\n 0.67 1.0E-4\n/DT/BRICK/CST\n 0.9 1.0E-6\n/ANIM/ELEM/ENER\n")
    ours = engine_file_text("box", EngineSettings(end_time=1.0, history_dt=0.01, anim_dt=0.1,
                                                  dtmin_abs=1e-5), "box.k")
    merged = merge_engine_files(generated, ours).splitlines()
    assert merged[0].startswith("# OpenRadioss engine input written by hollowbody")
    assert merged[1:3] == ["/RUN/box/1", f"{1.0:20.6g}"]  # ours, first
    assert merged.count("/ANIM/DT") == 1 and f"{0.0:20.6g}{0.1:20.6g}" in merged
    assert "/DT/NODA/CST/0" in merged and " 0.67 1.0E-4" in merged  # the starter's, kept
    assert "/DT/BRICK/CST" not in merged and "/DT/BRICK/STOP" in merged  # ours replaces it
    assert "/ANIM/ELEM/ENER" in merged and "/TH/TITLE" in merged
    assert " 0.9 1.0E-6" not in merged


def test_a_finished_openradioss_run_folder_becomes_hollowbodys_files(tmp_path):
    """The runner's last step on a folder as OpenRadioss leaves it (synthetic files)."""
    import json

    from hollowbody.engines.commands import Command, RunPlan
    from hollowbody.engines.runner import Prepared, _collect_radioss
    from hollowbody.io.results.history import read_history

    (tmp_path / "box_0001.out").write_text(LISTING + "     NORMAL TERMINATION\n")
    for k in (1, 2):
        (tmp_path / f"boxA00{k}.vtk").write_text("# vtk DataFile Version 3.0\n")
    cmd = Command("engine", "engine_linux64_gf", ("-i", "box_0001.rad"), tmp_path)
    text = engine_file_text("box", EngineSettings(end_time=1.0, history_dt=0.01, anim_dt=0.25))
    prep = Prepared(RunPlan("openradioss", tmp_path / "box.k", tmp_path, (cmd,)),
                    ("box_0001.rad", text), end_time_ms=1.0)
    s = _collect_radioss(prep, 2.0, {"starter": 0, "engine": 0}, [cmd.argv()])
    assert s["status"] == NORMAL and s["engine"] == "openradioss"
    assert s["engine_version"] == "OpenRadioss Engine 2026.08.21" and s["cycles"] == 100
    assert json.loads((tmp_path / "summary.json").read_text()) == s
    g = read_history(tmp_path / "glstat.csv")
    assert list(g["cycle"]) == [0.0, 100.0]
    pvd = (tmp_path / "states.pvd").read_text()
    assert 'timestep="0" file="boxA001.vtk"' in pvd and 'timestep="0.25" file="boxA002.vtk"' in pvd
    # a starter that stopped is an error termination pointing at its listing
    s = _collect_radioss(prep, 0.1, {"starter": 2}, [])
    assert s["status"] == ERROR and "box_0000.out" in s["reason"]


def test_the_starters_errors_are_read_from_its_listing(tmp_path):
    """A starter listing (SYNTHETIC, in the layout of the messages OpenRadioss's starter
    writes to ROOT_0000.out) gives the first errors, one line each."""
    from hollowbody.engines.radioss_listing import starter_errors

    (tmp_path / "d_0000.out").write_text(
        "   INTERFACE NUMBER :         1 tissue-impactor\n\n"
        "ERROR ID :   2087\n** REFERENCE TO UNDEFINED GROUP ID\nDESCRIPTION :  \n"
        "   -- INTER ID   : 1\n   -- INTER TITLE: tissue-impactor\n"
        "   REFERENCE TO UNDEFINED GROUP ID 5\n\n    TYPE==25  MUTI-TYPE IMPACTING\n\n"
        "WARNING ID :    343\n** WARNING: INITIAL PENETRATIONS IN INTERFACE\n\n"
        "ERROR ID :   1000\n** ERROR IN INTERFACE DEFINITION\nDESCRIPTION :  \n"
        "   IN INTERFACE NB 1\n   Surf_1 DOES NOT EXIST\n\n")
    errs = starter_errors(tmp_path / "d_0000.out")
    assert errs == ["error 2087: REFERENCE TO UNDEFINED GROUP ID; -- INTER ID   : 1; "
                    "-- INTER TITLE: tissue-impactor; REFERENCE TO UNDEFINED GROUP ID 5",
                    "error 1000: ERROR IN INTERFACE DEFINITION; IN INTERFACE NB 1; "
                    "Surf_1 DOES NOT EXIST"]
    assert starter_errors(tmp_path / "missing.out") == []
