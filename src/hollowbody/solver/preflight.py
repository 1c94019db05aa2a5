"""What a run would do at t = 0, without running: the first time step and the set-up
errors (``hollowbody check``).

The first step is the run's own: the plan is assembled, the State initialised
and the forces at t = 0 computed exactly as :func:`hollowbody.solver.explicit.run`
does (:func:`hollowbody.solver.step.start`), so ``check`` and ``run`` agree by
construction and ``check`` rejects every deck the run's set-up rejects, with the
same message.
"""

from __future__ import annotations

import numpy as np

from hollowbody.errors import UserInputError
from hollowbody.solver import threads as th
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import Termination, start


def _smallest(plan, rotational: bool, family: str | None = None
              ) -> dict | None:  # noqa: ANN001 - Assembly
    best = None
    for rt in plan.elements:
        if bool(getattr(rt, "rotational", False)) != rotational or rt.n_elem == 0 \
                or getattr(rt, "family", "") == "discrete":  # reported as "discrete"
            continue
        if getattr(rt, "family", None) != family:  # solids, shells: no family name
            continue
        d = np.asarray(rt.dt_elem) * getattr(rt, "step_factor", 1.0)
        k = int(np.argmin(d))
        if np.isfinite(d[k]) and (best is None or d[k] < best["dt"]):
            best = {"dt": float(d[k]), "element": int(rt.elem_ids[k]), "part": int(rt.pid)}
    return best


def first_time_step(model, threads: int | str | None = None) -> dict:  # noqa: ANN001 - Model
    """The run's time steps at t = 0 (ms) and its numba threads.

    Returns {"solid": {dt, element, part} or None, "shell": ..., "beam": ... (the smallest
    critical step of each element family, before TSSFAC, with its step
    factor), "tssfac", "run_dt" (the first step the run takes), "element",
    "part" (what sets it), "mass_scaling_target", "threads": {"count",
    "reason"}}: the threads the run would use with the ``threads`` setting
    (None: the process default, as the run does; see
    :mod:`hollowbody.solver.threads`), which also compute the forces at t = 0.
    Raises DeckError for what the run's set-up rejects and
    :class:`~hollowbody.solver.step.Termination` when nothing sets a step.
    """
    plan = assemble(model)
    try:
        n_threads, why = th.resolve(threads if threads is not None else th.default(),
                                    th.model_work(plan))
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    state = init_state(model, plan)
    with th.using(n_threads):
        start(model, plan, state)
    elem, pid = state.dt_crit_elem
    disc = [rt for rt in plan.elements if getattr(rt, "family", "") == "discrete"]
    steps = [(float(np.min(rt.dt_elem)), rt) for rt in disc if rt.n_elem]
    low = min(steps, key=lambda p: p[0], default=None)
    discrete = None if low is None or not np.isfinite(low[0]) else {
        "dt": low[0], "element": int(low[1].elem_ids[int(np.argmin(low[1].dt_elem))]),
        "part": int(low[1].pid)}
    return {"solid": _smallest(plan, False), "shell": _smallest(plan, True),
            "discrete": discrete,
            "beam": _smallest(plan, True, "beams"),
            "tssfac": plan.tssfac, "run_dt": float(state.dt_next), "element": int(elem),
            "part": int(pid), "mass_scaling_target": state.mass_scaling.target,
            "threads": {"count": n_threads, "reason": why}}


__all__ = ["Termination", "first_time_step"]
