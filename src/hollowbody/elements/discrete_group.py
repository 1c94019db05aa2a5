"""Runtimes of discrete element groups (springs and dampers, one per part).

:func:`discrete_runtimes` gives :meth:`solver.setup.assemble` one
:class:`DiscreteGroupRuntime` per ``Model.discrete_groups`` entry (``family =
"discrete"``). Torsional groups (DRO = 1) are ``rotational``: the cycle passes
them the angular velocities and the moment array. The runtime is bound to the
plan once the masses and rigid bodies are known (:meth:`DiscreteGroupRuntime.bind`,
called by the set-up), which fixes each element's critical step and rejects a
spring on a node without mass (translational) or without rotational inertia
(torsional). Kernels: :mod:`hollowbody.elements.discrete_kernels`; see
docs/discrete.md.

**Time step.** An element between the (effective) masses m1, m2 (a grounded
element: 1/m2 = 0; a node on a rigid body: the body's mass, or its smallest
principal inertia for a torsional element) is a two-mass oscillator with
``omega = sqrt(k (1/m1 + 1/m2))``; with a damper c, the central-difference
limit is ``dt = (2 / omega) (sqrt(1 + xi^2) - xi)``, ``xi = c (1/m1 + 1/m2) /
(2 omega)`` (``2 / (c (1/m1 + 1/m2))`` without a spring). k is the element's
current tangent stiffness times |S| (K for S01; for S04 / S06 the largest slope
of the curve segments around the current deflection, so a stiffening curve is
seen one segment ahead), recomputed every cycle, plus the stiffness bounds (K,
largest curve slope, times |S|) of the other discrete elements at the same
nodes (the larger of the two nodes' sums): springs and dampers on the same
nodes act in parallel, and c is the sum of the dampers there. Discrete elements
get no mass from mass scaling (DT2MS): their step stays.
"""

from __future__ import annotations

import numpy as np

from hollowbody.elements.discrete_kernels import (
    H_SHIFT,
    H_YC,
    H_YT,
    curve_inverse,
    discrete_forces,
)
from hollowbody.errors import DeckError
from hollowbody.model.discrete import DISCRETE_LAWS, LAW_NAMES, DiscreteGroup


def _curve(model, lcid: int) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001 - Model
    c = model.curves[int(lcid)]
    return (np.ascontiguousarray(c.x, dtype=np.float64),
            np.ascontiguousarray(c.y, dtype=np.float64))


def _max_slope(cx: np.ndarray, cy: np.ndarray) -> float:
    if cx.size < 2:
        return 0.0
    return float(np.max(np.abs(np.diff(cy) / np.diff(cx))))


class DiscreteGroupRuntime:
    """Springs / dampers of one part (e elements).

    Attributes: pid, kind, law (1, 2, 4, 6), torsional, rotational (= torsional),
    elem_ids (e,) int64, conn (e, 2) int32 node indices (a grounded element
    repeats N1), n_elem, alive (e,) bool, force (e,) kN (torsional kN*mm, S
    applied), defl (e,) mm or rad, rate (e,), energy (e,) J per element,
    internal_energy (J, sum), hourglass_energy (0), stress (e, 6) zeros (NaN where the
    force is not finite, for the solver's checks), mass (e,) zeros (no element mass),
    k_bound (e,) and c_bound (e,) the stiffness and damping used for the step.
    """

    family = "discrete"
    #: not given mass by mass scaling (solver.mass_scaling)
    mass_scaled = False
    STATE_FIELDS: tuple[str, ...] = ("alive", "hist", "force", "defl", "rate", "direction",
                                     "energy", "stress", "internal_energy", "failed", "_dte")

    def __init__(self, group: DiscreteGroup, model, x0: np.ndarray) -> None:  # noqa: ANN001
        self.group = group
        self.pid = int(group.pid)
        self.kind = group.kind
        self.law = int(DISCRETE_LAWS[group.kind])
        self.torsional = bool(group.torsional)
        self.rotational = self.torsional
        self.elem_ids = np.asarray(group.elem_ids, dtype=np.int64)
        e = self.n_elem = int(self.elem_ids.size)
        self.n1 = np.ascontiguousarray(group.n1, dtype=np.int64)
        self.n2 = np.ascontiguousarray(group.n2, dtype=np.int64)
        self.conn = np.column_stack([self.n1, np.where(self.n2 >= 0, self.n2, self.n1)]
                                    ).astype(np.int32)
        self.fixed = np.ascontiguousarray(group.fixed_axis, dtype=np.bool_)
        self.axis = np.ascontiguousarray(group.axis, dtype=np.float64)
        self.scale = np.ascontiguousarray(group.scale, dtype=np.float64)
        self.offset = np.ascontiguousarray(group.offset, dtype=np.float64)
        self.print_flag = np.asarray(group.print_flag)
        self.warnings: list[str] = []
        x0 = np.asarray(x0, dtype=np.float64)
        x1 = x0[self.n1]
        x2 = np.where((self.n2 >= 0)[:, None], x0[np.maximum(self.n2, 0)], x1)
        self.length0 = np.linalg.norm(x2 - x1, axis=1)
        # ground: the ground point (line) or the reference vector of a fixed axis
        ref = np.where((self.n2 >= 0)[:, None], x2 - x1, -x1)
        self.ground = np.ascontiguousarray(np.where(self.fixed[:, None], ref, x1))
        p = model.materials[group.mid].params
        self.params = np.zeros(5)
        self.params[4] = float(group.failure_deflection)
        empty = np.zeros(1)
        self.lx = self.ly = self.ux = self.uy = empty
        slope = 0.0
        if self.law == 1:
            self.params[0] = p["K"]
            slope = p["K"]
        elif self.law == 2:
            self.params[0] = p["DC"]
        elif self.law == 4:
            self.lx, self.ly = _curve(model, p["LCD"])
            slope = _max_slope(self.lx, self.ly)
            if int(p.get("LCR", 0.0)):
                self.warnings.append(f"part {self.pid}: LCR (rate effects of "
                                     "*MAT_SPRING_NONLINEAR_ELASTIC) is not applied")
        else:
            self.lx, self.ly = _curve(model, p["LCDL"])
            if int(p["LCDU"]):
                self.ux, self.uy = _curve(model, p["LCDU"])
                if np.any(np.diff(self.uy) <= 0.0):
                    mat = model.materials[group.mid]
                    raise DeckError(f"material {group.mid}: the unloading curve LCDU "
                                    f"{int(p['LCDU'])} must be strictly increasing",
                                    mat.source.file, mat.source.line, mat.keyword or None)
            else:  # unloading elastic with the loading curve's largest slope
                k0 = max(_max_slope(self.lx, self.ly), 1e-300)
                self.ux, self.uy = np.array([-1.0, 1.0]), np.array([-k0, k0])
            slope = max(_max_slope(self.lx, self.ly), _max_slope(self.ux, self.uy))
            self.params[1], self.params[2], self.params[3] = p["BETA"], p["TYI"], p["CYI"]
        self.k_bound = np.abs(self.scale) * slope
        self.c_bound = np.abs(self.scale) * (p["DC"] if self.law == 2 else 0.0)
        # state
        self.alive = np.ones(e, dtype=np.bool_)
        self.hist = np.zeros((e, 4))
        self.hist[:, H_YT] = self.params[2]
        self.hist[:, H_YC] = self.params[3]
        if self.law == 6:  # LCDU placed with its zero force at zero deflection
            self.hist[:, H_SHIFT] = -curve_inverse(self.ux, self.uy, 0.0)
        self.force = np.zeros(e)
        self.defl = self.offset.copy()
        self.rate = np.zeros(e)
        d0 = x2 - x1
        n0 = np.linalg.norm(d0, axis=1)
        self.direction = np.where(self.fixed[:, None], self.axis,
                                  d0 / np.where(n0 > 0.0, n0, 1.0)[:, None])
        self.energy = np.zeros(e)
        self.stress = np.zeros((e, 6))
        self.internal_energy = 0.0
        self.hourglass_energy = 0.0
        self.failed: list[int] = []
        self.mass = np.zeros(e)
        self.r2 = np.zeros(e)
        self.mass_q = np.zeros(e)
        self._dte = np.full(e, np.inf)
        # time step data (bind): other elements' stiffness, damping, 1/m1 + 1/m2
        self.k_other = np.zeros(e)
        self.c_use = np.ascontiguousarray(self.c_bound.copy())
        self.minv = np.zeros(e)
        self._wzero = np.zeros((0, 3))
        self._mzero = np.zeros((0, 3))

    # -- set-up ---------------------------------------------------------------------
    def lumped_rotational_inertia(self, n_nodes: int) -> np.ndarray:
        """(n,) kg*mm^2: none (discrete elements are massless)."""
        return np.zeros(n_nodes)

    def bind(self, step_k: np.ndarray, step_c: np.ndarray, inv_mass: np.ndarray,
             body_of: np.ndarray) -> None:
        """Fix the critical step of every element.

        step_k, step_c (n,): sums of ``k_bound`` / ``c_bound`` of all discrete
        groups of the same kind (translational or torsional) at each node;
        inv_mass (n,): 1/m (1/I for torsional) of each node's effective mass, 0
        for a node that does not move (fully fixed) and NaN for one without mass;
        body_of (n,) int: rigid body index of each node (-1: none). Raises
        DeckError at the element's card for a node without mass.
        """
        g = self.group
        dof = "rotational inertia" if self.torsional else "mass"
        for side, nodes in (("N1", self.n1), ("N2", self.n2)):
            has = nodes >= 0
            bad = np.nonzero(has & np.isnan(inv_mass[np.maximum(nodes, 0)]))[0]
            if bad.size:
                k = int(bad[0])
                src = g.sources[k]
                raise DeckError(f"discrete element {int(self.elem_ids[k])}: node {side} has no "
                                f"{dof} (give it an *ELEMENT_MASS or attach it to an element "
                                "or rigid body" + (" with rotational DOFs" if self.torsional
                                                    else "") + ")",
                                src.file, src.line, "ELEMENT_DISCRETE")
        im1 = inv_mass[self.n1]
        im2 = np.where(self.n2 >= 0, inv_mass[np.maximum(self.n2, 0)], 0.0)
        minv = im1 + im2
        same = (self.n2 >= 0) & (body_of[self.n1] >= 0) & \
            (body_of[self.n1] == body_of[np.maximum(self.n2, 0)])
        minv[same] = 0.0  # both ends on one rigid body: internal, no motion
        has2 = self.n2 >= 0
        n2 = np.maximum(self.n2, 0)
        k = np.maximum(step_k[self.n1], np.where(has2, step_k[n2], 0.0))
        c = np.maximum(step_c[self.n1], np.where(has2, step_c[n2], 0.0))
        self.k_other = np.ascontiguousarray(np.maximum(k - self.k_bound, 0.0))
        self.c_use = np.ascontiguousarray(c)
        self.minv = np.ascontiguousarray(minv)
        self._dte = critical_step(k, c, minv)  # until the first call (bounds)

    # -- the cycle ------------------------------------------------------------------
    def add_forces(self, x: np.ndarray, v: np.ndarray, dt: float, f: np.ndarray,
                   w: np.ndarray | None = None, moment: np.ndarray | None = None
                   ) -> tuple[float, int, int]:
        """Add the group's forces (translational) or moments (torsional, into
        ``moment``) at t^{n+1}; returns ``(dt_crit ms, index, -1)``."""
        if w is None:
            if self._wzero.shape != v.shape:
                self._wzero = np.zeros_like(v)
            w = self._wzero
        mom = moment if moment is not None else self._mzero
        if self.torsional and moment is None:
            raise RuntimeError("a torsional discrete group needs the moment array")
        failed = discrete_forces(self.law, self.torsional, x, v, w, float(dt), self.n1,
                                 self.n2, self.ground, self.fixed, self.axis, self.length0,
                                 self.offset, self.scale, self.alive, self.params, self.lx,
                                 self.ly, self.ux, self.uy, self.hist, self.force, self.defl,
                                 self.rate, self.direction, self.energy, self.k_other,
                                 self.c_use, self.minv, self._dte, f, mom)
        self.internal_energy = float(self.energy.sum())
        # no stress in a spring: zeros, but a non-finite force shows (the solver's
        # non-finite check names the element from it)
        self.stress[:, 0] = 0.0 * self.force
        if failed >= 0:
            for i in np.nonzero(~self.alive)[0]:
                if int(i) not in self.failed:
                    self.failed.append(int(i))
        if self.n_elem == 0:
            return np.inf, -1, -1
        if self.failed and self.alive.any():  # failed elements (FD) set no step
            live = np.nonzero(self.alive)[0]
            i = int(live[np.argmin(self._dte[live])])
        else:  # all failed: their last steps, so a run of springs alone goes on
            i = int(np.argmin(self._dte))
        d = float(self._dte[i])
        return (d, i, -1) if np.isfinite(d) else (np.inf, -1, -1)

    def erode(self, idx: np.ndarray) -> None:
        """Delete elements ``idx`` (indices in the group)."""
        idx = np.asarray(idx, dtype=np.int64)
        self.alive[idx] = False
        self.force[idx] = 0.0
        self._dte[idx] = np.inf

    @property
    def dt_elem(self) -> np.ndarray:
        """(e,) ms critical step of each element (inf: deleted or internal to a body)."""
        return self._dte

    def law_name(self) -> str:
        return LAW_NAMES[self.kind]


def critical_step(k: np.ndarray, c: np.ndarray, minv: np.ndarray) -> np.ndarray:
    """(e,) ms central-difference limit of a spring k (kN/mm) and damper c (kN*ms/mm)
    between masses with 1/m1 + 1/m2 = minv (1/kg); inf where nothing limits it."""
    k = np.asarray(k, dtype=np.float64)
    c = np.asarray(c, dtype=np.float64)
    minv = np.asarray(minv, dtype=np.float64)
    out = np.full(k.shape, np.inf)
    om = np.sqrt(np.maximum(k * minv, 0.0))
    cm = c * minv
    spring = om > 0.0
    xi = np.where(spring, cm / (2.0 * np.where(spring, om, 1.0)), 0.0)
    out[spring] = 2.0 / om[spring] * (np.sqrt(1.0 + xi[spring] ** 2) - xi[spring])
    damper = ~spring & (cm > 0.0)
    out[damper] = 2.0 / cm[damper]
    return out


def discrete_runtimes(model, x0: np.ndarray) -> list:  # noqa: ANN001 - Model
    """One runtime per discrete group of ``model``; x0 (n, 3) mm."""
    return [DiscreteGroupRuntime(g, model, x0) for g in model.discrete_groups
            if g.n_elem > 0]


def bind_discrete(runtimes: list, node_mass: np.ndarray, node_rot_inertia: np.ndarray,
                  bodies: list, fixed: np.ndarray, fixed_rot: np.ndarray) -> None:
    """Critical steps of the discrete runtimes (:meth:`DiscreteGroupRuntime.bind`).

    node_mass, node_rot_inertia (n,) kg, kg*mm^2; bodies: rigid bodies (``nodes``,
    ``mass``, ``inertia0``); fixed, fixed_rot (n, 3) bool SPC'd DOFs.
    """
    groups = [rt for rt in runtimes if isinstance(rt, DiscreteGroupRuntime)]
    if not groups:
        return
    n = node_mass.size
    body_of = np.full(n, -1, dtype=np.int64)
    body_mass = np.zeros(n)
    body_inertia = np.zeros(n)
    for k, b in enumerate(bodies):
        body_of[b.nodes] = k
        body_mass[b.nodes] = b.mass
        body_inertia[b.nodes] = float(np.linalg.eigvalsh(np.asarray(b.inertia0)).min())
    for torsional in (False, True):
        members = [rt for rt in groups if rt.torsional == torsional]
        if not members:
            continue
        m = np.where(body_of >= 0, body_inertia if torsional else body_mass,
                     node_rot_inertia if torsional else node_mass)
        still = (fixed_rot if torsional else fixed).all(axis=1) & (body_of < 0)
        inv = np.where(m > 0.0, 1.0 / np.where(m > 0.0, m, 1.0), np.nan)
        inv[still] = 0.0
        sk, sc = np.zeros(n), np.zeros(n)
        for rt in members:
            for nodes in (rt.n1, rt.n2[rt.n2 >= 0]):
                kb = rt.k_bound if nodes is rt.n1 else rt.k_bound[rt.n2 >= 0]
                cb = rt.c_bound if nodes is rt.n1 else rt.c_bound[rt.n2 >= 0]
                np.add.at(sk, nodes, kb)
                np.add.at(sc, nodes, cb)
        for rt in members:
            rt.bind(sk, sc, inv, body_of)
