"""Plots of force-displacement curves: raw and CFC-filtered force over displacement.

Every plot of the project draws a curve the same way (:func:`draw_curve`): the
raw force thin and faint, the filtered force bold, both in the legend (the
filtered one with the filter class actually used), and the direction of
travel marked: arrows along the loading and the unloading branch of the
filtered curve and a ring at the maximum displacement, where loading turns
into unloading. :func:`clip_force_axis` keeps single-cycle raw contact spikes
from flattening the filtered curves; its note, like every note of these plots
(:func:`add_note`), is written below the axes, clear of the data and the
legend.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from hollowbody.curves.force_displacement import ForceDisplacement

#: Filter class of the run folders' force-displacement plot and CSV (Hz).
RUN_CFC = 600.0
#: Legend text of the turning-point marker.
TURN_LABEL = "max displacement (loading \u2192 unloading)"


def filter_label(cfc: float | None) -> str:
    """Legend text of a filter class: ``"CFC 180"``, or ``"unfiltered"`` for None/0."""
    return f"CFC {cfc:g}" if cfc else "unfiltered"


def _arrow(ax: Any, x: np.ndarray, y: np.ndarray, scale: tuple[float, float],
           where: float, colour: str) -> None:
    """An arrowhead on the polyline (x, y) at fraction ``where`` of its length."""
    if x.size < 2:
        return
    seg = np.hypot(np.diff(x) / scale[0], np.diff(y) / scale[1])
    length = np.concatenate([[0.0], np.cumsum(seg)])
    if length[-1] <= 0.0:
        return
    i = int(np.searchsorted(length, where * length[-1]))
    i = min(max(i, 1), x.size - 1)
    j = i - 1
    while j > 0 and length[i] - length[j] < 0.01 * length[-1]:
        j -= 1
    if length[i] == length[j]:
        return
    ax.annotate("", xy=(x[i], y[i]), xytext=(x[j], y[j]),
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.2,
                            "mutation_scale": 14, "shrinkA": 0, "shrinkB": 0})


def mark_direction(ax: Any, displacement: np.ndarray, force: np.ndarray, colour: str,
                   label: str | None = TURN_LABEL) -> None:
    """Arrows along the loading and unloading branch of a curve (displacement (k,) mm,
    force (k,) kN) and a ring at its maximum displacement (``label`` in the legend)."""
    x = np.asarray(displacement, dtype=float)
    y = np.asarray(force, dtype=float)
    if x.size < 3:
        return
    k = int(np.argmax(x))
    scale = (max(float(np.ptp(x)), 1e-12), max(float(np.ptp(y)), 1e-12))
    _arrow(ax, x[:k + 1], y[:k + 1], scale, 0.45, colour)
    if k < x.size - 2:
        _arrow(ax, x[k:], y[k:], scale, 0.5, colour)
    ring = {"ls": "", "marker": "o", "ms": 7, "mfc": "none", "mew": 1.4}
    ax.plot([x[k]], [y[k]], mec=colour, **ring)
    if label:
        ax.plot([], [], mec="0.25", label=label, **ring)


def add_legend(ax: Any, **kwargs: Any) -> Any:
    """The axes' legend (if it has entries) with the turning-point entry last;
    ``kwargs`` go to ``ax.legend`` (fontsize 8 by default). Returns it or None."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    order = sorted(range(len(labels)), key=lambda i: labels[i] == TURN_LABEL)
    kwargs.setdefault("fontsize", 8)
    return ax.legend([handles[i] for i in order], [labels[i] for i in order], **kwargs)


def draw_curve(ax: Any, raw: tuple[np.ndarray, np.ndarray],
               filtered: tuple[np.ndarray, np.ndarray], *, colour: str, label: str,
               cfc: float | None, ls: str = "-", show_raw: bool = True,
               turn_label: str | None = TURN_LABEL) -> Any:
    """One curve: raw (displacement, force) thin and faint, filtered bold with the
    direction marks. Legend: ``"<label> raw"`` and ``"<label> <filter>"`` (the class
    ``cfc`` the filtered force was made with). Arrays (k,) in mm and kN; returns the
    filtered line."""
    prefix = f"{label} " if label else ""
    if show_raw:
        ax.plot(raw[0], raw[1], color=colour, lw=0.5, alpha=0.35, ls=ls,
                label=f"{prefix}raw")
    line, = ax.plot(filtered[0], filtered[1], color=colour, lw=1.8, ls=ls,
                    label=f"{prefix}{filter_label(cfc)}")
    mark_direction(ax, filtered[0], filtered[1], colour, label=turn_label)
    return line


def add_note(ax: Any, text: str) -> Any:
    """A note in small grey type below the axes (right-aligned under the axis label),
    clear of the data and the legend; ``fig.tight_layout`` makes room for it."""
    n_notes = sum(1 for t in ax.texts if getattr(t, "_hollowbody_note", False))
    note = ax.annotate(text, xy=(1.0, 0.0), xycoords="axes fraction",
                       xytext=(0.0, -30.0 - 10.0 * n_notes), textcoords="offset points",
                       ha="right", va="top", fontsize=7, color="0.35")
    note._hollowbody_note = True
    return note


def plot(curves: list[ForceDisplacement], path: str | Path, title: str = "",
         cfc: float | None = RUN_CFC) -> None:
    """Force-displacement plot (PNG) of one or more curves, filtered with class ``cfc``
    (Hz; None: unfiltered) on their own time samples, as in the run's CSV."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6), dpi=120)
    filtered, raw = [], []
    for i, c in enumerate(curves):
        f = c.force_filtered(cfc) if cfc else np.asarray(c.force, dtype=float)
        filtered.append(f)
        raw.append(c.force)
        draw_curve(ax, (c.displacement, c.force), (c.displacement, f), colour=f"C{i}",
                   label=c.label, cfc=cfc, show_raw=bool(cfc),
                   turn_label=TURN_LABEL if i == 0 else None)
    ax.set_xlabel("impactor displacement [mm]")
    ax.set_ylabel("contact force [kN]")
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.set_xlim(left=0.0)
    clip_force_axis(ax, filtered, raw)
    add_legend(ax)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def clip_force_axis(ax: Any, filtered: list[np.ndarray], raw: list[np.ndarray],
                    factor: float = 1.3) -> float | None:
    """Limit a force axis to ``factor`` x the largest filtered force, so single-cycle raw
    contact spikes (first contact: several times the filtered peak) do not flatten the
    curves; a note below the axes names the clipped raw maximum (kN). Returns it, or
    None when nothing was clipped (axes left as they are)."""
    top = max((float(np.max(f)) for f in filtered if f.size), default=0.0)
    raw_top = max((float(np.max(r)) for r in raw if r.size), default=0.0)
    if top <= 0.0 or raw_top <= factor * top:
        return None
    low = min((float(np.min(f)) for f in filtered if f.size), default=0.0)
    ax.set_ylim(bottom=min(0.0, 1.1 * low), top=factor * top)
    add_note(ax, f"raw spikes up to {raw_top:.3g} kN clipped")
    return raw_top
