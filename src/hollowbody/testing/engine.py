"""The engine's own cycle, cycle by cycle, for tests that watch a run as it goes.

:class:`EngineRun` assembles the plan of a Model, creates its State, computes
the forces at t = 0 and then advances with the engine's
:func:`hollowbody.solver.step.step`: the same central-difference cycle, element
kernels, constraints and time-step rule as ``hollowbody run``, without output
files. Units: mm, ms, kg, kN.
"""

from __future__ import annotations

import numpy as np

from hollowbody.model.model import Model
from hollowbody.solver.energies import kinetic_energy
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step


class EngineRun:
    """A run of ``model`` driven one cycle at a time.

    dt: a constant step (ms) instead of the engine's TSSFAC x critical step.
    Attributes: ``plan`` (the Assembly), ``state`` (the State).
    """

    def __init__(self, model: Model, dt: float | None = None) -> None:
        self.model = model
        self.plan = assemble(model)
        self.state = init_state(model, self.plan)
        start(model, self.plan, self.state)
        self.fixed_dt = dt

    @property
    def t(self) -> float:
        """Time (ms) of the State."""
        return self.state.t

    @property
    def mass(self) -> np.ndarray:
        """(n,) kg lumped nodal masses of the run."""
        return self.state.node_mass

    def step(self) -> np.ndarray:
        """One engine cycle; returns the full-step velocities v^{n+1} = v^{n+1/2} +
        dt/2 f^{n+1} / m (n, 3) mm/ms, with dt the step just taken."""
        s = self.state
        dt = self.fixed_dt if self.fixed_dt is not None else s.dt_next
        step(self.model, self.plan, s, dt)
        return s.v + 0.5 * dt * s.f * s.inv_m[:, None]

    def kinetic(self, v: np.ndarray) -> float:
        """Kinetic energy (J) of the deformable nodes at velocities v (n, 3) mm/ms."""
        d = self.plan.deformable
        return 0.5 * float((self.state.node_mass[d, None] * v[d] ** 2).sum())

    def kinetic_energy(self) -> float:
        """The run's own kinetic energy (J) of the State (as in glstat)."""
        return kinetic_energy(self.plan, self.state)
