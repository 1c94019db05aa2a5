"""Signals of a test run, and their ratings, on synthetic run folders.

The run folder is written with the solver's own history writer, from analytic
signals: a hub travelling along an oblique direction at constant speed, a
half-sine contact force on it, and a reference node moving along the same
direction. The signals read back must be those (exact up to the CFC filter,
which is checked separately), and the ratings must rank a curve equal to the
test mean above one three times too large.
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.io.keyword import Deck
from hollowbody.io.results.history import HistoryWriter
from hollowbody.solver.outputs import NODOUT_COLUMNS, RCFORC_COLUMNS
from hollowbody.validation.cases import CASES
from hollowbody.validation.ratings import rate, rate_run, reference_data
from hollowbody.validation.setup import Setup
from hollowbody.validation.signals import read_signals

RBDOUT = ["time [ms]", "part", "ux [mm]", "uy [mm]", "uz [mm]", "vx [mm/ms]", "vy [mm/ms]",
          "vz [mm/ms]", "fx [kN]", "fy [kN]", "fz [kN]"]
D = np.array([-0.5, -np.sqrt(3.0) / 2.0, 0.0])  # 30 deg forward of lateral, from the left


def _setup(**kw) -> Setup:
    base = dict(case="thorax", speed=4.4, tissue="solid", deck=Deck(), end_time=60.0,
                impactor_pid=900, impactor_mass=23.4, contact_id=90, direction=tuple(D),
                impact_point=(0.0, 150.0, 1275.0), contact_time=0.5, reference_node=77)
    base.update(kw)
    return Setup(**base)


def write_run(folder, s: Setup, force, ref_disp, t) -> None:
    """Histories of a hub moving at s.speed along s.direction from t = 0, a contact
    force ``force(t)`` [kN] pushing it back, a reference node at ``ref_disp(t)`` mm."""
    d = np.asarray(s.direction)
    rc = HistoryWriter(folder / "rcforc.csv", list(RCFORC_COLUMNS))
    rb = HistoryWriter(folder / "rbdout.csv", RBDOUT)
    nd = HistoryWriter(folder / "nodout.csv", list(NODOUT_COLUMNS))
    for ti in t:
        f_hub = -force(ti) * d  # the body pushes the hub back
        rc.write([ti, s.contact_id, *(-f_hub), *f_hub])
        rc.write([ti, s.contact_id + 1, 1.0, 2.0, 3.0, -1.0, -2.0, -3.0])  # another contact
        rb.write([ti, s.impactor_pid, *(s.speed * ti * d), *(s.speed * d), *f_hub])
        nd.write([ti, s.reference_node, *(ref_disp(ti) * d), 0.0, 0.0, 0.0])
        nd.write([ti, 5, *(s.speed * ti * d), *(s.speed * d)])  # a node of the hub
    ti = t[-1]  # the last state written twice, as at the end of a run
    rc.write([ti, s.contact_id, *(force(ti) * d), *(-force(ti) * d)])
    for w in (rc, rb, nd):
        w.close()


def _half_sine(peak: float, t0: float, width: float):
    return lambda t: peak * np.sin(np.pi * (t - t0) / width) if t0 < t < t0 + width else 0.0


def test_signals_are_the_projected_histories(tmp_path):
    s = _setup()
    t = np.round(np.arange(0.0, 40.0001, 0.1), 6)
    write_run(tmp_path, s, _half_sine(2.0, 0.5, 30.0), lambda ti: 0.05 * ti * ti, t)
    sig = read_signals(tmp_path, s, cfc=None)
    # time zero at contact
    assert sig.time[0] == pytest.approx(-0.5)
    f = np.array([_half_sine(2.0, 0.5, 30.0)(ti) for ti in t])
    np.testing.assert_allclose(sig.force, f, atol=1e-9)
    # deflection: hub travel past the gap minus the reference node's displacement
    np.testing.assert_allclose(sig.deflection, 4.4 * t - 0.05 * t * t - 4.4 * 0.5,
                               atol=1e-6)
    assert sig.moment is None
    # the same travel from a history node of the hub (what external engines give)
    by_node = read_signals(tmp_path, _setup(impactor_node=5, impactor_pid=-1), cfc=None)
    np.testing.assert_allclose(by_node.deflection, sig.deflection, atol=1e-9)
    tt, ff = sig.curve("force")
    assert tt[0] >= 0.0 and ff.size == np.count_nonzero(sig.time >= 0.0)
    # the loading branch ends at the largest deflection (d' = 4.4 - 0.1 t = 0 at 44 ms:
    # beyond the run, so the whole run is loading), strictly increasing
    x, y = sig.curve("force_deflection")
    assert np.all(np.diff(x) > 0.0) and x[-1] == pytest.approx(sig.deflection.max())


def test_filtered_force_keeps_a_slow_pulse(tmp_path):
    """CFC 180 (-3 dB near 300 Hz) leaves a 30 ms half-sine (17 Hz) within 0.5 % of
    its peak; it is the filter of the impactor channels, not a smoother of the pulse."""
    s = _setup()
    t = np.round(np.arange(0.0, 40.0001, 0.1), 6)
    write_run(tmp_path, s, _half_sine(2.0, 0.5, 30.0), lambda ti: 0.0, t)
    sig = read_signals(tmp_path, s)
    assert sig.force.max() == pytest.approx(2.0, rel=5e-3)


def test_bending_moment_is_f_a_b_over_span(tmp_path):
    s = _setup(case="thigh-bending", speed=1.5, direction=(0.0, -1.0, 0.0), reference_node=None,
               span=400.0, load_a=150.0, load_b=250.0, contact_time=2.0)
    t = np.round(np.arange(0.0, 20.0001, 0.1), 6)
    write_run(tmp_path, s, _half_sine(3.0, 2.0, 20.0), lambda ti: 0.0, t)
    sig = read_signals(tmp_path, s, cfc=None)
    np.testing.assert_allclose(sig.moment, sig.force * 150.0 * 250.0 / 400.0)
    np.testing.assert_allclose(sig.deflection, 1.5 * (t - 2.0), atol=1e-9)


def test_missing_rows_name_the_file(tmp_path):
    from hollowbody.errors import UserInputError

    s = _setup()
    t = np.arange(0.0, 2.0, 0.1)
    write_run(tmp_path, s, _half_sine(1.0, 0.0, 2.0), lambda ti: 0.0, t)
    with pytest.raises(UserInputError, match="rcforc.csv: no rows for contact 5"):
        read_signals(tmp_path, _setup(contact_id=5))
    with pytest.raises(UserInputError, match="nodout.csv: no rows for reference node 8"):
        read_signals(tmp_path, _setup(reference_node=8))
    with pytest.raises(UserInputError, match="glstat|missing"):
        read_signals(tmp_path / "nothing", s)


def test_the_test_mean_rates_high_and_a_tripled_curve_low():
    """Rated against the Viano 1989 thorax 4.4 m/s data, the specimen mean itself must
    score near the top (cross-correlation 1 by construction; the corridor part < 1 only
    where the mean leaves the corridor) and three times the mean must score far lower."""
    case = CASES["thorax"]
    data = reference_data(case, 4.4, "force")
    assert data is not None and data.corridor is not None and len(data.specimens) == 4
    x, y = data.reference
    good = rate(x, y, data.reference, "force", "test", data.corridor)
    bad = rate(x, 3.0 * y, data.reference, "force", "test", data.corridor)
    assert good.error is None and bad.error is None
    assert good.cora_cross == pytest.approx(1.0, abs=1e-6)
    assert good.iso == pytest.approx(1.0, abs=1e-6)
    assert good.cora > 0.8 and good.inside > 0.8
    assert bad.cora < good.cora - 0.3 and bad.iso < 0.5 and bad.inside < 0.5


def test_no_data_no_test_rating_but_hollow_against_solid():
    case = CASES["shoulder"]
    assert reference_data(case, 4.4, "force") is None
    assert reference_data(CASES["thorax"], 5.0, "force") is None  # not a test speed
    assert reference_data(CASES["pelvis"], 9.8, "force").corridor is None  # specimens only


def test_rate_run_rates_each_quantity_against_test_and_solid(tmp_path):
    s = _setup()
    t = np.round(np.arange(0.0, 60.0001, 0.1), 6)
    write_run(tmp_path, s, _half_sine(2.2, 0.5, 40.0), lambda ti: 0.02 * ti * ti, t)
    sig = read_signals(tmp_path, s)
    out = rate_run(CASES["thorax"], 4.4, sig, solid=sig)
    kinds = {(r.quantity, r.against) for r in out}
    assert kinds == {("force", "test"), ("force", "solid"), ("force_deflection", "test"),
                     ("force_deflection", "solid")}
    same = [r for r in out if r.against == "solid"]
    assert all(r.error is None and r.cora == pytest.approx(1.0, abs=1e-6) for r in same)


def test_a_curve_that_never_rises_is_kept_with_its_reason():
    x = np.linspace(0.0, 10.0, 101)
    r = rate(x, np.zeros_like(x), (x, np.zeros_like(x)), "force", "solid")
    assert r.error and r.cora is None and "not rated" in r.short()
