"""Deck -> Model for discrete elements: *SECTION_DISCRETE, *ELEMENT_DISCRETE,
*DEFINE_SD_ORIENTATION and the spring / damper materials (S01, S02, S04, S06).

Every reference is checked here (parts, sections, materials, curves, nodes,
orientations) and so is the geometry: a translational or torsional element needs
a direction, the line N1 -> N2 or a fixed vector (VID), so an element of zero
length (coincident nodes, or grounded with N2 = 0) without VID is a DeckError
at its card. Section options that are not run (KD, CL, CDL, TDL) are refused
rather than ignored. See docs/discrete.md.
"""

from __future__ import annotations

import numpy as np

from hollowbody.build.common import item_error
from hollowbody.io.keyword import ElementDiscrete, Material, SectionDiscrete
from hollowbody.io.keyword.kw_discrete import DefineSdOrientation
from hollowbody.model.discrete import DISCRETE_LAWS, DiscreteGroup
from hollowbody.model.model import Model

#: mm: two nodes closer than this are coincident (no direction for the element)
ZERO_LENGTH = 1.0e-9
#: curve fields of each discrete material kind
_CURVES = {"spring_nonlinear": ("LCD", "LCR"), "spring_general": ("LCDL", "LCDU")}


def _sections(b) -> dict[int, SectionDiscrete]:  # noqa: ANN001 - builder
    out = {}
    for s in b.of(SectionDiscrete):
        if int(s.dro) not in (0, 1):
            raise item_error(s, f"section {s.secid}: DRO must be 0 (translational) or 1 "
                             f"(torsional), not {s.dro}")
        for name, value in (("KD", s.kd), ("CL", s.cl), ("CDL", s.cdl), ("TDL", s.tdl)):
            if value:
                raise item_error(s, f"section {s.secid}: {name} = {value:g} is not supported "
                                 "(dynamic magnification, clearance and deflection limits are "
                                 "not implemented; leave it blank)")
        if s.fd < 0.0:
            raise item_error(s, f"section {s.secid}: FD must be >= 0")
        out[int(s.secid)] = s
    return out


def _orientations(b) -> dict[int, np.ndarray]:  # noqa: ANN001 - builder
    out = {}
    for o in b.of(DefineSdOrientation):
        if int(o.iop) != 0:
            raise item_error(o, f"orientation {o.vid}: IOP {o.iop} is not supported (only "
                             "IOP 0, a fixed vector XT YT ZT)")
        v = np.array([o.xt, o.yt, o.zt], dtype=np.float64)
        norm = float(np.linalg.norm(v))
        if norm <= 0.0:
            raise item_error(o, f"orientation {o.vid}: the vector XT YT ZT is zero")
        out[int(o.vid)] = v / norm
    return out


def _check_material(b, model: Model, mid: int, pid: int) -> None:  # noqa: ANN001
    mat = model.materials[mid]
    item = next((m for m in b.of(Material) if int(m.mid) == mid), None)
    where = item if item is not None else None
    p = mat.params

    def fail(msg: str):  # noqa: ANN202
        from hollowbody.errors import DeckError
        if where is not None:
            return item_error(where, msg)
        return DeckError(msg, mat.source.file, mat.source.line, mat.keyword or None)

    for key in _CURVES.get(mat.kind, ()):
        lc = int(p.get(key, 0.0))
        if lc and lc not in model.curves:
            raise fail(f"material {mid} refers to curve {lc} ({key}) which is not defined")
        if lc and model.curves[lc].x.size < 2:
            raise fail(f"material {mid}: curve {lc} ({key}) needs at least two points")
    if mat.kind == "spring_nonlinear" and not int(p["LCD"]):
        raise fail(f"material {mid}: LCD (the force-deflection curve) is missing")
    if mat.kind == "spring_general":
        if not int(p["LCDL"]):
            raise fail(f"material {mid}: LCDL (the loading curve) is missing")
        if p["TYI"] < 0.0 or p["CYI"] > 0.0:
            raise fail(f"material {mid}: TYI must be >= 0 and CYI <= 0")
        if p["BETA"] not in (0.0, 1.0) and p["TYI"] - p["CYI"] <= 0.0:
            raise fail(f"material {mid}: kinematic hardening (BETA = {p['BETA']:g}) needs an "
                       "elastic range: give the initial yield forces TYI > 0 and/or CYI < 0")
    if mat.kind == "spring_elastic" and p["K"] < 0.0:
        raise fail(f"material {mid}: K must be >= 0")
    if mat.kind == "damper_viscous" and p["DC"] < 0.0:
        raise fail(f"material {mid}: DC must be >= 0")


def build(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """Read the discrete elements of ``b``'s deck into ``model.discrete_groups``."""
    items = b.of(ElementDiscrete)
    sections = _sections(b)
    orient = _orientations(b)
    if not items:
        return
    seen: dict[int, ElementDiscrete] = {}
    rows: dict[int, list[ElementDiscrete]] = {}
    for it in items:
        eid = int(it.eid)
        if eid in seen:
            raise item_error(it, f"discrete element {eid} is defined twice (first at "
                             f"{seen[eid].source.file}:{seen[eid].source.line})")
        seen[eid] = it
        pid = int(it.pid)
        part = model.parts.get(pid)
        if part is None:
            raise item_error(it, f"discrete element {eid} refers to part {pid} which is not "
                             "defined")
        sec = model.sections.get(part.secid)
        if sec is None or sec.kind != "discrete":
            raise item_error(it, f"discrete element {eid}: part {pid} has no "
                             "*SECTION_DISCRETE (its section is "
                             f"{'missing' if sec is None else '*SECTION_' + sec.kind.upper()})")
        kind = model.materials[part.mid].kind
        if kind not in DISCRETE_LAWS:
            raise item_error(it, f"discrete element {eid}: the material {part.mid} of part "
                             f"{pid} is not a spring or damper material (S01, S02, S04, S06)")
        if int(it.vid) and int(it.vid) not in orient:
            raise item_error(it, f"discrete element {eid} refers to orientation VID "
                             f"{it.vid} (*DEFINE_SD_ORIENTATION) which is not defined")
        rows.setdefault(pid, []).append(it)
    x0 = model.node_x0
    for pid in sorted(rows):
        its = rows[pid]
        part = model.parts[pid]
        _check_material(b, model, part.mid, pid)
        sec = sections[part.secid]
        e = len(its)
        n1 = np.zeros(e, np.int64)
        n2 = np.full(e, -1, np.int64)
        axis = np.zeros((e, 3))
        fixed = np.zeros(e, bool)
        for k, it in enumerate(its):
            n1[k] = b.node_list(np.array([it.n1]), it, f"discrete element {it.eid} (N1)")[0]
            if int(it.n2):
                n2[k] = b.node_list(np.array([it.n2]), it, f"discrete element {it.eid} (N2)")[0]
            if int(it.vid):
                axis[k] = orient[int(it.vid)]
                fixed[k] = True
            elif n2[k] < 0 or np.linalg.norm(x0[n2[k]] - x0[n1[k]]) <= ZERO_LENGTH:
                what = "is grounded (N2 = 0)" if n2[k] < 0 else \
                    f"has coincident nodes N1 = N2 position ({it.n1}, {it.n2})"
                raise item_error(it, f"discrete element {it.eid} {what}: its direction is "
                                 "undefined; give an orientation vector VID "
                                 "(*DEFINE_SD_ORIENTATION)")
        scale = np.array([float(it.s) if it.s else 1.0 for it in its])
        model.discrete_groups.append(DiscreteGroup(
            pid=pid, kind=model.materials[part.mid].kind, mid=int(part.mid),
            torsional=int(sec.dro) == 1,
            elem_ids=np.array([int(it.eid) for it in its], np.int64), n1=n1, n2=n2,
            scale=scale, offset=np.array([float(it.offset) for it in its]),
            print_flag=np.array([int(it.pf) for it in its], np.int64), fixed_axis=fixed,
            axis=axis, failure_deflection=float(sec.fd),
            sources=[it.source for it in its], source=sec.source))
