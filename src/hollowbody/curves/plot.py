"""Plots of force-displacement curves: raw and CFC 600 filtered force over displacement.

:func:`clip_force_axis` keeps single-cycle raw contact spikes from flattening
the filtered curves; the reports use it for their overlays too.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hollowbody.curves.force_displacement import ForceDisplacement


def plot(curves: list[ForceDisplacement], path: str | Path, title: str = "") -> None:
    """Force-displacement plot (PNG) of one or more curves."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6), dpi=120)
    for c in curves:
        line, = ax.plot(c.displacement, c.force_filtered(), lw=1.8,
                        label=(c.label + " (CFC 600)") if c.label else "CFC 600")
        ax.plot(c.displacement, c.force, lw=0.6, alpha=0.4, color=line.get_color())
    ax.set_xlabel("impactor displacement [mm]")
    ax.set_ylabel("contact force [kN]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.set_xlim(left=0.0)
    top = max((c.peak_force for c in curves if c.force.size), default=1.0)
    ax.set_ylim(bottom=min(0.0, min((c.force_filtered().min() for c in curves
                                     if c.force.size), default=0.0)),
                top=1.3 * top if top > 0 else None)  # raw first-contact spikes clipped
    if any(c.label for c in curves):
        ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def clip_force_axis(ax, filtered: list[np.ndarray], raw: list[np.ndarray],
                    factor: float = 1.3) -> float | None:
    """Limit a force axis to ``factor`` x the largest filtered force, so single-cycle raw
    contact spikes (first contact: several times the filtered peak) do not flatten the
    curves; a note in the axes names the clipped raw maximum (kN). Returns it, or None
    when nothing was clipped (axes left as they are)."""
    top = max((float(np.max(f)) for f in filtered if f.size), default=0.0)
    raw_top = max((float(np.max(r)) for r in raw if r.size), default=0.0)
    if top <= 0.0 or raw_top <= factor * top:
        return None
    low = min((float(np.min(f)) for f in filtered if f.size), default=0.0)
    ax.set_ylim(bottom=min(0.0, 1.1 * low), top=factor * top)
    ax.text(0.99, 0.01, f"raw spikes up to {raw_top:.3g} kN clipped", transform=ax.transAxes,
            ha="right", va="bottom", fontsize=7, color="0.4")
    return raw_top
