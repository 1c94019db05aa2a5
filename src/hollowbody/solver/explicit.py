"""Central-difference explicit time integration (the run loop).

One cycle, from t^n to t^{n+1} (order as in LS-DYNA / OpenRadioss engines):

1. accelerations a^n = f^n / m (deformable nodes); rigid bodies from their
   resultant force and moment;
2. velocities v^{n+1/2} = v^{n-1/2} + dt_avg a^n; constraints (SPC,
   prescribed motion, rigid-body motion) imposed on them;
3. positions x^{n+1} = x^n + dt v^{n+1/2} (rigid nodes placed by their body);
4. forces f^{n+1}: element internal + hourglass + bulk viscosity, contact;
5. energies, histories, monitors, states; next step dt = TSSFAC * min dt_crit.

Termination: end time (normal), negative volume (error, unless ERODE),
DTMIN, non-finite numbers (error), Ctrl-C (user interrupt). Every output is
written and flushed as the run goes, so whatever ends the run, what was
computed is kept.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.solver.boundary import Constraints
from hollowbody.solver.mass_scaling import MassScaling
from hollowbody.solver.monitors import Monitors
from hollowbody.solver.outputs import RunOutputs
from hollowbody.solver.progress import Progress
from hollowbody.solver.setup import Assembly, assemble

NORMAL = "normal termination"
ERROR = "error termination"
INTERRUPT = "user interrupt"


@dataclass
class RunOptions:
    """How to run: output folder, overrides and display.

    end_time: overrides *CONTROL_TERMINATION ENDTIM (ms) when given.
    erode: overrides *CONTROL_TIMESTEP ERODE when given.
    vtk: write ParaView states; quiet: no progress bar.
    """

    out_dir: Path
    end_time: float | None = None
    erode: bool | None = None
    vtk: bool = True
    quiet: bool = False
    label: str = "run"


@dataclass
class RunResult:
    """Summary of a finished run (also written to summary.json)."""

    status: str
    reason: str
    end_time_ms: float
    cycles: int
    summary: dict = field(default_factory=dict)
    out_dir: Path | None = None


class _Terminate(Exception):
    def __init__(self, status: str, reason: str, **where: object) -> None:
        super().__init__(reason)
        self.status = status
        self.reason = reason
        self.where = where


def run(model, options: RunOptions) -> RunResult:  # noqa: ANN001 - Model
    """Run ``model`` (a :class:`hollowbody.model.model.Model`) to termination."""
    out = Path(options.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    wall0 = time.perf_counter()
    asm = assemble(model)
    end_time = options.end_time if options.end_time is not None else model.controls.end_time
    erode = bool(options.erode) if options.erode is not None else bool(model.controls.erode)
    outputs = RunOutputs(out, model, asm, end_time, vtk=options.vtk)
    outputs.log(f"hollowbody explicit run: {model.n_nodes} nodes, "
                f"{asm.element_counts()} ; end time {end_time:g} ms; erosion "
                f"{'on' if erode else 'off'}")
    for rt in asm.elements:
        for w in getattr(rt, "warnings", []) or []:
            outputs.log(f"part {rt.pid}: {w}", logging.WARNING)
    if asm.ties is not None:  # [tied] set-up messages (hollowbody.solver.tied)
        asm.ties.log(lambda lvl, msg: outputs.log(msg, getattr(logging, lvl.upper())))
    loop = _Loop(model, asm, outputs, end_time, erode)
    status, reason, where = NORMAL, f"end time {end_time:g} ms reached", {}
    try:
        with Progress(end_time, quiet=options.quiet, label=options.label) as progress:
            loop.progress = progress
            loop.start()
            loop.run()
    except _Terminate as term:
        status, reason, where = term.status, term.reason, term.where
    except KeyboardInterrupt:
        status, reason = INTERRUPT, f"interrupted by the user at t={loop.t:.6g} ms"
    wall = time.perf_counter() - wall0
    summary = outputs.finish(loop, status, reason, where, wall)
    return RunResult(status, reason, loop.t, loop.cycle, summary, out)


class _Loop:
    """The time loop's state (t, cycle, x, v, f) and one method per phase."""

    def __init__(self, model, asm: Assembly, outputs: RunOutputs, end_time: float,
                 erode: bool) -> None:
        self.model = model
        self.asm = asm
        self.out = outputs
        self.end_time = end_time
        self.erode = erode
        n = model.n_nodes
        self.t = 0.0
        self.cycle = 0
        self.x = model.node_x0.astype(np.float64).copy()
        self.v = model.node_v0.astype(np.float64).copy()
        self.f = np.zeros((n, 3))
        # rotational DOFs (shell nodes): angular velocity, moment, rotational inertia
        self.w = model.node_w0.astype(np.float64).copy()
        self.mom = np.zeros((n, 3))
        self.inv_i = np.where(asm.node_rot_inertia > 0.0,
                              1.0 / np.maximum(asm.node_rot_inertia, 1e-300), 0.0)
        self.m = asm.node_mass
        self.inv_m = np.where(asm.node_mass > 0.0, 1.0 / np.maximum(asm.node_mass, 1e-300), 0.0)
        self.constraints = Constraints(model, asm.bodies)
        self.mass_scaling = MassScaling(asm.elements, model.controls.dt2ms, self.m,
                                        asm.node_rot_inertia, self.inv_m, self.inv_i)
        self.dt = 0.0
        self.dt_next = 0.0
        self.dt_crit_elem = (-1, -1)
        self.ext_work = 0.0
        self.e0 = 0.0
        self.monitors: Monitors | None = None
        self.progress: Progress | None = None
        self.n_eroded = 0
        self.dt_min = np.inf
        self.dtmin_abs = 0.0
        #: wall seconds spent in element and contact force passes
        self.timing = {"elements": 0.0, "contact": 0.0}

    # -- set-up ---------------------------------------------------------------
    def start(self) -> None:
        # prescribed rigid-body velocities hold from t = 0 (initial conditions, in the
        # initial kinetic energy, not a jump in the first cycle)
        self.constraints.apply_rigid(0.0, 0.0)
        for body in self.asm.bodies:
            self.v[body.nodes] = body.node_velocities(self.x)
        self.constraints.apply_nodes(self.v, self.x, 0.0, 0.0)
        if self.asm.ties is not None:  # [tied] slaves start with their segments' motion
            self.asm.ties.start(self.x, self.v, self.w)
        self._forces(0.0)
        self.mass_scaling.work = 0.0  # mass added at t = 0 is in the initial energy
        if not np.isfinite(self.dt_next) or self.dt_next <= 0.0:
            raise _Terminate(ERROR, "no deformable element sets a time step "
                             "(a model of rigid parts only cannot be run)")
        self.dt0 = self.dt_next
        self.dtmin_abs = self.model.controls.dtmin * self.dt0
        self.monitors = Monitors(dt_initial=self.dt0)
        self.e0 = self.kinetic_energy()
        self.out.log(f"initial time step {self.dt0:.4e} ms (element {self.dt_crit_elem[0]}, "
                     f"part {self.dt_crit_elem[1]}); initial kinetic energy {self.e0:.6g} J")
        ms = self.mass_scaling
        if self.model.controls.dt2ms > 0.0:
            self.out.log("DT2MS > 0 (mass scaling of every element to one step) runs as "
                         "DT2MS < 0: only elements below the target get mass",
                         logging.WARNING)
        if ms.target > 0.0:
            self.out.log(f"mass scaling (DT2MS): elements keep a step >= {ms.target:.4e} ms "
                         f"(run step >= {self.asm.tssfac * ms.target:.4e} ms); "
                         f"{ms.total_added:.4g} kg added at t=0")
        self.out.record(self, force=True)

    # -- one cycle ------------------------------------------------------------
    def run(self) -> None:
        dtmin = self.model.controls.dtmin
        while self.t < self.end_time * (1.0 - 1e-12):
            dt_prev = self.dt
            dt = min(self.dt_next, self.end_time - self.t) if self.end_time > self.t else 0.0
            # v^{1/2} = v^0 + dt/2 a^0 on the first cycle, then the mean of both steps
            dt_avg = 0.5 * dt if self.cycle == 0 else 0.5 * (dt_prev + dt)
            self.dt = dt
            self._advance(dt, dt_avg)
            self.t += dt
            self.cycle += 1
            self._forces(dt)
            self.dt_min = min(self.dt_min, dt)
            running = self.t < self.end_time * (1.0 - 1e-12)
            if running and not np.isfinite(self.dt_next):
                raise _Terminate(ERROR, f"no deformable element left at t={self.t:.6g} ms "
                                 f"({self.n_eroded} eroded)")
            if running and not self.dt_next > 0.0:
                elem, pid = self.dt_crit_elem
                raise _Terminate(ERROR, f"time step collapsed to zero at t={self.t:.6g} ms "
                                 f"(element {elem}, part {pid})", element=elem, part=pid)
            if dtmin > 0.0 and not self.erode and self.dt_next < dtmin * self.dt0:
                elem, pid = self.dt_crit_elem
                raise _Terminate(ERROR, f"time step {self.dt_next:.4e} ms below DTMIN "
                                 f"({dtmin:g} x initial) set by element {elem} (part {pid}) "
                                 f"at t={self.t:.6g} ms", element=elem, part=pid)
            self.out.record(self)
            if self.progress is not None:
                self.progress.update(self.t, self.cycle, dt)

    def _advance(self, dt: float, dt_avg: float) -> None:
        x, v, f = self.x, self.v, self.f
        v_free = v + dt_avg * f * self.inv_m[:, None]
        v[:] = v_free
        if self.asm.has_rotations:
            self.w += dt_avg * self.mom * self.inv_i[:, None]
            self.w[self.constraints.fixed_rot] = 0.0
        for body in self.asm.bodies:
            body.advance_velocity(dt_avg)
            free_v, free_w = body.vel_free, body.omega_free
            self.constraints.apply_rigid(self.t, dt)
            # work of the prescribed-motion reaction impulse, M (V_imp - V_free) . V_imp
            # (force times the step's displacement, as for prescribed nodes below)
            self.ext_work += body.mass * float((body.vel - free_v) @ body.vel)
            self.ext_work += float((body.omega - free_w) @ body.inertia() @ body.omega)
        self.constraints.apply_nodes(v, x, self.t, dt)
        pn = self.constraints.prescribed_nodes
        if pn.size:
            dv = v[pn] - v_free[pn]
            self.ext_work += float((self.m[pn, None] * dv * v[pn]).sum())
        x_old_rigid = [x[b.nodes].copy() for b in self.asm.bodies]
        x += dt * v
        for body, xr in zip(self.asm.bodies, x_old_rigid):
            body.advance_position(dt, x)
            if dt > 0.0:
                v[body.nodes] = (x[body.nodes] - xr) / dt
            if self.asm.has_rotations:
                self.w[body.nodes] = body.omega
        if self.asm.ties is not None:  # [tied] slaves placed on their moved segments
            self.asm.ties.follow(x, v, self.w, dt)

    def _forces(self, dt: float) -> None:
        f = self.f
        t0 = time.perf_counter()
        dt_crit, elem, pid = self._element_pass(dt)
        t1 = time.perf_counter()
        for c in self.asm.contacts:
            c.add_forces(self.x, self.v, dt, self.cycle, f)
        if self.asm.ties is not None:  # [tied] slave forces passed to the master nodes
            self.asm.ties.distribute(f, self.mom)
        t2 = time.perf_counter()
        self.timing["elements"] += t1 - t0
        self.timing["contact"] += t2 - t1
        for body in self.asm.bodies:
            body.gather(self.x, f, self.mom)
        if self.mass_scaling.active:
            self.mass_scaling.apply(self.v, self.w if self.asm.has_rotations else None)
            if self.mass_scaling.target > 0.0:
                dt_crit, elem, pid = self.mass_scaling.critical_step()
        self.dt_next = self.asm.tssfac * dt_crit
        ms = self.mass_scaling
        if ms.target > 0.0 and ms.percent_added > self.model.controls.endmas:
            pid = max(ms.added_mass, key=ms.added_mass.get)
            raise _Terminate(ERROR, f"mass scaling added {ms.percent_added:.3g} % of the "
                             f"model's mass (ENDMAS {self.model.controls.endmas:g} %), most in "
                             f"part {pid}, at t={self.t:.6g} ms", part=pid)
        self.dt_crit_elem = (elem, pid)
        if not np.all(np.isfinite(f)):
            bad = int(np.nonzero(~np.isfinite(f).all(axis=1))[0][0])
            nid = int(self.model.node_ids[bad])
            elem, pid = self._element_at(bad)
            where = (f" in element {elem} (part {pid})" if elem >= 0 else
                     " (no element of the node: from a contact or a load)")
            raise _Terminate(ERROR, f"non-finite force at node {nid}{where} at t={self.t:.6g} "
                             "ms", node=nid, element=elem, part=pid)

    def _element_at(self, node: int) -> tuple[int, int]:
        """(element id, part id) of a live element on ``node`` with a non-finite
        stress, else of any live element on it; (-1, -1) when none."""
        first = (-1, -1)
        for rt in self.asm.elements:
            on = np.nonzero((np.asarray(rt.conn) == node).any(axis=1) & rt.alive)[0]
            if on.size == 0:
                continue
            sick = on[~np.isfinite(rt.stress[on]).all(axis=1)]
            if sick.size:
                return int(rt.elem_ids[sick[0]]), int(rt.pid)
            if first[0] < 0:
                first = (int(rt.elem_ids[on[0]]), int(rt.pid))
        return first

    def _element_pass(self, dt: float) -> tuple[float, int, int]:
        """Element forces of every group into f (and moments); returns the smallest
        scaled critical step with its element id and part id.

        A negative volume ends the run (error termination) unless erosion is on;
        then the offending elements (and, with DTMIN, those whose step fell below
        it) are deleted and the pass is redone: groups already updated this cycle
        are called again with dt = 0 (forces from their updated stresses only).
        """
        done: set[int] = set()
        while True:
            self.f[:] = 0.0
            self.mom[:] = 0.0
            dt_crit, elem, pid = np.inf, -1, -1
            restart = False
            for k, rt in enumerate(self.asm.elements):
                d, i, neg = self._element_forces(rt, 0.0 if k in done else dt)
                done.add(k)
                small = self.erode and self.dtmin_abs > 0.0 and \
                    self.mass_scaling.target <= 0.0 and self.asm.tssfac * d < self.dtmin_abs
                if neg >= 0 and not self.erode:
                    eid = int(rt.elem_ids[neg])
                    if getattr(rt, "rotational", False):
                        what = (f"shell element {eid} (part {rt.pid}) collapsed in its plane "
                                "(area below 1% of the initial, or inside out)")
                    else:
                        what = f"negative volume in solid element {eid} (part {rt.pid})"
                    raise _Terminate(ERROR, f"{what} at t={self.t:.6g} ms",
                                     element=eid, part=rt.pid)
                if (neg >= 0 or small) and self._erode(rt, small):
                    restart = True
                    break
                if d < dt_crit and i >= 0:
                    dt_crit, elem, pid = d, int(rt.elem_ids[i]), rt.pid
            if not restart:
                return dt_crit, elem, pid

    def _element_forces(self, rt, dt: float) -> tuple[float, int, int]:
        """One group's forces; its critical step scaled by its ``step_factor``."""
        if getattr(rt, "rotational", False):
            d, i, neg = rt.add_forces(self.x, self.v, dt, self.f, self.w, self.mom)
        else:
            d, i, neg = rt.add_forces(self.x, self.v, dt, self.f)
        return d * getattr(rt, "step_factor", 1.0), i, neg

    def _erode(self, rt, small_step: bool) -> int:
        """Delete the elements of ``rt`` whose volume is <= 0 (solids) and, with
        ``small_step``, those whose step is below DTMIN x initial step, as
        LS-DYNA's ERODE=1 does (solids and shells). Returns how many were deleted."""
        volume = getattr(rt, "volume", None)
        if volume is not None:
            bad = (volume <= 0.0) & rt.alive
            why = "negative volume"
        else:  # shells: collapsed in their plane
            bad = rt.inverted.copy()
            why = "collapsed in its plane"
        if small_step:
            bad |= (self.asm.tssfac * getattr(rt, "step_factor", 1.0) * rt.dt_elem
                    < self.dtmin_abs) & rt.alive
            why = f"{why} or time step below DTMIN"
        bad = np.nonzero(bad)[0]
        kind = "solid" if volume is not None else "shell"
        for i in bad:
            self.out.log(f"erosion: {kind} element {int(rt.elem_ids[i])} (part {rt.pid}) "
                         f"deleted at t={self.t:.6g} ms ({why})")
        self.n_eroded += int(bad.size)
        if bad.size:
            rt.erode(bad)
            for c in self.asm.contacts:  # their segments leave the contacts
                if hasattr(c, "deactivate_elements"):
                    c.deactivate_elements(rt.pid, rt.elem_ids[bad])
        return int(bad.size)

    # -- energies ---------------------------------------------------------------
    def _half_next(self) -> float:
        """dt^{n+1} / 2 for the full-step velocity estimates (0 when no step is set)."""
        return 0.5 * self.dt_next if np.isfinite(self.dt_next) else 0.0

    def node_velocity_full_step(self) -> np.ndarray:
        """v^{n+1} estimated as v^{n+1/2} + dt/2 a^{n+1} (deformable nodes); degrees
        of freedom held by an SPC stay at zero (their force is the reaction)."""
        v = self.v + self._half_next() * self.f * self.inv_m[:, None]
        if self.constraints.any_fixed:
            v[self.constraints.fixed] = 0.0
        return v

    def kinetic_energy(self) -> float:
        v = self.node_velocity_full_step()
        ke = 0.5 * float((self.m[self.asm.deformable] *
                          (v[self.asm.deformable] ** 2).sum(axis=1)).sum())
        if self.asm.has_rotations:
            w = self.w + self._half_next() * self.mom * self.inv_i[:, None]
            d = self.asm.deformable
            ke += 0.5 * float((self.asm.node_rot_inertia[d] * (w[d] ** 2).sum(axis=1)).sum())
        return ke + sum(b.kinetic_energy() for b in self.asm.bodies)

    def energies(self) -> dict[str, float]:
        ke = self.kinetic_energy()
        ie = sum(rt.internal_energy for rt in self.asm.elements)
        hg = sum(rt.hourglass_energy for rt in self.asm.elements)
        ce = sum(c.energy for c in self.asm.contacts)
        total = ke + ie + hg + ce
        ref = self.e0 + self.ext_work + self.mass_scaling.work
        ratio = total / ref if abs(ref) > 1e-30 else 1.0
        return {"kinetic": ke, "internal": ie, "hourglass": hg, "contact": ce,
                "external_work": self.ext_work, "total": total, "energy_ratio": ratio,
                "mass_scaling_work": self.mass_scaling.work,
                "added_mass": self.mass_scaling.total_added}
