"""Force-displacement curves of impactor tests: extraction, CSV and plots.

The impactor displacement is the displacement of an impactor node along the
impact direction (from ``nodout.csv``), the contact force the resultant
contact force on the impactor along the opposite direction (from
``rcforc.csv``), so both are positive while the impactor compresses the
tissue.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hollowbody.io.results.history import read_history


@dataclass
class ForceDisplacement:
    """time (k,) ms, displacement (k,) mm, force (k,) kN."""

    time: np.ndarray
    displacement: np.ndarray
    force: np.ndarray
    label: str = ""

    @property
    def peak_force(self) -> float:
        """Peak of the CFC 600 filtered force (kN); see :func:`cfc_filter`."""
        return float(self.force_filtered().max()) if self.force.size else 0.0

    @property
    def peak_force_raw(self) -> float:
        """Peak of the unfiltered force (kN), including the first-contact spike."""
        return float(self.force.max()) if self.force.size else 0.0

    def force_filtered(self, cfc: float = 600.0) -> np.ndarray:
        """Contact force (kN) filtered with an SAE J211 channel frequency class."""
        return cfc_filter(self.time, self.force, cfc)

    @property
    def max_displacement(self) -> float:
        return float(self.displacement.max()) if self.displacement.size else 0.0


def extract(run_dir: str | Path, node_id: int, contact_id: int, direction: np.ndarray,
            side: str = "master", label: str = "") -> ForceDisplacement:
    """Force-displacement of a run's impactor.

    node_id: impactor history node; contact_id: the impactor contact;
    direction: (3,) unit impact direction (e.g. (0, 0, -1)); side: which
    contact side is the impactor ('master' or 'slave').
    """
    run_dir = Path(run_dir)
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    nod = read_history(run_dir / "nodout.csv")
    rc = read_history(run_dir / "rcforc.csv")
    sel = nod["node"] == node_id
    t_n = nod["time [ms]"][sel]
    u = np.column_stack([nod[f"u{c} [mm]"][sel] for c in "xyz"]) @ d
    selc = rc["contact"] == contact_id
    t_c = rc["time [ms]"][selc]
    fc = np.column_stack([rc[f"{side}_f{c} [kN]"][selc] for c in "xyz"]) @ (-d)
    if t_n.size == 0 or t_c.size == 0:
        return ForceDisplacement(np.zeros(0), np.zeros(0), np.zeros(0), label)
    t = t_c
    disp = np.interp(t, t_n, u)
    return ForceDisplacement(t, disp, fc, label)


def cfc_filter(time: np.ndarray, y: np.ndarray, cfc: float = 600.0) -> np.ndarray:
    """SAE J211 / ISO 6487 channel-frequency-class filter.

    Phase-less 4-pole Butterworth low pass (a 2-pole design run forward and
    backward) with corner frequency 1.65 * CFC Hz, as crash-test data are
    filtered (CFC 600 for impactor forces). time in ms (uniform steps),
    returns y filtered; series too short or too coarsely sampled are returned
    unchanged.
    """
    from scipy.signal import butter, filtfilt

    if time.size < 16:
        return y.copy()
    fs = 1000.0 / float(np.median(np.diff(time)))  # Hz
    fc = 1.65 * cfc
    if fc >= 0.45 * fs:
        return y.copy()
    b, a = butter(2, fc / (0.5 * fs))
    return filtfilt(b, a, y, padlen=min(3 * max(len(a), len(b)), y.size - 1))


def write_csv(fd: ForceDisplacement, path: str | Path) -> None:
    """CSV: time_ms, impactor_displacement_mm, contact_force_kN, contact_force_cfc600_kN."""
    data = np.column_stack([fd.time, fd.displacement, fd.force, fd.force_filtered()])
    np.savetxt(path, data, delimiter=",", fmt="%.9g",
               header="time_ms,impactor_displacement_mm,contact_force_kN,"
                      "contact_force_cfc600_kN", comments="")


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
