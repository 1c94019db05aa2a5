"""Energies of a run's State (J): kinetic, internal, hourglass, contact, the balance.

The energy ratio is total / (initial kinetic energy + external work + the
kinetic energy given to mass added by mass scaling); it checks the
integration (1 within a few % for a sound run).
"""

from __future__ import annotations

import numpy as np


def _half_next(state) -> float:  # noqa: ANN001 - State
    """dt^{n+1} / 2 for the full-step velocity estimates (0 when no step is set)."""
    return 0.5 * state.dt_next if np.isfinite(state.dt_next) else 0.0


def node_velocity_full_step(plan, state) -> np.ndarray:  # noqa: ANN001
    """v^{n+1} (n, 3) mm/ms estimated as v^{n+1/2} + dt/2 a^{n+1} (deformable nodes);
    degrees of freedom held by an SPC stay at zero (their force is the reaction)."""
    v = state.v + _half_next(state) * state.f * state.inv_m[:, None]
    if plan.constraints.any_fixed:
        v[plan.constraints.fixed] = 0.0
    return v


def kinetic_energy(plan, state) -> float:  # noqa: ANN001
    """Kinetic energy (J) of deformable nodes (translation, rotation) and rigid bodies."""
    v = node_velocity_full_step(plan, state)
    d = plan.deformable
    ke = 0.5 * float((state.node_mass[d] * (v[d] ** 2).sum(axis=1)).sum())
    if plan.has_rotations:
        w = state.w + _half_next(state) * state.mom * state.inv_i[:, None]
        w[plan.constraints.fixed_rot] = 0.0  # SPC'd rotations: their moment is the reaction
        ke += 0.5 * float((state.node_rot_inertia[d] * (w[d] ** 2).sum(axis=1)).sum())
    return ke + sum(b.kinetic_energy() for b in plan.bodies)


def energies(plan, state) -> dict[str, float]:  # noqa: ANN001
    """{kinetic, internal, hourglass, contact, external_work, total, energy_ratio,
    mass_scaling_work, added_mass (kg)} at the State's time."""
    ke = kinetic_energy(plan, state)
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
