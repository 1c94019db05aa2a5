"""The rigid bodies of a model and their mass properties, in one place.

Used by the run (:func:`hollowbody.solver.rigid.build_rigid_bodies`) and by
``hollowbody check`` (:func:`rigid_body_summary`), so both report the same
mass, centre and inertia. A body is

- a *MAT_RIGID part together with the rigid parts merged into it by
  *CONSTRAINED_RIGID_BODIES (chains A <- B <- C make one body, led by the part
  that is constrained to no other) and the deformable nodes it carries
  (*CONSTRAINED_EXTRA_NODES); identified by the lead part's id; or
- a nodal rigid body (*CONSTRAINED_NODAL_RIGID_BODY), identified by its PID.

Mass properties (mass kg, centre mm, inertia kg*mm^2 about the centre in global
axes): the lumped masses of the body's nodes as point masses, each node counted
once; a part with *PART_INERTIA brings its given values instead of its nodes'
masses, and then what is attached to it (merged parts, extra nodes) counts only
with IFLAG = 1 (LS-DYNA: with IFLAG = 0 the given values are taken to include
them). The contributions are summed with the parallel-axis theorem. A nodal
rigid body with _INERTIA takes the given values.

The references are checked when the model is built
(:mod:`hollowbody.build.rigid_constraints`); this module trusts them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.model.mass import MassProperties, part_nodes, point_mass_properties
from hollowbody.model.model import Model

#: LS-DYNA CON1 (translations) / CON2 (rotations) codes -> constrained global axes.
CON_AXES = {0: (), 1: (0,), 2: (1,), 3: (2,), 4: (0, 1), 5: (1, 2), 6: (2, 0), 7: (0, 1, 2)}


@dataclass
class RigidBodyDef:
    """One rigid body at t = 0.

    pid: the body's id (lead part or nodal rigid body PID); pids: every part id
    it is made of (lead first; [pid] for a nodal rigid body); kind: ``"part"``
    or ``"nodal"``; nodes: (k,) int64 sorted node indices; mass kg; centre (3,)
    mm; inertia (3, 3) kg*mm^2 about the centre, global axes; vel (3,) mm/ms,
    omega (3,) rad/ms initial velocities; fixed_trans / fixed_rot (3,) bool;
    pnode: node index placed at the centre (-1 none); iprt: 2 = no rbdout.
    """

    pid: int
    pids: list[int]
    kind: str
    nodes: np.ndarray
    mass: float
    centre: np.ndarray
    inertia: np.ndarray
    vel: np.ndarray
    omega: np.ndarray
    fixed_trans: np.ndarray = field(default_factory=lambda: np.zeros(3, dtype=bool))
    fixed_rot: np.ndarray = field(default_factory=lambda: np.zeros(3, dtype=bool))
    pnode: int = -1
    iprt: int = 0
    #: what the definition changed that the user should know (SPCs moved to the body)
    notes: list[str] = field(default_factory=list)

    def principal_inertia(self) -> np.ndarray:
        """(3,) kg*mm^2 principal moments about the centre, ascending."""
        return np.linalg.eigvalsh(0.5 * (self.inertia + self.inertia.T))


def combine(parts: list[MassProperties]) -> MassProperties:
    """Mass properties of a union of bodies (parallel-axis theorem)."""
    parts = [p for p in parts if p.mass > 0.0]
    total = float(sum(p.mass for p in parts))
    if total <= 0.0:
        return MassProperties(0.0, np.zeros(3), np.zeros((3, 3)))
    centre = sum(p.mass * np.asarray(p.centre, float) for p in parts) / total
    inertia = np.zeros((3, 3))
    for p in parts:
        d = np.asarray(p.centre, float) - centre
        inertia += np.asarray(p.inertia, float) + p.mass * (float(d @ d) * np.eye(3)
                                                            - np.outer(d, d))
    return MassProperties(total, centre, inertia)


def local_axes_inertia(moments: np.ndarray, xaxis: np.ndarray,
                       inplane: np.ndarray) -> np.ndarray:
    """Inertia tensor (3, 3) kg*mm^2 in global axes of principal moments (3,) about
    local axes: x along ``xaxis``, z = x cross ``inplane``, y = z cross x (LS-DYNA's
    IRCS = 1: XL YL ZL, XLIP YLIP ZLIP). ValueError when the axes are degenerate."""
    e1 = np.asarray(xaxis, dtype=float)
    lip = np.asarray(inplane, dtype=float)
    e3 = np.cross(e1, lip)
    if np.linalg.norm(e1) == 0.0 or \
            np.linalg.norm(e3) <= 1e-12 * np.linalg.norm(e1) * np.linalg.norm(lip):
        raise ValueError("the local x axis XL YL ZL is zero or parallel to the in-plane "
                         "vector XLIP YLIP ZLIP")
    e1 = e1 / np.linalg.norm(e1)
    e3 = e3 / np.linalg.norm(e3)
    q = np.column_stack([e1, np.cross(e3, e1), e3])
    return q @ np.diag(np.asarray(moments, dtype=float)) @ q.T


def lead_of(model: Model) -> dict[int, int]:
    """{rigid part id: the id of the body's lead part} over every rigid part."""
    parent = {m.constrained: m.lead for m in model.rigid_merges}
    out = {}
    for pid in model.rigid_pids():
        root, seen = pid, {pid}
        while root in parent:
            root = parent[root]
            if root in seen:  # a cycle (rejected when building): stop
                break
            seen.add(root)
        out[pid] = root
    return out


def _fitted_velocity(model: Model, nodes: np.ndarray, m: np.ndarray, x0: np.ndarray,
                     centre: np.ndarray, inertia: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rigid motion (V, w) with the nodes' initial momentum and angular momentum
    (m: (k,) kg of the nodes, x0: (n, 3) mm)."""
    v0 = model.node_v0[nodes]
    r = x0[nodes] - centre
    vel = (m[:, None] * v0).sum(axis=0) / max(float(m.sum()), 1e-300)
    ang = np.cross(r, m[:, None] * (v0 - vel)).sum(axis=0)
    # pseudo-inverse: no spin about an axis the body has no inertia about (nodes on a line)
    omega = np.linalg.pinv(inertia, rcond=1e-9) @ ang if np.any(inertia) else np.zeros(3)
    return vel, omega


def _constraints(model: Model, pid: int) -> tuple[np.ndarray, np.ndarray]:
    """*MAT_RIGID CMO/CON1/CON2 of part ``pid`` as (fixed_trans, fixed_rot) (3,) bool."""
    mat = model.material_of(pid)
    fixed_t = np.zeros(3, dtype=bool)
    fixed_r = np.zeros(3, dtype=bool)
    cmo = int(mat.params.get("CMO", 0.0))
    if cmo == 1:
        con1 = int(mat.params.get("CON1", 0.0))
        con2 = int(mat.params.get("CON2", 0.0))
        if con1 not in CON_AXES or con2 not in CON_AXES:
            raise DeckError(f"CON1={con1}/CON2={con2} not supported (0-7)",
                            mat.source.file, mat.source.line, mat.keyword or "MAT_RIGID")
        fixed_t[list(CON_AXES[con1])] = True
        fixed_r[list(CON_AXES[con2])] = True
    elif cmo == -1:
        raise DeckError("CMO=-1 (constraints in local SPC system) is not supported; "
                        "use CMO=1 with global constraints", mat.source.file,
                        mat.source.line, mat.keyword or "MAT_RIGID")
    return fixed_t, fixed_r


def _part_body(model: Model, lead: int, members: list[int], node_mass: np.ndarray,
               x0: np.ndarray) -> RigidBodyDef | None:
    """The body led by rigid part ``lead`` (members: its parts, lead first)."""
    children: dict[int, list] = {}
    for mg in model.rigid_merges:
        children.setdefault(mg.lead, []).append(mg)
    extras: dict[int, list] = {}
    for ex in model.extra_nodes:
        extras.setdefault(ex.pid, []).append(ex)
    all_nodes = [part_nodes(model, p) for p in members]
    all_nodes += [ex.nodes for p in members for ex in extras.get(p, [])]
    nodes = np.unique(np.concatenate(all_nodes)).astype(np.int64) if all_nodes else \
        np.zeros(0, np.int64)
    if nodes.size == 0:
        return None
    counted_nodes: list[np.ndarray] = []
    given: list[MassProperties] = []

    def visit(pid: int) -> None:
        pin = model.part_inertia.get(pid)
        if pin is not None:
            given.append(MassProperties(float(pin.tm), np.asarray(pin.xc, float),
                                        np.asarray(pin.inertia, float)))
        else:
            counted_nodes.append(part_nodes(model, pid))
        for ex in extras.get(pid, []):
            if pin is None or ex.iflag == 1:
                counted_nodes.append(ex.nodes)
        for mg in children.get(pid, []):
            if pin is None or mg.iflag == 1:
                visit(mg.constrained)

    visit(lead)
    pts = np.unique(np.concatenate(counted_nodes)).astype(np.int64) if counted_nodes else \
        np.zeros(0, np.int64)
    props = combine([point_mass_properties(x0[pts], node_mass[pts]), *given])
    mat = model.material_of(lead)
    if props.mass <= 0.0:
        raise DeckError(f"rigid part {lead} has no mass", mat.source.file, mat.source.line,
                        mat.keyword or "MAT_RIGID")
    pin = model.part_inertia.get(lead)
    if pin is not None:
        vel, omega = np.asarray(pin.v0, float).copy(), np.asarray(pin.w0, float).copy()
    else:
        vel, omega = _fitted_velocity(model, nodes, node_mass[nodes], x0, props.centre,
                                      props.inertia)
    fixed_t = np.zeros(3, dtype=bool)
    fixed_r = np.zeros(3, dtype=bool)
    for p in members:  # any merged part's *MAT_RIGID constraint holds the body
        ft, fr = _constraints(model, p)
        fixed_t |= ft
        fixed_r |= fr
    return RigidBodyDef(pid=lead, pids=list(members), kind="part", nodes=nodes,
                        mass=float(props.mass), centre=np.asarray(props.centre, float),
                        inertia=np.asarray(props.inertia, float), vel=vel, omega=omega,
                        fixed_trans=fixed_t, fixed_rot=fixed_r)


def _nodal_body(model: Model, nrb, node_mass: np.ndarray,  # noqa: ANN001 - NodalRigidBody
                x0: np.ndarray) -> RigidBodyDef:
    nodes = np.asarray(nrb.nodes, dtype=np.int64)
    if nrb.inertia is not None:
        gi = nrb.inertia
        props = MassProperties(float(gi.mass), np.asarray(gi.centre, float),
                               np.asarray(gi.inertia, float))
    else:
        props = point_mass_properties(x0[nodes], node_mass[nodes])
    if props.mass <= 0.0:
        raise DeckError(f"nodal rigid body {nrb.pid} has no mass (its nodes have no mass; "
                        "give TM with the _INERTIA option)", nrb.source.file,
                        nrb.source.line, nrb.keyword)
    if nrb.inertia is not None and (np.any(nrb.inertia.v0) or np.any(nrb.inertia.w0)):
        vel, omega = nrb.inertia.v0.astype(float).copy(), nrb.inertia.w0.astype(float).copy()
    else:
        vel, omega = _fitted_velocity(model, nodes, node_mass[nodes], x0, props.centre,
                                      props.inertia)
    return RigidBodyDef(pid=nrb.pid, pids=[nrb.pid], kind="nodal", nodes=nodes,
                        mass=float(props.mass), centre=np.asarray(props.centre, float),
                        inertia=np.asarray(props.inertia, float), vel=vel, omega=omega,
                        fixed_trans=nrb.fixed_trans.copy(), fixed_rot=nrb.fixed_rot.copy(),
                        pnode=int(nrb.pnode), iprt=int(nrb.iprt))


def rigid_body_defs(model: Model, node_mass: np.ndarray,
                    x0: np.ndarray | None = None) -> list[RigidBodyDef]:
    """Every rigid body of ``model``: part bodies (lead part order), then nodal ones.

    node_mass: (n,) kg lumped nodal masses; x0: (n, 3) mm initial coordinates
    (None: ``model.node_x0``). Initial velocities: *PART_INERTIA's / _INERTIA's
    when given, else the rigid motion with the nodes' initial linear and angular
    momentum. The *MAT_RIGID (or _SPC) constraints zero the held components.
    """
    x0 = model.node_x0 if x0 is None else x0
    leads = lead_of(model)
    members: dict[int, list[int]] = {}
    for pid in model.rigid_pids():
        members.setdefault(leads[pid], [])
    for pid in model.rigid_pids():
        if pid != leads[pid]:
            members[leads[pid]].append(pid)
    out = []
    for lead in model.rigid_pids():
        if lead not in members:
            continue
        body = _part_body(model, lead, [lead, *members[lead]], node_mass, x0)
        if body is not None:
            out.append(body)
    out += [_nodal_body(model, nrb, node_mass, x0) for nrb in model.nodal_rigid_bodies]
    _spcs_to_bodies(model, out)
    for b in out:
        _regularize(b)
        b.vel[b.fixed_trans] = 0.0
        b.omega[b.fixed_rot] = 0.0
    return out


#: smallest principal moment of a body, as a fraction of its largest (see _regularize)
INERTIA_FLOOR = 1.0e-6


def _regularize(b: RigidBodyDef) -> None:
    """A body whose nodes lie on a line (a two-node nodal rigid body) has no inertia
    about that line and the rotation update cannot invert its tensor: it gets
    INERTIA_FLOOR x its largest principal moment about that axis (nodal forces have
    no moment about the line, so this only keeps the update defined). Noted."""
    inertia = 0.5 * (b.inertia + b.inertia.T)
    lam, vec = np.linalg.eigh(inertia)
    floor = INERTIA_FLOOR * lam[-1]
    low = lam < floor
    if lam[-1] <= 0.0 or not low.any():
        return
    for k in np.flatnonzero(low):
        inertia = inertia + (floor - lam[k]) * np.outer(vec[:, k], vec[:, k])
    b.inertia = inertia
    b.notes.append(f"rigid body {b.pid}: its nodes lie on a line (principal moment "
                   f"{lam[0]:.3g} kg*mm^2); the moment about that axis is set to "
                   f"{floor:.3g} kg*mm^2 ({INERTIA_FLOOR:g} x the largest) so that its "
                   "rotation stays defined")


def _spcs_to_bodies(model: Model, bodies: list[RigidBodyDef]) -> None:
    """An SPC on a node of a rigid body holds the body: its translational DOFs the
    centre's translations, its rotational DOFs the body's rotations (global axes),
    as LS-DYNA converts nodal SPCs on rigid bodies. Noted in ``notes``."""
    if not bodies or not model.spcs:
        return
    owner = np.full(model.n_nodes, -1, dtype=np.int64)
    for k, b in enumerate(bodies):
        owner[b.nodes] = k
    for spc in model.spcs:
        nodes = np.asarray(spc.nodes, dtype=np.int64)
        dofs = np.asarray(spc.dofs, dtype=bool)
        on = np.flatnonzero((owner[nodes] >= 0) & dofs.any(axis=1))
        for k in np.unique(owner[nodes[on]]).tolist():
            rows = on[owner[nodes[on]] == k]
            held = dofs[rows].any(axis=0)
            b = bodies[k]
            b.fixed_trans |= held[:3]
            b.fixed_rot |= held[3:6]
            axes = [n for n, h in zip(("x", "y", "z", "rx", "ry", "rz"), held) if h]
            b.notes.append(f"{spc.source}: SPC on {rows.size} node(s) of rigid body {b.pid} "
                           f"(first: node {int(model.node_ids[nodes[rows[0]]])}): the body's "
                           f"{', '.join(axes)} held at its centre of mass (as LS-DYNA "
                           "converts nodal SPCs on rigid bodies; prefer *MAT_RIGID CON1/CON2 "
                           "or *CONSTRAINED_NODAL_RIGID_BODY_SPC)")


def rigid_body_summary(model: Model, node_mass: np.ndarray,
                       x0: np.ndarray | None = None) -> list[dict]:
    """JSON-ready rows for ``hollowbody check``: pid, pids, kind, nodes (count),
    mass_kg, centre_mm (3), principal_inertia_kg_mm2 (3, ascending)."""
    return [{"pid": b.pid, "pids": list(b.pids), "kind": b.kind, "nodes": int(b.nodes.size),
             "mass_kg": b.mass, "centre_mm": b.centre.tolist(),
             "principal_inertia_kg_mm2": b.principal_inertia().tolist()}
            for b in rigid_body_defs(model, node_mass, x0)]
