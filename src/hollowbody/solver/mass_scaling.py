"""Selective mass scaling (LS-DYNA *CONTROL_TIMESTEP DT2MS < 0) and the
rotational inertia of thickening shells.

**Mass scaling.** With a target step ``T = |DT2MS|`` (ms, an element's
critical step before TSSFAC, so the run's step never falls below
``TSSFAC * T``), every element whose critical step ``dt_e`` falls below
``T`` gets the mass that brings it back to ``T``: since ``dt_e`` grows as the
square root of the element's mass, its mass becomes ``m_e (T / dt_e)^2``. The
added mass is spread evenly over the element's distinct nodes. Mass is only
ever added (an element keeps the largest mass it needed), so it is reported
as a total in the run's summary and in glstat. Added mass takes the velocity
of its node: its kinetic energy ``0.5 dm |v|^2`` (and ``0.5 dI |w|^2``) is
counted as work supplied by mass scaling, so the energy ratio still checks
the integration. It is not physics: momentum is not conserved where mass is
added to moving nodes, and a run should add only a small fraction of the
model's mass (the summary reports it per part).

**Thickening shells.** A shell with thickness update (ISTUPD = 1) that gets
thicker keeps its mass but gains bending stiffness as t^3. Its nodal
rotational inertia ``m_e max(t^2/12, A0/4)`` (see
:mod:`hollowbody.elements.shell_group`) is raised with the current thickness
so that rotations still never govern the step; the shell kernel shortens the
element's step by ``sqrt(t0 / t)`` (the membrane stiffness grows with t).
"""

from __future__ import annotations

import numpy as np


class _GroupState:
    """Per-group bookkeeping: mass factor and assigned rotational inertia."""

    #: time-varying attributes (saved by the run's State)
    STATE_FIELDS = ("mfac", "inertia")

    def __init__(self, rt) -> None:  # noqa: ANN001 - element-group runtime
        self.rt = rt
        e = int(rt.n_elem) if hasattr(rt, "n_elem") else int(rt.mass.shape[0])
        self.mfac = np.ones(e)
        conn = np.asarray(rt.conn)
        s = np.sort(conn, axis=1)
        first = np.ones_like(s, dtype=bool)
        first[:, 1:] = s[:, 1:] != s[:, :-1]
        self.nodes = s
        self.first = first
        self.n_distinct = first.sum(axis=1)
        self.shell = bool(getattr(rt, "rotational", False))
        self.update_thickness = self.shell and bool(getattr(rt, "thickness_update", False))
        self.inertia = rt.mass * rt.r2 if self.shell else None

    def spread(self, idx: np.ndarray, amount: np.ndarray, out: np.ndarray) -> None:
        """Add ``amount`` (k,) of elements ``idx`` evenly onto their distinct nodes."""
        share = amount / self.n_distinct[idx]
        nodes = self.nodes[idx]
        first = self.first[idx]
        np.add.at(out, nodes[first], np.broadcast_to(share[:, None], nodes.shape)[first])


class MassScaling:
    """Adds mass where needed after every element pass; see the module docstring.

    target: |DT2MS| in ms (0: no mass scaling, only the thickening shells'
    inertia); node_mass, node_inertia: (n,) kg, kg*mm^2 nodal arrays of the
    run, updated in place; inv_m, inv_i: their inverses, updated in place.
    """

    #: time-varying attributes (saved by the run's State); the node arrays belong to it
    STATE_FIELDS = ("added_mass", "work")

    def __init__(self, elements: list, target: float, node_mass: np.ndarray,
                 node_inertia: np.ndarray, inv_m: np.ndarray, inv_i: np.ndarray) -> None:
        self.target = float(abs(target))
        self.node_mass = node_mass
        self.node_inertia = node_inertia
        self.inv_m = inv_m
        self.inv_i = inv_i
        self.groups = [_GroupState(rt) for rt in elements]
        #: kg added so far, per part id
        self.added_mass: dict[int, float] = {}
        #: J kinetic energy of the added mass at the moment it was added
        self.work = 0.0
        self.active = self.target > 0.0 or any(g.update_thickness for g in self.groups)
        self._base = float(sum(float(g.rt.mass.sum()) for g in self.groups))
        self._dm = np.zeros_like(node_mass)
        self._di = np.zeros_like(node_inertia)

    @property
    def total_added(self) -> float:
        """kg added so far (all parts)."""
        return float(sum(self.added_mass.values()))

    @property
    def percent_added(self) -> float:
        """Added mass in % of the deformable elements' initial mass."""
        return 100.0 * self.total_added / self._base if self._base > 0.0 else 0.0

    def summary(self) -> dict:
        """What mass scaling did, for summary.json (masses kg, energy J)."""
        return {"target_dt_ms": self.target, "added_mass_kg": self.total_added,
                "added_mass_percent": self.percent_added,
                "added_mass_by_part_kg": {str(k): v for k, v in self.added_mass.items()},
                "added_kinetic_energy_J": self.work}

    def apply(self, v: np.ndarray, w: np.ndarray | None) -> None:
        """Raise masses and inertias where needed (call after the element pass).

        v (n,3) mm/ms, w (n,3) rad/ms or None: the nodal velocities the added
        mass takes (their kinetic energy goes to :attr:`work`).
        """
        if not self.active:
            return
        touched = False
        for g in self.groups:
            rt = g.rt
            if self.target > 0.0:
                touched |= self._scale_group(g, rt)
            if g.update_thickness:
                touched |= self._inertia_group(g, rt)
        if not touched:
            return
        hit = np.nonzero(self._dm)[0]
        self.node_mass[hit] += self._dm[hit]
        self.inv_m[hit] = 1.0 / self.node_mass[hit]
        self.work += 0.5 * float((self._dm[hit] * (v[hit] ** 2).sum(axis=1)).sum())
        self._dm[hit] = 0.0
        hit = np.nonzero(self._di)[0]
        if hit.size and self.node_inertia.size:
            self.node_inertia[hit] += self._di[hit]
            self.inv_i[hit] = 1.0 / self.node_inertia[hit]
            if w is not None:
                self.work += 0.5 * float((self._di[hit] * (w[hit] ** 2).sum(axis=1)).sum())
            self._di[hit] = 0.0

    def _scale_group(self, g: _GroupState, rt) -> bool:  # noqa: ANN001
        if not getattr(rt, "mass_scaled", True):  # massless (discrete): the step stays
            return False
        d = rt.dt_elem * getattr(rt, "step_factor", 1.0) * np.sqrt(g.mfac)
        need = np.nonzero((d < self.target) & rt.alive)[0]
        if need.size == 0:
            return False
        old = g.mfac[need]
        new = old * (self.target / np.maximum(d[need], 1e-300)) ** 2
        dm = rt.mass[need] * (new - old)
        g.mfac[need] = new
        g.spread(need, dm, self._dm)
        if g.shell:  # rotational groups (shells, beams): inertia grows with the mass
            if hasattr(rt, "mass_q"):  # the shells' nodal mass share
                rt.mass_q[need] += 0.25 * dm
            di = rt.r2[need] * dm
            g.inertia[need] += di
            g.spread(need, di, self._di)
        self.added_mass[rt.pid] = self.added_mass.get(rt.pid, 0.0) + float(dm.sum())
        return True

    def _inertia_group(self, g: _GroupState, rt) -> bool:  # noqa: ANN001
        r2 = np.maximum(rt.thickness ** 2 / 12.0, rt.area0 / 4.0)
        grow = np.nonzero(r2 > rt.r2)[0]
        if grow.size == 0:
            return False
        rt.r2[grow] = r2[grow]
        want = rt.mass[grow] * g.mfac[grow] * r2[grow]
        di = np.maximum(want - g.inertia[grow], 0.0)
        g.inertia[grow] += di
        g.spread(grow, di, self._di)
        return True

    def critical_step(self) -> tuple[float, int, int]:
        """Smallest element step with the scaled masses (before TSSFAC): (dt ms,
        element id, part id); (inf, -1, -1) when no element is alive."""
        best, elem, pid = np.inf, -1, -1
        for g in self.groups:
            rt = g.rt
            d = rt.dt_elem * getattr(rt, "step_factor", 1.0) * np.sqrt(g.mfac)
            if d.size == 0:
                continue
            i = int(np.argmin(d))
            if d[i] < best:
                best, elem, pid = float(d[i]), int(rt.elem_ids[i]), rt.pid
        return best, elem, pid
