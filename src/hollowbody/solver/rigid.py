"""Rigid bodies: one per *MAT_RIGID part.

A rigid body has mass ``M`` (kg), centre ``xc`` (3,) mm, inertia about the
centre in the body's initial orientation ``I0`` (3, 3) kg*mm^2 and rotation
``R`` (3, 3). Its nodes follow ``x_i = xc + R (X_i - Xc0)``; the forces the
rest of the model puts on those nodes (contact) are summed into a resultant
force and moment, and the body is advanced with the same central-difference
step as the nodes:

    V^{n+1/2} = V^{n-1/2} + dt * F / M
    w^{n+1/2} = w^{n-1/2} + dt * I^{-1} (Mc - w x I w)      (I = R I0 R^T)
    xc^{n+1}  = xc^n + dt V^{n+1/2};   R^{n+1} = exp(dt [w^{n+1/2}]x) R^n

Constraints (*MAT_RIGID CMO = +1, CON1 / CON2 in global axes) zero the
corresponding components of V and w. Mass properties come from the lumped
nodal masses of the part, or from *PART_INERTIA when given.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.model.mass import part_nodes, point_mass_properties
from hollowbody.model.model import Model

# LS-DYNA CON1 (translations) / CON2 (rotations) codes -> constrained axes.
_CON_AXES = {0: (), 1: (0,), 2: (1,), 3: (2,), 4: (0, 1), 5: (1, 2), 6: (2, 0), 7: (0, 1, 2)}


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
    STATE_FIELDS = ("xc", "rot", "vel", "omega", "force", "moment", "vel_free", "omega_free")

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
            gyro = np.cross(self.omega, inertia @ self.omega)
            alpha = np.linalg.solve(inertia, self.moment - gyro)
            self.omega_free = self.omega + dt * alpha
            self.omega_free[self.fixed_rot] = 0.0
            alpha[self.fixed_rot | self.prescribed_rot] = 0.0
            self.omega = self.omega + dt * alpha
        self.omega[self.fixed_rot] = 0.0

    def advance_position(self, dt: float, x: np.ndarray) -> None:
        """Move the centre and rotation over dt and place the body's nodes in x."""
        self.xc = self.xc + dt * self.vel
        self.rot = _rotation(dt * self.omega) @ self.rot
        x[self.nodes] = self.xc + self.local0 @ self.rot.T


def build_rigid_bodies(model: Model, node_mass: np.ndarray,
                       node_x0: np.ndarray | None = None) -> list[RigidBody]:
    """One RigidBody per rigid part, with initial velocity from ``model.node_v0``.

    The initial V and w are the least-squares rigid motion of the part's nodal
    initial velocities (momentum-preserving), unless *PART_INERTIA gives them.
    node_x0: (n, 3) mm initial coordinates (None: ``model.node_x0``).
    """
    bodies = []
    for pid in model.rigid_pids():
        mat = model.material_of(pid)
        nodes = part_nodes(model, pid)
        if nodes.size == 0:
            continue
        x0 = (model.node_x0 if node_x0 is None else node_x0)[nodes]
        props = point_mass_properties(x0, node_mass[nodes])
        pin = model.part_inertia.get(pid)
        if pin is not None:
            mass, xc, inertia = pin.tm, np.asarray(pin.xc, float), np.asarray(pin.inertia, float)
        else:
            mass, xc, inertia = props.mass, props.centre, props.inertia
        if mass <= 0.0:
            raise DeckError(f"rigid part {pid} has no mass", mat.source.file, mat.source.line,
                            mat.keyword or "MAT_RIGID")
        r = x0 - xc
        m = node_mass[nodes]
        if pin is not None:
            vel, omega = np.asarray(pin.v0, float).copy(), np.asarray(pin.w0, float).copy()
        else:
            v0 = model.node_v0[nodes]
            vel = (m[:, None] * v0).sum(axis=0) / max(float(m.sum()), 1e-300)
            ang = np.cross(r, m[:, None] * (v0 - vel)).sum(axis=0)
            omega = np.linalg.solve(inertia, ang) if np.linalg.det(inertia) > 0 else np.zeros(3)
        cmo = int(mat.params.get("CMO", 0.0))
        fixed_t = np.zeros(3, dtype=bool)
        fixed_r = np.zeros(3, dtype=bool)
        if cmo == 1:
            con1 = int(mat.params.get("CON1", 0.0))
            con2 = int(mat.params.get("CON2", 0.0))
            if con1 not in _CON_AXES or con2 not in _CON_AXES:
                raise DeckError(f"CON1={con1}/CON2={con2} not supported (0-7)",
                                mat.source.file, mat.source.line, mat.keyword or "MAT_RIGID")
            fixed_t[list(_CON_AXES[con1])] = True
            fixed_r[list(_CON_AXES[con2])] = True
        elif cmo == -1:
            raise DeckError("CMO=-1 (constraints in local SPC system) is not supported; "
                            "use CMO=1 with global constraints", mat.source.file,
                            mat.source.line, mat.keyword or "MAT_RIGID")
        vel[fixed_t] = 0.0
        omega[fixed_r] = 0.0
        bodies.append(RigidBody(
            pid=pid, nodes=nodes, mass=float(mass), xc=np.asarray(xc, float).copy(),
            inertia0=np.asarray(inertia, float), rot=np.eye(3), vel=vel, omega=omega,
            local0=r.copy(), fixed_trans=fixed_t, fixed_rot=fixed_r, force=np.zeros(3),
            moment=np.zeros(3), prescribed_trans=np.zeros(3, dtype=bool),
            prescribed_rot=np.zeros(3, dtype=bool), xc0=np.asarray(xc, float).copy()))
    return bodies
