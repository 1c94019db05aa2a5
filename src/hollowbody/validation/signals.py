"""A test run's signals: impactor force, deflection and bending moment.

From the run's histories (written by the solver or converted from another
engine's results, same columns) and the :class:`~hollowbody.validation.setup.Setup`
record:

- force F(t) [kN]: the impactor contact's master-side resultant (``rcforc.csv``,
  the force the body applies to the impactor) projected on ``-direction``:
  positive when the body pushes back; SAE J211 CFC 180 filtered (the class
  used for impactor forces) unless ``cfc`` is None;
- impactor travel u(t) [mm]: the ``nodout.csv`` displacement of
  ``impactor_node`` (else ``rbdout.csv`` of the impactor part) projected on
  ``direction``;
- deflection d(t) [mm]: u minus the gap (speed x contact_time: the free
  flight up to the skin), minus the displacement of ``reference_node``
  (``nodout.csv``) along ``direction`` when the set-up names one (impacts);
- moment M(d) [kN*mm]: F a b / span at the load point (bending).

Time zero of every signal is ``Setup.contact_time`` (the face reaching the
skin), the time zero of the test curves. Force-deflection curves are the
loading branch, up to the largest deflection.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hollowbody.curves.cfc import cfc_filter
from hollowbody.errors import UserInputError
from hollowbody.io.results.history import read_history
from hollowbody.rating.signals import resample
from hollowbody.validation.setup import Setup, unit

#: CFC class (Hz) of the force (impactor force channels, SAE J211).
FORCE_CFC = 180.0


@dataclass
class Signals:
    """The signals of one run, each (n,) arrays, time from first contact [ms].

    Attributes
    ----------
    time : ndarray
        ms after ``contact_time`` (negative before).
    force : ndarray
        kN, filtered (``cfc``).
    force_raw : ndarray
        kN, unfiltered.
    deflection : ndarray
        mm (impactor travel past first contact when there is no reference node).
    moment : ndarray or None
        kN*mm at the load point (bending only).
    cfc : float or None
        Filter class of ``force`` [Hz].
    """

    time: np.ndarray
    force: np.ndarray
    force_raw: np.ndarray
    deflection: np.ndarray
    moment: np.ndarray | None
    cfc: float | None

    def curve(self, quantity: str) -> tuple[np.ndarray, np.ndarray]:
        """(x, y) of ``force`` (time, force from contact on), ``force_deflection`` or
        ``moment_deflection`` (loading branch: up to the largest deflection)."""
        after = self.time >= 0.0
        if quantity == "force":
            return self.time[after], self.force[after]
        d = self.deflection[after]
        if d.size == 0:
            return d, d
        k = int(np.argmax(d)) + 1
        y = self.force if quantity == "force_deflection" else self.moment
        if y is None:
            raise ValueError(f"this run has no {quantity}")
        # the loading branch, kept strictly increasing in deflection (rating abscissa)
        x, yy = d[:k], y[after][:k]
        keep = np.concatenate([[True], np.diff(np.maximum.accumulate(x)) > 0.0])
        return np.maximum.accumulate(x)[keep], yy[keep]


def _rows(path: Path, what: str) -> dict[str, np.ndarray]:
    if not path.is_file():
        raise UserInputError(f"{path}: missing ({what}); was the run written with the "
                             "set-up's outputs?")
    return read_history(path)


def _resample(t: np.ndarray, y: np.ndarray, grid: np.ndarray) -> np.ndarray:
    order = np.argsort(t, kind="stable")  # histories are in time order; be sure
    return resample(t[order], y[order], grid)


def _node_along(nd: dict[str, np.ndarray], node: int, d: np.ndarray, t: np.ndarray,
                run: Path, what: str) -> np.ndarray:
    """Displacement of ``node`` along ``d`` [mm] at times ``t`` (from nodout rows)."""
    sel = nd["node"] == node
    if not np.any(sel):
        raise UserInputError(f"{run / 'nodout.csv'}: no rows for {what} {node}")
    u = np.column_stack([nd[f"u{c} [mm]"][sel] for c in "xyz"]) @ d
    return _resample(nd["time [ms]"][sel], u, t)


def read_signals(run_dir: str | Path, s: Setup, cfc: float | None = FORCE_CFC) -> Signals:
    """The signals of the run in ``run_dir`` of set-up ``s`` (see the module doc).

    Raises UserInputError naming the file when a history or its rows for the
    impactor (contact, part, reference node) are missing.
    """
    run = Path(run_dir)
    d = unit(s.direction)
    rc = _rows(run / "rcforc.csv", "contact forces")
    sel = rc["contact"] == s.contact_id
    if not np.any(sel):
        raise UserInputError(f"{run / 'rcforc.csv'}: no rows for contact {s.contact_id}")
    idx = np.flatnonzero(sel)
    # one row per time: the final state can be written twice at the end of a run
    _, last = np.unique(rc["time [ms]"][idx][::-1], return_index=True)
    idx = idx[::-1][last]
    t = rc["time [ms]"][idx]
    fm = np.column_stack([rc[f"master_f{c} [kN]"][idx] for c in "xyz"])
    force_raw = -(fm @ d)
    nd = None
    if s.impactor_node is not None:
        nd = _rows(run / "nodout.csv", "node histories")
        travel = _node_along(nd, s.impactor_node, d, t, run, "impactor node")
    else:
        rb = _rows(run / "rbdout.csv", "rigid-body motion")
        rsel = rb["part"] == s.impactor_pid
        if not np.any(rsel):
            raise UserInputError(f"{run / 'rbdout.csv'}: no rows for impactor part "
                                 f"{s.impactor_pid}")
        u = np.column_stack([rb[f"u{c} [mm]"][rsel] for c in "xyz"]) @ d
        travel = _resample(rb["time [ms]"][rsel], u, t)
    if s.reference_node is not None:
        nd = nd if nd is not None else _rows(run / "nodout.csv", "node histories")
        travel = travel - _node_along(nd, s.reference_node, d, t, run, "reference node")
    # the free flight up to the skin (the gap) is not deflection
    deflection = travel - s.speed * s.contact_time
    if cfc is not None and t.size > 1:
        grid = np.linspace(t[0], t[-1], t.size)
        force = np.interp(t, grid, cfc_filter(grid, np.interp(grid, t, force_raw), cfc))
    else:
        force = force_raw.copy()
    moment = None
    if s.span and s.load_a is not None and s.load_b is not None:
        moment = force * s.load_a * s.load_b / s.span
    return Signals(t - s.contact_time, force, force_raw, deflection, moment, cfc)
