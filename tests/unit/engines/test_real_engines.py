"""Runs on the real engines: skipped, with the reason, when the engine is not installed.

OpenRadioss is found through OPENRADIOSS_PATH or the PATH, LS-DYNA through
LSDYNA or the PATH (docs/engines.md). The first deck is the worked example
``examples/loads/block_drop.k`` (no contact): a block dropped onto a rigid wall
for 60 ms. The run must end normally at the deck's end time and write hollowbody's glstat.csv and
summary.json; its energy balance holds in free fall (kinetic energy = work of
gravity) and the rigid wall only takes energy out (OpenRadioss counts the
energy a kinematic rigid wall removes nowhere: measured 0.905 at the end).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from hollowbody.cli.main import main
from hollowbody.engines.discovery import EngineNotFound, find_lsdyna, find_openradioss
from hollowbody.io.results.history import read_history

EXAMPLE = Path(__file__).parents[3] / "examples" / "loads" / "block_drop.k"


def _installed(find) -> str | None:
    try:
        find()
    except EngineNotFound as exc:
        return str(exc)
    return None


@pytest.mark.parametrize("engine, find", [("openradioss", find_openradioss),
                                          ("lsdyna", find_lsdyna)])
def test_example_runs_to_normal_termination_on_the_engine(engine, find, tmp_path):
    missing = _installed(find)
    if missing:
        pytest.skip(f"{engine} is not installed here: {missing}")
    out = tmp_path / "out"
    code = main(["run", str(EXAMPLE), "--engine", engine, "--out", str(out), "--quiet"])
    s = json.loads((out / "summary.json").read_text())
    assert code == 0, s["reason"]
    assert s["engine"] == engine and s["status"] == "normal termination"
    assert s["end_time_ms"] == pytest.approx(60.0, rel=1e-3)
    g = read_history(out / "glstat.csv")
    assert g["time [ms]"].size > 10
    # free fall: kinetic energy = work of gravity until the block meets the wall (the
    # row of largest kinetic energy); 2 %: the listing prints 4 significant digits
    k = int(np.argmax(g["kinetic [J]"]))
    assert g["energy_ratio"][k] == pytest.approx(1.0, abs=0.02)
    # the rigid wall (a kinematic condition) can only take energy out of the block
    assert 0.0 < g["energy_ratio"][-1] <= 1.02


def test_block_test_on_lsdyna_writes_the_same_files():
    """``hollowbody block --engine lsdyna``: the solid muscle block at 40 km/h ends
    normally with its curve, plot and summary in the output folder, the impactor
    stopped by the tissue, and the run's energy balance within 5 % (as above)."""
    missing = _installed(find_lsdyna)
    if missing:
        pytest.skip(f"lsdyna is not installed here: {missing}")
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "block"
        code = main(["block", "--engine", "lsdyna", "--out", str(out), "--no-vtk", "--quiet"])
        s = json.loads((out / "summary.json").read_text())
        assert code == 0, s["reason"]
        assert s["engine"] == "lsdyna" and s["impact_outcome"] == "stopped"
        for name in ("force_displacement.csv", "force_displacement.png", "deck.k"):
            assert (out / name).is_file(), name
        assert s["energy_ratio"] == pytest.approx(1.0, abs=0.05)


@pytest.mark.parametrize("structure", ["solid", "hollow"])
def test_block_test_with_its_contacts_on_openradioss(structure):
    """``hollowbody block --engine openradioss`` (coarse 15 mm block, 4 ms, the impact
    under way): normal termination, the impactor pushed back by the tissue, and
    the impulse-momentum balance of the rigid impactor (5 kg, guided along z, the
    contact the only force on it in z): m (v(t) - v0) = integral of the contact
    force on it (master side of contact 1). 3 %: the time history is sampled every
    0.02 ms in single precision and the converter differentiates impulses by
    central differences, integrated back here by the trapezoid rule. The run's
    energy balance within 5 % as above."""
    missing = _installed(find_openradioss)
    if missing:
        pytest.skip(f"openradioss is not installed here: {missing}")
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "block"
        code = main(["block", "--engine", "openradioss", "--structure", structure,
                     "--mesh", "15", "--end-time", "4", "--out", str(out), "--no-vtk",
                     "--quiet"])
        s = json.loads((out / "summary.json").read_text())
        assert code == 0, s["reason"]
        assert s["engine"] == "openradioss" and s["status"] == "normal termination"
        run = out / "openradioss"
        nod = read_history(run / "nodout.csv")
        rc = read_history(run / "rcforc.csv")
        sel = nod["node"] == 1_000_001
        t, vz = nod["time [ms]"][sel], nod["vz [mm/ms]"][sel]
        selc = rc["contact"] == 1
        tc, fz = rc["time [ms]"][selc], rc["master_fz [kN]"][selc]
        assert fz.max() > 0.5  # kN: the tissue pushes the impactor back (+z)
        impulse = np.concatenate([[0.0], np.cumsum(0.5 * (fz[1:] + fz[:-1]) * np.diff(tc))])
        dv = 5.0 * (np.interp(tc, t, vz) - vz[0])  # kg mm/ms = kN ms
        assert impulse[-1] == pytest.approx(dv[-1], rel=0.03)
        assert s["energy_ratio"] == pytest.approx(1.0, abs=0.05)
