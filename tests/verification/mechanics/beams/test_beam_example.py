"""The example deck examples/beams/cantilever.k runs with ``hollowbody run`` (briefly),
keeps its energy, and a run resumed from a restart file writes the same
histories as the straight run."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hollowbody.api import run_deck
from hollowbody.cli.main import main as cli_main
from hollowbody.solver.restart import dump_files

DECK = Path(__file__).resolve().parents[4] / "examples" / "beams" / "cantilever.k"


pytestmark = pytest.mark.usefixtures("one_thread")


def test_example_runs_with_the_cli(tmp_path):
    assert cli_main(["run", str(DECK), "--out", str(tmp_path / "run"), "--end-time", "0.6"]) \
        == 0
    glstat = np.genfromtxt(tmp_path / "run" / "glstat.csv", delimiter=",", skip_header=1)
    # energy ratio within 0.1 % over the run (measured 0.99997 .. 1.000008 to 5 ms)
    assert np.abs(glstat[:, 9] - 1.0).max() < 1e-3
    assert glstat[:, 4].max() > 0.1 * glstat[0, 3]  # it bends: internal energy grows


def test_example_restart_equals_straight_run(tmp_path):
    ref = run_deck(DECK, tmp_path / "ref", end_time=0.6, vtk=False)
    assert ref.summary["element_counts"]["beams"] == 10
    out = tmp_path / "cut"
    run_deck(DECK, out, end_time=0.6, vtk=False, dump_cycles=100)
    files = dump_files(out)
    assert len(files) >= 2
    res = run_deck(DECK, out, end_time=0.6, vtk=False, restart=files[1], dump_cycles=0,
                   overwrite=True)
    assert res.cycles == ref.cycles
    for name in ("glstat.csv", "nodout.csv"):
        assert (out / name).read_text() == (tmp_path / "ref" / name).read_text(), name


def test_mass_scaling_of_beams(tmp_path):
    """DT2MS = -0.003 ms on the example (L / c = 1.981e-3 ms): every beam gets
    (T c / L)^2 times its mass (mass and rotational inertia scale together, so
    the step becomes T exactly); the run steps at TSSFAC T and keeps its energy."""
    text = DECK.read_text().replace("*CONTROL_TIMESTEP\n         0       0.9\n",
                                    "*CONTROL_TIMESTEP\n         0       0.9         0"
                                    "       0.0    -0.003\n")
    deck = tmp_path / "scaled.k"
    deck.write_text(text)
    res = run_deck(deck, tmp_path / "run", end_time=0.6, vtk=False)
    ms = res.summary["mass_scaling"]
    l_over_c = 10.0 / np.sqrt(200.0 / 7.85e-6)
    assert ms["added_mass_percent"] == pytest.approx(100.0 * ((0.003 / l_over_c) ** 2 - 1.0),
                                                     rel=1e-6)
    glstat = np.genfromtxt(tmp_path / "run" / "glstat.csv", delimiter=",", skip_header=1)
    assert glstat[1:-1, 2] == pytest.approx(0.9 * 0.003, rel=1e-6)
    # the final record (the end-time state, written twice) is left out: its
    # kinetic energy is that of the half step (measured ratio 1.0002 there)
    assert np.abs(glstat[:-2, 9] - 1.0).max() < 1e-4


def test_beams_in_the_vtk_states(tmp_path):
    """The states files hold the beams as line cells with their part, id, mean
    section stress and alive flag."""
    import meshio

    run_deck(DECK, tmp_path / "run", end_time=0.05, vtk=True)
    files = sorted((tmp_path / "run").rglob("*.vtu"))
    assert files
    mesh = meshio.read(files[-1])
    lines = [c for c in mesh.cells if c.type == "line"]
    assert len(lines) == 1 and lines[0].data.shape == (10, 2)
    k = [c.type for c in mesh.cells].index("line")
    assert mesh.cell_data["element"][k].tolist() == list(range(1, 11))
    assert np.all(mesh.cell_data["alive"][k] == 1)
