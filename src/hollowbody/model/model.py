"""The static model: everything a run needs that does not change in time.

A :class:`Model` is produced by :func:`hollowbody.build.build_model`
from a parsed keyword deck (ids resolved to 0-based indices, references
checked). The solver never looks at keyword text; it only sees this.

Naming: ``<entity>_<quantity>``; every array documents shape, dtype and unit
(mm, ms, kg, kN, GPa; see :mod:`hollowbody.units`). Node references inside
element connectivities, sets and contacts are **0-based node indices** into
the node arrays, never LS-DYNA ids (``node_ids[i]`` is the id of index ``i``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.source import Source

# ---------------------------------------------------------------------------
# Curves, materials, sections, hourglass


@dataclass
class Curve:
    """*DEFINE_CURVE with scale factors and offsets already applied.

    x = SFA * (a + OFFA), y = SFO * (o + OFFO); ``x`` strictly increasing.
    """

    lcid: int
    x: np.ndarray  # (m,) float64
    y: np.ndarray  # (m,) float64
    title: str = ""
    source: Source = field(default_factory=Source)

    def __call__(self, t: float) -> float:
        """Linear interpolation, constant extrapolation beyond the ends."""
        return float(np.interp(t, self.x, self.y))


#: Material kinds and the keys of ``MaterialDef.params`` (LS-DYNA field names,
#: deck units). Curve ids (LCID, LCSS, LCSR) are stored as floats and resolved
#: via ``Model.curves``.
MATERIAL_PARAMS = {
    "elastic": ("E", "PR"),  # *MAT_ELASTIC (001)
    "null": ("PC", "MU", "TEROD", "CEROD", "YM", "PR"),  # *MAT_NULL (009): shells only
    "rigid": ("E", "PR", "CMO", "CON1", "CON2"),  # *MAT_RIGID (020)
    "rubber181": ("KM", "MU", "G", "SIGF", "REF", "SGL", "SW", "ST", "LCID"),  # 181
    "plastic003": ("E", "PR", "SIGY", "ETAN", "BETA", "SRC", "SRP"),  # 003
    "pwl024": ("E", "PR", "SIGY", "ETAN", "FAIL", "TDEL", "C", "P", "LCSS", "LCSR"),  # 024
    # discrete springs and dampers (model.discrete, docs/discrete.md)
    "spring_elastic": ("K",),  # *MAT_SPRING_ELASTIC (S01)
    "damper_viscous": ("DC",),  # *MAT_DAMPER_VISCOUS (S02)
    "spring_nonlinear": ("LCD", "LCR"),  # *MAT_SPRING_NONLINEAR_ELASTIC (S04)
    "spring_general": ("LCDL", "LCDU", "BETA", "TYI", "CYI"),  # *MAT_SPRING_GENERAL_NONLINEAR
}


@dataclass
class MaterialDef:
    """One *MAT_ card: ``kind`` is a key of :data:`MATERIAL_PARAMS`.

    ``density`` in kg/mm^3; ``params`` in deck units (GPa for moduli and
    stresses). ``keyword`` is the keyword as written (e.g. ``MAT_ELASTIC``).
    """

    mid: int
    kind: str
    density: float
    params: dict[str, float]
    keyword: str = ""
    title: str = ""
    source: Source = field(default_factory=Source)


#: *SECTION_SOLID ELFORM values run by the fully integrated hexahedron (-1 and -2,
#: LS-DYNA's variants for poor aspect ratios, run as 2 with a warning).
FULL_ELFORMS = (2, -1, -2)


@dataclass
class SectionDef:
    """*SECTION_SOLID, *SECTION_SHELL or *SECTION_BEAM.

    kind: ``"solid"``, ``"shell"`` or ``"beam"``. ``elform``: LS-DYNA element
    formulation (solid default 1 = one-point hexahedron; shell default 2 =
    Belytschko-Tsay; beam default 1, see docs/beams.md).
    ``params``: for shells T1..T4 (mm), NIP, SHRF, QR (0 Gauss, -1 Lobatto as
    stored by LS-DYNA's IRID/QR convention), for solids possibly empty; for
    beams the *SECTION_BEAM fields by their LS-DYNA names
    (:func:`hollowbody.build.beams.section_def`).
    """

    secid: int
    kind: str
    elform: int
    params: dict[str, float] = field(default_factory=dict)
    title: str = ""
    source: Source = field(default_factory=Source)


@dataclass
class HourglassDef:
    """*HOURGLASS card (or the *CONTROL_HOURGLASS default with hgid 0).

    ihq: 1-3 viscous, 4-5 stiffness (Flanagan-Belytschko), 6 assumed-strain stiffness
    (Belytschko-Bindeman; solids); qm: coefficient
    (QH, default 0.1); q1, q2: bulk viscosity coefficients (defaults 1.5, 0.06).
    """

    hgid: int
    ihq: int = 1
    qm: float = 0.1
    q1: float = 1.5
    q2: float = 0.06
    source: Source = field(default_factory=Source)


@dataclass
class PartDef:
    """*PART: ``hgid`` 0 means the global *CONTROL_HOURGLASS default."""

    pid: int
    secid: int
    mid: int
    hgid: int = 0
    title: str = ""
    source: Source = field(default_factory=Source)


# ---------------------------------------------------------------------------
# Element groups (one part = one group per element family)


@dataclass
class SolidGroup:
    """Solid elements of one part (one material, one section).

    conn: (e, 8) int32 node indices, LS-DYNA node order (N1..N8); wedges and
    tetrahedra are stored as degenerate hexahedra as in the deck
    (N1 N2 N3 N4 N5 N5 N6 N6 for a wedge, N1 N2 N3 N4 N4 N4 N4 N4 for a tet);
    the 4-node tetrahedron card form is expanded to that on reading.
    """

    pid: int
    elem_ids: np.ndarray  # (e,) int64
    conn: np.ndarray  # (e, 8) int32


@dataclass
class ShellGroup:
    """Shell elements of one part.

    conn: (e, 4) int32 node indices; triangles have N4 == N3.
    thickness: (e, 4) float64 mm nodal thicknesses (from the element card when
    given there, else from the section's T1..T4).
    """

    pid: int
    elem_ids: np.ndarray  # (e,) int64
    conn: np.ndarray  # (e, 4) int32
    thickness: np.ndarray  # (e, 4) float64 mm


# ---------------------------------------------------------------------------
# Boundary conditions, loads, rigid bodies


@dataclass
class NodalSPC:
    """Fixed degrees of freedom.

    nodes: (k,) int64 node indices; dofs: (k, 6) bool (x, y, z, rx, ry, rz).
    """

    nodes: np.ndarray
    dofs: np.ndarray
    source: Source = field(default_factory=Source)


@dataclass
class PrescribedMotion:
    """*BOUNDARY_PRESCRIBED_MOTION_NODE/_SET/_RIGID.

    target: ``"nodes"`` (``nodes`` holds indices) or ``"rigid"`` (``pid``).
    dof: LS-DYNA DOF code (1 x, 2 y, 3 z, 5 rx, 6 ry, 7 rz; 4 = xyz? not used).
    vad: 0 velocity, 1 acceleration, 2 displacement. Value at time t is
    ``sf * curve(t)`` between ``birth`` and ``death`` (ms).
    """

    target: str
    dof: int
    vad: int
    lcid: int
    sf: float = 1.0
    nodes: np.ndarray | None = None  # (k,) int64
    pid: int = 0
    birth: float = 0.0
    death: float = 1.0e28
    source: Source = field(default_factory=Source)


@dataclass
class PartInertia:
    """*PART_INERTIA: mass properties that replace the computed ones of a rigid part.

    xc: (3,) mm centre of mass; tm: kg; inertia: (3, 3) kg*mm^2 (global axes);
    v0 / w0: (3,) initial translational (mm/ms) / rotational (rad/ms) velocity.
    """

    pid: int
    xc: np.ndarray
    tm: float
    inertia: np.ndarray
    v0: np.ndarray
    w0: np.ndarray
    source: Source = field(default_factory=Source)


@dataclass
class SurfaceRef:
    """One side of a contact, as the deck gives it (resolved to indices).

    kind: ``"parts"`` (``pids``), ``"nodes"`` (``nodes``), ``"segments"``
    (``segments``: (s, 4) int32 node indices, triangles with N4 == N3) or
    ``"all"`` (every part of the model).
    """

    kind: str
    pids: list[int] = field(default_factory=list)
    nodes: np.ndarray | None = None
    segments: np.ndarray | None = None


@dataclass
class ContactDef:
    """*CONTACT_AUTOMATIC_... (surface-to-surface, nodes-to-surface, single surface).

    kind: ``"surface_to_surface"``, ``"nodes_to_surface"``, ``"single_surface"``.
    ``slave`` (LS-DYNA SSID side) and ``master`` (MSID side; None for single
    surface). Friction: fs static, fd dynamic, dc exponential decay (ms/mm),
    vdc viscous damping (% critical). soft: 0 or 1 (2 read, treated as 1);
    sofscl: SOFT=1 scale (default 0.1); sfs, sfm: penalty scale factors;
    sst, mst: contact thickness overrides (0 = use shell thickness).
    """

    cid: int
    kind: str
    slave: SurfaceRef
    master: SurfaceRef | None
    fs: float = 0.0
    fd: float = 0.0
    dc: float = 0.0
    vdc: float = 0.0
    soft: int = 0
    sofscl: float = 0.1
    sfs: float = 1.0
    sfm: float = 1.0
    sst: float = 0.0
    mst: float = 0.0
    title: str = ""
    source: Source = field(default_factory=Source)


@dataclass
class TiedContactDef:
    """*CONTACT_TIED_NODES_TO_SURFACE / _SHELL_EDGE_TO_SURFACE / _SURFACE_TO_SURFACE.

    kind: ``"nodes_to_surface"``, ``"shell_edge_to_surface"`` or
    ``"surface_to_surface"``. ``slave``: the tied nodes (a node set, or the
    nodes of a segment set / parts); ``master``: the surface they are tied to
    (segments or parts). offset: ``_OFFSET`` / ``_CONSTRAINED_OFFSET`` (the
    initial gap is kept, nodes are not moved onto the surface). sst, mst (mm):
    contact thickness overrides (0 = shell thickness; negative = the search
    tolerance itself); sfst, sfmt: their scale factors. See
    :mod:`hollowbody.contact.tied`.
    """

    cid: int
    kind: str
    slave: SurfaceRef
    master: SurfaceRef
    offset: bool = False
    sst: float = 0.0
    mst: float = 0.0
    sfst: float = 1.0
    sfmt: float = 1.0
    title: str = ""
    source: Source = field(default_factory=Source)


# ---------------------------------------------------------------------------
# Controls and output requests


@dataclass
class Controls:
    """*CONTROL_* cards (deck units) with LS-DYNA defaults."""

    end_time: float = 0.0  # ENDTIM, ms
    dtmin: float = 0.0  # DTMIN (fraction of the initial step; 0 = off)
    endmas: float = 1.0e8  # ENDMAS: % of mass added by mass scaling that ends the run
    tssfac: float = 0.9
    dt2ms: float = 0.0  # DT2MS < 0: selective mass scaling to |DT2MS| ms (> 0 runs as < 0)
    istupd: int = 0  # *CONTROL_SHELL ISTUPD: 1 = shell thickness follows the membrane strain
    erode: int = 0
    hourglass: HourglassDef = field(default_factory=lambda: HourglassDef(hgid=0))
    slsfac: float = 0.1
    contact_sort_interval: int = 100  # cycles between bucket sorts (NSBCS)
    tiedprj: int = 0  # TIEDPRJ: 0 tied slave nodes moved onto the surface, 1 kept where they are
    #: not an LS-DYNA card (set through the API; docs/shells.md): a drilling spring of
    #: ``shell_drilling * G t A`` per shell node (0: none, LS-DYNA's Belytschko-Tsay shell;
    #: None: 0, or ``TANGENT_DRILLING`` when the tangent spring is on)
    shell_drilling: float | None = None
    #: not an LS-DYNA card: the shells' drilling springs load with the section's tangent
    #: ratio (opt-in)
    shell_tangent_drilling: bool = False


@dataclass
class OutputRequests:
    """*DATABASE_* cards: interval per database in ms (0 = not requested)."""

    intervals: dict[str, float] = field(default_factory=dict)  # glstat, rcforc, ...
    d3plot_dt: float = 0.0
    d3dump_cycles: int = 0  # *DATABASE_BINARY_D3DUMP CYCL: cycles between restart dumps
    history_nodes: np.ndarray = field(
        default_factory=lambda: np.zeros(0, dtype=np.int64))  # (k,) node indices


# ---------------------------------------------------------------------------
# The model


@dataclass
class Model:
    """All static data of a run.

    node_ids: (n,) int64 LS-DYNA node ids; node_x0: (n, 3) float64 mm.
    node_extra_mass: (n,) float64 kg from *ELEMENT_MASS (element masses are
    lumped by :mod:`hollowbody.model.mass`).
    node_v0: (n, 3) float64 mm/ms initial velocity; node_w0: (n, 3) rad/ms.
    """

    node_ids: np.ndarray
    node_x0: np.ndarray
    node_extra_mass: np.ndarray
    node_v0: np.ndarray
    node_w0: np.ndarray
    parts: dict[int, PartDef] = field(default_factory=dict)
    sections: dict[int, SectionDef] = field(default_factory=dict)
    materials: dict[int, MaterialDef] = field(default_factory=dict)
    hourglass: dict[int, HourglassDef] = field(default_factory=dict)
    curves: dict[int, Curve] = field(default_factory=dict)
    solid_groups: list[SolidGroup] = field(default_factory=list)
    shell_groups: list[ShellGroup] = field(default_factory=list)
    spcs: list[NodalSPC] = field(default_factory=list)
    prescribed: list[PrescribedMotion] = field(default_factory=list)
    part_inertia: dict[int, PartInertia] = field(default_factory=dict)
    contacts: list[ContactDef] = field(default_factory=list)
    tied_contacts: list[TiedContactDef] = field(default_factory=list)
    controls: Controls = field(default_factory=Controls)
    output: OutputRequests = field(default_factory=OutputRequests)
    title: str = ""
    #: Resolved sets by LS-DYNA set id: node sets (k,) int64 node indices,
    #: part sets [pid, ...], segment sets (s, 4) int32 node indices.
    node_sets: dict[int, np.ndarray] = field(default_factory=dict)
    part_sets: dict[int, list[int]] = field(default_factory=dict)
    segment_sets: dict[int, np.ndarray] = field(default_factory=dict)
    #: Unsupported keywords seen while reading: (keyword, file, line).
    unsupported: list[tuple[str, str, int]] = field(default_factory=list)
    # -- body mechanics (docs/mechanics.md); each family's records are defined in
    # its own module of this package and built by its own module of ``build``
    #: *ELEMENT_BEAM groups, one per part (``model.beams``)
    beam_groups: list = field(default_factory=list)
    #: *ELEMENT_DISCRETE groups, one per part (``model.discrete``)
    discrete_groups: list = field(default_factory=list)
    #: *LOAD_BODY_*, *LOAD_NODE_*, *LOAD_RIGID_BODY (``model.loads``)
    loads: list = field(default_factory=list)
    #: *RIGIDWALL_PLANAR (``model.loads``)
    rigid_walls: list = field(default_factory=list)
    #: *CONSTRAINED_RIGID_BODIES, *CONSTRAINED_NODAL_RIGID_BODY,
    #: *CONSTRAINED_EXTRA_NODES (``model.rigid_constraints``)
    rigid_merges: list = field(default_factory=list)
    nodal_rigid_bodies: list = field(default_factory=list)
    extra_nodes: list = field(default_factory=list)
    #: *CONSTRAINED_JOINT_*, *CONSTRAINED_JOINT_STIFFNESS_* (``model.joints``)
    joints: list = field(default_factory=list)
    joint_stiffness: list = field(default_factory=list)
    #: *DEFINE_COORDINATE_* by CID (``model.joints``)
    coordinate_systems: dict = field(default_factory=dict)

    @property
    def n_nodes(self) -> int:
        return int(self.node_ids.shape[0])

    def material_of(self, pid: int) -> MaterialDef:
        return self.materials[self.parts[pid].mid]

    def hourglass_of(self, pid: int) -> HourglassDef:
        hgid = self.parts[pid].hgid
        return self.hourglass.get(hgid, self.controls.hourglass) if hgid else \
            self.controls.hourglass

    def rigid_pids(self) -> list[int]:
        return [pid for pid, p in self.parts.items()
                if self.materials[p.mid].kind == "rigid"]
