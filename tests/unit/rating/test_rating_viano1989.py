"""Viano (1989) loaders read every packaged file correctly."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.rating import viano1989 as viano


def test_data_ship_with_notice_and_licence():
    names = {p.name for p in viano.data_dir().iterdir()}
    assert {"NOTICE.md", "LICENSE-Apache-2.0.txt", "Thorax.csv", "abdomen.csv"} <= names
    assert "Apache" in viano.data_dir().joinpath("NOTICE.md").read_text(encoding="utf-8")
    csv_files = {n for n in names if n.endswith(".csv")}
    assert len(csv_files) == 10


def test_available_lists_every_test_series():
    entries = viano.available()
    got = {(e["region"], e["speed"]): (e["specimens"], e["corridors"]) for e in entries}
    both = ("force_time", "force_deflection")
    assert got == {
        ("thorax", 4.4): (4, both), ("thorax", 6.5): (3, both), ("thorax", 9.5): (5, both),
        ("abdomen", 4.8): (5, both), ("abdomen", 6.8): (3, both), ("abdomen", 9.4): (4, both),
        ("pelvis", 5.2): (4, ("force_time",)), ("pelvis", 9.8): (4, ()),
    }


@pytest.mark.parametrize("entry", viano.available(), ids=lambda e: f"{e['region']}{e['speed']}")
def test_every_file_loads(entry):
    curves = viano.load_specimens(entry["region"], entry["speed"])
    for c in curves:
        assert c.time.size >= 20 and np.all(np.diff(c.time) > 0)
        assert c.time[0] < 0.2 and 25.0 < c.time[-1] < 61.0      # ms
        assert 1.0 < c.force.max() < 13.0                        # kN
    for kind in entry["corridors"]:
        corr = viano.load_corridor(entry["region"], entry["speed"], kind)
        assert corr.x[0] == 0.0 and np.all(corr.lower <= corr.upper)
        assert entry["region"] in corr.name
        if kind == "force_time":
            # the specimens mostly lie inside their own corridor
            inside = [corr.fraction_inside(c.time, c.force) for c in curves]
            assert np.mean(inside) > 0.5


def test_thorax_low_speed_values():
    curves = viano.load_specimens("thorax", 4.4)
    assert [c.name for c in curves] == ["17", "36", "40", "41"]
    assert curves[0].time[1] == pytest.approx(0.04990312)
    assert curves[0].force[1] == pytest.approx(0.104392799)
    ft = viano.load_corridor("Thorax", 4.4)
    lo, up = ft.bounds_at(np.array([10.0, 30.0, 60.0]))
    assert up == pytest.approx([3.2, 3.2, 1.0]) and lo == pytest.approx([0.75, 1.5, 0.0])
    fd = viano.load_corridor("thorax", 4.4, "force_deflection")
    # deflection converted from cm to mm; upper 3.2 kN from 50 mm, lower 1.5 kN at 70-80 mm
    assert fd.x_range == (0.0, 80.0)
    lo, up = fd.bounds_at(np.array([50.0, 70.0, 80.0]))
    assert up == pytest.approx([3.2, 3.2, 3.2]) and lo == pytest.approx([1.5 * 5 / 7, 1.5, 1.5])


def test_abdomen_column_order_and_medium_speed():
    ft = viano.load_corridor("abdomen", 6.8)
    assert ft.x_range == (0.0, 50.0)
    lo, up = ft.bounds_at(np.array([18.0, 26.0]))
    assert up == pytest.approx([4.5, 4.5]) and lo == pytest.approx([3.0, 3.0])
    fd = viano.load_corridor("abdomen", 6.8, "force_deflection")
    assert fd.x_range == (0.0, 120.0)


def test_pelvis_special_header():
    curves = viano.load_specimens("pelvis", 5.2)
    assert [c.name for c in curves] == ["21", "25", "26", "31"]   # "corr" is not a specimen
    assert curves[0].time[0] == pytest.approx(-0.050420481)
    assert curves[0].force[0] == pytest.approx(2.48e-05)
    corr = viano.load_corridor("pelvis", 5.2)
    assert corr.x_range == (0.0, 30.0)
    assert corr.bounds_at(np.array([10.0]))[1] == pytest.approx([8.0])
    assert [c.name for c in viano.load_specimens("pelvis", 9.8)] == ["22", "27", "32", "39"]


@pytest.mark.parametrize(("args", "words"), [
    (("neck", 4.4), "unknown region"),
    (("thorax", 5.0), "4.4, 6.5, 9.5"),
    (("pelvis", 9.8), "no force-time corridor"),
    (("pelvis", 5.2, "force_deflection"), "no force-deflection corridor"),
    (("thorax", 4.4, "stiffness"), "kind must be"),
])
def test_loader_errors(args, words):
    with pytest.raises(ValueError, match=words):
        viano.load_corridor(*args)
