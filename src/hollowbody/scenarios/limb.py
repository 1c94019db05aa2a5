"""Limb segment and the dynamic three-point bending test (the paper's Fig. 4 / 7).

:func:`limb_deck` generates a straight thigh or leg segment along z:

- long bone: a single-layer shell tube (the paper models limb bones as
  shells), *MAT_PLASTIC_KINEMATIC with representative cortical-bone values
  (E 15 GPa, yield 0.1 GPa, tangent 0.5 GPa, density 2.0e-6 kg/mm^3,
  thickness 5 mm femur / 4 mm tibia);
- muscle: hexahedra filling the annulus between bone and skin,
  *MAT_SIMPLIFIED_RUBBER with the default skeletal-muscle curve and bulk
  modulus of :mod:`hollowbody.tissues`;
- skin: a shell tube, *MAT_ELASTIC E 5 MPa, PR 0.45, 1 mm, 1.1e-6 kg/mm^3.

Muscle, bone and skin share their nodes (bone = inner, skin = outer surface
of the muscle), as in a human body model. Geometry (mm): thigh bone outer
radius 14, soft-tissue radius 75, length 400; leg 11 / 55 / 350.

:func:`three_point_bending_deck` adds the Kerrigan-style test: lateral-medial
loading (-y) at mid-span by a rigid cylinder (radius 25 mm, axis x) moving
at a constant 1.5 m/s (= mm/ms, prescribed), the bone ends simply supported
(end rings of the bone's nodes: x, y fixed at both ends, z fixed at z = 0;
rotations free; flesh unsupported). Deflection = impactor travel, force =
impactor contact force, mid-span moment = F span / 4 (span = segment length).

:func:`run_three_point_bending` builds both the solid and the hollowized
segment (muscle part converted by :func:`hollowbody.hollow.convert.hollowize`),
runs them and plots force- and moment-deflection side by side with wall times.
Runs need the deformable-shell runtime (bone and skin are shells).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.io.keyword import (
    BoundarySpcSet,
    Contact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    Deck,
    DefineCurve,
    Hourglass,
    MassElements,
    MatElastic,
    MatPlasticKinematic,
    MatRigid,
    MatSimplifiedRubber,
    Nodes,
    Part,
    PrescribedMotionRigid,
    SectionShell,
    SectionSolid,
    SetNodeList,
    ShellElements,
    SolidElements,
)
from hollowbody.scenarios.block import SOLID_HOURGLASS
from hollowbody.tissues import tissue

PID_BONE, PID_MUSCLE, PID_SKIN, PID_IMPACTOR = 1, 2, 3, 4
#: Segment geometry (mm): bone outer radius, cortical thickness, soft-tissue radius, length.
SEGMENTS = {"thigh": (14.0, 5.0, 75.0, 400.0), "leg": (11.0, 4.0, 55.0, 350.0)}
BONE = {"E": 15.0, "yield": 0.1, "etan": 0.5, "pr": 0.3, "rho": 2.0e-6}  # GPa, kg/mm^3
SKIN = {"E": 0.005, "pr": 0.45, "rho": 1.1e-6, "t": 1.0}
SPEED = 1.5  # mm/ms = m/s
IMPACTOR_RADIUS = 25.0
IMPACTOR_T = 1.0
CONTACT_IMPACTOR = 1


def limb_deck(segment: str = "thigh", length: float | None = None, n_theta: int = 20,
              n_radial: int = 5, axial: float = 10.0, bone_radius: float | None = None,
              limb_radius: float | None = None) -> Deck:
    """The limb segment as a :class:`Deck` (parts bone 1, muscle 2, skin 3).

    segment: ``thigh`` or ``leg`` (default dimensions); length, bone_radius,
    limb_radius (mm) override them; n_theta elements around, n_radial through
    the muscle, ``axial`` mm element length along z (0 <= z <= length).
    """
    if segment not in SEGMENTS:
        raise ValueError(f"segment must be one of {sorted(SEGMENTS)} (got {segment!r})")
    rb, tb, rs, ln = SEGMENTS[segment]
    rb = bone_radius if bone_radius is not None else rb
    rs = limb_radius if limb_radius is not None else rs
    ln = length if length is not None else ln
    if not 0.0 < rb - 0.5 * tb < rs or ln <= 0.0 or n_theta < 3 or n_radial < 1:
        raise ValueError("need 0 < bone radius < limb radius, a positive length, "
                         "n_theta >= 3 and n_radial >= 1")
    r_in = rb - 0.5 * tb  # bone mid-surface = muscle inner surface
    nz = max(1, int(round(ln / axial)))
    th = 2.0 * math.pi * np.arange(n_theta) / n_theta
    rr = np.linspace(r_in, rs, n_radial + 1)
    zz = np.linspace(0.0, ln, nz + 1)
    z, r, t = np.meshgrid(zz, rr, th, indexing="ij")
    xyz = np.column_stack([(r * np.cos(t)).ravel(), (r * np.sin(t)).ravel(), z.ravel()])

    def nid(k, j, i):
        return (k * (n_radial + 1) + j) * n_theta + (i % n_theta) + 1

    k, j, i = np.meshgrid(np.arange(nz), np.arange(n_radial), np.arange(n_theta), indexing="ij")
    k, j, i = k.ravel(), j.ravel(), i.ravel()
    hexes = np.column_stack([nid(k, j, i), nid(k, j + 1, i), nid(k, j + 1, i + 1),
                             nid(k, j, i + 1), nid(k + 1, j, i), nid(k + 1, j + 1, i),
                             nid(k + 1, j + 1, i + 1), nid(k + 1, j, i + 1)])
    k2, i2 = (a.ravel() for a in np.meshgrid(np.arange(nz), np.arange(n_theta), indexing="ij"))

    def tube(jr):
        return np.column_stack([nid(k2, jr, i2), nid(k2, jr, i2 + 1), nid(k2 + 1, jr, i2 + 1),
                                nid(k2 + 1, jr, i2)])

    m = tissue("muscle")
    deck = Deck()
    deck.title = f"hollowbody limb segment: {segment}, length {ln:g} mm"
    deck.add_nodes(np.arange(1, xyz.shape[0] + 1), xyz)
    deck.add_shells(np.arange(1, nz * n_theta + 1), PID_BONE, tube(0))
    deck.add_solids(np.arange(1, hexes.shape[0] + 1) + 100000, PID_MUSCLE, hexes)
    deck.add_shells(np.arange(1, nz * n_theta + 1) + 200000, PID_SKIN, tube(n_radial))
    deck.add(Part(pid=PID_BONE, secid=1, mid=1, title=f"{segment} bone (cortical shell)"))
    deck.add(Part(pid=PID_MUSCLE, secid=2, mid=2, hgid=1, title=f"{segment} muscle"))
    deck.add(Part(pid=PID_SKIN, secid=3, mid=3, title=f"{segment} skin"))
    deck.add(SectionShell(secid=1, elform=2, nip=5, t1=tb, t2=tb, t3=tb, t4=tb))
    deck.add(SectionSolid(secid=2))
    deck.add(SectionShell(secid=3, elform=2, nip=3, t1=SKIN["t"], t2=SKIN["t"], t3=SKIN["t"],
                          t4=SKIN["t"]))
    deck.add(MatPlasticKinematic(mid=1, ro=BONE["rho"], e=BONE["E"], pr=BONE["pr"],
                                 sigy=BONE["yield"], etan=BONE["etan"], beta=1.0,
                                 title="cortical bone"))
    deck.add(MatSimplifiedRubber(mid=2, ro=m.density, km=m.bulk_modulus, lcid=1,
                                 title="skeletal muscle"))
    deck.add(DefineCurve(lcid=1, points=np.column_stack([m.strain, m.stress]).tolist(),
                         title="muscle: engineering stress [GPa] vs strain"))
    deck.add(MatElastic(mid=3, ro=SKIN["rho"], e=SKIN["E"], pr=SKIN["pr"], title="skin"))
    # the block test's and the pedestrian's control for the same MAT_181 muscle: the
    # assumed-strain form adds no stiffness of its own (docs/block.md)
    deck.add(Hourglass(hgid=1, ihq=SOLID_HOURGLASS[0], qm=SOLID_HOURGLASS[1]))
    return deck


def _part_nodes(deck: Deck, pid: int) -> np.ndarray:
    conns = [it.conn[it.pids == pid].ravel() for it in deck.of_type(ShellElements)]
    return np.unique(np.concatenate(conns)) if conns else np.zeros(0, np.int64)


def _cylinder_x(radius: float, length: float, n_around: int, n_along: int
                ) -> tuple[np.ndarray, np.ndarray]:
    """Shell tube along x centred on the origin: (nodes (n, 3), quads (q, 4) 0-based)."""
    a = 2.0 * math.pi * np.arange(n_around) / n_around
    xs = np.linspace(-0.5 * length, 0.5 * length, n_along + 1)
    x, t = np.meshgrid(xs, a, indexing="ij")
    nodes = np.column_stack([x.ravel(), radius * np.cos(t).ravel(), radius * np.sin(t).ravel()])
    k, i = (v.ravel() for v in np.meshgrid(np.arange(n_along), np.arange(n_around),
                                           indexing="ij"))

    def n(kk, ii):
        return kk * n_around + ii % n_around

    return nodes, np.column_stack([n(k, i), n(k, i + 1), n(k + 1, i + 1), n(k + 1, i)])


@dataclass
class BendingSetup:
    """What :func:`three_point_bending_deck` placed: impactor history node, span (mm),
    contact id, loading direction (3,)."""

    impactor_node: int
    span: float
    contact_id: int = CONTACT_IMPACTOR
    direction: tuple[float, float, float] = (0.0, -1.0, 0.0)


def three_point_bending_deck(limb: Deck, speed: float = SPEED, end_time: float = 20.0,
                             friction: float = 0.2, output_dt: float = 0.05,
                             dtmin: float = 0.0, erode: bool = False
                             ) -> tuple[Deck, BendingSetup]:
    """The dynamic three-point bending test of a limb segment deck (solid or hollowized).

    Returns a new flat deck (the limb's keywords followed by the test's) and
    the set-up. speed mm/ms (= m/s), end_time ms; dtmin: *CONTROL_TERMINATION
    DTMIN (fraction of the initial step, 0 = off); erode: *CONTROL_TIMESTEP
    ERODE = 1 (elements whose step falls below DTMIN are deleted, as crushed
    wall slivers under the impactor do, instead of ending the run).
    """
    items = list(limb.iter_items())
    nodes = [it for it in items if isinstance(it, Nodes)]
    ids = np.concatenate([n.ids for n in nodes])
    xyz = np.vstack([n.xyz for n in nodes])
    bone = _part_nodes(limb, PID_BONE)
    skin = _part_nodes(limb, PID_SKIN)
    if bone.size == 0 or skin.size == 0:
        raise ValueError("the deck has no bone (part 1) or skin (part 2) shells")
    order = np.argsort(ids)
    bx = xyz[order[np.searchsorted(ids[order], bone)]]
    sx = xyz[order[np.searchsorted(ids[order], skin)]]
    z0, z1 = float(bx[:, 2].min()), float(bx[:, 2].max())
    r_skin = float(np.hypot(sx[:, 0], sx[:, 1]).max())
    deck = Deck()
    deck.title = (limb.title or "limb") + f"; three-point bending at {speed:g} m/s"
    for it in items:
        if it.__class__.__name__ != "Title":
            deck.add(it)
    # rigid cylinder impactor above mid-span, moving in -y
    max_node = int(ids.max())
    max_elem = max(int(it.ids.max()) for it in items
                   if isinstance(it, (SolidElements, ShellElements, MassElements)) and it.ids.size)
    node0 = (max_node // 100000 + 1) * 100000 + 1
    elem0 = (max_elem // 100000 + 1) * 100000 + 1
    xi, qi = _cylinder_x(IMPACTOR_RADIUS, 2.0 * r_skin + 40.0, 36, 15)
    gap = 0.5 * SKIN["t"] + 0.5 * IMPACTOR_T + 0.1
    xi = xi + np.array([0.0, r_skin + IMPACTOR_RADIUS + gap, 0.5 * (z0 + z1)])
    imp_ids = node0 + np.arange(xi.shape[0])
    deck.add_nodes(imp_ids, xi)
    deck.add_shells(elem0 + np.arange(qi.shape[0]), PID_IMPACTOR, imp_ids[qi])
    deck.add(Part(pid=PID_IMPACTOR, secid=4, mid=4, title="impactor (rigid cylinder)"))
    deck.add(SectionShell(secid=4, t1=IMPACTOR_T))
    area = 2.0 * math.pi * IMPACTOR_RADIUS * (2.0 * r_skin + 40.0)
    deck.add(MatRigid(mid=4, ro=5.0 / (area * IMPACTOR_T), e=210.0, pr=0.3, cmo=1, con1=6,
                      con2=7, title="impactor"))
    deck.add(DefineCurve(lcid=9001, points=[[0.0, 1.0], [10.0 * end_time, 1.0]],
                         title="constant impactor speed"))
    deck.add(PrescribedMotionRigid(pid=PID_IMPACTOR, dof=2, vad=0, lcid=9001, sf=-speed))
    # simple supports on the bone's end rings
    end0 = bone[np.abs(bx[:, 2] - z0) < 1e-6]
    end1 = bone[np.abs(bx[:, 2] - z1) < 1e-6]
    deck.add(SetNodeList(sid=9001, nodes=end0, title="bone end z = 0 (pin)"))
    deck.add(SetNodeList(sid=9002, nodes=end1, title="bone end z = L (roller)"))
    deck.add(BoundarySpcSet(nsid=9001, dofx=1, dofy=1, dofz=1))
    deck.add(BoundarySpcSet(nsid=9002, dofx=1, dofy=1))
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=CONTACT_IMPACTOR,
                     heading="skin-impactor", ssid=PID_SKIN, sstyp=3, msid=PID_IMPACTOR,
                     mstyp=3, fs=friction, fd=friction, soft=1))
    deck.add(ControlTermination(endtim=end_time, dtmin=dtmin))
    deck.add(ControlTimestep(tssfac=0.9, erode=1 if erode else 0))
    for name in ("GLSTAT", "RCFORC", "NODOUT", "SPCFORC", "MATSUM"):
        deck.add(DatabaseAscii(name=name, dt=output_dt))
    deck.add(DatabaseBinaryD3plot(dt=end_time / 20.0))
    deck.add(DatabaseHistoryNode(ids=[int(imp_ids[0])]))
    return deck, BendingSetup(impactor_node=int(imp_ids[0]), span=z1 - z0)


# ---------------------------------------------------------------------------
# the runner


@dataclass
class BendingRun:
    """One run: ``status`` (or ``skipped: reason``), wall seconds, cycles, the final
    energy ratio and the curves (deflection mm, force kN, moment kN mm)."""

    structure: str
    status: str
    wall_seconds: float = float("nan")
    cycles: int = 0
    energy_ratio: float = float("nan")
    deflection: np.ndarray = field(default_factory=lambda: np.zeros(0))
    force: np.ndarray = field(default_factory=lambda: np.zeros(0))
    moment: np.ndarray = field(default_factory=lambda: np.zeros(0))
    deck: Path | None = None


def run_three_point_bending(out_dir: str | Path, segment: str = "thigh",
                            end_time: float = 20.0, structures: tuple[str, ...] = ("solid",
                                                                                   "hollow"),
                            hollow_options=None, limb_kwargs: dict | None = None,
                            quiet: bool = True, vtk: bool = False, dtmin: float = 0.0,
                            erode: bool = False) -> dict[str, BendingRun]:
    """Build, write, run and compare the solid and hollow three-point bending tests.

    Writes ``<structure>/deck.k`` (+ the run's outputs), ``bending.csv`` and
    ``bending.png`` (force- and moment-deflection side by side, wall times in
    the legend) in ``out_dir``. The muscle is hollowized with ``hollow_options``
    (default: the default options without self-contact). ``dtmin`` / ``erode``: see
    :func:`three_point_bending_deck` (the same for both structures). A
    structure whose run cannot start because deformable shells are not
    available is reported as skipped.
    """
    from hollowbody.api import run_deck
    from hollowbody.curves import force_displacement as fdr
    from hollowbody.errors import DeckError
    from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
    from hollowbody.io.keyword import write_deck

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    limb = limb_deck(segment, **(limb_kwargs or {}))
    runs: dict[str, BendingRun] = {}
    for structure in structures:
        if structure == "hollow":
            # no self-contact by default: it pushes tied wall edges apart (docs/hollowize.md)
            seg, _ = hollowize(limb, Selection(parts=[PID_MUSCLE]),
                               hollow_options or HollowOptions(self_contact=False))
        elif structure == "solid":
            seg = limb
        else:
            raise ValueError(f"structure must be 'solid' or 'hollow' (got {structure!r})")
        deck, setup = three_point_bending_deck(seg, end_time=end_time, dtmin=dtmin,
                                               erode=erode)
        folder = out / structure
        folder.mkdir(parents=True, exist_ok=True)
        write_deck(deck, folder / "deck.k")
        t0 = time.perf_counter()
        try:
            res = run_deck(folder / "deck.k", folder, vtk=vtk, quiet=quiet,
                           overwrite=True)  # the folder is the scenario's own
        except DeckError as exc:
            if "deformable shell" not in str(exc):
                raise
            runs[structure] = BendingRun(structure, f"skipped: {exc}", deck=folder / "deck.k")
            continue
        except Exception as exc:  # noqa: BLE001 - keep the other structure's result
            runs[structure] = BendingRun(structure, f"failed: {type(exc).__name__}: {exc}",
                                         deck=folder / "deck.k")
            continue
        wall = res.summary.get("wall_seconds", time.perf_counter() - t0)
        c = fdr.extract(folder, setup.impactor_node, setup.contact_id, setup.direction,
                        side="master", label=structure)
        runs[structure] = BendingRun(structure, res.status, float(wall), int(res.cycles),
                                     float(res.summary.get("energy_ratio") or float("nan")),
                                     c.displacement, c.force, c.force * setup.span / 4.0,
                                     folder / "deck.k")
    plot_bending(runs, out / "bending.png", f"{segment} three-point bending, {SPEED:g} m/s")
    _write_csv(runs, out / "bending.csv")
    return runs


def _write_csv(runs: dict[str, BendingRun], path: Path) -> None:
    rows = ["structure,deflection_mm,force_kN,moment_kNmm"]
    for name, r in runs.items():
        rows += [f"{name},{d:.6g},{f:.6g},{m:.6g}" for d, f, m in
                 zip(r.deflection, r.force, r.moment)]
    path.write_text("\n".join(rows) + "\n")


def plot_bending(runs: dict[str, BendingRun], path: str | Path, title: str = "") -> None:
    """Force- and moment-deflection side by side (PNG); wall times in the legend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11.0, 4.4), dpi=120)
    for name, r in runs.items():
        label = (f"{name}: {r.status}" if r.status.startswith(("skipped", "failed")) else
                 f"{name} ({r.wall_seconds:.1f} s wall, {r.cycles} cycles)")
        label = label[:70]
        a1.plot(r.deflection, r.force, lw=1.8, label=label)
        a2.plot(r.deflection, r.moment / 1000.0, lw=1.8, label=label)
    a1.set_xlabel("deflection [mm]")
    a1.set_ylabel("impactor force [kN]")
    a2.set_xlabel("deflection [mm]")
    a2.set_ylabel("mid-span moment [kN m]")
    for ax in (a1, a2):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
