"""Corridors from polygons, bounds and specimens; fraction inside; plots."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.rating.corridors import Corridor, plot_corridor


def test_polygon_envelope_of_a_trapezoid():
    # upper 0 -> (10, 3) -> (30, 3) -> (60, 1); lower back (60, 0) -> (35, 1.5) -> (20, 1.5)
    px = [0, 10, 30, 60, 60, 35, 20, 0]
    py = [0, 3, 3, 1, 0, 1.5, 1.5, 0]
    c = Corridor.from_polygon(px, py, name="trap")
    lo, up = c.bounds_at(np.array([0.0, 5.0, 10.0, 25.0, 47.5, 60.0]))
    assert up == pytest.approx([0.0, 1.5, 3.0, 3.0, 3.0 - 2.0 * 17.5 / 30.0, 1.0])
    assert lo == pytest.approx([0.0, 0.375, 0.75, 1.5, 1.5 * 12.5 / 25.0, 0.0])
    assert c.x_range == (0.0, 60.0) and c.name == "trap"
    assert c.outline.shape == (8, 2)  # closed outline without a duplicated first point


def test_polygon_with_a_vertical_step_keeps_the_step():
    # a box whose top drops from 2 to 1 at x = 1
    px = [0, 0, 1, 1, 2, 2]
    py = [0, 2, 2, 1, 1, 0]
    c = Corridor.from_polygon(px, py)
    assert list(c.x) == [0.0, 1.0, 1.0, 2.0]
    assert list(c.upper) == [2.0, 2.0, 1.0, 1.0] and list(c.lower) == [0.0] * 4
    assert c.contains(np.array([0.5, 1.5, 1.5]), np.array([1.8, 0.9, 1.1])).tolist() == [
        True, True, False]


def test_polygon_errors():
    with pytest.raises(ValueError):
        Corridor.from_polygon([0, 1], [0, 1])
    with pytest.raises(ValueError, match="same abscissa"):
        Corridor.from_polygon([1, 1, 1], [0, 1, 2])


def test_from_bounds_covers_the_common_range():
    c = Corridor.from_bounds([0, 7, 8], [0, 1.5, 1.5], [0, 5, 10], [0, 3.2, 3.2])
    assert c.x_range == (0.0, 8.0)
    lo, up = c.bounds_at(np.array([5.0, 8.0, 9.0]))
    assert lo[:2] == pytest.approx([1.5 * 5 / 7, 1.5]) and up[:2] == pytest.approx([3.2, 3.2])
    assert np.isnan(lo[2]) and np.isnan(up[2])


def test_from_specimens_is_mean_plus_minus_sd():
    x = np.linspace(0.0, 10.0, 11)
    curves = [(x, np.full(11, 1.0)), (x, np.full(11, 3.0)), (x + 5.0, np.full(11, 2.0))]
    c = Corridor.from_specimens(curves, n_sd=1.0, n_points=6)
    assert c.x_range == (5.0, 10.0)
    assert c.center == pytest.approx(np.full(6, 2.0))
    assert c.upper == pytest.approx(np.full(6, 3.0)) and c.lower == pytest.approx(np.ones(6))
    c2 = Corridor.from_specimens(curves, n_sd=2.0)
    assert c2.upper[0] == pytest.approx(4.0)
    with pytest.raises(ValueError):
        Corridor.from_specimens(curves[:1])


def test_fraction_inside_counts_samples_in_range():
    c = Corridor(np.array([0.0, 10.0]), np.array([0.0, 0.0]), np.array([1.0, 1.0]))
    t = np.arange(0.0, 20.0, 1.0)                    # 11 samples in range 0..10
    y = np.where(t < 4.0, 0.5, 2.0)                  # 4 of them inside
    assert c.fraction_inside(t, y) == pytest.approx(4 / 11)
    assert np.isnan(c.fraction_inside(t + 100.0, y))
    assert c.widened(1.0).fraction_inside(t, y) == pytest.approx(1.0)
    with pytest.raises(ValueError):
        c.widened(-1.0)


def test_invalid_corridors():
    with pytest.raises(ValueError):
        Corridor(np.array([0.0, 1.0]), np.array([2.0, 2.0]), np.array([1.0, 1.0]))
    with pytest.raises(ValueError):
        Corridor(np.array([1.0, 0.0]), np.zeros(2), np.ones(2))


def test_plot_writes_a_png(tmp_path):
    x = np.linspace(0, 10, 50)
    c = Corridor.from_specimens([(x, np.sin(x)), (x, np.sin(x) + 0.3)])
    out = plot_corridor(tmp_path / "c.png", corridor=c, response=(x, np.sin(x) + 0.1),
                        specimens=[(x, np.sin(x))], reference=(x, np.sin(x)),
                        title="t", note="R = 1")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
