"""Force terms: loads, rigid walls and joints, listed in one place.

A *term* is a runtime object of the plan (``Assembly.terms``) that acts on the
nodes (and rigid bodies) besides the elements and contacts. The cycle
(:mod:`hollowbody.solver.step`) calls, in this order:

1. ``term.constrain(state, dt)`` (optional): after the velocities
   v^{n+1/2} are set and the SPCs / prescribed motions imposed, before the
   positions move; a velocity constraint (a stationary rigid wall stopping the
   nodes that would pass it);
2. ``term.add_forces(state, dt) -> (dt_crit, element_id, part_id)``: after the
   element and contact forces at t^{n+1}, before the tied slaves' forces go to
   their masters and before the rigid bodies gather their resultants; adds
   kN to ``state.f`` (and kN*mm to ``state.mom``); returns the term's own
   critical step (ms, ``inf`` when it sets none) and what sets it (ids or -1);
3. ``term.after_gather(state, bodies, dt)`` (optional): after the rigid bodies have
   gathered their resultant force and moment (``body.force``, ``body.moment``),
   for loads that act on a body as a whole (gravity on a rigid body with
   *PART_INERTIA mass, *LOAD_RIGID_BODY).

Energy (J, accumulated over the run, read by :mod:`hollowbody.solver.energies`):
``internal_energy`` (springs, penalty joints: stored plus dissipated),
``contact_energy`` (rigid walls) and ``external_work`` (loads). A missing
attribute counts as 0. A term whose data change in time lists them in
``STATE_FIELDS`` (saved in restart files under ``terms/<k>``).
"""

from __future__ import annotations


def collect_terms(model, plan) -> list:  # noqa: ANN001 - Model, Assembly
    """Every force term of ``model`` (loads, rigid walls, joints), in cycle order."""
    from hollowbody.solver.joints import joint_terms
    from hollowbody.solver.loads import load_terms
    from hollowbody.solver.rigidwall import rigidwall_terms

    return [*load_terms(model, plan), *joint_terms(model, plan),
            *rigidwall_terms(model, plan)]
