"""Whole runs get an honest verdict in summary.json, messages.log and the console.

- ok: an elastic impact (energy ratio within 1 %, no collapse, no pass-through);
- warning: a crushed shell strip whose mass scaling adds 4.4 % mass (between the
  2 % and 5 % limits; same strip and step target family as the mass-scaling tests);
- suspect: the same strip with a larger target (7.3 % mass added) and with a
  target of half the element step (229 % added);
- a tighter threshold given to the run turns the sound impact into a warning.

Also the reaction work of a prescribed node that starts from rest: with a
displacement ramp (VAD 2) the node jumps to the ramp's velocity in the first
cycle; the energy balance must be the one of the same motion given as a velocity
(VAD 0), which holds that velocity from t = 0.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from solver_decks import crushed_strip, cube_and_plate

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.io.results.history import read_history
from hollowbody.solver.verdict import Thresholds


def _run(deck, tmp_path, **kw):
    return run_model(build_model(deck), tmp_path, vtk=False, **kw)


def _strip_step() -> float:
    """Critical step of the strip's 5 mm squares (E 0.1 GPa, nu 0.3, rho 1e-6)."""
    return 5.0 / math.sqrt(0.1 / (1.0e-6 * (1 - 0.3 ** 2)))


def _verdict_line(tmp_path) -> str:
    return [ln for ln in (tmp_path / "messages.log").read_text().splitlines()
            if "normal termination - " in ln][-1]


def test_elastic_impact_is_ok(tmp_path):
    res = _run(cube_and_plate(e=0.1, speed=3.0, end=4.0), tmp_path)
    s = json.loads((tmp_path / "summary.json").read_text())
    assert res.status == "normal termination"
    assert s["quality"] == "ok" and s["quality_reasons"] == []
    assert s["quality_thresholds"] == Thresholds().to_dict()
    assert _verdict_line(tmp_path).endswith("normal termination - quality ok")


def test_a_tighter_threshold_makes_the_same_run_a_warning(tmp_path):
    res = _run(cube_and_plate(e=0.1, speed=3.0, end=4.0), tmp_path,
               quality=Thresholds(energy_ratio_warn=1e-6))
    assert res.summary["quality"] == "warning"
    assert [r["indicator"] for r in res.summary["quality_reasons"]] == ["energy_ratio"]
    assert "WARNING: energy ratio 1" in _verdict_line(tmp_path)


def test_moderate_mass_scaling_is_a_warning(tmp_path):
    res = _run(crushed_strip(crush=10.0, end=1.0, dt2ms=-0.26 * _strip_step()), tmp_path)
    s = res.summary
    assert res.status == "normal termination"
    assert 2.0 < s["mass_scaling"]["added_mass_percent"] < 5.0
    assert s["quality"] == "warning"
    assert [r["indicator"] for r in s["quality_reasons"]] == ["added_mass"]
    assert "normal termination - WARNING: mass scaling added 4" in _verdict_line(tmp_path)


def test_large_mass_scaling_is_suspect(tmp_path):
    for f, lo, hi in ((0.27, 5.0, 10.0), (0.5, 100.0, 1e4)):
        res = _run(crushed_strip(crush=10.0, end=1.0, dt2ms=-f * _strip_step()),
                   tmp_path / f"{f:g}")
        s = res.summary
        assert res.status == "normal termination"  # the run ends well, its result is not
        assert lo < s["mass_scaling"]["added_mass_percent"] < hi
        assert s["quality"] == "suspect", s["quality_reasons"]
        assert "normal termination - SUSPECT: mass scaling added" in \
            _verdict_line(tmp_path / f"{f:g}")


def test_cli_prints_the_verdict_last(tmp_path, capsys):
    from hollowbody.cli.main import main
    from hollowbody.io.keyword.writer import write_deck

    deck = tmp_path / "strip.k"
    write_deck(crushed_strip(crush=10.0, end=1.0, dt2ms=-0.27 * _strip_step()), deck)
    assert main(["run", str(deck), "--out", str(tmp_path / "out"), "--no-vtk",
                 "--quiet"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("normal termination - SUSPECT: mass scaling added 7")
    # a threshold from the command line
    assert main(["run", str(deck), "--out", str(tmp_path / "out2"), "--no-vtk", "--quiet",
                 "--quality", "added_mass_suspect_percent=50"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("normal termination - WARNING: mass scaling added 7")
    assert main(["run", str(deck), "--quality", "nonsense=1"]) == 2
    assert "unknown quality threshold" in capsys.readouterr().err


def _one_cube(vad: int):
    """One elastic hex (10 mm, E 1 GPa), free but for its node 8 pulled up at 1 mm/ms:
    by a velocity from t = 0 (VAD 0) or by a displacement ramp from rest (VAD 2)."""
    from hollowbody.io.keyword import (
        ControlTermination,
        ControlTimestep,
        DatabaseAscii,
        Deck,
        DefineCurve,
        Hourglass,
        MatElastic,
        Part,
        PrescribedMotionNode,
        SectionSolid,
    )
    from hollowbody.mesh import standing_block

    xb, cb = standing_block((10.0, 10.0, 10.0), 10.0)
    ids = np.arange(1, 9)
    d = Deck()
    d.add_nodes(ids, xb)
    d.add_solids(np.array([1]), 1, ids[cb])
    d.add(Part(pid=1, secid=1, mid=1, hgid=1))
    d.add(SectionSolid(secid=1))
    d.add(MatElastic(mid=1, ro=1e-6, e=1.0, pr=0.3))
    d.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    pts = [[0.0, 1.0], [100.0, 1.0]] if vad == 0 else [[0.0, 0.0], [1.0, 1.0]]
    d.add(DefineCurve(lcid=1, points=pts))
    d.add(PrescribedMotionNode(nid=8, dof=3, vad=vad, lcid=1))
    d.add(ControlTermination(endtim=1.0))
    d.add(ControlTimestep(tssfac=0.9))
    d.add(DatabaseAscii(name="GLSTAT", dt=0.01))
    return d


def test_prescribed_node_from_rest_balances_like_a_prescribed_velocity(tmp_path):
    # the VAD 2 node jumps from rest to 1 mm/ms: its reaction impulse m dv does
    # work m dv (0 + 1) / 2 = 1/2 m, its kinetic energy; m dv . v counted m
    # (twice it) and the energy ratio fell to 0.58
    for vad in (0, 2):
        _run(_one_cube(vad), tmp_path / str(vad))
    g0 = read_history(tmp_path / "0" / "glstat.csv")
    g2 = read_history(tmp_path / "2" / "glstat.csv")
    m_node = 1e-6 * 1000.0 / 8  # kg
    assert g0["kinetic [J]"][0] == pytest.approx(0.5 * m_node * 1.0 ** 2, rel=1e-12)
    assert g2["kinetic [J]"][0] == 0.0
    # the same motion from the second cycle on: the same balance
    e0 = g0["external_work [J]"] + g0["kinetic [J]"][0]
    e2 = g2["external_work [J]"]
    np.testing.assert_allclose(e2[2:], e0[2:], rtol=1e-6)
    assert np.abs(g2["energy_ratio"][2:] - g0["energy_ratio"][2:]).max() < 1e-6
