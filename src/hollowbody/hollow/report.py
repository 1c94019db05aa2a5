"""The conversion report of ``hollowbody hollowize``: per part what was removed and added,
mass / centre of mass / principal inertia before and after, the smallest shell and its
time step; as a JSON-ready dict and as Markdown.

Units: mm, ms, kg; stresses in MPa (labelled), densities kg/mm^3.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.model.mass import MassProperties


def mass_dict(p: MassProperties) -> dict:
    """Mass kg, centre (3,) mm, principal moments (3,) kg mm^2 (ascending), inertia (3, 3)."""
    return {"mass_kg": float(p.mass), "centre_mm": [float(v) for v in p.centre],
            "principal_kg_mm2": [float(v) for v in np.sort(np.linalg.eigvalsh(p.inertia))],
            "inertia_kg_mm2": np.asarray(p.inertia, dtype=float).tolist()}


@dataclass
class PartReport:
    """One converted part (see the fields; all JSON-ready)."""

    pid: int
    title: str
    solids_removed: dict
    nodes_removed: int
    nodes_kept: int
    boundary_shells: dict
    wall_shells: dict
    new_nodes: int
    merged_nodes: int
    tied_nodes: int
    max_tie_gap_mm: float
    grid: dict
    material: dict
    mass_before: dict
    mass_after: dict
    errors: dict
    mass_plan: dict
    smallest_shell: dict
    coverage: dict
    ids: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)

    @property
    def shells_added(self) -> int:
        return int(sum(self.boundary_shells.values()) + sum(self.wall_shells.values()))

    @property
    def ok(self) -> bool:
        e = self.errors
        return bool(e["ok_mass"] and e["ok_centre"] and e["ok_inertia"])


@dataclass
class ConversionReport:
    """All converted parts, the options, the files written and warnings.

    ``changed_decks``: the new deck's file-level decks that differ from the
    input (used by the writer; not part of the JSON).
    """

    source: str
    parts: list[PartReport] = field(default_factory=list)
    options: dict = field(default_factory=dict)
    files: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    changed_decks: list = field(default_factory=list, repr=False)

    def to_dict(self) -> dict:
        parts = []
        for p in self.parts:
            d = asdict(p)
            d["shells_added"] = p.shells_added
            d["within_tolerance"] = p.ok
            parts.append(d)
        return {"source": self.source, "options": self.options, "files": self.files,
                "warnings": self.warnings, "parts": parts,
                "totals": {"solids_removed": sum(sum(p.solids_removed.values())
                                                 for p in self.parts),
                           "shells_added": sum(p.shells_added for p in self.parts),
                           "within_tolerance": all(p.ok for p in self.parts)}}

    def write_json(self, path: str | Path) -> None:
        Path(path).write_text(json.dumps(self.to_dict(), indent=2) + "\n")

    def write_markdown(self, path: str | Path) -> None:
        Path(path).write_text(self.to_markdown())

    def to_markdown(self) -> str:
        d = self.to_dict()
        o = self.options
        lines = ["# hollowize: solid soft tissue -> hollow shell structure", "",
                 f"Input: `{self.source}`", ""]
        if self.files:
            lines += ["Files written: " + ", ".join(f"`{f}`" for f in self.files), ""]
        lines += [f"Options: cell {o.get('cell')} mm, wall thickness {o.get('thickness')} mm, "
                  f"{o.get('elements_per_edge')} elements per cell edge, grid axes "
                  f"{o.get('grid_axes')}, mass mode {o.get('mass_mode')}, self-contact "
                  f"{'on' if o.get('self_contact') else 'off'}.", ""]
        t = d["totals"]
        lines += [f"**{len(self.parts)} part(s) converted: {t['solids_removed']} solids removed, "
                  f"{t['shells_added']} shells added; mass / centre / inertia "
                  f"{'within' if t['within_tolerance'] else 'NOT within'} tolerance "
                  "(0.1 %, 1 mm, 5 %).**", ""]
        for p in self.parts:
            lines += _part_markdown(p)
        if self.warnings:
            lines += ["## Warnings", ""] + [f"- {w}" for w in self.warnings] + [""]
        return "\n".join(lines)


def _v(a: list, fmt: str = "{:.4g}") -> str:
    return "(" + ", ".join(fmt.format(v) for v in a) + ")"


def _part_markdown(p: PartReport) -> list[str]:
    sr = p.solids_removed
    m = p.material
    g = p.grid
    b, a, e = p.mass_before, p.mass_after, p.errors
    lines = [f"## Part {p.pid}" + (f" — {p.title}" if p.title else ""), "",
             f"- solids removed: {sum(sr.values())} ({sr.get('hexahedra', 0)} hexahedra, "
             f"{sr.get('wedges', 0)} wedges, {sr.get('tetrahedra', 0)} tetrahedra"
             + (f", {sr['other']} other" if sr.get("other") else "") + "); nodes removed "
             f"{p.nodes_removed}" + (f" ({p.nodes_kept} interior nodes kept: referenced "
                                      "elsewhere)" if p.nodes_kept else ""),
             f"- shells added: {p.shells_added} — boundary surface {p.boundary_shells['quads']} "
             f"quads + {p.boundary_shells['triangles']} triangles (original nodes), interior "
             f"walls {p.wall_shells['quads']} quads + {p.wall_shells['triangles']} triangles; "
             f"{p.new_nodes} new nodes",
             f"- walls meet the boundary: {p.merged_nodes} wall nodes merged with boundary "
             f"nodes, {p.tied_nodes} tied to the boundary surface (max gap "
             f"{p.max_tie_gap_mm:.3g} mm)",
             f"- grid: {g['axes']} axes, cell {g['cell']:g} mm, lattice step {g['h']:.4g} mm, "
             f"cells {g['cells']}",
             f"- wall material *MAT_PLASTIC_KINEMATIC: E {m['E_MPa']:g} MPa, yield "
             f"{m['yield_MPa']:g} MPa, ETAN {m['etan_MPa']:g} MPa, PR {m['pr']:g} "
             f"({m['source']}); density {p.mass_plan['density']:.5g} kg/mm^3",
             f"- point masses: {p.mass_plan['count']} *ELEMENT_MASS, "
             f"{p.mass_plan['nodal_kg']:.5g} kg ({100 * (1 - p.mass_plan['phi']):.1f} % of the "
             "mass)" + (f" — {p.mass_plan['note']}" if p.mass_plan.get("note") else ""),
             f"- smallest shell: element {p.smallest_shell['element']}, length (area / longest "
             f"side) {p.smallest_shell['length_mm']:.4g} mm, time step "
             f"{p.smallest_shell['dt_ms']:.4g} ms",
             f"- coverage: {100 * p.coverage['fraction']:.2f} % of the removed solids' centroids "
             f"enclosed by walls within one cell along all six grid directions", "",
             "| | mass (kg) | centre of mass (mm) | principal moments (kg mm^2) |",
             "|---|---|---|---|",
             f"| solid (exact) | {b['mass_kg']:.6g} | {_v(b['centre_mm'], '{:.3f}')} | "
             f"{_v(b['principal_kg_mm2'])} |",
             f"| hollow (lumped) | {a['mass_kg']:.6g} | {_v(a['centre_mm'], '{:.3f}')} | "
             f"{_v(a['principal_kg_mm2'])} |",
             f"| error | {100 * e['mass_rel']:+.4f} % | {e['centre_mm']:.4f} mm | "
             f"{_v([100 * v for v in e['inertia_rel']], '{:+.3f}')} % |", ""]
    lines += [f"- note: {n}" for n in p.notes]
    if p.notes:
        lines.append("")
    return lines
