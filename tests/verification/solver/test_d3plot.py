"""d3plot output read back with lasso-python: ids, coordinates, stresses, energies.

The d3plot holds the same states as the ParaView series (same times, same
coordinates and solid stresses to single precision: relative 1e-6) and the
run's energies at its last state (glstat.csv, single precision).
"""

from __future__ import annotations

import csv
from pathlib import Path

import meshio
import numpy as np
import pytest
from solver_decks import cube_and_plate

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.errors import UserInputError
from hollowbody.io.results.d3plot import D3plotSeries, Geometry, StateFields
from hollowbody.solver.d3plot_output import shell_frames

lasso = pytest.importorskip("lasso.dyna")
A = lasso.ArrayType


def _run(tmp_path: Path, **kw: object) -> tuple[object, Path]:
    model = build_model(cube_and_plate(e=0.1, speed=3.0, end=0.2, gap=0.2))
    out = tmp_path / "run"
    run_model(model, out, d3plot=True, **kw)
    return model, out


def test_d3plot_round_trip(tmp_path: Path) -> None:
    model, out = _run(tmp_path)
    d = lasso.D3plot(str(out / "d3plot"))
    arr = d.arrays
    np.testing.assert_array_equal(arr[A.node_ids], model.node_ids)
    np.testing.assert_allclose(arr[A.node_coordinates], model.node_x0, rtol=1e-6)
    np.testing.assert_array_equal(arr[A.element_solid_ids], model.solid_groups[0].elem_ids)
    np.testing.assert_array_equal(arr[A.element_shell_ids], model.shell_groups[0].elem_ids)
    np.testing.assert_array_equal(arr[A.part_ids], [1, 2])
    np.testing.assert_array_equal(arr[A.element_solid_node_indexes],
                                  model.solid_groups[0].conn)
    # the same states as the ParaView series
    pvd = (out / "states.pvd").read_text()
    times = [float(s.split('"')[1]) for s in pvd.split("timestep=")[1:]]
    np.testing.assert_allclose(arr[A.global_timesteps], times, rtol=1e-6)
    last = meshio.read(out / sorted(p.name for p in out.glob("states_*.vtu"))[-1])
    np.testing.assert_allclose(arr[A.node_displacement][-1], last.points, rtol=1e-6,
                               atol=1e-5)
    stress = last.cell_data["stress [GPa]"][0]
    scale = np.abs(stress).max()
    assert scale > 0.0  # the plate has struck the cube
    np.testing.assert_allclose(arr[A.element_solid_stress][-1, :, 0], stress,
                               atol=1e-6 * scale)
    assert np.all(arr[A.element_solid_is_alive] > 0.5)
    # energies of the last state against glstat.csv
    rows = list(csv.reader((out / "glstat.csv").open()))
    head, lastrow = rows[0], [float(v) for v in rows[-1]]
    ke = lastrow[head.index("kinetic [J]")]
    total = lastrow[head.index("total [J]")]
    assert arr[A.global_kinetic_energy][-1] == pytest.approx(ke, rel=1e-6)
    assert arr[A.global_total_energy][-1] == pytest.approx(total, rel=1e-6)


def test_d3plot_off_and_missing_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    model = build_model(cube_and_plate(e=0.1, speed=3.0, end=0.05))
    run_model(model, tmp_path / "off", d3plot=False)
    assert not (tmp_path / "off" / "d3plot").exists()
    import hollowbody.solver.explicit as ex

    monkeypatch.setattr(ex, "d3plot_available", lambda: False)
    with pytest.raises(UserInputError, match="lasso-python"):
        run_model(model, tmp_path / "missing", d3plot=True)
    assert not (tmp_path / "missing").exists()  # refused before anything is written


def _geometry() -> Geometry:
    x0 = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    return Geometry(node_ids=np.arange(1, 5), x0=x0, solid_conn=np.zeros((0, 8), int),
                    solid_part=np.zeros(0, int), solid_ids=np.zeros(0, int),
                    shell_conn=np.array([[0, 1, 2, 3]]), shell_part=np.array([0]),
                    shell_ids=np.array([7]), part_ids=np.array([3]), part_titles=["skin"])


def _state(t: float) -> StateFields:
    x = _geometry().x0 + t
    return StateFields(t=t, x=x, v=np.full((4, 3), t), solid_stress=np.zeros((0, 6)),
                       solid_eps=np.zeros(0), solid_alive=np.zeros(0, bool),
                       shell_stress=np.full((1, 3, 6), t), shell_eps=np.full((1, 3), t),
                       shell_thickness=np.array([1.0 + t]), shell_alive=np.array([t < 2.5]),
                       kinetic=t, internal=2 * t, total=3 * t)


def test_resume_keeps_the_states_written(tmp_path: Path) -> None:
    s = D3plotSeries(tmp_path / "d3plot", _geometry())
    for t in (0.0, 1.0, 2.0):
        s.add(_state(t))
    s.write()
    again = D3plotSeries(tmp_path / "d3plot", _geometry())
    again.resume(2)  # the restart file was written after the second state
    again.add(_state(3.0))
    again.write()
    arr = lasso.D3plot(str(tmp_path / "d3plot")).arrays
    np.testing.assert_allclose(arr[A.global_timesteps], [0.0, 1.0, 3.0])
    np.testing.assert_allclose(arr[A.element_shell_stress][:, 0, 0, 0], [0.0, 1.0, 3.0])
    np.testing.assert_allclose(arr[A.element_shell_thickness][:, 0], [1.0, 2.0, 4.0])
    np.testing.assert_array_equal(arr[A.element_shell_is_alive][:, 0] > 0.5,
                                  [True, True, False])


def test_shell_frame_rotates_stress_to_global() -> None:
    """A square shell turned by a rotation Q: its frame is Q times the flat one, and a
    local stress S maps to Q_flat S Q_flat^T, so invariants are kept."""
    rng = np.random.default_rng(3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    x = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]) @ q.T
    frame = shell_frames(np.array([[0, 1, 2, 3]]), x)[0]
    flat = shell_frames(np.array([[0, 1, 2, 3]]), x @ q)[0]
    np.testing.assert_allclose(frame, flat @ q.T, atol=1e-12)
    np.testing.assert_allclose(frame @ frame.T, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(frame[2], q[:, 2], atol=1e-12)  # normal of the turned plane


def test_shell_layer_stress_in_global_axes() -> None:
    """The layers' stresses written for a turned shell: local sigma_xx 2 / 1 / -2 GPa
    at the first, middle and last point (a 1-2 shear of 0.5, transverse shears 0.1 /
    0.2) come out as R^T S R with R the shell's frame; plastic strains as given."""
    from types import SimpleNamespace

    from hollowbody.solver.d3plot_output import _shell_layers

    rng = np.random.default_rng(5)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    x = np.array([[0.0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]]) @ q.T
    conn = np.array([[0, 1, 2, 3]])
    sig = np.zeros((1, 5, 3))
    sig[0, :, 0] = [2.0, 0.0, 1.0, 0.0, -2.0]
    sig[0, :, 2] = 0.5
    rt = SimpleNamespace(sig=sig, tau=np.array([[0.1, 0.2]]),
                         epsp=np.array([[0.3, 0.0, 0.1, 0.0, 0.4]]))
    stress, eps = _shell_layers(rt, conn, x)
    r = shell_frames(conn, x)[0]
    for layer, point in enumerate((0, 2, 4)):
        s = np.array([[sig[0, point, 0], 0.5, 0.1], [0.5, 0.0, 0.2], [0.1, 0.2, 0.0]])
        g = r.T @ s @ r
        np.testing.assert_allclose(stress[0, layer], [g[0, 0], g[1, 1], g[2, 2], g[0, 1],
                                                      g[1, 2], g[2, 0]], atol=1e-14)
    np.testing.assert_array_equal(eps[0], [0.3, 0.1, 0.4])


def test_d3plot_beams(tmp_path: Path) -> None:
    """The swinging cantilever example: beam ids, nodes and part, and its resultants in
    every state (the root moment of a clamped beam is not zero once it swings)."""
    from hollowbody.api import load_model

    deck = Path(__file__).resolve().parents[3] / "examples" / "beams" / "cantilever.k"
    model = load_model(deck)
    run_model(model, tmp_path / "run", end_time=1.0, d3plot=True)
    arr = lasso.D3plot(str(tmp_path / "run" / "d3plot")).arrays
    g = model.beam_groups[0]
    np.testing.assert_array_equal(arr[A.element_beam_ids], g.elem_ids)
    np.testing.assert_array_equal(arr[A.element_beam_node_indexes][:, :3], g.conn)
    n_states = arr[A.global_timesteps].size
    assert arr[A.element_beam_bending_moment].shape == (n_states, g.conn.shape[0], 2)
    root = np.abs(arr[A.element_beam_bending_moment][1:, 0]).max()
    assert np.isfinite(root) and root > 0.0
    assert np.all(arr[A.element_beam_is_alive] > 0.5)
