"""Convert the solid soft tissue of a keyword deck into hollow shell structures.

>>> from hollowbody.io.keyword import read_deck
>>> from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
>>> deck = read_deck("model.k")                                     # doctest: +SKIP
>>> new, report = hollowize(deck, Selection(material_type=181), HollowOptions())  # doctest: +SKIP

For every selected solid part:

- its boundary surface (faces used by one of its elements; faces shared with
  other parts included) becomes shells on the original nodes, so the part
  still shares its nodes with bones, skin and organs
  (:mod:`~hollowbody.hollow.boundary`);
- its volume is filled with a cubic grid of shell walls clipped to it
  (:mod:`~hollowbody.hollow.fill`); wall nodes on the boundary either are
  boundary nodes (merged) or are tied to the boundary surface by a
  ``*CONTACT_TIED_SHELL_EDGE_TO_SURFACE`` (slave: node set, master: segment
  set of the boundary shells);
- the part keeps its id (so contacts, sets and loads that name it still
  apply, now to its shells) and gets a new ``*SECTION_SHELL`` (ELFORM 2,
  NIP 5) and ``*MAT_PLASTIC_KINEMATIC``; the solids and the nodes only they
  used are removed;
- the mass is kept (:mod:`~hollowbody.hollow.mass_match`), optionally a
  ``*CONTACT_AUTOMATIC_SINGLE_SURFACE`` on the part is added (self-contact
  of the hollow structure, as in the paper).

Everything else is unchanged; new ids come from free ranges above the deck's
maxima; new keywords go into the file that holds the part's solids. The
input deck object is not modified.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hollowbody.build import build_model
from hollowbody.errors import UserInputError
from hollowbody.hollow import deck_edit as de
from hollowbody.hollow.boundary import boundary_faces, solid_mass_properties, solid_tets
from hollowbody.hollow.fill import fill_walls, grid_frame
from hollowbody.hollow.mass_match import compare, lumped_volumes, match_mass
from hollowbody.hollow.report import ConversionReport, PartReport, mass_dict
from hollowbody.hollow.spatial import TriangleSurface
from hollowbody.io.keyword import (
    Contact,
    Deck,
    Hourglass,
    MassElements,
    Material,
    MatPlasticKinematic,
    Nodes,
    Part,
    SectionShell,
    SetNodeList,
    SetPartList,
    SetPartListGenerate,
    SetSegment,
    ShellElements,
    SolidElements,
)
from hollowbody.model.mass import point_mass_properties
from hollowbody.model.model import Model
from hollowbody.model.summary import solid_kinds
from hollowbody.tissues import TISSUES

#: MAT_181 bulk modulus (GPa) from which the paper's muscle wall material is the default.
MUSCLE_KM = 0.1
WALL_PR = 0.3


@dataclass
class Selection:
    """Which solid parts to convert: ``parts`` (ids), a ``part_set`` id, or every part whose
    material is LS-DYNA type ``material_type`` (e.g. 181). Nothing given: type 181."""

    parts: list[int] | None = None
    part_set: int | None = None
    material_type: int | None = None


@dataclass
class HollowOptions:
    """Conversion options (mm, MPa).

    cell: cubic cell edge; thickness: wall thickness; elements_per_edge:
    shells along a cell edge; material: (E, yield) MPa of the walls, else
    ``calibration`` (a JSON file with ``{"best": {"E": ..., "yield": ...}}``
    in MPa), else the paper's values by the tissue's bulk modulus; etan:
    tangent modulus MPa; grid_axes: ``global`` or ``principal`` (the part's
    principal axes of inertia); mass_mode: ``density`` or ``nodal``;
    thickness_from_calibration: a wall thickness in the calibration file
    replaces ``thickness``; geometry_from_calibration: the cell and the shells
    per cell edge the calibration's block walls had replace ``cell`` and
    ``elements_per_edge`` (:func:`read_calibration_geometry`); self_contact: add a
    single-surface contact on
    each converted part;
    snap, merge: lattice-step fractions (see :mod:`hollowbody.hollow.fill`);
    coverage: measure the coverage of the removed solids (report).
    """

    cell: float = 30.0
    thickness: float = 1.5
    elements_per_edge: int = 4
    material: tuple[float, float] | None = None
    calibration: str | Path | None = None
    etan: float = 0.0
    thickness_from_calibration: bool = True
    geometry_from_calibration: bool = True
    grid_axes: str = "global"
    mass_mode: str = "density"
    self_contact: bool = True
    friction: float = 0.2
    #: walls' *HOURGLASS IHQ (0: none, the deck's default) and QM, as the block
    #: test's ``--wall-hourglass`` (docs/block.md)
    wall_hourglass_ihq: int = 0
    wall_hourglass_qm: float = 0.1
    snap: float = 0.25
    merge: float = 0.05
    coverage: bool = True

    def validate(self) -> None:
        """UserInputError naming the first bad option."""
        if not self.cell > 0.0:
            raise UserInputError(f"--cell must be positive (got {self.cell:g} mm)")
        if not self.thickness > 0.0:
            raise UserInputError(f"--thickness must be positive (got {self.thickness:g} mm)")
        if int(self.elements_per_edge) < 1:
            raise UserInputError("--elements-per-edge must be at least 1 "
                                 f"(got {self.elements_per_edge})")
        if self.wall_hourglass_ihq not in (0, 1, 2, 3, 4, 5) or self.wall_hourglass_qm < 0.0:
            raise UserInputError("--wall-hourglass must be 0 (none) or 1-5 and its QM >= 0 "
                                 f"(got {self.wall_hourglass_ihq}, "
                                 f"{self.wall_hourglass_qm:g})")
        if self.grid_axes not in ("global", "principal"):
            raise UserInputError(f"--grid-axes must be 'global' or 'principal' "
                                 f"(got {self.grid_axes!r})")
        if self.mass_mode not in ("density", "nodal"):
            raise UserInputError(f"--mass-mode must be 'density' or 'nodal' "
                                 f"(got {self.mass_mode!r})")
        if self.material is not None and (len(self.material) != 2
                                          or not min(self.material) > 0.0):
            raise UserInputError("--material needs two positive values E,YIELD in MPa "
                                 f"(got {self.material})")
        if self.material is not None and self.calibration is not None:
            raise UserInputError("give either --material or --calibration, not both")
        if not 0.0 < self.snap < 0.5 or not 0.0 <= self.merge < 0.5:
            raise UserInputError("snap must be in (0, 0.5) and merge in [0, 0.5)")
        if self.etan < 0.0:
            raise UserInputError(f"ETAN must not be negative (got {self.etan:g} MPa)")


def read_calibration(path: str | Path) -> dict[str, float]:
    """Wall parameters (MPa, mm) of a calibration JSON file: ``E``, ``yield`` and, when
    given, ``etan`` and ``thickness``.

    Accepts ``{"best": {"E": ..., "yield": ...}}``, the calibration driver's
    ``{"best_parameters": {...}, "simulator": {"fixed": {...}}}`` (fixed values
    fill in what was not calibrated), or the keys at the top level; keys are
    case-insensitive, ``sigy`` is accepted for ``yield``.
    """
    try:
        data = json.loads(Path(path).read_text())
    except OSError as exc:
        raise UserInputError(f"calibration file '{path}': {exc.strerror}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise UserInputError(f"calibration file '{path}' is not JSON: {exc}") from None
    if not isinstance(data, dict):
        raise UserInputError(f"calibration file '{path}' is not a JSON object")
    best = data.get("best", data.get("best_parameters", data))
    if not isinstance(best, dict):
        raise UserInputError(f"calibration file '{path}' has no best parameters")
    sim = data.get("simulator")
    fixed = sim.get("fixed") if isinstance(sim, dict) else None
    merged = {**(fixed if isinstance(fixed, dict) else {}), **best}
    low = {str(k).lower(): v for k, v in merged.items()}
    if "yield" not in low and "sigy" in low:
        low["yield"] = low["sigy"]
    out: dict[str, float] = {}
    try:
        for key in ("e", "yield", "etan", "thickness"):
            if key in low:
                out["E" if key == "e" else key] = float(low[key])
    except (TypeError, ValueError):
        raise UserInputError(f"calibration file '{path}': parameters must be numbers") from None
    if "E" not in out or "yield" not in out:
        raise UserInputError(f"calibration file '{path}' needs best.E and best.yield "
                             "(numbers, MPa)")
    if not (out["E"] > 0.0 and out["yield"] > 0.0) or out.get("thickness", 1.0) <= 0.0:
        raise UserInputError(f"calibration file '{path}': E, yield and thickness must be "
                             "positive")
    return out


def read_calibration_geometry(path: str | Path) -> dict[str, float | int]:
    """The walls' geometry of a calibration driver's file: ``cell`` (mm; recorded when
    not the paper's 30 mm) and ``elements_per_edge`` from its ``simulator``; {} for
    other calibration files (those :func:`read_calibration` reads it has checked)."""
    sim = json.loads(Path(path).read_text()).get("simulator")
    if not isinstance(sim, dict):
        return {}
    out: dict[str, float | int] = {}
    options = sim.get("options")  # (the calibration layer's wall_geometry, read here)
    try:
        if isinstance(options, dict) and "cell" in options:
            out["cell"] = float(options["cell"])
        if "elements_per_edge" in sim:
            out["elements_per_edge"] = int(sim["elements_per_edge"])
    except (TypeError, ValueError):
        raise UserInputError(f"calibration file '{path}': the simulator's cell and "
                             "elements_per_edge must be numbers") from None
    return out


def wall_material(model: Model, pid: int, options: HollowOptions) -> dict:
    """E, yield, ETAN (MPa), PR and where they come from, for part ``pid``'s walls."""
    etan = options.etan
    if options.material is not None:
        e, y = (float(v) for v in options.material)
        source = "--material"
    elif options.calibration is not None:
        cal = read_calibration(options.calibration)
        e, y, etan = cal["E"], cal["yield"], cal.get("etan", etan)
        source = f"calibration {Path(options.calibration).name}"
    else:
        mat = model.material_of(pid)
        km = mat.params.get("KM") if mat.kind == "rubber181" else None
        tissue = "muscle" if km is None or km >= MUSCLE_KM else "fat"
        t = TISSUES[tissue]
        e, y = t.hollow_E * 1000.0, t.hollow_yield * 1000.0
        source = (f"paper's {tissue} fit (KM {km:g} GPa)" if km is not None
                  else "paper's muscle fit (material is not MAT_181)")
    return {"E_MPa": e, "yield_MPa": y, "etan_MPa": float(etan), "pr": WALL_PR, "source": source}


def select_parts(deck: Deck, model: Model, selection: Selection) -> list[int]:
    """Part ids to convert (sorted); UserInputError for parts that do not exist, have no
    solids or are rigid, unknown part sets, or a material type no solid part has."""
    pids = _requested(model, selection)
    for pid in pids:
        if model.material_of(pid).kind == "rigid":
            raise UserInputError(f"part {pid} is rigid (*MAT_RIGID); only deformable solid "
                                 "parts can be made hollow")
    return pids


def _requested(model: Model, selection: Selection) -> list[int]:
    solid_pids = {g.pid for g in model.solid_groups}
    if selection.parts:
        for pid in selection.parts:
            if pid not in model.parts:
                raise UserInputError(f"part {pid} does not exist in the deck")
            if pid not in solid_pids:
                raise UserInputError(f"part {pid} has no solid elements")
        return sorted(set(int(p) for p in selection.parts))
    if selection.part_set is not None:
        sid = int(selection.part_set)
        if sid not in model.part_sets:
            raise UserInputError(f"part set {sid} does not exist in the deck")
        pids = sorted(set(model.part_sets[sid]))
        if not pids:
            raise UserInputError(f"part set {sid} is empty")
        for pid in pids:
            if pid not in solid_pids:
                raise UserInputError(f"part {pid} (in part set {sid}) has no solid elements")
        return pids
    mtype = 181 if selection.material_type is None else int(selection.material_type)
    classes = [c for c in Material.__subclasses__() if f"MAT_{mtype:03d}" in c.ALIASES]
    kinds = {c.KIND for c in classes} - {"rigid"}
    if not kinds:
        raise UserInputError(f"material type {mtype} is not a deformable material the deck "
                             "reader knows (1, 3, 24, 181)")
    pids = sorted(pid for pid in solid_pids if model.material_of(pid).kind in kinds)
    if not pids:
        raise UserInputError(f"no solid part has a material of type {mtype}")
    return pids


def hollowize(deck: Deck, selection: Selection | None = None,
              options: HollowOptions | None = None) -> tuple[Deck, ConversionReport]:
    """Convert the selected solid parts of ``deck`` into hollow shell structures.

    Returns the new deck (include structure kept; unchanged files share the
    input's items) and the report. ``deck`` itself is not modified. Bad
    requests raise :class:`~hollowbody.errors.UserInputError` (DeckError for a
    deck that does not build).
    """
    selection = selection or Selection()
    options = options or HollowOptions()
    if options.calibration is not None:
        t = read_calibration(options.calibration).get("thickness")  # a readable file first
        if t is not None and options.thickness_from_calibration:
            options = dataclasses.replace(options, thickness=t)
        if options.geometry_from_calibration:
            options = dataclasses.replace(options,
                                          **read_calibration_geometry(options.calibration))
    options.validate()
    model = build_model(deck)
    pids = select_parts(deck, model, selection)
    report = ConversionReport(source=str(deck.path or "<deck>"),
                              options=_options_dict(options, selection, pids))
    ids = de.IdAllocator(deck)
    new = de.copy_tree(deck)
    changed: set[int] = set()
    groups = {g.pid: g for g in model.solid_groups}
    results = [_convert_part(model, groups[pid], options, ids, report) for pid in pids]
    # nodes that only the removed solids used
    boundary_ids = np.unique(np.concatenate([r.boundary_node_ids for r in results]))
    referenced = de.referenced_nodes(deck, set(pids))
    for r in results:
        interior = np.setdiff1d(r.part_node_ids, boundary_ids)
        kept = np.intersect1d(interior, referenced)
        r.removed_nodes = np.setdiff1d(interior, kept)
        r.report.nodes_removed, r.report.nodes_kept = int(r.removed_nodes.size), int(kept.size)
        if kept.size:
            report.warnings.append(
                f"part {r.pid}: {kept.size} interior node(s) are referenced by other keywords "
                f"and were kept (no element uses them now; first: {int(kept[0])})")
    removed_nodes = np.concatenate([r.removed_nodes for r in results])
    _edit_files(new, pids, results, removed_nodes, changed)
    report.parts = [r.report for r in results]
    report.changed_decks = [d for d in de.file_decks(new) if id(d) in changed]
    _warn_references(deck, pids, report)
    return new, report


# ---------------------------------------------------------------------------
# one part


@dataclass
class _PartResult:
    pid: int
    part_node_ids: np.ndarray
    boundary_node_ids: np.ndarray
    new_items: list
    part_update: dict
    report: PartReport
    removed_nodes: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, np.int64))


def _convert_part(model: Model, group, options: HollowOptions, ids: de.IdAllocator,
                  report: ConversionReport) -> _PartResult:
    pid = group.pid
    x = model.node_x0
    conn = group.conn.astype(np.int64)
    rho = model.material_of(pid).density
    target = solid_mass_properties(x, conn, rho)
    if not target.mass > 0.0:
        raise UserInputError(f"part {pid} has no mass (density RO {rho:g} of material "
                             f"{model.parts[pid].mid}); nothing to keep")
    part_nodes = np.unique(conn)
    frame = grid_frame(x, target.inertia if options.grid_axes == "principal" else None)
    extent = np.ptp(x[part_nodes] @ frame, axis=0)
    if options.cell >= extent.max() * (1.0 - 1e-9):
        raise UserInputError(
            f"--cell {options.cell:g} mm is not smaller than part {pid}'s bounding box "
            f"({extent[0]:.4g} x {extent[1]:.4g} x {extent[2]:.4g} mm): no wall would be "
            "inside the part")
    faces, _ = boundary_faces(x, conn)
    tets = solid_tets(conn)
    walls = fill_walls(x, tets, part_nodes, faces, options.cell, options.elements_per_edge,
                       frame, options.snap, options.merge)
    n_orig = x.shape[0]
    xa = np.vstack([x, walls.x_new])
    node0 = ids.take("node", walls.x_new.shape[0])
    comb_ids = np.concatenate([model.node_ids, node0 + np.arange(walls.x_new.shape[0])])
    shells = np.vstack([faces, walls.conn])
    n_skin = faces.shape[0]
    elem0 = ids.take("element", shells.shape[0])
    shell_ids = elem0 + np.arange(shells.shape[0])
    # mass
    mat = wall_material(model, pid, options)
    nodes, vol = lumped_volumes(shells, xa, options.thickness)
    plan = match_mass(xa[nodes], vol, target, options.mass_mode, rho)
    node_mass = plan.density * vol + plan.nodal
    after = point_mass_properties(xa[nodes], node_mass)
    errors = compare(target, after)
    point = plan.nodal > 1e-12 * target.mass
    # time step: area / longest side over the plate wave speed
    length = _shell_lengths(shells, xa)
    e_gpa = mat["E_MPa"] / 1000.0
    c = float(np.sqrt(e_gpa / (plan.density * (1.0 - WALL_PR**2)))) if plan.density > 0 else 0.0
    k = int(np.argmin(length))
    smallest = {"element": int(shell_ids[k]), "length_mm": float(length[k]),
                "area_mm2": float(_areas(shells[k:k + 1], xa)[0]),
                "dt_ms": float(length[k] / c) if c > 0 else float("inf"),
                "wave_speed_mm_per_ms": c}
    coverage = _coverage(x, conn, xa, shells, frame, options) if options.coverage else \
        {"fraction": float("nan"), "uncovered": -1}
    # keywords
    secid, mid = ids.take("section"), ids.take("material")
    title = model.parts[pid].title
    items: list = [de.comment([
        f"hollowbody hollowize: part {pid} is now a hollow shell structure",
        f"  {conn.shape[0]} solids removed; {n_skin} boundary shells and "
        f"{walls.conn.shape[0]} wall shells",
        f"  shells {elem0}..{shell_ids[-1]}; cell {options.cell:g} mm, walls "
        f"{options.thickness:g} mm, {options.elements_per_edge} per cell edge",
        f"  grid axes {options.grid_axes}, mass mode {options.mass_mode}"])]
    if walls.x_new.shape[0]:
        items.append(Nodes(ids=comb_ids[n_orig:], xyz=walls.x_new))
    items.append(ShellElements(ids=shell_ids, pids=pid, conn=comb_ids[shells]))
    items.append(SectionShell(secid=secid, elform=2, nip=5, t1=options.thickness,
                              t2=options.thickness, t3=options.thickness, t4=options.thickness,
                              title=f"hollow walls of part {pid}"))
    items.append(MatPlasticKinematic(mid=mid, ro=float(plan.density), e=e_gpa, pr=WALL_PR,
                                     sigy=mat["yield_MPa"] / 1000.0,
                                     etan=mat["etan_MPa"] / 1000.0, beta=1.0,
                                     title=f"hollow walls of part {pid}"))
    if point.any():
        m0 = ids.take("element", int(point.sum()))
        items.append(MassElements(ids=m0 + np.arange(int(point.sum())),
                                  nids=comb_ids[nodes[point]], mass=plan.nodal[point]))
    id_info = {"nodes": [int(node0), int(node0 + walls.x_new.shape[0] - 1)],
               "shells": [int(elem0), int(shell_ids[-1])], "section": secid, "material": mid}
    max_gap = float(walls.tie_gap.max()) if walls.tied.size else 0.0
    if walls.tied.size:
        nsid, ssid, cid = ids.take("node_set"), ids.take("segment_set"), ids.take("contact")
        items.append(SetSegment(sid=ssid, segments=comb_ids[faces],
                                title=f"boundary of hollow part {pid}"))
        items.append(SetNodeList(sid=nsid, nodes=comb_ids[walls.tied],
                                 title=f"wall nodes tied to the boundary of part {pid}"))
        mst = max(options.thickness, 2.5 * max_gap)
        items.append(de.tied_shell_edge_contact(cid, f"hollow walls -> boundary, part {pid}",
                                                nsid, ssid, mst))
        id_info.update(tie_contact=cid, tie_node_set=nsid, tie_segment_set=ssid)
    if options.self_contact:
        cid = ids.take("contact")
        items.append(Contact(type="AUTOMATIC_SINGLE_SURFACE", cid=cid,
                             heading=f"hollow part {pid} self-contact", ssid=pid, sstyp=3,
                             fs=options.friction, fd=options.friction, soft=1))
        id_info["self_contact"] = cid
    kinds = solid_kinds(conn)
    tri_skin = int((faces[:, 3] == faces[:, 2]).sum())
    tri_wall = int((walls.conn[:, 3] == walls.conn[:, 2]).sum())
    part_report = PartReport(
        pid=pid, title=title,
        solids_removed={"hexahedra": kinds["hexahedra"], "wedges": kinds["wedges"],
                        "tetrahedra": kinds["tetrahedra"], "other": kinds["other_solids"]},
        nodes_removed=0, nodes_kept=0,
        boundary_shells={"quads": n_skin - tri_skin, "triangles": tri_skin},
        wall_shells={"quads": walls.conn.shape[0] - tri_wall, "triangles": tri_wall},
        new_nodes=int(walls.x_new.shape[0]), merged_nodes=int(walls.stats.get("merged_nodes", 0)),
        tied_nodes=int(walls.tied.size), max_tie_gap_mm=max_gap,
        grid={"axes": options.grid_axes, "frame": walls.frame.T.tolist(),
              "planes_mm": [np.asarray(pl).tolist() for pl in walls.planes],
              "cell": options.cell, "h": walls.h,
              "elements_per_edge": options.elements_per_edge,
              "cells": walls.cells.tolist(), "stats": walls.stats},
        material=mat, mass_before=mass_dict(target), mass_after=mass_dict(after), errors=errors,
        mass_plan={"mode": options.mass_mode, "density": float(plan.density),
                   "phi": float(plan.phi), "nodal_kg": float(plan.nodal.sum()),
                   "count": int(point.sum()), "note": plan.note},
        smallest_shell=smallest, coverage=coverage, ids=id_info)
    if walls.stats.get("unattached_free_nodes"):
        part_report.notes.append(
            f"{walls.stats['unattached_free_nodes']} free-edge wall node(s) are farther than "
            "the snap distance from the boundary and are not tied")
    if not part_report.ok:
        report.warnings.append(f"part {pid}: mass / centre / inertia not within tolerance "
                               f"({plan.note})")
    hgid = 0
    if options.wall_hourglass_ihq:
        hgid = ids.take("hourglass")
        items.append(Hourglass(hgid=hgid, ihq=options.wall_hourglass_ihq,
                               qm=options.wall_hourglass_qm))
        id_info["hourglass"] = hgid
    update = {"secid": secid, "mid": mid, "hgid": hgid, "eosid": 0,
              "title": (title + " (hollow)")[:80] if title else "hollow"}
    return _PartResult(pid=pid, part_node_ids=model.node_ids[part_nodes],
                       boundary_node_ids=model.node_ids[np.unique(faces)], new_items=items,
                       part_update=update, report=part_report)


def _areas(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    xe = x[conn]
    return 0.5 * np.linalg.norm(np.cross(xe[:, 2] - xe[:, 0], xe[:, 3] - xe[:, 1]), axis=1)


def _shell_lengths(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """area / longest side (mm) of shells (w, 4)."""
    xe = x[conn]
    sides = np.linalg.norm(xe - np.roll(xe, -1, axis=1), axis=2).max(axis=1)
    return _areas(conn, x) / np.maximum(sides, 1e-300)


def _coverage(x: np.ndarray, conn: np.ndarray, xa: np.ndarray, shells: np.ndarray,
              frame: np.ndarray, options: HollowOptions) -> dict:
    """Share of the removed solids whose centroid is enclosed by the hollow structure within
    one cell: rays along the six grid directions all hit a shell within ``cell`` mm."""
    s = np.sort(conn, axis=1)
    first = np.ones_like(s, dtype=bool)
    first[:, 1:] = s[:, 1:] != s[:, :-1]
    cnt = first.sum(axis=1)
    centroid = np.einsum("ek,ekj->ej", first.astype(float), x[s]) / cnt[:, None]
    surface = TriangleSurface.from_shells(xa, shells, size=options.cell / 2)
    dirs = np.vstack([frame.T, -frame.T])
    hits = surface.ray_hits(centroid, dirs, options.cell * (1.0 + 1e-6)).all(axis=1)
    return {"fraction": float(hits.mean()) if hits.size else 1.0,
            "uncovered": int((~hits).sum())}


# ---------------------------------------------------------------------------
# the deck edits


def _edit_files(new: Deck, pids: list[int], results: list[_PartResult],
                removed_nodes: np.ndarray, changed: set[int]) -> None:
    by_pid = {r.pid: r for r in results}
    target: dict[int, Deck] = {}
    for d in de.file_decks(new):
        for item in list(d.items):
            if isinstance(item, SolidElements):
                hit = np.isin(item.pids, pids)
                if not hit.any():
                    continue
                for pid in np.unique(item.pids[hit]).tolist():
                    target.setdefault(pid, d)
                keep = ~hit
                de.replace_item(d, item, SolidElements(
                    ids=item.ids[keep], pids=item.pids[keep], conn=item.conn[keep],
                    source=item.source) if keep.any() else None)
                changed.add(id(d))
            elif isinstance(item, Nodes) and removed_nodes.size:
                gone = np.isin(item.ids, removed_nodes)
                if not gone.any():
                    continue
                keep = ~gone
                de.replace_item(d, item, Nodes(
                    ids=item.ids[keep], xyz=item.xyz[keep],
                    tc=None if item.tc is None else item.tc[keep],
                    rc=None if item.rc is None else item.rc[keep],
                    source=item.source) if keep.any() else None)
                changed.add(id(d))
            elif isinstance(item, Part) and item.pid in by_pid:
                de.replace_item(d, item, dataclasses.replace(item, **by_pid[item.pid].part_update))
                changed.add(id(d))
    for pid in pids:
        d = target[pid]
        for it in by_pid[pid].new_items:
            d.add(it)
        changed.add(id(d))


def _warn_references(deck: Deck, pids: list[int], report: ConversionReport) -> None:
    """Warnings about keywords that may refer to the removed solids."""
    seen = set()
    for raw in deck.unsupported:
        name = raw[0]
        if name.startswith(("SET_SOLID", "ELEMENT_SOLID", "DATABASE_HISTORY_SOLID",
                            "INITIAL_STRESS_SOLID", "CONSTRAINED")) and name not in seen:
            seen.add(name)
            report.warnings.append(f"{raw[1]}:{raw[2]}: *{name} is kept as text and may refer "
                                   "to removed solids or nodes; check it")
    for s in deck.of_type(SetPartList) + deck.of_type(SetPartListGenerate):
        ids = s.parts if isinstance(s, SetPartList) else s.expand()
        if np.isin(ids, pids).any():
            report.warnings.append(f"part set {s.sid} contains converted part(s); it now "
                                   "refers to their shells")


def _options_dict(o: HollowOptions, s: Selection, pids: list[int]) -> dict:
    d = dataclasses.asdict(o)
    d["calibration"] = str(o.calibration) if o.calibration is not None else None
    d["material"] = list(o.material) if o.material is not None else None
    d["selection"] = dataclasses.asdict(s)
    d["parts"] = pids
    return d
