"""The run monitors: each warns once, names where, and ignores negligible energies."""

from __future__ import annotations

from hollowbody.solver.monitors import Monitors


def _check(m: Monitors, **kw):
    args = dict(t=1.0, energy_ratio=1.0, internal=10.0, hourglass=0.0,
                part_energy={1: 5.0, 2: 5.0}, part_hourglass={1: (0.0, -1), 2: (0.0, -1)},
                dt=1e-3, dt_elem=7, dt_part=2, total=100.0)
    args.update(kw)
    return m.check(**args)


def test_hourglass_warns_once_naming_part_and_element():
    m = Monitors(dt_initial=1e-3)
    w = _check(m, internal=10.0, hourglass=2.0, part_hourglass={1: (0.1, -1), 2: (1.9, 44)})
    assert len(w) == 1 and w[0]["kind"] == "hourglass"
    assert "part 2, element 44" in w[0]["message"] and "20.0%" in w[0]["message"]
    assert _check(m, internal=10.0, hourglass=3.0, part_hourglass={2: (3.0, 44)}) == []


def test_negligible_hourglass_at_the_start_is_not_a_warning():
    """Before anything deforms both energies are round-off (1e-40 J): their ratio means
    nothing. Below 1 % of the run's energy (the verdict's 'negligible') no warning;
    the same share once it matters warns."""
    m = Monitors(dt_initial=1e-3)
    assert _check(m, internal=5e-41, hourglass=2.4e-40,
                  part_hourglass={1: (2.4e-40, 3)}) == []
    w = _check(m, internal=5.0, hourglass=2.0, part_hourglass={1: (2.0, 3)})
    assert [x["kind"] for x in w] == ["hourglass"]


def test_without_total_the_old_rule_holds():
    m = Monitors(dt_initial=1e-3)
    w = _check(m, internal=5e-41, hourglass=2.4e-40, part_hourglass={1: (2.4e-40, 3)},
               total=None)
    assert [x["kind"] for x in w] == ["hourglass"]


def test_energy_ratio_names_the_part_that_grew_most():
    m = Monitors(dt_initial=1e-3)
    assert _check(m) == []
    w = _check(m, energy_ratio=1.3, part_energy={1: 5.0, 2: 9.0})
    assert w[0]["kind"] == "energy_ratio" and "part 2" in w[0]["message"]
