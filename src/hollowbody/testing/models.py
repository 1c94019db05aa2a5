"""Small Models built directly (no deck) for contact and solver tests, benchmarks and docs.

:func:`assemble_model` makes a Model of parts given as node arrays and
connectivities (see :mod:`hollowbody.mesh` for structured ones);
:func:`explicit_run` integrates point masses under contact forces only. Nothing
here is used by the solver. Units as everywhere: mm, ms, kg, kN, GPa.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.model.model import (
    ContactDef,
    Controls,
    MaterialDef,
    Model,
    PartDef,
    SectionDef,
    ShellGroup,
    SolidGroup,
    SurfaceRef,
)


@dataclass
class PartSpec:
    """One part for :func:`assemble_model`.

    family ``"solid"`` (conn (e, 8)) or ``"shell"`` (conn (e, 4), thickness mm);
    material kind and params as in ``MATERIAL_PARAMS`` (GPa), density kg/mm^3.
    """

    pid: int
    x: np.ndarray
    conn: np.ndarray
    family: str = "solid"
    kind: str = "elastic"
    params: dict[str, float] = field(default_factory=lambda: {"E": 0.01, "PR": 0.3})
    density: float = 1.0e-6
    thickness: float = 1.0


def assemble_model(parts: list[PartSpec], contacts: list[ContactDef] | None = None,
                   slsfac: float = 0.1, sort_interval: int = 100) -> Model:
    """A Model made of the given parts (nodes of different parts are distinct)."""
    xs, offs = [], []
    off = 0
    for p in parts:
        xs.append(np.asarray(p.x, dtype=np.float64))
        offs.append(off)
        off += xs[-1].shape[0]
    x = np.concatenate(xs) if xs else np.zeros((0, 3))
    n = x.shape[0]
    model = Model(node_ids=np.arange(1, n + 1, dtype=np.int64), node_x0=x,
                  node_extra_mass=np.zeros(n), node_v0=np.zeros((n, 3)),
                  node_w0=np.zeros((n, 3)),
                  controls=Controls(slsfac=slsfac, contact_sort_interval=sort_interval))
    for p, o in zip(parts, offs):
        model.materials[p.pid] = MaterialDef(mid=p.pid, kind=p.kind, density=p.density,
                                             params=dict(p.params))
        conn = np.asarray(p.conn, dtype=np.int32) + o
        ids = np.arange(1, conn.shape[0] + 1, dtype=np.int64) + 1000 * p.pid
        if p.family == "solid":
            model.sections[p.pid] = SectionDef(secid=p.pid, kind="solid", elform=1)
            model.solid_groups.append(SolidGroup(pid=p.pid, elem_ids=ids, conn=conn))
        else:
            model.sections[p.pid] = SectionDef(secid=p.pid, kind="shell", elform=2,
                                               params={"T1": p.thickness})
            model.shell_groups.append(ShellGroup(pid=p.pid, elem_ids=ids, conn=conn,
                                                 thickness=np.full((conn.shape[0], 4),
                                                                   p.thickness)))
        model.parts[p.pid] = PartDef(pid=p.pid, secid=p.pid, mid=p.pid)
    model.contacts = list(contacts or [])
    return model


def part_contact(cid: int, kind: str, slave_pids: list[int], master_pids: list[int] | None,
                 **kw) -> ContactDef:
    """ContactDef between parts (``kw``: fs, fd, dc, vdc, soft, sofscl, sfs, sfm, sst, mst)."""
    master = SurfaceRef(kind="parts", pids=list(master_pids)) if master_pids else None
    return ContactDef(cid=cid, kind=kind, slave=SurfaceRef(kind="parts", pids=list(slave_pids)),
                      master=master, **kw)


def explicit_run(runtimes: list, x0: np.ndarray, v0: np.ndarray, mass: np.ndarray, dt: float,
                 n_steps: int, fixed: np.ndarray | None = None,
                 f_ext: np.ndarray | None = None, callback=None) -> tuple[np.ndarray, np.ndarray]:
    """Central-difference integration of point masses under contact forces only.

    x0, v0: (n, 3) mm, mm/ms (v0 taken as v at t^{-1/2}); mass: (n,) kg;
    fixed: (n,) bool nodes held in place; f_ext: (n, 3) kN constant load;
    callback(step, x, v) after each step. Returns the final x, v.
    """
    x = np.array(x0, dtype=np.float64)
    v = np.array(v0, dtype=np.float64)
    f = np.zeros_like(x)
    inv_m = 1.0 / mass
    for step in range(n_steps):
        f[:] = 0.0 if f_ext is None else f_ext
        for rt in runtimes:
            rt.add_forces(x, v, dt, step, f)
        v += dt * f * inv_m[:, None]
        if fixed is not None:
            v[fixed] = 0.0
        x += dt * v
        if callback is not None:
            callback(step, x, v)
    return x, v
