"""Force-displacement curves of impactor tests: extraction from histories, CSV, smoothing.

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

from hollowbody.curves.cfc import cfc_filter
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
        """Peak of the CFC 600 filtered force (kN); see :func:`force_filtered`."""
        return float(self.force_filtered().max()) if self.force.size else 0.0

    @property
    def peak_force_raw(self) -> float:
        """Peak of the unfiltered force (kN), including the first-contact spike."""
        return float(self.force.max()) if self.force.size else 0.0

    def force_filtered(self, cfc: float = 600.0) -> np.ndarray:
        """Contact force (k,) kN filtered with SAE J211 class ``cfc``
        (:func:`hollowbody.curves.cfc.cfc_filter`; the output times are uniform)."""
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


def write_csv(fd: ForceDisplacement, path: str | Path) -> None:
    """CSV: time_ms, impactor_displacement_mm, contact_force_kN, contact_force_cfc600_kN."""
    data = np.column_stack([fd.time, fd.displacement, fd.force, fd.force_filtered()])
    np.savetxt(path, data, delimiter=",", fmt="%.9g",
               header="time_ms,impactor_displacement_mm,contact_force_kN,"
                      "contact_force_cfc600_kN", comments="")


def uniform_in_time(curve: ForceDisplacement) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(time, displacement, force) resampled on a uniform time grid (repeated times
    dropped; the step is the median sampling interval)."""
    t = np.asarray(curve.time, dtype=float)
    keep = np.concatenate([[True], np.diff(t) > 0.0]) if t.size else np.zeros(0, bool)
    t, d, f = t[keep], np.asarray(curve.displacement)[keep], np.asarray(curve.force)[keep]
    if t.size < 2:
        return t, d, f
    dt = float(np.median(np.diff(t)))
    n = int(round((t[-1] - t[0]) / dt)) + 1
    tu = np.linspace(t[0], t[-1], max(n, 2))
    return tu, np.interp(tu, t, d), np.interp(tu, t, f)


def smoothed(curve: ForceDisplacement, cfc: float | None = 180.0) -> ForceDisplacement:
    """The curve on a uniform time grid with its force CFC-filtered (``cfc`` None: raw)."""
    t, d, f = uniform_in_time(curve)
    if cfc:
        f = cfc_filter(t, f, cfc)
    return ForceDisplacement(t, d, f, curve.label)
