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
        return float(self.force.max()) if self.force.size else 0.0

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


def write_csv(fd: ForceDisplacement, path: str | Path) -> None:
    """CSV with columns time_ms, impactor_displacement_mm, contact_force_kN."""
    data = np.column_stack([fd.time, fd.displacement, fd.force])
    np.savetxt(path, data, delimiter=",", fmt="%.9g",
               header="time_ms,impactor_displacement_mm,contact_force_kN", comments="")


def plot(curves: list[ForceDisplacement], path: str | Path, title: str = "") -> None:
    """Force-displacement plot (PNG) of one or more curves."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6), dpi=120)
    for c in curves:
        ax.plot(c.displacement, c.force, lw=1.8, label=c.label or None)
    ax.set_xlabel("impactor displacement [mm]")
    ax.set_ylabel("contact force [kN]")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=min(0.0, min((c.force.min() for c in curves if c.force.size),
                                    default=0.0)))
    if any(c.label for c in curves):
        ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
