"""Force-displacement plots: legend entries, filter labels, direction marks, notes."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.text import Annotation  # noqa: E402

from hollowbody.curves.force_displacement import ForceDisplacement, smoothed  # noqa: E402
from hollowbody.curves.plot import (  # noqa: E402
    TURN_LABEL,
    add_legend,
    clip_force_axis,
    draw_curve,
    filter_label,
    mark_direction,
)


def loop_curve(label: str = "solid") -> ForceDisplacement:
    """Loading to 40 mm and unloading, with a first-contact spike (kN, mm, ms)."""
    t = np.linspace(0.0, 10.0, 501)
    d = 40.0 * np.sin(np.pi * t / 12.0)  # max displacement at 6 ms
    f = np.where(t <= 6.0, 0.3 * d, 0.3 * d * np.exp(-(t - 6.0))) + 0.0
    f[1:3] = 45.0
    return ForceDisplacement(t, d, f, label)


def test_filter_label_names_the_class_used():
    assert filter_label(180.0) == "CFC 180"
    assert filter_label(600) == "CFC 600"
    assert filter_label(None) == "unfiltered" and filter_label(0.0) == "unfiltered"


def test_draw_curve_legend_has_raw_filtered_and_turning_point():
    c = loop_curve()
    sm = smoothed(c, 180.0)
    fig, ax = plt.subplots()
    draw_curve(ax, (c.displacement, c.force), (sm.displacement, sm.force), colour="C0",
               label="solid", cfc=180.0)
    h = loop_curve("hollow")
    sh = smoothed(h, 180.0)
    draw_curve(ax, (h.displacement, h.force), (sh.displacement, 0.5 * sh.force),
               colour="C3", label="hollow", cfc=180.0, turn_label=None)
    legend = add_legend(ax)
    labels = [t.get_text() for t in legend.get_texts()]
    assert labels == ["solid raw", "solid CFC 180", "hollow raw", "hollow CFC 180",
                      TURN_LABEL]
    # raw faint and thin, filtered bold, same colour per curve
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    assert lines["solid raw"].get_linewidth() < lines["solid CFC 180"].get_linewidth()
    assert lines["solid raw"].get_alpha() < 1.0
    assert lines["solid raw"].get_color() == lines["solid CFC 180"].get_color()
    plt.close(fig)


def test_direction_arrows_point_along_loading_and_unloading():
    c = loop_curve()
    sm = smoothed(c, 180.0)
    fig, ax = plt.subplots()
    mark_direction(ax, sm.displacement, sm.force, "C0")
    arrows = [a for a in ax.texts if isinstance(a, Annotation) and a.arrow_patch]
    assert len(arrows) == 2
    (x0, _), (x1, _) = arrows[0].xyann, arrows[0].xy  # tail -> head
    assert x1 > x0  # loading: displacement grows
    (x0, _), (x1, _) = arrows[1].xyann, arrows[1].xy
    assert x1 < x0  # unloading: displacement falls
    # the ring sits at the maximum displacement
    ring = [ln for ln in ax.get_lines() if ln.get_marker() == "o" and len(ln.get_xdata())]
    assert ring[0].get_xdata()[0] == pytest.approx(float(sm.displacement.max()))
    plt.close(fig)


def test_clip_note_is_below_the_axes_clear_of_the_data():
    c = loop_curve()
    sm = smoothed(c, 180.0)
    fig, ax = plt.subplots()
    ax.plot(sm.displacement, sm.force)
    raw_top = clip_force_axis(ax, [sm.force], [c.force])
    assert raw_top == pytest.approx(45.0)
    notes = [t for t in ax.texts if "clipped" in t.get_text()]
    assert len(notes) == 1
    fig.canvas.draw()
    box = notes[0].get_window_extent()
    axes_box = ax.get_window_extent()
    assert box.y1 < axes_box.y0  # wholly below the plotting area
    plt.close(fig)


def test_filtered_curve_starts_near_zero_force_at_zero_displacement():
    """The smoothed curve of a force that is zero at first contact starts at zero
    (a first-contact spike of 45 kN does not smear into the start)."""
    c = loop_curve()
    for cfc in (180.0, 600.0):
        sm = smoothed(c, cfc)
        assert sm.displacement[0] == 0.0
        assert abs(sm.force[0]) < 1e-6
        assert abs(c.force_filtered(cfc)[0]) < 1e-6
