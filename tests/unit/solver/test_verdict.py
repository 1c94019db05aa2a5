"""The run verdict from a summary: every indicator at its warning and suspect limits."""

from __future__ import annotations

import pytest

from hollowbody.solver.verdict import (
    OK,
    SUSPECT,
    WARNING,
    Thresholds,
    assess,
    headline,
    quality_of,
    verdict_of,
)


def _summary(**over) -> dict:
    """A sound run's summary: 10 J in, balance kept, little hourglass, nothing else."""
    s = {"energy_ratio": 1.0, "nodes": 1000, "dt_initial_ms": 1e-3, "dt_min_ms": 0.5e-3,
         "energies_J": {"kinetic": 2.0, "internal": 7.5, "hourglass": 0.3, "contact": 0.2,
                        "total": 10.0},
         "mass_scaling": {"added_mass_percent": 0.0},
         "contact_pass_through": {"1": {"events": 0, "nodes": 0}}}
    for k, v in over.items():
        if k in ("kinetic", "internal", "hourglass", "contact", "total"):
            s["energies_J"][k] = v
        else:
            s[k] = v
    return s


def _indicators(summary: dict, th: Thresholds | None = None) -> dict[str, str]:
    return {r["indicator"]: r["level"] for r in assess(summary, th)[1]}


def test_a_sound_run_is_ok():
    assert assess(_summary()) == (OK, [])
    assert headline(OK, []) == "quality ok"


@pytest.mark.parametrize("ratio, level", [(1.05, None), (0.95, None), (1.15, WARNING),
                                          (0.85, WARNING), (1.25, SUSPECT), (0.7, SUSPECT),
                                          (10.05, SUSPECT)])
def test_energy_ratio_bands(ratio, level):
    assert _indicators(_summary(energy_ratio=ratio)).get("energy_ratio") == level


@pytest.mark.parametrize("hg, level", [(0.7, None), (1.0, WARNING), (3.0, SUSPECT)])
def test_hourglass_share_of_internal_energy(hg, level):
    # internal 7.5 J: 0.7 J = 9 %, 1.0 J = 13 %, 3.0 J = 40 %
    assert _indicators(_summary(hourglass=hg)).get("hourglass") == level


def test_hourglass_negligible_against_the_total_is_not_flagged():
    # 50 % of a tiny internal energy, but 0.5 % of the energy of the run
    assert "hourglass" not in _indicators(_summary(internal=0.1, hourglass=0.05))


def test_hourglass_without_internal_energy_is_suspect():
    assert _indicators(_summary(internal=0.0, hourglass=1.0))["hourglass"] == SUSPECT


@pytest.mark.parametrize("hg, level", [(-0.1, None), (-0.5, WARNING), (-2.3, SUSPECT)])
def test_negative_hourglass_energy(hg, level):
    # total 10 J: -0.1 J = 1 % (below the 2 % warning), -0.5 J = 5 %, -2.3 J = 23 %; energy
    # an hourglass form created (viscous forms dissipate, stiffness forms store >= 0)
    ind = _indicators(_summary(hourglass=hg))
    assert ind.get("hourglass_negative") == level
    assert "hourglass" not in ind  # the share of internal energy is not graded then


@pytest.mark.parametrize("ce, level", [(-0.1, None), (-0.5, WARNING), (-2.3, SUSPECT),
                                       (0.5, None)])
def test_negative_contact_energy(ce, level):
    assert _indicators(_summary(contact=ce)).get("contact_energy") == level


@pytest.mark.parametrize("dtmin, level", [(0.02e-3, None), (0.5e-5, WARNING),
                                          (0.5e-6, SUSPECT)])
def test_time_step_collapse(dtmin, level):
    assert _indicators(_summary(dt_min_ms=dtmin)).get("time_step") == level


@pytest.mark.parametrize("pct, level", [(1.0, None), (4.4, WARNING), (7.3, SUSPECT)])
def test_added_mass(pct, level):
    s = _summary(mass_scaling={"added_mass_percent": pct})
    assert _indicators(s).get("added_mass") == level


@pytest.mark.parametrize("nodes, level", [(0, None), (1, WARNING), (10, WARNING),
                                          (11, SUSPECT)])
def test_pass_through(nodes, level):
    # 1000 nodes: any node through a surface warns, more than 1 % is suspect
    s = _summary(contact_pass_through={"1": {"events": nodes, "nodes": nodes}})
    assert _indicators(s).get("pass_through") == level


def test_the_worst_indicator_decides_and_the_headline_lists_it_first():
    s = _summary(energy_ratio=10.05, hourglass=8.0, mass_scaling={"added_mass_percent": 3.0})
    quality, reasons = assess(s)
    assert quality == SUSPECT
    assert [r["level"] for r in reasons] == [SUSPECT, SUSPECT, WARNING]
    text = headline(quality, reasons)
    assert text.startswith("SUSPECT: energy ratio 10.1, hourglass 107 % of internal energy")
    assert "also mass scaling added 3 % mass" in text


def test_thresholds_are_overridable_and_parsed():
    th = Thresholds.parse(["energy_ratio_warn=0.01", "hourglass_suspect = 2"])
    assert th.energy_ratio_warn == 0.01 and th.hourglass_suspect == 2.0
    assert _indicators(_summary(energy_ratio=1.03), th)["energy_ratio"] == WARNING
    assert _indicators(_summary(hourglass=3.0), th)["hourglass"] == WARNING
    with pytest.raises(ValueError, match="unknown quality threshold"):
        Thresholds.parse(["energy_band=0.1"])
    with pytest.raises(ValueError, match="not a number"):
        Thresholds.parse(["hourglass_warn=high"])


def test_a_summary_without_a_verdict_is_assessed_and_one_with_it_is_kept():
    s = _summary(energy_ratio=2.0)
    assert quality_of(s) == SUSPECT
    kept = {**_summary(), "quality": WARNING, "quality_reasons": [{"message": "x"}]}
    assert verdict_of(kept) == (WARNING, [{"message": "x"}])
    assert quality_of(None) is None
    assert quality_of({"status": "normal termination", "surrogate": True}) is None


def _energies(ratio: float, hourglass: float = 0.3, time_ms: float | None = None) -> dict:
    e = {"kinetic": 2.0, "internal": 7.5, "hourglass": hourglass, "contact": 0.2,
         "total": 10.0 * ratio, "energy_ratio": ratio}
    if time_ms is not None:
        e["time_ms"] = time_ms
    return e


@pytest.mark.parametrize("status, last, prev, kept", [
    ("error termination", 4.9e26, 1.0002, True),   # collapse in the failing cycle
    ("error termination", 4.9e26, 1.28, False),    # unbalanced before it: no excuse
    ("error termination", 1.0001, 1.0002, False),  # balanced to the end
    ("error termination", 1.25, 1.09, False),  # drifting out: graded as it ends
    ("error termination", 2.5, 1.0002, True),  # energy more than doubled in one interval
    ("error termination", float("nan"), 1.0002, True),  # not finite
    ("normal termination", 4.9e26, 1.0002, False),  # only error terminations
])
def test_before_error_keeps_the_last_balanced_record(status, last, prev, kept):
    from hollowbody.solver.verdict import before_error

    got = before_error(status, _energies(last), _energies(prev, time_ms=3.86))
    assert bool(got) is kept
    if kept:
        assert got["energies_before_error_J"]["energy_ratio"] == prev
        assert got["energies_before_error_J"]["time_ms"] == 3.86
    assert before_error("error termination", _energies(4.9e26), {}) == {}
    # the first record's predecessor has no energies
    assert before_error("error termination", _energies(4.9e26), {"time_ms": 0.0}) == {}
    # a user's tighter band: 1.0002 is not balanced within 1e-4
    from hollowbody.solver.verdict import Thresholds as T

    assert before_error("error termination", _energies(4.9e26), _energies(1.0002, time_ms=1.0),
                        T(energy_ratio_warn=1e-4)) == {}


def test_an_error_terminations_failing_cycle_is_named_and_the_rest_graded_before_it():
    """The energy indicators of a run whose element collapsed in its last cycle are those
    of the last balanced record (hourglass 12 % there: a warning), and the failing cycle's
    imbalance is named with the time of that record."""
    s = _summary(energy_ratio=4.9e26, status="error termination")
    s["energies_J"] = _energies(4.9e26, hourglass=0.01)
    s["energies_before_error_J"] = _energies(1.0002, hourglass=0.9, time_ms=3.8601)
    q, reasons = assess(s)
    by = {r["indicator"]: r for r in reasons}
    assert "energy_ratio" not in by  # 1.0002 before the failing cycle
    assert by["failing_cycle"]["level"] == WARNING
    assert "4.9e+26 in the failing cycle" in by["failing_cycle"]["message"]
    assert "t=3.8601 ms, one output interval before" in by["failing_cycle"]["message"]
    assert by["hourglass"]["level"] == WARNING and by["hourglass"]["value"] == pytest.approx(0.12)
    assert q == WARNING


def test_a_failing_cycle_with_energies_not_finite_is_named_too():
    s = _summary(energy_ratio=float("nan"), status="error termination")
    s["energies_before_error_J"] = _energies(1.0002, time_ms=0.46)
    q, reasons = assess(s)
    (fc,) = [r for r in reasons if r["indicator"] == "failing_cycle"]
    assert fc["message"].startswith("energy ratio not finite in the failing cycle; 1.0002")
    assert q == WARNING
