"""Nodal constraints (SPC) and prescribed motions applied to velocities.

SPC: a fixed translational DOF has zero velocity; the reaction (spcforc) is
the force needed to keep it there: ``R = -f`` on that DOF (f being the sum of
all other nodal forces), since its acceleration is zero.

Prescribed motion (*BOUNDARY_PRESCRIBED_MOTION_...): VAD 0 sets the velocity,
VAD 1 integrates an acceleration, VAD 2 sets the velocity that brings the DOF
to the prescribed displacement at the end of the step (no drift). Rotational
DOFs (5-7) apply to rigid bodies only.
"""

from __future__ import annotations

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.model.model import Model, PrescribedMotion
from hollowbody.solver.rigid import RigidBody


class Constraints:
    """SPC masks and prescribed motions of a model.

    fixed: (n, 3) bool translational DOFs held at zero velocity.
    """

    def __init__(self, model: Model, bodies: list[RigidBody]) -> None:
        n = model.n_nodes
        self.fixed = np.zeros((n, 3), dtype=bool)
        self.fixed_rot = np.zeros((n, 3), dtype=bool)
        for spc in model.spcs:
            dofs = np.asarray(spc.dofs, dtype=bool)
            self.fixed[spc.nodes] |= dofs[:, :3]
            self.fixed_rot[spc.nodes] |= dofs[:, 3:6]
        self.any_fixed = bool(self.fixed.any())
        self.fixed_nodes = np.nonzero(self.fixed.any(axis=1))[0]
        self.x0 = model.node_x0
        self.curves = model.curves
        self.node_motions: list[PrescribedMotion] = []
        self.rigid_motions: list[tuple[PrescribedMotion, RigidBody]] = []
        by_pid = {p: b for b in bodies for p in (getattr(b, "pids", None) or [b.pid])}
        for pm in model.prescribed:
            if pm.lcid not in model.curves:
                raise DeckError(f"curve {pm.lcid} is not defined", pm.source.file,
                                pm.source.line, "BOUNDARY_PRESCRIBED_MOTION")
            if pm.dof not in (1, 2, 3, 5, 6, 7):
                raise DeckError(f"DOF={pm.dof} is not supported (1-3, 5-7)", pm.source.file,
                                pm.source.line, "BOUNDARY_PRESCRIBED_MOTION")
            if pm.target == "rigid":
                if pm.pid not in by_pid:
                    raise DeckError(f"part {pm.pid} is not a rigid body", pm.source.file,
                                    pm.source.line, "BOUNDARY_PRESCRIBED_MOTION_RIGID")
                body = by_pid[pm.pid]
                axis = (pm.dof - 1) if pm.dof <= 3 else (pm.dof - 5)
                (body.prescribed_trans if pm.dof <= 3 else body.prescribed_rot)[axis] = True
                self.rigid_motions.append((pm, body))
            else:
                if pm.dof > 3:
                    raise DeckError("rotational prescribed motion of nodes needs shells "
                                    "(not supported yet)", pm.source.file, pm.source.line,
                                    "BOUNDARY_PRESCRIBED_MOTION_NODE")
                self.node_motions.append(pm)
        self.prescribed_nodes = np.unique(np.concatenate(
            [pm.nodes for pm in self.node_motions])) if self.node_motions else \
            np.zeros(0, dtype=np.int64)

    def _value(self, pm: PrescribedMotion, t: float) -> float:
        return pm.sf * self.curves[pm.lcid](t)

    def _active(self, pm: PrescribedMotion, t: float) -> bool:
        return pm.birth <= t <= pm.death

    def apply_nodes(self, v: np.ndarray, x: np.ndarray, t: float, dt: float) -> None:
        """Impose SPC and nodal prescribed motion on v^{n+1/2} (n, 3) mm/ms.

        t: time t^n (ms) at the start of the step, dt: step to t^{n+1}.
        """
        if self.any_fixed:
            v[self.fixed] = 0.0
        for pm in self.node_motions:
            if not self._active(pm, t + dt):
                continue
            k = pm.dof - 1
            if pm.vad == 0:
                v[pm.nodes, k] = self._value(pm, t + 0.5 * dt)
            elif pm.vad == 1:
                v[pm.nodes, k] += dt * self._value(pm, t)
            elif dt > 0.0:
                target = self.x0[pm.nodes, k] + self._value(pm, t + dt)
                v[pm.nodes, k] = (target - x[pm.nodes, k]) / dt

    def apply_rigid(self, t: float, dt: float) -> None:
        """Impose prescribed motions on rigid-body velocities for the step t -> t + dt."""
        for pm, body in self.rigid_motions:
            if not self._active(pm, t + dt):
                continue
            rot = pm.dof > 3
            k = (pm.dof - 5) if rot else (pm.dof - 1)
            vec = body.omega if rot else body.vel
            if pm.vad == 0:
                vec[k] = self._value(pm, t + 0.5 * dt)
            elif pm.vad == 1:
                vec[k] += dt * self._value(pm, t)
            elif dt > 0.0 and not rot:
                vec[k] = (body.xc0[k] + self._value(pm, t + dt) - body.xc[k]) / dt
            elif dt > 0.0:  # rotation angle about a global axis, small-step rate
                vec[k] = (self._value(pm, t + dt) - self._value(pm, t)) / dt

    def reactions(self, f: np.ndarray) -> np.ndarray:
        """Total SPC reaction force (3,) kN: -sum of f over fixed DOFs."""
        if not self.any_fixed:
            return np.zeros(3)
        return -np.where(self.fixed, f, 0.0).sum(axis=0)
