"""Rigid bodies: *MAT_RIGID parts (with merged parts and extra nodes) and nodal
rigid bodies (:mod:`hollowbody.model.rigid_bodies` defines them).

A rigid body has mass ``M`` (kg), centre ``xc`` (3,) mm, inertia about the
centre in the body's initial orientation ``I0`` (3, 3) kg*mm^2 and rotation
``R`` (3, 3). Its nodes follow ``x_i = xc + R (X_i - Xc0)``; the forces the
rest of the model puts on those nodes (contact) are summed into a resultant
force and moment, and the body is advanced with the same central-difference
step as the nodes:

    V^{n+1/2} = V^{n-1/2} + dt * F / M
    L^{n-1/2} = I(R^{n-1}) w^{n-1/2};   L^{n+1/2} = L^{n-1/2} + dt * Mc
    w^{n+1/2} = I(R^n)^{-1} L^{n+1/2}                        (I(R) = R I0 R^T)
    xc^{n+1}  = xc^n + dt V^{n+1/2};   R^{n+1} = exp(dt [w^{n+1/2}]x) R^n

The rotation is advanced through the spatial angular momentum L (Euler's
equation dL/dt = Mc in the global frame), so a torque-free body keeps L to
round-off; ``rot_w`` is the rotation R^{n-1} at which the current w was made
(w^{n-1/2} = I(R^{n-1})^{-1} L^{n-1/2}). The kinetic energy of a tumbling body
is not exactly conserved by this explicit update (its error is first order in dt).

Constraints (*MAT_RIGID CMO = +1, CON1 / CON2 in global axes, or a nodal
rigid body's _SPC card) zero the corresponding components of V and w. Mass
properties: :func:`hollowbody.model.rigid_bodies.rigid_body_defs`. In the run
all bodies advance together (:mod:`hollowbody.solver.rigid_set`, one kernel over
every body); the methods below advance one body alone and give the same values.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from hollowbody.model.model import Model
from hollowbody.model.rigid_bodies import rigid_body_defs


def _rotation(phi: np.ndarray) -> np.ndarray:
    """Rotation matrix of the rotation vector phi (3,) rad (Rodrigues)."""
    angle = float(np.linalg.norm(phi))
    if angle < 1e-14:
        return np.eye(3)
    k = phi / angle
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(angle) * kx + (1.0 - np.cos(angle)) * (kx @ kx)


@dataclass
class RigidBody:
    """State of one rigid body (see module docstring for the symbols)."""

    #: time-varying attributes (saved by the run's State)
    STATE_FIELDS = ("xc", "rot", "vel", "omega", "force", "moment", "vel_free", "omega_free",
                    "rot_w")

    pid: int
    nodes: np.ndarray  # (k,) int64 node indices
    mass: float
    xc: np.ndarray  # (3,) mm
    inertia0: np.ndarray  # (3, 3) kg*mm^2
    rot: np.ndarray  # (3, 3)
    vel: np.ndarray  # (3,) mm/ms
    omega: np.ndarray  # (3,) rad/ms
    local0: np.ndarray  # (k, 3) mm node offsets at t=0
    fixed_trans: np.ndarray  # (3,) bool
    fixed_rot: np.ndarray  # (3,) bool
    force: np.ndarray  # (3,) kN resultant of the last cycle
    moment: np.ndarray  # (3,) kN*mm
    prescribed_trans: np.ndarray  # (3,) bool, velocity set by prescribed motion
    prescribed_rot: np.ndarray  # (3,) bool
    xc0: np.ndarray  # (3,) mm centre at t=0
    #: every part id the body is made of (lead first; [pid] for a nodal rigid body)
    pids: list[int] = field(default_factory=list)
    kind: str = "part"  # "part" (*MAT_RIGID parts) or "nodal" (nodal rigid body)
    iprt: int = 0  # 2: not written to rbdout
    pnode: int = -1  # node index kept at the centre of mass (-1: none)
    #: (3, 3) rotation at which omega was last updated (None: ``rot``)
    rot_w: np.ndarray | None = None

    def inertia(self) -> np.ndarray:
        return self.rot @ self.inertia0 @ self.rot.T

    def kinetic_energy(self) -> float:
        """J: translational + rotational."""
        return 0.5 * self.mass * float(self.vel @ self.vel) + \
            0.5 * float(self.omega @ self.inertia() @ self.omega)

    def node_velocities(self, x: np.ndarray) -> np.ndarray:
        """Velocities (k, 3) mm/ms of the body's nodes at positions x (n, 3)."""
        r = x[self.nodes] - self.xc
        return self.vel + np.cross(self.omega, r)

    def gather(self, x: np.ndarray, f: np.ndarray, moment: np.ndarray | None = None) -> None:
        """Resultant force and moment (about xc) of nodal forces f (n, 3) kN and
        nodal moments (n, 3) kN*mm (optional) on the body's nodes."""
        fn = f[self.nodes]
        self.force = fn.sum(axis=0)
        self.moment = np.cross(x[self.nodes] - self.xc, fn).sum(axis=0)
        if moment is not None:
            self.moment = self.moment + moment[self.nodes].sum(axis=0)

    def advance_velocity(self, dt: float) -> None:
        """V, w from t^{n-1/2} to t^{n+1/2} with the last gathered force."""
        acc = self.force / self.mass if self.mass > 0 else np.zeros(3)
        # velocities the forces alone would give (prescribed DOFs included): the
        # solver measures the work of a prescribed motion's reaction against them
        self.vel_free = self.vel + dt * acc
        self.vel_free[self.fixed_trans] = 0.0
        acc[self.fixed_trans | self.prescribed_trans] = 0.0
        self.vel = self.vel + dt * acc
        self.vel[self.fixed_trans] = 0.0
        self.omega_free = self.omega.copy()
        inertia = self.inertia()
        if np.any(np.diag(inertia) > 0.0):
            rw = self.rot if self.rot_w is None else self.rot_w
            ang = (rw @ self.inertia0 @ rw.T) @ self.omega  # L^{n-1/2}
            delta = np.linalg.solve(inertia, ang + dt * self.moment) - self.omega
            self.omega_free = self.omega + delta
            self.omega_free[self.fixed_rot] = 0.0
            delta[self.fixed_rot | self.prescribed_rot] = 0.0
            self.omega = self.omega + delta
        self.omega[self.fixed_rot] = 0.0
        self.rot_w = self.rot.copy()

    def advance_position(self, dt: float, x: np.ndarray) -> None:
        """Move the centre and rotation over dt and place the body's nodes in x."""
        self.xc = self.xc + dt * self.vel
        self.rot = _rotation(dt * self.omega) @ self.rot
        x[self.nodes] = self.xc + self.local0 @ self.rot.T


def build_rigid_bodies(model: Model, node_mass: np.ndarray,
                       node_x0: np.ndarray | None = None) -> list[RigidBody]:
    """One RigidBody per rigid body of ``model`` (:func:`rigid_body_defs`: *MAT_RIGID
    parts with their merged parts and extra nodes, then nodal rigid bodies).

    Mass properties and initial velocities come from
    :mod:`hollowbody.model.rigid_bodies` (the same values ``hollowbody check``
    prints). node_x0: (n, 3) mm initial coordinates (None: ``model.node_x0``).
    A body's PNODE (nodal rigid bodies) sits at the centre: its offset is zero.
    """
    x0_all = model.node_x0 if node_x0 is None else node_x0
    bodies = []
    for d in rigid_body_defs(model, node_mass, x0_all):
        for note in d.notes:
            warnings.warn(note, UserWarning, stacklevel=2)
        r = x0_all[d.nodes] - d.centre
        if d.pnode >= 0:
            r[np.searchsorted(d.nodes, d.pnode)] = 0.0
        bodies.append(RigidBody(
            pid=d.pid, nodes=d.nodes, mass=float(d.mass), xc=d.centre.copy(),
            inertia0=d.inertia.copy(), rot=np.eye(3), vel=d.vel.copy(), omega=d.omega.copy(),
            local0=r, fixed_trans=d.fixed_trans.copy(), fixed_rot=d.fixed_rot.copy(),
            force=np.zeros(3), moment=np.zeros(3), prescribed_trans=np.zeros(3, dtype=bool),
            prescribed_rot=np.zeros(3, dtype=bool), xc0=d.centre.copy(), pids=list(d.pids),
            kind=d.kind, iprt=d.iprt, pnode=d.pnode))
    return bodies
