"""``hollowbody check``: summary numbers computed by hand, exit codes, JSON."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.cli.main import main
from hollowbody.io.keyword import read_deck, read_deck_text
from hollowbody.model.summary import solid_lengths, summarize

DECKS = Path(__file__).resolve().parents[2] / "regression" / "decks"


def check_json(path: Path, capsys, *extra: str) -> tuple[int, dict]:
    code = main(["check", str(path), "--json", *extra])
    return code, json.loads(capsys.readouterr().out)


def test_hand_computed_masses_and_time_steps(capsys):
    code, s = check_json(DECKS / "hand_check.k", capsys)
    assert code == 0 and s["can_run"] and s["problems"] == []
    # cube 10 mm, rho 1e-6 -> 1e-3 kg; plate 20 x 10 x 2 mm steel -> 3.14e-3 kg; + 0.5 kg
    masses = {p["pid"]: p["mass_kg"] for p in s["parts"]}
    assert masses[1] == pytest.approx(1.0e-3) and masses[2] == pytest.approx(1.0e-3)
    assert masses[3] == pytest.approx(7.85e-6 * 200.0 * 2.0)
    assert s["mass_kg"] == pytest.approx(1e-3 + 1e-3 + 3.14e-3 + 0.5)
    assert s["element_mass_kg"] == 0.5
    # elastic cube: c = sqrt(E (1 - nu) / ((1 + nu)(1 - 2 nu)) / rho), L = V / A = 10, times
    # the one-point hexahedron's volumetric-mode factor sqrt((1 - nu) / (1 + nu)) (the run's
    # rule for a lone element, hollowbody.elements.solid_step_factor.volumetric_step_factor),
    # with the linear bulk viscosity Q2 c (0.06) in the step at rest
    c = math.sqrt(0.21 * 0.7 / (1.3 * 0.4) / 1.0e-6)
    q2 = 0.06 + math.sqrt(1.0 + 0.06**2)
    assert s["time_step"]["solid"] == {"dt": pytest.approx(10.0 / c * math.sqrt(0.7 / 1.3) / q2),
                                       "element": 1, "part": 1}
    # plate: L = area / longest side = 200 / 20, c = sqrt(E / (rho (1 - nu^2)))
    c = math.sqrt(210.0 / (7.85e-6 * 0.91))
    assert s["time_step"]["shell"] == {"dt": pytest.approx(10.0 / c), "element": 10, "part": 3}
    assert s["time_step"]["run_dt"] == pytest.approx(0.8 * 10.0 / c)
    assert s["elements"] == {"hexahedra": 2, "wedges": 0, "tetrahedra": 0, "other_solids": 0,
                             "shells": 1, "triangles": 0, "mass_elements": 1}
    assert s["bounding_box"] == {"min": [0.0, 0.0, 0.0], "max": [30.0, 10.0, 20.0]}
    assert s["nodes"] == 20 and s["end_time"] == 5.0
    part = {p["pid"]: p for p in s["parts"]}[2]
    assert part["material"] == "*MAT_SIMPLIFIED_RUBBER 2"
    assert part["section"] == "*SECTION_SOLID 1 (ELFORM 1)"


def test_rubber_wave_speed_from_the_curve_slope():
    # MAT_181 of hand_check.k: K = 0.001, curve slope at 0 = max(0.002, 0.001) per unit x,
    # strain = x / SGL (SGL = 2), stress = y / (SW ST) -> E0 = 0.004, G = E0 / 3
    m = build_model(read_deck(DECKS / "hand_check.k"))
    from hollowbody.model.summary import solid_wave_speed

    k, g = 0.001, 0.004 / 3.0
    assert solid_wave_speed(m, 2) == pytest.approx(math.sqrt((k + 4.0 * g / 3.0) / 1.0e-6))


def test_element_shapes_are_counted_from_degenerate_patterns(capsys):
    code, s = check_json(DECKS / "shapes.k", capsys)
    assert code == 0
    assert s["elements"] == {"hexahedra": 1, "wedges": 1, "tetrahedra": 2, "other_solids": 0,
                             "shells": 1, "triangles": 1, "mass_elements": 0}
    # solids: cube 1 + wedge 1/2 + two tetrahedra 1/6 each; rho 1e-6
    assert {p["pid"]: p["mass_kg"] for p in s["parts"]}[1] == pytest.approx(1e-6 * (1.5 + 1 / 3))


def test_tetrahedron_length_is_the_smallest_altitude():
    x = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    conn = np.array([[0, 1, 2, 3, 3, 3, 3, 3]])
    assert solid_lengths(conn, x)[0] == pytest.approx(1 / math.sqrt(3))


def test_unsupported_keywords_are_listed_with_lines(capsys):
    code, s = check_json(DECKS / "unsupported_mix.k", capsys)
    assert code == 0
    assert [(u["keyword"], u["line"]) for u in s["unsupported"]] == [
        ("KEYWORD_ID", 2), ("PARAMETER", 6), ("CONTROL_ENERGY", 8),
        ("DATABASE_EXTENT_BINARY", 12), ("SECTION_SPH", 19), ("EOS_LINEAR_POLYNOMIAL", 23),
        ("ELEMENT_TSHELL", 25), ("EOS_LINEAR_POLYNOMIAL", 40)]
    assert main(["check", str(DECKS / "unsupported_mix.k"), "--strict"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"hollowbody check: error: {DECKS / 'unsupported_mix.k'}:2: *KEYWORD_ID: "
                   "keyword not supported (strict mode)"]


def test_human_output_mentions_the_essentials(capsys):
    assert main(["check", str(DECKS / "hand_check.k")]) == 0
    out = capsys.readouterr().out
    for text in ("nodes 20", "2 hexahedra", "steel plate", "*MAT_SIMPLIFIED_RUBBER 2",
                 "total mass 0.50514 kg", "element 10, part 3", "the deck can run"):
        assert text in out


@pytest.mark.parametrize("edit, reason", [
    (lambda t: t.replace("       5.0\n", "\n"), "no termination time"),
    (lambda t: t.replace("         1    1.0e-6      0.21", "         1       0.0      0.21"),
     "part 1 has no mass"),
    (lambda t: "\n".join(ln[:-4] + "-10.0" if ln.startswith(("       5", "       6", "       7",
                                                             "       8")) else ln
                         for ln in t.splitlines()) + "\n",
     "zero or negative volume"),
])
def test_decks_that_cannot_run_exit_2_with_reasons(edit, reason, tmp_path, capsys):
    path = tmp_path / "bad.k"
    path.write_text(edit((DECKS / "hand_check.k").read_text()))
    code, s = check_json(path, capsys)
    assert code == 2 and not s["can_run"]
    assert any(reason in p for p in s["problems"]), s["problems"]


def test_no_elements_cannot_run():
    s = summarize(build_model(read_deck_text("*NODE\n1,0,0,0\n*CONTROL_TERMINATION\n1.0\n")))
    assert s["problems"] == ["no elements"]
