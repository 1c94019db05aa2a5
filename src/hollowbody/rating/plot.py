"""Plots of a response against a corridor, specimen curves and a reference.

Figures are drawn with matplotlib's Agg canvas directly (no pyplot, no
global backend switch), so plotting works on machines without a display and
does not disturb a caller's own matplotlib set-up.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from hollowbody.rating.corridors import Corridor

Curve = tuple[np.ndarray, np.ndarray]


def plot_corridor(path: str | Path, *, corridor: Corridor | None = None,
                  response: Curve | None = None, specimens: Sequence[Curve] = (),
                  reference: Curve | None = None, title: str = "",
                  xlabel: str = "time [ms]", ylabel: str = "force [kN]",
                  response_label: str = "response", reference_label: str = "reference",
                  specimen_labels: Sequence[str] | None = None,
                  note: str = "", dpi: int = 120) -> Path:
    """Draw a response against a corridor and specimen curves; save as PNG.

    Parameters
    ----------
    path : str or Path
        Output file (format from the suffix, PNG recommended).
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
    note : str
        Text put in the lower right corner (e.g. the ratings).

    Returns
    -------
    Path
        The written file.
    """
    fig = Figure(figsize=(7.0, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    if corridor is not None:
        ring = corridor.outline
        ax.fill(ring[:, 0], ring[:, 1], color="tab:blue", alpha=0.18, lw=0,
                label=corridor.name or "corridor")
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
        ax.legend(loc="upper right", fontsize=8)
    if note:
        ax.text(0.99, 0.02, note, transform=ax.transAxes, ha="right", va="bottom",
                fontsize=8, family="monospace",
                bbox={"boxstyle": "round", "fc": "white", "ec": "0.7", "alpha": 0.9})
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=dpi)
    return out
