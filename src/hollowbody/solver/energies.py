"""Energies of a run's State (J): kinetic, internal, hourglass, contact, the balance.

The energy ratio is total / (initial kinetic energy + external work + the
kinetic energy given to mass added by mass scaling); it checks the
integration (1 within a few % for a sound run).
"""

from __future__ import annotations

import numpy as np

from hollowbody.solver.energy_kernels import (
    full_step_velocity,
    rotational_energy,
    translational_energy,
)


def _half_step(state) -> float:  # noqa: ANN001 - State
    """Half the step just taken, dt^n / 2, for the full-step velocity estimates
    v^{n+1} = v^{n+1/2} + dt^n / 2 a^{n+1}: v^{n+1/2} is the velocity at the middle of
    that step, t^n + dt^n / 2, whatever the sequence of steps (exact for a constant
    acceleration, also when the last step was cut to land on the end time). 0 at
    cycle 0, where the State's velocities are the initial ones."""
    if state.cycle == 0:
        return 0.0
    return 0.5 * state.dt if np.isfinite(state.dt) else 0.0


def node_velocity_full_step(plan, state, out: np.ndarray | None = None) -> np.ndarray:  # noqa: ANN001
    """v^{n+1} (n, 3) mm/ms estimated as v^{n+1/2} + dt/2 a^{n+1} (deformable nodes);
    degrees of freedom held by an SPC stay at zero (their force is the reaction), and
    nodes on a rigid wall do not move into it (``term.full_step_velocity``). ``out``:
    an (n, 3) array to write into (default: a new one)."""
    v = np.empty_like(state.v) if out is None else out
    c = plan.constraints
    fixed = c.fixed if c is not None else np.zeros((0, 3), dtype=bool)
    full_step_velocity(state.v, state.f, state.inv_m, _half_step(state), fixed,
                       bool(c is not None and c.any_fixed), v)
    for term in getattr(plan, "terms", ()):  # velocity constraints (rigid walls)
        stop = getattr(term, "full_step_velocity", None)
        if stop is not None:
            stop(state, v)
    return v


def kinetic_energy(plan, state, v: np.ndarray | None = None) -> float:  # noqa: ANN001
    """Kinetic energy (J) of deformable nodes (translation, rotation) and rigid bodies;
    ``v``: the full-step velocities of :func:`node_velocity_full_step` when the caller
    has them."""
    if v is None:
        v = node_velocity_full_step(plan, state)
    d = np.flatnonzero(plan.deformable)
    ke = translational_energy(v, state.node_mass, d)
    if plan.has_rotations:  # SPC'd rotations at zero: their moment is the reaction
        ke += rotational_energy(state.w, state.mom, state.inv_i, _half_step(state),
                                plan.constraints.fixed_rot, state.node_rot_inertia, d)
    half = _half_step(state)
    return ke + sum(rigid_kinetic_energy(b, half) for b in plan.bodies)


def rigid_kinetic_energy(body, half: float) -> float:  # noqa: ANN001 - RigidBody
    """Kinetic energy (J) of a rigid body at the full step, as for the nodes:
    V^{n+1/2} + dt/2 F^{n+1} / M and w^{n+1/2} + dt/2 I^{-1} (M^{n+1} - w x I w)
    (constrained and prescribed components unchanged; ``half`` = dt^n / 2 ms)."""
    acc = body.force / body.mass if body.mass > 0.0 else np.zeros(3)
    acc = np.where(body.fixed_trans | body.prescribed_trans, 0.0, acc)
    vel = body.vel + half * acc
    inertia = body.inertia()
    omega = body.omega
    if half > 0.0 and np.linalg.det(inertia) > 0.0:
        alpha = np.linalg.solve(inertia, body.moment - np.cross(omega, inertia @ omega))
        omega = omega + half * np.where(body.fixed_rot | body.prescribed_rot, 0.0, alpha)
    return 0.5 * body.mass * float(vel @ vel) + 0.5 * float(omega @ inertia @ omega)


def energies(plan, state, v: np.ndarray | None = None) -> dict[str, float]:  # noqa: ANN001
    """{kinetic, internal, hourglass, contact, external_work, total, energy_ratio,
    mass_scaling_work, added_mass (kg)} at the State's time (``v``: as for
    :func:`kinetic_energy`)."""
    ke = kinetic_energy(plan, state, v)
    terms = getattr(plan, "terms", ())
    ie = sum(rt.internal_energy for rt in plan.elements)
    ie += sum(getattr(t, "internal_energy", 0.0) for t in terms)
    hg = sum(rt.hourglass_energy for rt in plan.elements)
    ce = sum(c.energy for c in plan.contacts)
    ce += sum(getattr(t, "contact_energy", 0.0) for t in terms)
    ext = state.ext_work + sum(getattr(t, "external_work", 0.0) for t in terms)
    total = ke + ie + hg + ce
    ms = state.mass_scaling
    ref = state.e0 + ext + ms.work
    ratio = total / ref if abs(ref) > 1e-30 else 1.0
    return {"kinetic": ke, "internal": ie, "hourglass": hg, "contact": ce,
            "external_work": ext, "total": total, "energy_ratio": ratio,
            "mass_scaling_work": ms.work, "added_mass": ms.total_added}
