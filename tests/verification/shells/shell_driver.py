"""A minimal explicit driver for shell verification tests (not the solver's loop).

Central differences on translations and rotations with lumped masses and the
runtime's rotational inertias, optional mass-proportional damping (for
quasi-static answers), fixed DOFs, prescribed nodal velocities and external
nodal forces / moments. Kept deliberately small: one shell group, no contact.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from hollowbody.elements.shell_group import ShellGroupRuntime
from hollowbody.model.model import HourglassDef, MaterialDef, SectionDef, ShellGroup


def plate_mesh(lx: float, ly: float, nx: int, ny: int) -> tuple[np.ndarray, np.ndarray]:
    """Flat rectangular mesh in the xy plane: nodes (n,3) mm and quads (e,4) int32.

    Node (i, j) (i along x, j along y) has index j * (nx + 1) + i.
    """
    xs = np.linspace(0.0, lx, nx + 1)
    ys = np.linspace(0.0, ly, ny + 1)
    gx, gy = np.meshgrid(xs, ys)
    x = np.stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)], axis=1)
    conn = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            conn.append([a, a + 1, a + nx + 2, a + nx + 1])
    return x, np.asarray(conn, dtype=np.int32)


def elastic(e_mod: float = 210.0, nu: float = 0.3, rho: float = 7.85e-6) -> MaterialDef:
    """*MAT_ELASTIC definition (GPa, kg/mm^3)."""
    return MaterialDef(mid=1, kind="elastic", density=rho, params={"E": e_mod, "PR": nu})


def section(nip: int = 5, qr: float = 0.0, shrf: float = 5.0 / 6.0) -> SectionDef:
    """*SECTION_SHELL definition with ELFORM 2."""
    return SectionDef(secid=1, kind="shell", elform=2,
                      params={"NIP": float(nip), "QR": qr, "SHRF": shrf})


class ShellDriver:
    """Central-difference integration of one shell group.

    State: x (n,3) mm, v (n,3) mm/ms and w (n,3) rad/ms at half steps, t ms.
    ``fix_v`` / ``fix_w`` (n,3) bool: fixed translations / rotations.
    ``prescribed``: optional (mask (n,3) bool, fn(t) -> (n,3) velocity).
    ``prescribed_w``: same for angular velocities.
    ``load``: optional fn(t, driver) -> (force (n,3) kN, moment (n,3) kN*mm).
    ``damping``: mass-proportional damping coefficient (1/ms).
    """

    def __init__(self, x0: np.ndarray, conn: np.ndarray, material: MaterialDef,
                 sec: SectionDef, thickness: float = 1.0,
                 hourglass: HourglassDef | None = None, curves: dict | None = None,
                 tssfac: float = 0.9, damping: float = 0.0, **runtime_kw) -> None:
        n = x0.shape[0]
        e = conn.shape[0]
        group = ShellGroup(pid=1, elem_ids=np.arange(1, e + 1, dtype=np.int64),
                           conn=np.asarray(conn, dtype=np.int32),
                           thickness=np.full((e, 4), float(thickness)))
        self.rt = ShellGroupRuntime(group, material, sec, hourglass or HourglassDef(hgid=0),
                                    curves or {}, x0, **runtime_kw)
        self.m = self.rt.lumped_mass(n)
        self.inertia = self.rt.lumped_rotational_inertia(n)
        self.x = np.array(x0, dtype=np.float64)
        self.v = np.zeros((n, 3))
        self.w = np.zeros((n, 3))
        self.f = np.zeros((n, 3))
        self.mom = np.zeros((n, 3))
        self.fix_v = np.zeros((n, 3), dtype=bool)
        self.fix_w = np.zeros((n, 3), dtype=bool)
        self.prescribed: tuple[np.ndarray, Callable] | None = None
        self.prescribed_w: tuple[np.ndarray, Callable] | None = None
        self.load: Callable | None = None
        self.damping = float(damping)
        self.tssfac = tssfac
        self.t = 0.0
        self.cycle = 0
        self.dt_prev = 0.0
        d, _, _ = self.rt.add_forces(self.x, self.v, 0.0, self.f, self.w, self.mom)
        self.dt_crit = d
        self.dt_fixed: float | None = None

    def _total_force(self) -> tuple[np.ndarray, np.ndarray]:
        if self.load is None:
            return self.f, self.mom
        fe, me = self.load(self.t, self)
        return self.f + fe, self.mom + me

    def step(self) -> float:
        """One cycle; returns the step dt used (ms)."""
        dt = self.dt_fixed if self.dt_fixed is not None else self.tssfac * self.dt_crit
        dt_avg = 0.5 * (self.dt_prev + dt) if self.cycle else 0.5 * dt
        f, mom = self._total_force()
        c = 0.5 * self.damping * dt_avg
        self.v = ((1.0 - c) * self.v + dt_avg * f / self.m[:, None]) / (1.0 + c)
        self.w = ((1.0 - c) * self.w + dt_avg * mom / self.inertia[:, None]) / (1.0 + c)
        self.v[self.fix_v] = 0.0
        self.w[self.fix_w] = 0.0
        th = self.t + 0.5 * dt
        if self.prescribed is not None:
            mask, fn = self.prescribed
            self.v[mask] = fn(th)[mask]
        if self.prescribed_w is not None:
            mask, fn = self.prescribed_w
            self.w[mask] = fn(th)[mask]
        self.x += dt * self.v
        self.t += dt
        self.cycle += 1
        self.dt_prev = dt
        self.f[:] = 0.0
        self.mom[:] = 0.0
        d, _, _ = self.rt.add_forces(self.x, self.v, dt, self.f, self.w, self.mom)
        self.dt_crit = d
        return dt

    def run(self, t_end: float, every: Callable | None = None) -> None:
        """Step until t >= t_end; ``every(driver)`` is called after each cycle."""
        while self.t < t_end:
            self.step()
            if every is not None:
                every(self)

    def kinetic_energy(self) -> float:
        """Translational + rotational kinetic energy (J) of the half-step velocities."""
        return 0.5 * float((self.m[:, None] * self.v ** 2).sum()
                           + (self.inertia[:, None] * self.w ** 2).sum())


def patch_mesh(scale: float = 100.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """MacNeal-Harder distorted 5-element patch (0.24 x 0.12, scaled; mm).

    Returns nodes (8,3), quads (5,4) int32 and the boundary mask (8,) bool.
    """
    x = np.array([[0.0, 0.0], [0.24, 0.0], [0.24, 0.12], [0.0, 0.12],
                  [0.04, 0.02], [0.18, 0.03], [0.16, 0.08], [0.08, 0.08]]) * scale
    x = np.column_stack([x, np.zeros(8)])
    conn = np.array([[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7], [4, 5, 6, 7]],
                    dtype=np.int32)
    boundary = np.zeros(8, dtype=bool)
    boundary[:4] = True
    return x, conn, boundary
