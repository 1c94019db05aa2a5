"""Set-up of a run: masses, element runtimes, rigid bodies, contacts.

Turns the static :class:`~hollowbody.model.model.Model` into the runtime
objects the time loop calls. Every element group gets the runtime of its
family (solid, shell); groups of rigid parts get none (their nodes follow a
:class:`~hollowbody.solver.rigid.RigidBody`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.elements.solid_step_factor import (
    group_min_axes,
    restrained_axes,
    volumetric_step_factor,
)
from hollowbody.errors import DeckError
from hollowbody.model.mass import hex_volumes, lumped_node_mass, quad_areas, spread_element_mass
from hollowbody.model.model import Model
from hollowbody.model.summary import shell_lengths, solid_lengths
from hollowbody.solver.boundary import Constraints
from hollowbody.solver.rigid import RigidBody, build_rigid_bodies
from hollowbody.solver.terms import collect_terms


@dataclass
class PartShare:
    """A part's nodes and its share of their lumped masses (for per-part KE)."""

    nodes: np.ndarray  # (k,) int64
    mass: np.ndarray  # (k,) kg


@dataclass
class Assembly:
    """Runtime objects of a model.

    node_mass: (n,) kg lumped; deformable: (n,) bool nodes not on a rigid body;
    elements: element-group runtimes (``add_forces`` interface); contacts:
    contact runtimes; bodies: rigid bodies; part_share: {pid: PartShare}.
    """

    node_mass: np.ndarray
    part_mass: dict[int, float]
    deformable: np.ndarray
    elements: list = field(default_factory=list)
    contacts: list = field(default_factory=list)
    bodies: list[RigidBody] = field(default_factory=list)
    part_share: dict[int, PartShare] = field(default_factory=dict)
    tssfac: float = 0.9
    node_rot_inertia: np.ndarray = field(default_factory=lambda: np.zeros(0))
    has_rotations: bool = False
    counts: dict[str, int] = field(default_factory=dict)
    #: tied contacts (:class:`hollowbody.contact.tied.TieSet`), None when there are none
    ties: object | None = None
    #: SPCs and prescribed motions (:class:`hollowbody.solver.boundary.Constraints`)
    constraints: Constraints | None = None
    #: delete failed elements instead of ending the run (ERODE, or the run's option)
    erode: bool = False
    #: (n, 3) float64 mm initial coordinates of the run: the model's with the tied
    #: slave nodes moved onto their master surface (the Model keeps the deck's)
    node_x0: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    #: force terms: loads, joints, rigid walls (:mod:`hollowbody.solver.terms`)
    terms: list = field(default_factory=list)
    #: ms: the critical step of the rigid parts' elements as if they were elastic with
    #: *MAT_RIGID's E and PR (inf without rigid elements); the step of a model in
    #: which nothing deformable sets one (rigid bodies on joints)
    rigid_dt: float = np.inf

    def element_counts(self) -> dict[str, int]:
        return dict(self.counts)


def _solid_kind_counts(conn: np.ndarray) -> dict[str, int]:
    s = np.sort(conn, axis=1)
    distinct = 1 + np.count_nonzero(np.diff(s, axis=1), axis=1)
    return {"hexahedra": int((distinct == 8).sum()), "wedges": int((distinct == 6).sum()),
            "tetrahedra": int((distinct == 4).sum()),
            "other_solids": int(((distinct != 8) & (distinct != 6) & (distinct != 4)).sum())}


def _part_share(n: int, conn: np.ndarray, elem_mass: np.ndarray) -> PartShare:
    m = np.zeros(n)
    spread_element_mass(m, conn, elem_mass)
    nodes = np.nonzero(m)[0]
    return PartShare(nodes=nodes, mass=m[nodes])


def assemble(model: Model) -> Assembly:
    """Build the runtime objects of ``model`` (raises DeckError for what cannot run)."""
    from hollowbody.contact import ContactRuntime
    from hollowbody.contact.tied import build_ties
    from hollowbody.elements.solid_group import SolidGroupRuntime

    ties = build_ties(model)  # [tied] first: may move slave nodes onto the master surface
    x0 = model.node_x0.copy() if ties is None else ties.node_x0  # [tied] the run's x0
    node_mass, part_mass = lumped_node_mass(model, x0)
    counts = {"hexahedra": 0, "wedges": 0, "tetrahedra": 0, "other_solids": 0, "shells": 0}
    asm = Assembly(node_mass=node_mass, part_mass=part_mass,
                   deformable=np.ones(model.n_nodes, dtype=bool), tssfac=model.controls.tssfac,
                   node_x0=x0)
    n = model.n_nodes
    axes = restrained_axes([g.conn for g in model.solid_groups])
    for g, g_axes in zip(model.solid_groups, axes):
        for k, c in _solid_kind_counts(g.conn).items():
            counts[k] += c
        mat = model.material_of(g.pid)
        elem_mass = mat.density * np.abs(hex_volumes(g.conn, x0))
        asm.part_share[g.pid] = _part_share(n, g.conn, elem_mass)
        if mat.kind == "rigid":
            continue
        if mat.kind == "null":  # [loads] *MAT_NULL solids are fluids: they need an *EOS
            raise DeckError(f"material {mat.mid} (*MAT_NULL) of part {g.pid}: solid elements "
                            "of *MAT_NULL need an equation of state (*EOS), which is not "
                            "supported; *MAT_NULL is supported on shells (contact surfaces)",
                            mat.source.file, mat.source.line, mat.keyword or None)
        if mat.kind not in ("elastic", "rubber181"):
            raise DeckError(f"material {mat.mid} ({mat.keyword or mat.kind}) of part {g.pid} "
                            "is not available for solid elements", mat.source.file,
                            mat.source.line, mat.keyword or None)
        sec = model.sections.get(model.parts[g.pid].secid)
        rt = SolidGroupRuntime(g, mat, model.hourglass_of(g.pid), model.curves, x0,
                               elform=sec.elform if sec is not None else 1)
        # the volumetric modes of free faces: hollowbody.elements.solid_step_factor
        rt.step_factor = volumetric_step_factor(mat.kind, mat.params, model.curves,
                                                min_axes=group_min_axes(g.conn, g_axes))
        asm.elements.append(rt)
    for g in model.shell_groups:
        counts["shells"] += int(g.conn.shape[0])
        mat = model.material_of(g.pid)
        elem_mass = mat.density * quad_areas(g.conn, x0) * g.thickness.mean(axis=1)
        asm.part_share[g.pid] = _part_share(n, g.conn, elem_mass)
        if mat.kind in ("rigid", "null"):  # [loads] null shells: mass, no element forces
            continue
        try:
            from hollowbody.elements.shell_group import ShellGroupRuntime, drilling_factor
        except ImportError:
            part = model.parts[g.pid]
            raise DeckError(f"part {g.pid} has deformable shell elements, which this version "
                            "cannot run yet (rigid shells only)", part.source.file,
                            part.source.line, "PART") from None
        asm.elements.append(ShellGroupRuntime(g, mat, model.sections[model.parts[g.pid].secid],
                                              model.hourglass_of(g.pid), model.curves,
                                              x0,
                                              thickness_update=model.controls.istupd == 1,
                                              drilling=drilling_factor(
                                                  model.controls.shell_drilling,
                                                  model.controls.shell_tangent_drilling),
                                              drilling_tangent=(
                                                  model.controls.shell_tangent_drilling)))
    from hollowbody.elements.beam_group import beam_runtimes
    from hollowbody.elements.discrete_group import discrete_runtimes

    for rt in [*beam_runtimes(model, x0), *discrete_runtimes(model, x0)]:
        counts[rt.family] = counts.get(rt.family, 0) + int(rt.n_elem)
        asm.elements.append(rt)
        if rt.family == "beams":  # [beams] part kinetic energies (matsum)
            asm.part_share[rt.pid] = _part_share(n, rt.conn, rt.mass)
    for rt in asm.elements:  # massless discrete parts: in matsum with their energy
        if getattr(rt, "family", "") == "discrete":
            asm.part_share.setdefault(rt.pid, PartShare(np.zeros(0, np.int64), np.zeros(0)))
    asm.counts = counts
    asm.node_rot_inertia = np.zeros(n)
    for rt in asm.elements:
        if getattr(rt, "rotational", False):
            asm.node_rot_inertia += rt.lumped_rotational_inertia(n)
            asm.has_rotations = True
    contact_mass = node_mass.copy()  # [tied] contacts see the element masses
    if ties is not None:  # [tied] slave masses / inertias moved to the master nodes
        ties.transfer_mass(node_mass, asm.node_rot_inertia)
    asm.ties = ties
    asm.bodies = build_rigid_bodies(model, node_mass, x0)
    for b in asm.bodies:
        asm.deformable[b.nodes] = False
        if b.pnode >= 0:  # a nodal rigid body's PNODE starts at its centre of mass
            asm.node_x0[b.pnode] = b.xc
    asm.constraints = Constraints(model, asm.bodies)
    from hollowbody.elements.discrete_group import bind_discrete  # springs' steps, masses

    bind_discrete(asm.elements, node_mass, asm.node_rot_inertia, asm.bodies,
                  asm.constraints.fixed, asm.constraints.fixed_rot)
    asm.rigid_dt = rigid_element_step(model, x0)
    asm.erode = bool(model.controls.erode)
    rigid_node = ~asm.deformable
    fixed_node = np.zeros((n, 3), dtype=bool)
    for spc in model.spcs:
        fixed_node[spc.nodes] |= np.asarray(spc.dofs, dtype=bool)[:, :3]
    rigid_share = np.full(n, np.inf)
    for b in asm.bodies:
        if b.nodes.size:
            rigid_share[b.nodes] = b.mass / b.nodes.size
    for cdef in model.contacts:
        asm.contacts.append(ContactRuntime(cdef, model, contact_mass, rigid_node,
                                           fixed_node.all(axis=1), rigid_share, x0=x0))
    asm.terms = collect_terms(model, asm)
    return asm


def rigid_element_step(model: Model, x0: np.ndarray) -> float:
    """Smallest L_e / c (ms) of the rigid parts' elements with *MAT_RIGID's E, PR and
    density (solids: dilatational, shells: plate wave speed); inf when there are none.

    LS-DYNA asks for realistic E and PR on *MAT_RIGID; a model of rigid bodies on
    joints (nothing deformable) runs with this step times TSSFAC.
    """
    best = np.inf
    for groups, lengths, solid in ((model.solid_groups, solid_lengths, True),
                                   (model.shell_groups, shell_lengths, False)):
        for g in groups:
            mat = model.material_of(g.pid)
            e, nu, rho = mat.params.get("E", 0.0), mat.params.get("PR", 0.0), mat.density
            if mat.kind != "rigid" or e <= 0.0 or rho <= 0.0 or g.conn.shape[0] == 0:
                continue
            if solid:
                c = np.sqrt(e * (1.0 - nu) / (rho * (1.0 + nu) * (1.0 - 2.0 * nu)))
            else:
                c = np.sqrt(e / (rho * (1.0 - nu * nu)))
            length = lengths(g.conn, x0)
            length = length[length > 0.0]
            if length.size:
                best = min(best, float(length.min() / c))
    return best
