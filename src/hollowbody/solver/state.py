"""The State of a run: everything that changes in time.

:class:`State` holds the node arrays (positions, velocities, rotations,
forces, the masses that mass scaling changes), the clock (time, cycle, steps),
the energy accumulators and the run's counters. The time-varying arrays of the
runtime objects of the plan (element groups' stresses and material history,
contacts' history, rigid bodies, ties, mass scaling, monitors) are part of the
State too: each such object names them in its class attribute
``STATE_FIELDS`` and the State lists the objects in ``parts`` under stable
keys (``elements/0``, ``contacts/1``, ``bodies/0``, ``ties``, ...).
:func:`snapshot` and :func:`restore` read and write all of it, which is what a
restart file is (:mod:`hollowbody.solver.restart`).

Arrays: n = number of nodes; x (n, 3) mm at t^n; v (n, 3) mm/ms at t^{n-1/2};
f (n, 3) kN at t^n; w (n, 3) rad/ms; mom (n, 3) kN*mm; node_mass (n,) kg,
node_rot_inertia (n,) kg*mm^2 and their inverses inv_m, inv_i (0 where the
mass is 0).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

import numpy as np

from hollowbody.solver.mass_scaling import MassScaling
from hollowbody.solver.monitors import Monitors

#: Scalars and arrays of the State itself that a snapshot carries.
STATE_SCALARS = ("t", "cycle", "dt", "dt_next", "dt0", "dt_min", "dtmin_abs", "dt_crit_elem",
                 "dt_contact", "ext_work", "e0", "n_eroded", "timing", "dt_stable", "dt_control")
#: Scalars added after restart files were first written: their value when a file lacks them.
_LATER_SCALARS = {"dt_stable": 0.0, "dt_control": (0.0, 0, math.inf, 0, 0, 0.0)}
STATE_ARRAYS = ("x", "v", "f", "w", "mom", "node_mass", "inv_m", "node_rot_inertia", "inv_i")


@dataclass
class State:
    """Time-varying data of one run (see the module docstring for shapes and units).

    t: ms; cycle: completed cycles; dt: the last step taken (ms); dt_next: the
    next step (ms): TSSFAC * smallest critical step as
    :mod:`hollowbody.solver.step_control` lets it change (dt_control: that control's
    state), lowered by the contacts' kinematic limit; dt_stable: TSSFAC * smallest
    critical step or that limit when smaller (ms); dt0: the first step;
    dt_min: the smallest stable step taken (a last step cut short to land on the
    end time is not counted); dtmin_abs: DTMIN x dt0 (ms, 0 = off);
    dt_crit_elem: (element id, part id) whose critical step is the smallest;
    dt_contact: id of the contact whose kinematic limit set dt_next below that
    element's TSSFAC x step (0: none; :mod:`hollowbody.contact.kinematic_step`); ext_work: J work of
    prescribed motions; e0: J initial kinetic energy; n_eroded: deleted elements;
    timing: wall seconds per force pass; events: (level, message) produced by
    the step for the observers (drained by the run loop); parts: {key: object
    with STATE_FIELDS}.
    """

    x: np.ndarray
    v: np.ndarray
    f: np.ndarray
    w: np.ndarray
    mom: np.ndarray
    node_mass: np.ndarray
    inv_m: np.ndarray
    node_rot_inertia: np.ndarray
    inv_i: np.ndarray
    mass_scaling: MassScaling
    monitors: Monitors | None = None
    t: float = 0.0
    cycle: int = 0
    dt: float = 0.0
    dt_next: float = 0.0
    dt_stable: float = 0.0
    dt_control: tuple[float, int, float, int, int, float] = (0.0, 0, math.inf, 0, 0, 0.0)
    dt0: float = 0.0
    dt_min: float = np.inf
    dtmin_abs: float = 0.0
    dt_crit_elem: tuple[int, int] = (-1, -1)
    dt_contact: int = 0
    ext_work: float = 0.0
    e0: float = 0.0
    n_eroded: int = 0
    timing: dict[str, float] = field(default_factory=lambda: {"elements": 0.0, "mechanics": 0.0,
                                                               "contact": 0.0})
    events: list[tuple[str, str]] = field(default_factory=list)
    parts: dict[str, object] = field(default_factory=dict)


def _inverse(a: np.ndarray) -> np.ndarray:
    return np.where(a > 0.0, 1.0 / np.maximum(a, 1e-300), 0.0)


def init_state(model, plan) -> State:  # noqa: ANN001 - Model, Assembly
    """The State at t = 0 of ``model`` run with ``plan`` (an Assembly), before the
    initial forces (see :func:`hollowbody.solver.step.start`)."""
    n = model.n_nodes
    x0 = plan.node_x0 if plan.node_x0.shape == (n, 3) else model.node_x0
    node_mass = plan.node_mass.copy()
    rot = plan.node_rot_inertia.copy() if plan.node_rot_inertia.size == n else np.zeros(n)
    inv_m, inv_i = _inverse(node_mass), _inverse(rot)
    ms = MassScaling(plan.elements, model.controls.dt2ms, node_mass, rot, inv_m, inv_i)
    state = State(x=np.asarray(x0, dtype=np.float64).copy(),
                  v=model.node_v0.astype(np.float64).copy(), f=np.zeros((n, 3)),
                  w=model.node_w0.astype(np.float64).copy(), mom=np.zeros((n, 3)),
                  node_mass=node_mass, inv_m=inv_m, node_rot_inertia=rot, inv_i=inv_i,
                  mass_scaling=ms)
    state.parts = state_parts(plan, state)
    return state


def state_parts(plan, state: State) -> dict[str, object]:  # noqa: ANN001 - Assembly
    """The objects whose STATE_FIELDS belong to the State, under stable keys."""
    parts: dict[str, object] = {}
    for k, rt in enumerate(plan.elements):
        parts[f"elements/{k}"] = rt
    for k, c in enumerate(plan.contacts):
        parts[f"contacts/{k}"] = c
        for j, p in enumerate(getattr(c, "passes", ())):
            parts[f"contacts/{k}/passes/{j}"] = p
    for k, b in enumerate(plan.bodies):
        parts[f"bodies/{k}"] = b
    if plan.ties is not None:
        parts["ties"] = plan.ties
    for k, term in enumerate(getattr(plan, "terms", ())):
        if getattr(type(term), "STATE_FIELDS", ()):
            parts[f"terms/{k}"] = term
    parts["mass_scaling"] = state.mass_scaling
    for k, g in enumerate(state.mass_scaling.groups):
        parts[f"mass_scaling/{k}"] = g
    return parts


def _fields(obj: object) -> tuple[str, ...]:
    names = getattr(type(obj), "STATE_FIELDS", None)
    if names is None:
        raise TypeError(f"{type(obj).__name__} does not declare STATE_FIELDS: its state "
                        "cannot be saved")
    return tuple(names)


def snapshot(state: State) -> dict[str, object]:
    """Deep copy of everything in ``state``: {"state": {...}, "parts": {key: {...}}}."""
    own = {name: copy.deepcopy(getattr(state, name)) for name in STATE_SCALARS}
    own.update({name: np.array(getattr(state, name)) for name in STATE_ARRAYS})
    if state.monitors is not None:
        own["monitors"] = {name: copy.deepcopy(getattr(state.monitors, name))
                           for name in Monitors.STATE_FIELDS}
    parts = {key: {name: copy.deepcopy(getattr(obj, name, None)) for name in _fields(obj)}
             for key, obj in state.parts.items()}
    return {"state": own, "parts": parts}


def _assign(obj: object, name: str, value: object) -> None:
    """Set ``obj.name`` to ``value``: arrays of the same shape and dtype in place (other
    objects may hold a reference to them), anything else by rebinding a copy."""
    cur = getattr(obj, name, None)
    if (isinstance(cur, np.ndarray) and isinstance(value, np.ndarray)
            and cur.shape == value.shape and cur.dtype == value.dtype):
        cur[...] = value
    else:
        setattr(obj, name, copy.deepcopy(value))


def _empty(obj: object, name: str) -> bool:
    value = getattr(obj, name, None)
    return isinstance(value, np.ndarray) and value.size == 0


def restore(state: State, snap: dict[str, object]) -> None:
    """Put a :func:`snapshot` back into ``state`` and its parts (same model and plan).

    Raises ValueError when the snapshot's parts do not match the State's.
    """
    own, parts = snap["state"], snap["parts"]
    missing = set(state.parts) ^ set(parts)
    if missing:
        raise ValueError(f"the saved state has other parts ({', '.join(sorted(missing))})")
    for key, obj in state.parts.items():
        saved = parts[key]
        # a field added in a later version that holds nothing in this run (an empty
        # array) may be missing from a dump written before it
        absent = {name for name in set(_fields(obj)) - set(saved) if _empty(obj, name)}
        if set(saved) | absent != set(_fields(obj)):
            raise ValueError(f"the saved state of {key} has other fields")
    for name in STATE_ARRAYS:
        cur, value = getattr(state, name), own[name]
        if cur.shape != value.shape:
            raise ValueError(f"the saved {name} has shape {value.shape}, not {cur.shape}")
        cur[...] = value
    for name in STATE_SCALARS:
        setattr(state, name, copy.deepcopy(own[name] if name in own else _LATER_SCALARS[name]))
    if "monitors" in own:
        if state.monitors is None:
            state.monitors = Monitors(dt_initial=state.dt0)
        for name, value in own["monitors"].items():
            setattr(state.monitors, name, copy.deepcopy(value))
    for key, obj in state.parts.items():
        for name, value in parts[key].items():
            if value is None and getattr(obj, name, None) is None:
                continue
            _assign(obj, name, value)
