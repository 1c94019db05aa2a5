"""The paper's block impact test (section 2.1), as specified in DESIGN.md section 5.

A 180 x 180 x 90 mm block of soft tissue (bottom face fixed) is struck at the
centre of its top face by a rigid flat-faced cylinder (diameter 90 mm, 5 kg,
face edge rounded with 5 mm) moving in -z. :func:`block_impact` builds the
deck, writes ``deck.k`` (the same run, repeatable in LS-DYNA or OpenRadioss),
reads it back, runs it and extracts the force-displacement curve.

Choices (all written into the deck):

- the impactor is a rigid shell surface (*MAT_RIGID, 4 mm shells: the
  thickness is the contact thickness; with 1 mm the soft fat block's nodes
  were pushed through the surface at 40 km/h) whose density gives 5 kg;
  it is guided along z (CMO=1, CON1=4 fixes x and y, CON2=7 fixes all
  rotations), as a guided impactor in a test rig;
- contact *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE, tissue slave, impactor
  master, FS = FD = 0.2, SOFT=1 (stiffness from nodal mass and time step,
  robust for soft tissues whose bulk modulus spans 4.6-1000 MPa);
- the hollow block stands on a floor (*RIGIDWALL_PLANAR at z = 0, its nodes as
  slaves; `rwforc.csv`) besides its fixed bottom walls: crushed walls are held
  above the base instead of being pushed through the fixed walls (at 70 / 100
  km/h the impactor then pushes no node through, 2 / 43 before);
- the impactor starts 0.1 mm above the top face, beyond the contact
  thickness offset (half the impactor shell thickness, plus half the wall
  thickness for the hollow block);
- hourglass control of the solid block *HOURGLASS IHQ=6, QH=1 (assumed-strain
  stiffness, Belytschko-Bindeman): its force follows the fully integrated
  hexahedron's (within 20 % from 10 mm of travel, 2-4 % from 30 mm on;
  docs/block.md). The Flanagan-Belytschko stiffness form (IHQ=4, scaled by the
  bulk modulus, thousands of times the tissue's shear modulus) about doubles the
  block's force, and the viscous form dissipates a large share of the impact
  energy in nearly incompressible rubber (hourglass energy above the internal
  energy with IHQ=1).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hollowbody.curves import force_displacement as fdr
from hollowbody.curves.plot import plot as plot_curves
from hollowbody.mesh import standing_block
from hollowbody.scenarios.geometry import cylinder_impactor_mesh, sphere_impactor_mesh
from hollowbody.tissues import tissue
from hollowbody.units import kmh_to_mm_per_ms

if TYPE_CHECKING:
    from hollowbody.engines.runner import ExternalEngine

BLOCK_SIZE = (180.0, 180.0, 90.0)
IMPACTOR_MASS = 5.0  # kg
IMPACTOR_DIAMETER = 90.0  # mm
IMPACTOR_SHELL_T = 4.0  # mm: shell (and contact) thickness of the rigid impactor surface
INITIAL_GAP = 0.1  # mm beyond the contact offset
PID_TISSUE, PID_IMPACTOR = 1, 2
CONTACT_ID = 1
IMPACTOR_NODE0 = 1_000_001
IMPACTOR_ELEM0 = 1_000_001
#: Default DTMIN of the hollow block (with erosion on): a wall element crushed until
#: its step is 5 % of the initial one is deleted. Hollow muscle, 40 km/h: 5,395 cycles
#: instead of 17,861 (erosion only at 1 % area), peak force and maximum displacement
#: within 1 % (docs/block.md).
DTMIN_HOLLOW = 0.05
#: the solid block's default *HOURGLASS (IHQ, QM) and the IHQ values it accepts
SOLID_HOURGLASS = (6, 1.0)
SOLID_HOURGLASS_TYPES = (1, 2, 3, 4, 5, 6, 7)
#: *HOURGLASS id of the hollow block's walls (when BlockConfig.wall_hourglass_ihq > 0)
WALL_HGID = 2


@dataclass
class BlockConfig:
    """Inputs of the block test (DESIGN.md section 5); units mm, ms, km/h as named.

    end_time None picks a duration long enough for the rebound at this speed.
    """

    tissue: str = "muscle"
    structure: str = "solid"
    speed_kmh: float = 40.0
    mesh: float = 7.5
    impactor: str = "cylinder"
    edge_radius: float = 5.0
    end_time: float | None = None
    friction: float = 0.2
    erode: bool | None = None  # None: off for solid blocks, on for hollow ones
    #: solid block's *HOURGLASS IHQ (1-7) and QM (docs/block.md, "How much of the solid
    #: block's force is hourglass control")
    hourglass_ihq: int = SOLID_HOURGLASS[0]
    hourglass_qh: float = SOLID_HOURGLASS[1]
    #: *SECTION_SOLID ELFORM of the solid block: 1 one-point with the hourglass
    #: control above, 2 fully integrated (no hourglass modes; about 4x the cost)
    elform: int = 1
    # hollow structure (structure="hollow"); None -> the paper's fit for the tissue
    hollow_E: float | None = None  # MPa
    hollow_yield: float | None = None  # MPa
    hollow_etan: float = 0.0  # MPa
    thickness: float = 1.5  # mm
    cell: float = 30.0  # mm
    elements_per_edge: int = 4
    imperfection: float | None = None  # mm panel buckling-mode offset; None -> 0.1 thickness
    mass_preserving: bool = True
    self_contact: bool = True
    #: walls' *HOURGLASS IHQ (0: none, LS-DYNA's default viscous form IHQ 1, QH 0.1) and
    #: its QM; IHQ 4 QM 0.1 keeps the hollow block's hourglass energy at 4-7 % of the
    #: internal energy at 40-100 km/h where IHQ 1 reaches 13-20 % (docs/block.md)
    wall_hourglass_ihq: int = 0
    wall_hourglass_qh: float = 0.1
    #: *CONTROL_TERMINATION DTMIN (fraction of the initial step; 0 off); None ->
    #: DTMIN_HOLLOW for hollow blocks (with erosion: wall elements whose step falls
    #: below it are deleted), off for solid ones
    dtmin: float | None = None
    #: ms: selective mass scaling target (*CONTROL_TIMESTEP DT2MS = -value); 0 off
    mass_scaling: float = 0.0
    #: shell thickness follows the membrane strain (*CONTROL_SHELL ISTUPD 1)
    thickness_update: bool = False
    output_dt: float = 0.02  # ms between history rows
    states: int = 25  # ParaView states over the run
    extra: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        tissue(self.tissue)  # ValueError for unknown tissue
        if self.structure not in ("solid", "hollow"):
            raise ValueError(f"structure must be 'solid' or 'hollow' (got {self.structure!r})")
        if self.impactor not in ("cylinder", "sphere"):
            raise ValueError(f"impactor must be 'cylinder' or 'sphere' (got {self.impactor!r})")
        if self.speed_kmh <= 0.0:
            raise ValueError("speed must be positive")
        if self.dtmin is not None and not 0.0 <= self.dtmin < 1.0:
            raise ValueError(f"dtmin must be in [0, 1) (got {self.dtmin:g})")
        if self.mass_scaling < 0.0:
            raise ValueError("mass scaling target must be >= 0 ms (0 = off)")
        if self.mesh <= 0.0:
            raise ValueError("mesh size must be positive")
        if not 0.0 <= self.edge_radius < 0.5 * IMPACTOR_DIAMETER:
            raise ValueError("edge radius must be in [0, 45) mm")
        if self.elform not in (1, 2):
            raise ValueError(f"solid ELFORM must be 1 or 2 (got {self.elform})")
        if self.elform != 1 and self.structure == "hollow":
            raise ValueError("the element formulation (ELFORM) is that of the solid block; "
                             "the hollow block has no solid elements")
        if self.hourglass_ihq not in SOLID_HOURGLASS_TYPES or self.hourglass_qh < 0.0:
            raise ValueError(f"solid hourglass IHQ must be 1-7 and its QM >= 0 "
                             f"(got {self.hourglass_ihq}, {self.hourglass_qh:g})")
        if self.wall_hourglass_ihq not in (0, 1, 2, 3, 4, 5) or self.wall_hourglass_qh < 0.0:
            raise ValueError("wall hourglass IHQ must be 0 (none) or 1-5 and its QM >= 0 "
                             f"(got {self.wall_hourglass_ihq}, {self.wall_hourglass_qh:g})")
        if self.structure == "hollow":
            if self.thickness <= 0.0 or self.elements_per_edge < 1:
                raise ValueError("wall thickness must be positive and elements per edge >= 1")
            for s in BLOCK_SIZE:
                k = s / self.cell
                if abs(k - round(k)) > 1e-9 * k or round(k) < 1:
                    raise ValueError(f"--cell {self.cell:g} mm does not divide the block "
                                     f"({BLOCK_SIZE[0]:g} x {BLOCK_SIZE[1]:g} x "
                                     f"{BLOCK_SIZE[2]:g} mm)")
        for s in BLOCK_SIZE:
            k = s / self.mesh
            if abs(k - round(k)) > 1e-9 * k:
                raise ValueError(f"--mesh {self.mesh:g} mm does not divide the block "
                                 f"({BLOCK_SIZE[0]:g} x {BLOCK_SIZE[1]:g} x {BLOCK_SIZE[2]:g} mm)")

    @property
    def speed(self) -> float:
        """Impact speed in mm/ms."""
        return kmh_to_mm_per_ms(self.speed_kmh)

    @property
    def erodes(self) -> bool:
        """Erosion on? Given, else on for the hollow block only: there a wall
        element crushed in its plane (area < 1 %) is deleted and the run goes on,
        as crush simulations of thin-walled structures do; in the solid block a
        negative volume is a finding (error termination)."""
        return bool(self.erode) if self.erode is not None else self.structure == "hollow"

    @property
    def dtmin_fraction(self) -> float:
        """DTMIN used: given, else :data:`DTMIN_HOLLOW` for the hollow block, 0 (off)
        for the solid one."""
        if self.dtmin is not None:
            return float(self.dtmin)
        return DTMIN_HOLLOW if self.structure == "hollow" else 0.0

    def duration(self) -> float:
        """Simulated time (ms): given, or long enough for compression and rebound."""
        if self.end_time is not None:
            return float(self.end_time)
        return 20.0 if self.tissue == "muscle" else 30.0


def _impactor(cfg: BlockConfig) -> tuple[np.ndarray, np.ndarray]:
    """Impactor surface mesh; a zero edge radius is meshed as a 0.01 mm rounding."""
    if cfg.impactor == "sphere":
        return sphere_impactor_mesh(IMPACTOR_DIAMETER, h=4.0)
    return cylinder_impactor_mesh(IMPACTOR_DIAMETER, max(cfg.edge_radius, 0.01), height=20.0,
                                  h=4.0)


def build_block_deck(cfg: BlockConfig):  # -> Deck
    """The block test as a keyword :class:`~hollowbody.io.keyword.Deck`."""
    from hollowbody.io.keyword import (
        BoundarySpcSet,
        Contact,
        ControlShell,
        ControlTermination,
        ControlTimestep,
        DatabaseAscii,
        DatabaseBinaryD3plot,
        DatabaseHistoryNode,
        Deck,
        InitialVelocityGeneration,
        MatRigid,
        Part,
        RigidwallPlanar,
        SectionShell,
        SetNodeList,
    )

    t = tissue(cfg.tissue)
    deck = Deck()
    deck.title = (f"hollowbody block test: {cfg.structure} {t.name}, {cfg.speed_kmh:g} km/h, "
                  f"{cfg.impactor} impactor")
    if cfg.structure == "solid":
        xb, block_ids, top_offset, tissue_side = _add_solid_block(deck, cfg)
    else:
        xb, block_ids, top_offset, tissue_side = _add_hollow_block(deck, cfg)
    xi, qi = _impactor(cfg)
    xi = xi + np.array([0.0, 0.0, BLOCK_SIZE[2] + top_offset + 0.5 * IMPACTOR_SHELL_T
                        + INITIAL_GAP])
    imp_ids = IMPACTOR_NODE0 + np.arange(xi.shape[0])
    area = float(0.5 * np.linalg.norm(np.cross(xi[qi[:, 2]] - xi[qi[:, 0]],
                                               xi[qi[:, 3]] - xi[qi[:, 1]]), axis=1).sum())
    rho_imp = IMPACTOR_MASS / (area * IMPACTOR_SHELL_T)
    end = cfg.duration()
    deck.add_nodes(imp_ids, xi)
    deck.add_shells(IMPACTOR_ELEM0 + np.arange(qi.shape[0]), PID_IMPACTOR, imp_ids[qi],
                    thickness=IMPACTOR_SHELL_T)
    deck.add(Part(pid=PID_IMPACTOR, secid=2, mid=2, title=f"impactor ({cfg.impactor})"))
    deck.add(SectionShell(secid=2, t1=IMPACTOR_SHELL_T, nip=2))
    deck.add(MatRigid(mid=2, ro=rho_imp, e=210.0, pr=0.3, cmo=1, con1=4, con2=7))
    bottom = block_ids[xb[:, 2] < base_tolerance(cfg)]
    deck.add(SetNodeList(sid=1, nodes=bottom.tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1, dofrx=1, dofry=1, dofrz=1))
    if cfg.structure == "hollow":  # the base is a floor: crushed walls stay above it
        deck.add(SetNodeList(sid=2, nodes=block_ids.tolist()))
        deck.add(RigidwallPlanar(nsid=2, xt=0.0, yt=0.0, zt=0.0, xh=0.0, yh=0.0, zh=1.0))
        deck.add(DatabaseAscii(name="RWFORC", dt=cfg.output_dt))
    deck.add(InitialVelocityGeneration(id=PID_IMPACTOR, styp=2, vz=-cfg.speed))
    ssid, sstyp = tissue_side
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=CONTACT_ID,
                     heading="tissue-impactor", ssid=ssid, sstyp=sstyp, msid=PID_IMPACTOR,
                     mstyp=3, fs=cfg.friction, fd=cfg.friction, soft=1))
    deck.add(ControlTermination(endtim=end, dtmin=cfg.dtmin_fraction))
    deck.add(ControlTimestep(tssfac=0.9, erode=1 if cfg.erodes else 0,
                             dt2ms=-abs(cfg.mass_scaling)))
    if cfg.thickness_update:
        deck.add(ControlShell(istupd=1))
    for name in ("GLSTAT", "RCFORC", "NODOUT", "SPCFORC", "MATSUM"):
        deck.add(DatabaseAscii(name=name, dt=cfg.output_dt))
    deck.add(DatabaseBinaryD3plot(dt=end / cfg.states))
    deck.add(DatabaseHistoryNode(ids=[int(imp_ids[0])]))
    return deck


def base_tolerance(cfg: BlockConfig) -> float:
    """Height (mm) below which a block node lies on the fixed base.

    The hollow block's bottom walls are offset out of their plane like every wall
    panel (the imperfection, up to its amplitude on either side): all their nodes
    rest on the base, so the bound is half the walls' in-plane element size, far
    above the offset and below the first row of the vertical walls. (With
    ``z <= 0`` the panels offset upwards were left free, membranes over a void
    through which the crushed walls were pushed below the base.)
    """
    if cfg.structure == "hollow":
        return 0.5 * cfg.cell / cfg.elements_per_edge
    return 1e-9


def _add_solid_block(deck, cfg: BlockConfig):
    """Hexahedra with MAT_181; returns (nodes, ids, top offset mm, contact side)."""
    from hollowbody.io.keyword import (
        DefineCurve,
        Hourglass,
        MatSimplifiedRubber,
        Part,
        SectionSolid,
    )

    t = tissue(cfg.tissue)
    xb, cb = standing_block(BLOCK_SIZE, cfg.mesh)
    ids = np.arange(1, xb.shape[0] + 1)
    deck.add_nodes(ids, xb)
    deck.add_solids(np.arange(1, cb.shape[0] + 1), PID_TISSUE, ids[cb])
    deck.add(Part(pid=PID_TISSUE, secid=1, mid=1, hgid=1, title=f"{cfg.tissue} (solid)"))
    deck.add(SectionSolid(secid=1, elform=cfg.elform))
    deck.add(MatSimplifiedRubber(mid=1, ro=t.density, km=t.bulk_modulus, lcid=1))
    deck.add(DefineCurve(lcid=1, points=np.column_stack([t.strain, t.stress]).tolist(),
                         title=f"{cfg.tissue}: engineering stress [GPa] vs strain"))
    deck.add(Hourglass(hgid=1, ihq=cfg.hourglass_ihq, qm=cfg.hourglass_qh))
    return xb, ids, 0.0, (PID_TISSUE, 3)


#: Part ids of the hollow walls by normal axis (x, y, z) and their part set.
PID_WALLS = (11, 12, 13)
PSET_WALLS = 10


def hollow_material(cfg: BlockConfig) -> tuple[float, float, float]:
    """(E, yield, Etan) in MPa of the walls: given, or the paper's fit for the tissue."""
    t = tissue(cfg.tissue)
    e = cfg.hollow_E if cfg.hollow_E is not None else t.hollow_E * 1000.0
    y = cfg.hollow_yield if cfg.hollow_yield is not None else t.hollow_yield * 1000.0
    return float(e), float(y), float(cfg.hollow_etan)


def _add_hollow_block(deck, cfg: BlockConfig):
    """Shell walls on a cubic cell grid with MAT_003 and self-contact."""
    from hollowbody.hollow.grid import hollow_box
    from hollowbody.io.keyword import (
        Contact,
        Hourglass,
        MatPlasticKinematic,
        Part,
        SectionShell,
        SetPartList,
    )

    t = tissue(cfg.tissue)
    g = hollow_box(BLOCK_SIZE, cell=cfg.cell, thickness=cfg.thickness,
                   elements_per_edge=cfg.elements_per_edge,
                   origin=(-BLOCK_SIZE[0] / 2, -BLOCK_SIZE[1] / 2, 0.0),
                   imperfection=(0.1 * cfg.thickness if cfg.imperfection is None
                                 else cfg.imperfection))
    solid_mass = t.density * BLOCK_SIZE[0] * BLOCK_SIZE[1] * BLOCK_SIZE[2]
    rho = g.density_for_mass(solid_mass) if cfg.mass_preserving else t.density
    e, y, etan = hollow_material(cfg)
    ids = np.arange(1, g.nodes.shape[0] + 1)
    deck.add_nodes(ids, g.nodes)
    eid = 1
    for axis, pid in enumerate(PID_WALLS):
        sel = g.orientation == axis
        q = g.quads[sel]
        deck.add_shells(np.arange(eid, eid + q.shape[0]), pid, ids[q], thickness=cfg.thickness)
        eid += q.shape[0]
        deck.add(Part(pid=pid, secid=1, mid=1, hgid=WALL_HGID if cfg.wall_hourglass_ihq else 0,
                      title=f"hollow {cfg.tissue} walls normal {'xyz'[axis]}"))
    if cfg.wall_hourglass_ihq:
        deck.add(Hourglass(hgid=WALL_HGID, ihq=cfg.wall_hourglass_ihq, qm=cfg.wall_hourglass_qh))
    deck.add(SectionShell(secid=1, elform=2, nip=5, t1=cfg.thickness))
    deck.add(MatPlasticKinematic(mid=1, ro=rho, e=e / 1000.0, pr=0.3, sigy=y / 1000.0,
                                 etan=etan / 1000.0, beta=1.0))
    deck.add(SetPartList(sid=PSET_WALLS, parts=list(PID_WALLS)))
    if cfg.self_contact:
        deck.add(Contact(type="AUTOMATIC_SINGLE_SURFACE", cid=2, heading="hollow self-contact",
                         ssid=PSET_WALLS, sstyp=2, fs=cfg.friction, fd=cfg.friction, soft=1))
    return g.nodes, ids, 0.5 * cfg.thickness, (PSET_WALLS, 2)


#: Outcomes of a block impact by the impactor's maximum travel (see :func:`impact_outcome`)
STOPPED, REACHED_BASE, THROUGH_BASE = "stopped", "reached the base", "through the base"
#: the run ended otherwise than normally (an error termination, an interrupt) while the
#: impactor was still pressing into the block
NOT_STOPPED = "ended before it stopped"


def impact_outcome(max_displacement: float | None, advancing: bool = False) -> str | None:
    """How far the impactor got, from its maximum travel (mm).

    ``stopped`` below 90 % of the block height (the tissue stopped it), unless
    ``advancing`` (the run ended while the impactor still moved into the block, e.g.
    an error termination): then ``ended before it stopped``;
    ``reached the base`` up to the height + 5 mm (it crushed the block onto the
    fixed base: the force peak is the base's, not the tissue's); ``through the
    base`` beyond (nodes of the fixed base were pushed through the impactor's
    contact surface, which cannot happen physically: the results after that
    moment are not valid). None when unknown.
    """
    if max_displacement is None or not np.isfinite(max_displacement):
        return None
    h = BLOCK_SIZE[2]
    if max_displacement < 0.9 * h:
        return NOT_STOPPED if advancing else STOPPED
    return REACHED_BASE if max_displacement <= h + 5.0 else THROUGH_BASE


def still_advancing(curve) -> bool:
    """True when the impactor's last recorded travel is its largest and still growing
    (a run that ended there ended before the tissue stopped the impactor)."""
    d = np.asarray(curve.displacement, dtype=float)
    return bool(d.size >= 2 and d[-1] > d[-2] and d[-1] >= np.nanmax(d))


@dataclass
class BlockResult:
    """What :func:`block_impact` returns: the curve, the run summary and the folder."""

    curve: fdr.ForceDisplacement
    summary: dict
    out_dir: Path
    config: BlockConfig


def block_impact(cfg: BlockConfig, out_dir: str | Path, vtk: bool = True,
                 quiet: bool = True, engine: ExternalEngine | None = None) -> BlockResult:
    """Build, write (``deck.k``), read back and run the block test; write the curve files.

    ``engine``: an installed OpenRadioss or LS-DYNA that runs ``deck.k`` instead of
    hollowbody's own engine, in ``out_dir/<engine>/`` (its histories converted to
    hollowbody's, :mod:`hollowbody.engines`); the curve files, the plot and
    ``summary.json`` (a copy of the engine's, with the impact outcome) are written to
    ``out_dir`` as for an embedded run. EngineNotFound when it is not installed.
    """
    from hollowbody.solver.run_lock import RunLock

    out = Path(out_dir)
    with RunLock(out):  # deck, run and curve files: one writer at a time
        return _block_impact(cfg, out, vtk, quiet, engine)


def _block_impact(cfg: BlockConfig, out: Path, vtk: bool, quiet: bool,
                  engine: ExternalEngine | None) -> BlockResult:
    """:func:`block_impact` with ``out`` held."""
    deck_path = write_block_deck(cfg, out)
    label = f"block {cfg.structure} {cfg.tissue} {cfg.speed_kmh:g} km/h"
    if engine is None:
        from hollowbody.api import load_model, run_model

        result = run_model(load_model(deck_path), out, vtk=vtk, quiet=quiet,
                           overwrite=True, label=label)  # its own folder
        folder, summary, status = out, result.summary, result.status
    else:
        folder = out / engine.name
        summary = engine.run(deck_path, folder, quiet=quiet)
        status = summary["status"]
    curve = _impactor_curve(folder, f"{cfg.structure} {cfg.tissue}")
    fdr.write_csv(curve, out / "force_displacement.csv")
    outcome = impact_outcome(float(curve.max_displacement) if curve.time.size else None,
                             advancing=status != "normal termination"
                             and still_advancing(curve))
    summary["impact_outcome"] = outcome
    summary_path = folder / "summary.json"
    if summary_path.exists():
        s = json.loads(summary_path.read_text())
        s["impact_outcome"] = outcome
        text = json.dumps(s, indent=2)
        summary_path.write_text(text)
        if folder != out:
            (out / "summary.json").write_text(text)
    plot_curves([curve], out / "force_displacement.png",
             title=f"block test: {cfg.structure} {tissue(cfg.tissue).name}, "
                   f"{cfg.speed_kmh:g} km/h ({status})"
                   + (f", {engine.name}" if engine is not None else ""))
    return BlockResult(curve=curve, summary=summary, out_dir=out, config=cfg)


def write_block_deck(cfg: BlockConfig, out_dir: str | Path) -> Path:
    """Write the block test's deck as ``out_dir/deck.k``; its path."""
    from hollowbody.io.keyword import write_deck

    deck_path = Path(out_dir) / "deck.k"
    write_deck(build_block_deck(cfg), deck_path)
    return deck_path


def _impactor_curve(folder: Path, label: str) -> fdr.ForceDisplacement:
    """The impactor's force-displacement from a run folder's nodout/rcforc; empty when a
    run (an external engine's, stopped early) left either file out."""
    if not ((folder / "nodout.csv").is_file() and (folder / "rcforc.csv").is_file()):
        return fdr.ForceDisplacement(np.zeros(0), np.zeros(0), np.zeros(0), label)
    return fdr.extract(folder, IMPACTOR_NODE0, CONTACT_ID, (0.0, 0.0, -1.0), side="master",
                       label=label)
