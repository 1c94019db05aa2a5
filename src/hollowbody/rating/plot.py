"""Plots of a response against a corridor, specimen curves and a reference.

Figures are drawn with matplotlib's Agg canvas directly (no pyplot, no
global backend switch), so plotting works on machines without a display and
does not disturb a caller's own matplotlib set-up.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from hollowbody.rating.corridors import Corridor

Curve = tuple[np.ndarray, np.ndarray]


def plot_corridor(path: str | Path, *, dpi: int = 120, **kwargs: Any) -> Path:
    """Draw a response against a corridor and specimen curves (:func:`corridor_figure`,
    same keyword arguments) and save it to ``path`` (format from the suffix, PNG
    recommended) at ``dpi``. Returns the written file."""
    fig = corridor_figure(**kwargs)
    out = Path(path)
    fig.savefig(out, dpi=dpi)
    return out


def corridor_figure(*, corridor: Corridor | None = None,
                    response: Curve | None = None, specimens: Sequence[Curve] = (),
                    reference: Curve | None = None, title: str = "",
                    xlabel: str = "time [ms]", ylabel: str = "force [kN]",
                    response_label: str = "response", reference_label: str = "reference",
                    specimen_labels: Sequence[str] | None = None,
                    corridor_label: str | None = None, note: str = "") -> Figure:
    """A figure of a response against a corridor and specimen curves.

    Parameters
    ----------
    corridor : Corridor, optional
        Drawn as a shaded band (its outline) with its mean line if it has one.
    response : (x, y), optional
        The curve being judged (arrays of shape (n,)), drawn bold.
    specimens : sequence of (x, y)
        Specimen (test) curves, drawn thin and grey.
    reference : (x, y), optional
        A single reference curve (e.g. the test the response is rated against).
    title, xlabel, ylabel : str
        Labels; the defaults suit force-time curves in hollowbody units.
    response_label, reference_label, specimen_labels, corridor_label : str
        Legend entries (the corridor's default: its name, else "corridor").
    note : str
        Text put below the axes at the right (e.g. the ratings), clear of the
        curves and the legend (placed where it covers the least data).

    Returns
    -------
    Figure
        The matplotlib figure (Agg canvas), laid out.
    """
    fig = Figure(figsize=(7.0, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    if corridor is not None:
        ring = corridor.outline
        ax.fill(ring[:, 0], ring[:, 1], color="tab:blue", alpha=0.18, lw=0,
                label=corridor_label or corridor.name or "corridor")
        ax.plot(ring[:, 0], ring[:, 1], color="tab:blue", lw=0.8)
        if corridor.center is not None:
            ax.plot(corridor.x, corridor.center, color="tab:blue", ls="--", lw=1.0,
                    label="corridor mean")
    for i, (x, y) in enumerate(specimens):
        label = None
        if specimen_labels is not None and i < len(specimen_labels):
            label = specimen_labels[i]
        elif i == 0:
            label = "specimens"
        ax.plot(x, y, color="0.55", lw=0.9, label=label)
    if reference is not None:
        ax.plot(reference[0], reference[1], color="k", lw=1.6, label=reference_label)
    if response is not None:
        ax.plot(response[0], response[1], color="tab:red", lw=2.0, label=response_label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.grid(True, lw=0.4, alpha=0.6)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=8)
    if note:
        ax.annotate(note, xy=(1.0, 0.0), xycoords="axes fraction", xytext=(0.0, -30.0),
                    textcoords="offset points", ha="right", va="top", fontsize=8,
                    family="monospace")
    fig.tight_layout()
    return fig
