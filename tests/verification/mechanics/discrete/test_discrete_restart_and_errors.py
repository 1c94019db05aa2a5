"""Discrete elements: a resumed run equals the straight run; bad decks are refused at
their card (file, line, keyword); the example deck runs."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np
import pytest
from discrete_decks import Driver, crossings, curve, f10, load, oscillator_deck

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.errors import DeckError
from hollowbody.io.keyword import read_deck
from hollowbody.solver.restart import dump_files
from hollowbody.solver.state import restore, snapshot
from hollowbody.solver.step import step

EXAMPLE = Path(__file__).resolve().parents[4] / "examples" / "discrete" / "spring_mass_damper.k"

S06 = ("*MAT_SPRING_GENERAL_NONLINEAR\n" + f10(1, 11, 12, 1.0, 2.0, -2.0) + "\n"
       + curve(11, [(0.0, 0.0), (2.0, 10.0), (10.0, 14.0)])
       + curve(12, [(-1.0, -10.0), (0.0, 0.0), (1.0, 10.0)]))
DAMPER = "*MAT_DAMPER_VISCOUS\n" + f10(2, 0.05) + "\n"


def test_resumed_state_equals_the_straight_run():
    """Snapshot (what a restart file holds) at cycle 150, run on; restore, run again:
    positions, velocities, histories and energies are bit-identical."""
    model = load(oscillator_deck([S06, DAMPER], v0=20.0, end=5.0, tssfac=0.2))
    dr = Driver(model)
    s, plan = dr.state, dr.plan
    for _ in range(150):
        step(model, plan, s, s.dt_next)
    snap = snapshot(s)
    for _ in range(200):
        step(model, plan, s, s.dt_next)
    first = (s.x.copy(), s.v.copy(), plan.elements[0].hist.copy(),
             plan.elements[0].internal_energy, plan.elements[1].internal_energy)
    assert np.any(plan.elements[0].hist[:, 1] != 0.0)  # the spring has yielded
    restore(s, snap)
    for _ in range(200):
        step(model, plan, s, s.dt_next)
    again = (s.x, s.v, plan.elements[0].hist, plan.elements[0].internal_energy,
             plan.elements[1].internal_energy)
    for a, b in zip(first, again):
        assert np.array_equal(a, b)


def test_restart_file_resumes_the_run_exactly(tmp_path, one_thread):
    """A run with restart files resumed from its second dump writes the same histories
    (deforc, glstat, nodout) as the straight run, to the last digit (one thread)."""
    text = oscillator_deck([S06, DAMPER], v0=20.0, end=20.0, tssfac=0.2).replace(
        "*END", "*DATABASE_DEFORC\n      0.02\n*DATABASE_HISTORY_NODE\n         2\n*END")
    straight, resumed = tmp_path / "a", tmp_path / "b"
    ref = run_model(load(text), straight, vtk=False)
    run_model(load(text), resumed, vtk=False, dump_cycles=40)
    dumps = dump_files(resumed)
    assert len(dumps) >= 2
    res = run_model(load(text), resumed, vtk=False, restart=dumps[1], dump_cycles=0)
    assert res.cycles == ref.cycles
    for name in ("deforc.csv", "glstat.csv", "nodout.csv"):
        assert (straight / name).read_text() == (resumed / name).read_text(), name
    assert len((straight / "deforc.csv").read_text().splitlines()) > 100


def _error(text: str) -> DeckError:
    with pytest.raises(DeckError) as info:
        Driver(load(text, "bad.k"))
    return info.value


def _line_of(text: str, needle: str) -> int:
    return text.splitlines().index(needle) + 1


SPRING = "*MAT_SPRING_ELASTIC\n" + f10(1, 1.0) + "\n"


def test_zero_length_spring_without_orientation_is_refused_at_its_card():
    text = oscillator_deck([SPRING], length=0.0)
    err = _error(text)
    assert err.file == "bad.k" and err.keyword == "ELEMENT_DISCRETE"
    assert err.line == _line_of(text, text.splitlines()[-2])
    assert "VID" in err.message and "direction" in err.message


def test_missing_curve_and_missing_node_are_refused():
    text = oscillator_deck(["*MAT_SPRING_NONLINEAR_ELASTIC\n" + f10(1, 99) + "\n"])
    err = _error(text)
    assert "curve 99" in err.message and err.keyword == "MAT_SPRING_NONLINEAR_ELASTIC"
    assert err.line == _line_of(text, f10(1, 99))
    text = oscillator_deck([SPRING]).replace(
        "       1       1       1       2", "       1       1       1      77")
    err = _error(text)
    assert "node 77" in err.message and err.keyword == "ELEMENT_DISCRETE"
    assert err.line == len(text.splitlines()) - 1


def test_spring_on_a_node_without_mass_is_refused_at_set_up():
    text = oscillator_deck([SPRING]).replace("*ELEMENT_MASS\n" + f"{1:>8}{2:>8}{1.0:>16}\n",
                                             "")
    err = _error(text)
    assert "has no mass" in err.message and err.keyword == "ELEMENT_DISCRETE"
    assert err.line == len(text.splitlines()) - 1


def test_torsional_spring_on_a_node_without_rotational_inertia_is_refused():
    text = oscillator_deck([SPRING], dro=1).replace(f10(2, 0, 0, 1, 1, 1, 1, 1),
                                                    f10(2, 0, 0, 1, 1))
    err = _error(text)
    assert "rotational inertia" in err.message and err.keyword == "ELEMENT_DISCRETE"


def test_unsupported_section_options_are_refused():
    text = oscillator_deck([SPRING]).replace(f10(1, 0) + "\n" + f10(0.0, 0.0),
                                             f10(1, 0, 0.0, 0.0, 2.0) + "\n" + f10(0.0, 0.0))
    err = _error(text)
    assert "CL" in err.message and err.keyword == "SECTION_DISCRETE"


def test_grounded_spring_with_a_fixed_orientation():
    """N2 = 0 with *DEFINE_SD_ORIENTATION along x: the same oscillator (period 2 pi)."""
    text = oscillator_deck([SPRING]).replace(
        "       1       1       1       2       0",
        "       1       1       2       0       5") .replace(
        "*END", "*DEFINE_SD_ORIENTATION\n" + f10(5, 0, 1.0, 0.0, 0.0) + "\n*END")
    dr = Driver(load(text))
    r = dr.run(4.5 * np.pi)
    u = r[:, 1] - 100.0
    assert abs(u.max() - 1.0) < 0.01  # amplitude v0 / omega
    period = np.diff(crossings(r[:, 0], u))
    assert period.size >= 1 and np.all(np.abs(period / (2.0 * np.pi) - 1.0) < 0.01)


def test_example_deck_runs(tmp_path):
    model = build_model(read_deck(EXAMPLE))
    res = run_model(model, tmp_path, end_time=10.0)
    assert res.status == "normal termination"
    assert abs(res.summary["energy_ratio"] - 1.0) < 0.01
    rows = (tmp_path / "deforc.csv").read_text().splitlines()
    assert rows[0].startswith("time [ms],element") and len(rows) > 100
    # matsum: the spring stores, the damper dissipates; states: the elements as lines
    last = {int(r.split(",")[1]): float(r.split(",")[3])
            for r in (tmp_path / "matsum.csv").read_text().splitlines()[-2:]}
    assert last[2] > 0.2 and last[1] >= 0.0
    mesh = meshio.read(sorted(tmp_path.glob("states_*.vtu"))[-1])
    assert [c.type for c in mesh.cells] == ["line"] and len(mesh.cells[0].data) == 2


@pytest.mark.parametrize("edit, words, keyword", [
    # orientation with IOP 1 (vector from nodes)
    (lambda t: t.replace("       1       1       1       2       0",
                         "       1       1       1       2       4").replace(
        "*END", "*DEFINE_SD_ORIENTATION\n" + f10(4, 1, 1.0) + "\n*END"),
     "IOP 1", "DEFINE_SD_ORIENTATION"),
    # orientation that does not exist
    (lambda t: t.replace("       1       1       1       2       0",
                         "       1       1       1       2       4"),
     "VID 4", "ELEMENT_DISCRETE"),
    # an element id twice
    (lambda t: t.replace("*END", "*ELEMENT_DISCRETE\n" + "       1       1       1       2\n"
                         + "*END"), "defined twice", "ELEMENT_DISCRETE"),
    # a part that does not exist
    (lambda t: t.replace("       1       1       1       2       0",
                         "       1       8       1       2       0"),
     "part 8", "ELEMENT_DISCRETE"),
    # kinematic hardening without an elastic range
    (lambda t: t.replace("*MAT_SPRING_ELASTIC\n" + f10(1, 1.0),
                         "*MAT_SPRING_GENERAL_NONLINEAR\n" + f10(1, 11, 0, 0.5)).replace(
        "*END", curve(11, [(0.0, 0.0), (1.0, 1.0)]) + "*END"),
     "elastic range", "MAT_SPRING_GENERAL_NONLINEAR"),
])
def test_bad_references_are_refused_at_their_card(edit, words, keyword):
    err = _error(edit(oscillator_deck([SPRING])))
    assert words in err.message and err.keyword == keyword and err.file == "bad.k"
    assert err.line and err.line > 0


def test_cli_exits_2_with_the_place_for_a_bad_spring(tmp_path, capsys):
    from hollowbody.cli.main import main as cli_main

    deck = tmp_path / "springs.k"
    deck.write_text(oscillator_deck([SPRING], length=0.0))
    for args in (["check", str(deck)], ["run", str(deck), "--out", str(tmp_path / "o")]):
        assert cli_main(args) == 2
        err = capsys.readouterr().err
        assert "springs.k:" in err and "*ELEMENT_DISCRETE" in err and "Traceback" not in err
