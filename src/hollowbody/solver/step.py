"""One central-difference cycle: ``step(model, plan, state, dt)``.

The cycle from t^n to t^{n+1} (order as in the LS-DYNA / OpenRadioss engines):

1. accelerations a^n = f^n / m (deformable nodes); rigid bodies from their
   resultant force and moment;
2. velocities v^{n+1/2} = v^{n-1/2} + dt_avg a^n; constraints (SPC,
   prescribed motion, rigid-body motion) imposed on them;
3. positions x^{n+1} = x^n + dt v^{n+1/2} (rigid nodes placed by their body,
   tied slaves by their segments);
4. forces f^{n+1}: element internal + hourglass + bulk viscosity, contact,
   ties; rigid-body resultants; mass scaling; the next step dt^{n+1} from the
   stable step TSSFAC * min dt_crit (:mod:`hollowbody.solver.step_control`:
   down at once, up when lasting), lowered where a contact closes fast (no
   node crosses its contact band in one step).

``plan`` is the static :class:`~hollowbody.solver.setup.Assembly`; everything
that changes lives in ``state`` (:class:`~hollowbody.solver.state.State`).
A condition that ends the run (negative volume without erosion, ENDMAS,
a non-finite force) raises :class:`Termination` once the cycle is complete,
so the State is always that of a whole cycle. Messages of the step (erosion)
are appended to ``state.events`` for the run loop to log.
"""

from __future__ import annotations

import time

import numpy as np
from numba import njit

from hollowbody.solver.rigid_set import rigid_set
from hollowbody.solver.step_control import StepControl

NORMAL = "normal termination"
ERROR = "error termination"
INTERRUPT = "user interrupt"


class Termination(Exception):
    """The run ends: ``status`` (NORMAL / ERROR / INTERRUPT), ``reason`` (one line)
    and where (element, part, node ids)."""

    def __init__(self, status: str, reason: str, **where: object) -> None:
        super().__init__(reason)
        self.status = status
        self.reason = reason
        self.where = where


def start(model, plan, state) -> None:  # noqa: ANN001 - Model, Assembly, State
    """Initial conditions and the forces at t = 0 (``state.dt_next``, ``state.dt0``).

    Raises Termination when nothing sets a time step (no deformable element and no
    rigid element with E and density: ``Assembly.rigid_dt``).
    """
    cons = plan.constraints
    # prescribed rigid-body velocities hold from t = 0 (initial conditions, in the
    # initial kinetic energy, not a jump in the first cycle)
    cons.apply_rigid(0.0, 0.0)
    for body in plan.bodies:
        state.v[body.nodes] = body.node_velocities(state.x)
    cons.apply_nodes(state.v, state.x, 0.0, 0.0)
    if plan.ties is not None:  # [tied] slaves start with their segments' motion
        plan.ties.start(state.x, state.v, state.w)
    forces(model, plan, state, 0.0)
    state.mass_scaling.work = 0.0  # mass added at t = 0 is in the initial energy
    if not np.isfinite(state.dt_next) or state.dt_next <= 0.0:
        raise Termination(ERROR, "nothing sets a time step: no deformable element, and "
                          "no rigid element with E and density on its *MAT_RIGID")
    state.dt0 = state.dt_next
    state.dtmin_abs = model.controls.dtmin * state.dt0


def step(model, plan, state, dt: float) -> None:  # noqa: ANN001 - Model, Assembly, State
    """Advance ``state`` by one cycle of ``dt`` ms (t, cycle, x, v, f, histories).
    ``state.dt_min`` takes ``dt`` (the run loop puts back the stable step when it
    cut ``dt`` short to land on the end time)."""
    dt_avg = 0.5 * dt if state.cycle == 0 else 0.5 * (state.dt + dt)
    state.dt = dt
    state.dt_min = min(state.dt_min, dt)
    advance(plan, state, dt, dt_avg)
    state.t += dt
    state.cycle += 1
    forces(model, plan, state, dt)


def advance(plan, state, dt: float, dt_avg: float) -> None:  # noqa: ANN001
    """Velocities to t^{n+1/2} and positions to t^{n+1} (steps 1-3 of the cycle)."""
    x, v, f = state.x, state.v, state.f
    cons = plan.constraints
    pn = cons.prescribed_nodes
    v_old = v[pn]
    _kick(v, f, state.inv_m, dt_avg)
    v_free = v[pn]  # before the constraints: their reaction impulses below
    if plan.has_rotations:
        state.w += dt_avg * state.mom * state.inv_i[:, None]
        state.w[cons.fixed_rot] = 0.0
    rs = rigid_set(plan) if plan.bodies else None
    if rs is not None:  # every rigid body at once (solver.rigid_set)
        rs.advance_velocity(dt_avg)
        cons.apply_rigid(state.t, dt)
        if cons.rigid_motions:
            # work of the prescribed-motion reaction impulses, M (V_imp - V_free) . V_imp
            # (force times the step's displacement, as for prescribed nodes below)
            state.ext_work += rs.prescribed_work()
    cons.apply_nodes(v, x, state.t, dt)
    for term in plan.terms:  # velocity constraints (stationary rigid walls)
        constrain = getattr(term, "constrain", None)
        if constrain is not None:
            constrain(state, dt)
    if pn.size:
        # reaction impulse m (v^{n+1/2} - v_free) times the node's displacement
        # (x^{n+1} - x^{n-1}) / 2 per unit step: the mean of v^{n-1/2} and v^{n+1/2}
        dv = v[pn] - v_free
        state.ext_work += float((state.node_mass[pn, None] * dv
                                 * 0.5 * (v_old + v[pn])).sum())
    x_old_rigid = rs.old_positions(x) if rs is not None else None
    _drift(x, v, dt)
    if rs is not None:  # rigid nodes placed by their bodies, v = (x^{n+1} - x^n) / dt
        rs.advance_position(dt, x, v, state.w if plan.has_rotations else None, x_old_rigid)
    if plan.ties is not None:  # [tied] slaves placed on their moved segments
        plan.ties.follow(x, v, state.w, dt)


@njit(cache=True)
def _kick(v, f, inv_m, dt_avg):
    """v (n, 3) mm/ms += dt_avg ms * f (n, 3) kN * inv_m (n,) 1/kg, in place (the
    numpy expression's order of operations: the same numbers, no temporaries; the
    hollow pedestrian's 71,000 nodes took 2.2 ms per cycle with them)."""
    for i in range(v.shape[0]):
        w = inv_m[i]
        for a in range(3):
            v[i, a] = v[i, a] + (dt_avg * f[i, a]) * w


@njit(cache=True)
def _drift(x, v, dt):
    """x (n, 3) mm += dt ms * v (n, 3) mm/ms, in place."""
    for i in range(x.shape[0]):
        for a in range(3):
            x[i, a] = x[i, a] + dt * v[i, a]


def forces(model, plan, state, dt: float) -> None:  # noqa: ANN001
    """Forces at t^{n+1} into ``state.f`` / ``state.mom`` and the next step (step 4)."""
    f = state.f
    t0 = time.perf_counter()
    dt_crit, elem, pid, ended = _element_pass(model, plan, state, dt)
    t1 = time.perf_counter()
    for c in plan.contacts:
        c.add_forces(state.x, state.v, dt, state.cycle, f)
    t2 = time.perf_counter()
    for term in plan.terms:  # loads, joints, rigid walls (solver.terms)
        d, eid, pid_t = term.add_forces(state, dt)
        if d < dt_crit:
            dt_crit, elem, pid = d, eid, pid_t
    if plan.ties is not None:  # [tied] slave forces passed to the master nodes
        plan.ties.distribute(f, state.mom)
    t3 = time.perf_counter()
    state.timing["elements"] += t1 - t0
    state.timing["contact"] += t2 - t1
    state.timing["mechanics"] += t3 - t2
    if plan.bodies:
        rigid_set(plan).gather(state.x, f, state.mom)
    for term in plan.terms:  # loads on rigid bodies as a whole
        after = getattr(term, "after_gather", None)
        if after is not None:
            after(state, plan.bodies, dt)
    if not plan.elements and plan.rigid_dt < dt_crit:
        # rigid bodies only (on joints): setup.rigid_element_step, unless a term
        # (a joint's penalty springs) needs a smaller step
        dt_crit, elem, pid = plan.rigid_dt, -1, -1
    ms = state.mass_scaling
    if ms.active:
        ms.apply(state.v, state.w if plan.has_rotations else None)
        if ms.target > 0.0:
            dt_crit, elem, pid = ms.critical_step()
    stable = plan.tssfac * dt_crit
    control = StepControl(*state.dt_control)  # a steady step (solver.step_control)
    held = control.next_step(stable)
    state.dt_next = held
    state.dt_control = control.state
    state.dt_crit_elem = (elem, pid)
    t4 = time.perf_counter()
    state.dt_contact = _contact_limit(plan, state)
    state.timing["contact"] += time.perf_counter() - t4  # the contacts' step limit
    # the stable step, or the contacts' limit where it set the step
    state.dt_stable = state.dt_next if state.dt_next < held else stable
    if ended is not None:
        raise ended
    if ms.target > 0.0 and ms.percent_added > model.controls.endmas:
        pid = max(ms.added_mass, key=ms.added_mass.get)
        raise Termination(ERROR, f"mass scaling added {ms.percent_added:.3g} % of the "
                          f"model's mass (ENDMAS {model.controls.endmas:g} %), most in "
                          f"part {pid}, at t={state.t:.6g} ms", part=pid)
    if not np.all(np.isfinite(f)):
        bad = int(np.nonzero(~np.isfinite(f).all(axis=1))[0][0])
        nid = int(model.node_ids[bad])
        elem, pid = element_at(plan, bad)
        where = (f" in element {elem} (part {pid})" if elem >= 0 else
                 " (no element of the node: from a contact or a load)")
        raise Termination(ERROR, f"non-finite force at node {nid}{where} at t={state.t:.6g} "
                          "ms", node=nid, element=elem, part=pid)


def _contact_limit(plan, state) -> int:  # noqa: ANN001
    """Lower ``state.dt_next`` to the contacts' kinematic limit (no node crosses its
    contact band in one step, :mod:`hollowbody.contact.kinematic_step`); returns the
    id of the contact that set it (0: none) and counts the cycle on it."""
    best = None
    for c in plan.contacts:
        d = c.kinematic_step(state.dt_next)
        if d < state.dt_next:
            state.dt_next, best = d, c
    if best is None:
        return 0
    best.n_step_limited += 1
    best.dt_kin_min = min(best.dt_kin_min, state.dt_next)
    return int(best.cid)


def element_at(plan, node: int) -> tuple[int, int]:  # noqa: ANN001
    """(element id, part id) of a live element on ``node`` with a non-finite
    stress, else of any live element on it; (-1, -1) when none."""
    first = (-1, -1)
    for rt in plan.elements:
        on = np.nonzero((np.asarray(rt.conn) == node).any(axis=1) & rt.alive)[0]
        if on.size == 0:
            continue
        sick = on[~np.isfinite(rt.stress[on]).all(axis=1)]
        if sick.size:
            return int(rt.elem_ids[sick[0]]), int(rt.pid)
        if first[0] < 0:
            first = (int(rt.elem_ids[on[0]]), int(rt.pid))
    return first


def _element_pass(model, plan, state, dt: float
                  ) -> tuple[float, int, int, Termination | None]:  # noqa: ANN001
    """Element forces of every group into f (and moments); returns the smallest
    scaled critical step with its element id and part id, and the termination
    to raise at the end of the cycle (negative volume without erosion) or None.

    With erosion on, elements with a negative volume (and, with DTMIN, those
    whose step fell below it) are deleted and the pass is redone: groups
    already updated this cycle are called again with dt = 0 (forces from their
    updated stresses only).
    """
    erode = bool(plan.erode)
    done: set[int] = set()
    while True:
        state.f[:] = 0.0
        state.mom[:] = 0.0
        dt_crit, elem, pid = np.inf, -1, -1
        restart = False
        ended: Termination | None = None
        for k, rt in enumerate(plan.elements):
            d, i, neg = _group_forces(rt, state, 0.0 if k in done else dt)
            done.add(k)
            small = erode and state.dtmin_abs > 0.0 and \
                state.mass_scaling.target <= 0.0 and plan.tssfac * d < state.dtmin_abs
            if neg >= 0 and not erode and ended is None:
                eid = int(rt.elem_ids[neg])
                if getattr(rt, "rotational", False):
                    what = (f"shell element {eid} (part {rt.pid}) collapsed in its plane "
                            "(area below 1% of the initial, or inside out)")
                else:
                    what = f"negative volume in solid element {eid} (part {rt.pid})"
                ended = Termination(ERROR, f"{what} at t={state.t:.6g} ms", element=eid,
                                    part=rt.pid)
            if (neg >= 0 or small) and erode and _erode(plan, state, rt, small):
                restart = True
                break
            if d < dt_crit and i >= 0:
                dt_crit, elem, pid = d, int(rt.elem_ids[i]), rt.pid
        if not restart:
            return dt_crit, elem, pid, ended


def _group_forces(rt, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
    """One group's forces; its critical step scaled by its ``step_factor``."""
    if getattr(rt, "rotational", False):
        d, i, neg = rt.add_forces(state.x, state.v, dt, state.f, state.w, state.mom)
    else:
        d, i, neg = rt.add_forces(state.x, state.v, dt, state.f)
    return d * getattr(rt, "step_factor", 1.0), i, neg


def _erode(plan, state, rt, small_step: bool) -> int:  # noqa: ANN001
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
        bad |= (plan.tssfac * getattr(rt, "step_factor", 1.0) * rt.dt_elem
                < state.dtmin_abs) & rt.alive
        why = f"{why} or time step below DTMIN"
    bad = np.nonzero(bad)[0]
    kind = "solid" if volume is not None else "shell"
    for i in bad:
        state.events.append(("info", f"erosion: {kind} element {int(rt.elem_ids[i])} "
                                     f"(part {rt.pid}) deleted at t={state.t:.6g} ms ({why})"))
    state.n_eroded += int(bad.size)
    if bad.size:
        rt.erode(bad)
        for c in plan.contacts:  # their segments leave the contacts
            if hasattr(c, "deactivate_elements"):
                c.deactivate_elements(rt.pid, rt.elem_ids[bad])
    return int(bad.size)
