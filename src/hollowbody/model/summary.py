"""A model summary for ``hollowbody check``: counts, masses, extent.

:func:`summarize` returns a JSON-ready dict; :func:`problems` lists why a
model cannot run. The time step is not estimated here: ``check`` reports the
run's own first step (:mod:`hollowbody.solver.preflight`). The element lengths
and wave speeds below are LS-DYNA's estimates, used to flag parts that could
not set a step (zero wave speed): solids ``L = V / (largest face area)``
(tetrahedra: smallest altitude ``3 V / largest face area``) and
``c = sqrt((K + 4 G / 3) / rho)``; shells ``L = area / longest side`` with
``c = sqrt(E / (rho (1 - nu^2)))``. Units: mm, ms, kg (``c`` in mm/ms).
"""

from __future__ import annotations

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.model.discrete import LAW_NAMES
from hollowbody.model.joints import joint_summary
from hollowbody.model.loads import loads_summary
from hollowbody.model.mass import hex_volumes, lumped_node_mass, quad_areas
from hollowbody.model.model import Model
from hollowbody.model.rigid_bodies import rigid_body_summary

#: Faces of the hexahedron, LS-DYNA node order (0-based local nodes).
HEX_FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
                      [3, 0, 4, 7]])
#: Poisson's ratio assumed for MAT_181 in shells (LS-DYNA's default for PR = 0).
RUBBER_NU = 0.495


def distinct_nodes(conn: np.ndarray) -> np.ndarray:
    """Number of distinct nodes per element row, (e,) int."""
    s = np.sort(conn, axis=1)
    return 1 + np.count_nonzero(np.diff(s, axis=1), axis=1)


def solid_kinds(conn: np.ndarray) -> dict[str, int]:
    """Counts of hexahedra (8 distinct nodes), wedges (6), tetrahedra (4), others."""
    d = distinct_nodes(conn)
    return {"hexahedra": int((d == 8).sum()), "wedges": int((d == 6).sum()),
            "tetrahedra": int((d == 4).sum()),
            "other_solids": int(((d != 8) & (d != 6) & (d != 4)).sum())}


def _curve_slope_at_zero(x: np.ndarray, y: np.ndarray) -> float:
    """dy/dx at x = 0 (the larger one-sided slope at a kink; end segment outside)."""
    if x.size < 2:
        return 0.0
    slopes = np.diff(y) / np.diff(x)
    k = int(np.searchsorted(x, 0.0))
    if k < x.size and x[k] == 0.0:
        side = [slopes[j] for j in (k - 1, k) if 0 <= j < slopes.size]
        return float(max(side))
    return float(slopes[min(max(k - 1, 0), slopes.size - 1)])


def moduli(model: Model, pid: int) -> tuple[float, float] | None:
    """(bulk K, shear G) in GPa of part ``pid``'s material, None for rigid and
    *MAT_NULL (no stiffness)."""
    mat = model.material_of(pid)
    p = mat.params
    if mat.kind in ("rigid", "null"):
        return None
    if mat.kind == "rubber181":
        curve = model.curves.get(int(p["LCID"]))
        e0 = 0.0
        if curve is not None:
            e0 = _curve_slope_at_zero(curve.x, curve.y) * p["SGL"] / (p["SW"] * p["ST"])
        return p["KM"], e0 / 3.0
    e, nu = p.get("E", 0.0), p.get("PR", 0.0)
    return e / (3.0 * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))


def solid_wave_speed(model: Model, pid: int) -> float:
    """Dilatational wave speed (mm/ms) of a solid part; 0 for rigid or massless."""
    km = moduli(model, pid)
    rho = model.material_of(pid).density
    if km is None or rho <= 0.0:
        return 0.0
    return float(np.sqrt(max(km[0] + 4.0 * km[1] / 3.0, 0.0) / rho))


def shell_wave_speed(model: Model, pid: int) -> float:
    """Plate wave speed (mm/ms) of a shell part; 0 for rigid or massless."""
    mat = model.material_of(pid)
    if mat.kind in ("rigid", "null") or mat.density <= 0.0:
        return 0.0
    if mat.kind == "rubber181":
        km = moduli(model, pid)
        e, nu = 3.0 * km[1], RUBBER_NU  # type: ignore[index]
    else:
        e, nu = mat.params.get("E", 0.0), mat.params.get("PR", 0.0)
    return float(np.sqrt(max(e, 0.0) / (mat.density * (1.0 - nu * nu))))


def solid_lengths(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Characteristic lengths (e,) mm of (degenerate) hexahedra."""
    vol = np.abs(hex_volumes(conn, x))
    faces = np.stack([quad_areas(conn[:, f], x) for f in HEX_FACES], axis=1)
    length = vol / np.maximum(faces.max(axis=1), 1e-300)
    tet = distinct_nodes(conn) == 4
    if tet.any():
        s = np.sort(conn[tet], axis=1)
        first = np.ones_like(s, dtype=bool)
        first[:, 1:] = s[:, 1:] != s[:, :-1]
        n4 = s[first].reshape(-1, 4)
        tri = [[0, 1, 2, 2], [0, 1, 3, 3], [0, 2, 3, 3], [1, 2, 3, 3]]
        a_max = np.stack([quad_areas(n4[:, t], x) for t in tri], axis=1).max(axis=1)
        length[tet] = 3.0 * vol[tet] / np.maximum(a_max, 1e-300)
    return length


def shell_lengths(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Characteristic lengths (e,) mm of shells: area / longest side."""
    xe = x[conn]
    sides = np.linalg.norm(xe - np.roll(xe, -1, axis=1), axis=2).max(axis=1)
    return quad_areas(conn, x) / np.maximum(sides, 1e-300)


def by_keyword(pairs: list[tuple[str, int]]) -> dict[str, list[int]]:
    """{"*KEYWORD": sorted ids} from (keyword, id) pairs."""
    out: dict[str, list[int]] = {}
    for kw, ident in pairs:
        out.setdefault(kw, []).append(int(ident))
    return {k: sorted(v) for k, v in sorted(out.items())}


def unsupported_entries(model: Model) -> list[dict]:  # or a Deck: both have .unsupported
    """The unsupported keywords of ``model`` as JSON-ready entries (file, line, keyword)."""
    return [{"keyword": k, "file": f, "line": n} for k, f, n in model.unsupported]


def unsupported_lines(model: Model) -> list[str]:
    """One message line per unsupported keyword: ``file:line: *KEYWORD: ... ignored``."""
    return [f"{f}:{n}: *{k}: keyword not supported, ignored" for k, f, n in model.unsupported]


def summarize(model: Model) -> dict:
    """JSON-ready summary of ``model`` (see the module docstring for the time steps)."""
    x = model.node_x0
    elements = {"hexahedra": 0, "wedges": 0, "tetrahedra": 0, "other_solids": 0, "shells": 0,
                "triangles": 0, "mass_elements": int(np.count_nonzero(model.node_extra_mass))}
    count: dict[int, int] = {}
    for g in model.solid_groups:
        for k, v in solid_kinds(g.conn).items():
            elements[k] += v
        count[g.pid] = count.get(g.pid, 0) + g.conn.shape[0]
    for g in model.shell_groups:
        tri = int((g.conn[:, 3] == g.conn[:, 2]).sum())
        elements["triangles"] += tri
        elements["shells"] += g.conn.shape[0] - tri
        count[g.pid] = count.get(g.pid, 0) + g.conn.shape[0]
    discrete: dict[str, int] = {}  # discrete elements per law (model.discrete)
    for g in model.discrete_groups:
        name = LAW_NAMES.get(g.kind, g.kind) + (" (torsional)" if g.torsional else "")
        discrete[name] = discrete.get(name, 0) + g.n_elem
        count[g.pid] = count.get(g.pid, 0) + g.n_elem
    if discrete:
        elements["discrete"] = sum(discrete.values())
    for g in model.beam_groups:  # [beams]
        elements["beams"] = elements.get("beams", 0) + int(g.conn.shape[0])
        count[g.pid] = count.get(g.pid, 0) + g.conn.shape[0]
    node_mass, part_mass = lumped_node_mass(model)
    for pid, pin in model.part_inertia.items():
        if pin.tm > 0.0:
            part_mass[pid] = pin.tm
    parts = []
    for pid, p in sorted(model.parts.items()):
        sec, mat = model.sections[p.secid], model.materials[p.mid]
        parts.append({"pid": pid, "title": p.title, "elements": count.get(pid, 0),
                      "section": f"*SECTION_{sec.kind.upper()} {sec.secid} (ELFORM {sec.elform})",
                      "material": f"*{mat.keyword or mat.kind} {mat.mid}",
                      "mass_kg": float(part_mass.get(pid, 0.0))})
    extra = float(model.node_extra_mass.sum())
    summary = {
        "title": model.title,
        "nodes": model.n_nodes,
        "elements": elements,
        "parts": parts,
        "materials": by_keyword([(f"*{d.keyword or d.kind}", mid)
                                  for mid, d in model.materials.items()]),
        "sections": by_keyword([(f"*SECTION_{d.kind.upper()}", sid)
                                 for sid, d in model.sections.items()]),
        "mass_kg": float(sum(part_mass.values()) + extra),
        "element_mass_kg": extra,
        "bounding_box": {"min": x.min(axis=0).tolist() if x.size else None,
                         "max": x.max(axis=0).tolist() if x.size else None},
        "end_time": model.controls.end_time,
        "discrete": discrete,
        "contacts": len(model.contacts),
        "tied_contacts": len(model.tied_contacts),
        **joint_summary(model),
        **loads_summary(model),
        "unsupported": unsupported_entries(model),
        "rigid_bodies": _rigid_bodies(model, node_mass),
    }
    summary["problems"] = problems(model, summary)
    summary["can_run"] = not summary["problems"]
    return summary


def _rigid_bodies(model: Model, node_mass: np.ndarray) -> list[dict]:
    """The rigid bodies' mass properties (:func:`rigid_body_summary`, the run's own);
    [] when they cannot be computed (the run's set-up reports why)."""
    try:
        return rigid_body_summary(model, node_mass)
    except DeckError:
        return []


def problems(model: Model, summary: dict) -> list[str]:
    """Reasons why ``model`` cannot run (empty when it can)."""
    out = []
    if model.n_nodes == 0:
        out.append("no nodes")
    if not (model.solid_groups or model.shell_groups or model.discrete_groups
            or model.beam_groups):
        out.append("no elements")
    if model.controls.end_time <= 0.0:
        out.append("no termination time (*CONTROL_TERMINATION ENDTIM is 0)")
    for part in summary["parts"]:
        if part["elements"] and part["mass_kg"] <= 0.0 and \
                not part["section"].startswith("*SECTION_DISCRETE"):  # massless springs
            out.append(f"part {part['pid']} has no mass (density RO of {part['material']})")
    for g in model.solid_groups:
        vol = hex_volumes(g.conn, model.node_x0)
        bad = np.flatnonzero(vol <= 0.0)
        if bad.size:
            out.append(f"{bad.size} solid element(s) of part {g.pid} with zero or negative "
                       f"volume (first: element {g.elem_ids[bad[0]]})")
    for g in model.shell_groups:
        bad = np.flatnonzero(quad_areas(g.conn, model.node_x0) <= 0.0)
        if bad.size:
            out.append(f"{bad.size} shell element(s) of part {g.pid} with zero area "
                       f"(first: element {g.elem_ids[bad[0]]})")
        if np.any(g.thickness <= 0.0):
            out.append(f"shell part {g.pid} has zero thickness (section T1 or element "
                       "thickness)")
    for g in model.solid_groups:
        if model.material_of(g.pid).kind != "rigid" and solid_wave_speed(model, g.pid) <= 0.0:
            out.append(f"part {g.pid}: wave speed is zero (check the material's moduli)")
    return out
