"""Build the static :class:`~hollowbody.model.model.Model` from a keyword deck.

LS-DYNA ids become 0-based indices, elements are grouped into one
SolidGroup / ShellGroup per part (element order kept, groups by part id),
blank and zero fields take their LS-DYNA defaults, sets are resolved, and
every reference is checked: a problem raises :class:`DeckError` at the file
and line of the card that refers (``deck.k:12: *PART: part 3 refers to
material 9 which is not defined``).
"""

from __future__ import annotations

from collections import defaultdict

import numpy as np

from hollowbody.build.beams import section_def as beam_section_def
from hollowbody.build.common import item_error, no_cid, node_set, or_default
from hollowbody.build.initial_velocities import initial_velocities
from hollowbody.build.mechanics import build_mechanics
from hollowbody.build.surface_refs import defined_surface
from hollowbody.build.tied import tied_contacts
from hollowbody.build.unsupported import not_defined, unsupported_definitions
from hollowbody.errors import DeckError
from hollowbody.io.keyword import (
    BoundarySpcNode,
    BoundarySpcSet,
    ConstrainedNodalRigidBodyKeyword,
    Contact,
    ControlBulkViscosity,
    ControlContact,
    ControlHourglass,
    ControlShell,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3dump,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    DatabaseHistoryNodeSet,
    Deck,
    DefineCurve,
    Hourglass,
    KeywordItem,
    MassElements,
    Material,
    Nodes,
    Part,
    PartInertia,
    PrescribedMotionKeyword,
    PrescribedMotionRigid,
    PrescribedMotionSet,
    SectionBeam,
    SectionDiscrete,
    SectionShell,
    SectionSolid,
    SetNodeList,
    SetNodeListGenerate,
    SetPartList,
    SetPartListGenerate,
    SetSegment,
    ShellElements,
    SolidElements,
    TiedContact,
)
from hollowbody.model import model as m
from hollowbody.model.rigid_bodies import local_axes_inertia

#: *DATABASE_* ASCII files whose intervals go into ``OutputRequests.intervals``.
OUTPUT_DATABASES = ("glstat", "rcforc", "nodout", "spcforc", "matsum", "rwforc", "deforc",
                    "rbdout")
# *NODE TC / RC and *MAT_RIGID CON codes -> constrained axes.
_AXES = {0: (), 1: (0,), 2: (1,), 3: (2,), 4: (0, 1), 5: (1, 2), 6: (2, 0), 7: (0, 1, 2)}
_MOTION_DOFS = (1, 2, 3, 5, 6, 7)


_err = item_error
_or = or_default


class _Rows:
    """Rows of several bulk items concatenated, with their file:line."""

    def __init__(self, items: list) -> None:
        self.items = items
        self.offsets = np.cumsum([0] + [len(it.ids) for it in items])

    def locate(self, row: int) -> tuple[KeywordItem, int]:
        k = int(np.searchsorted(self.offsets, row, side="right") - 1)
        item = self.items[k]
        lines = item.row_lines
        return item, int(lines[row - self.offsets[k]]) if lines is not None else item.source.line

    def error(self, row: int, message: str) -> DeckError:
        item, line = self.locate(row)
        return _err(item, message, line)


def _first_duplicate(ids: np.ndarray) -> tuple[int, int] | None:
    """(first row, second row) of the first repeated id, or None."""
    if ids.size < 2:
        return None
    order = np.argsort(ids, kind="stable")
    s = ids[order]
    rep = np.flatnonzero(s[1:] == s[:-1])
    if rep.size == 0:
        return None
    seconds = order[rep + 1]
    k = int(np.argmin(seconds))
    return int(order[rep[k]]), int(seconds[k])


def _unique_ids(items: list, what: str, attr: str) -> dict[int, KeywordItem]:
    """{id: item} of keyword items, DeckError on a repeated id."""
    out: dict[int, KeywordItem] = {}
    for it in items:
        key = int(getattr(it, attr))
        if key in out:
            first = out[key].source
            raise _err(it, f"{what} {key} is defined twice (first at {first})")
        out[key] = it
    return out


class _Builder:
    def __init__(self, deck: Deck) -> None:
        groups: dict[type, list] = defaultdict(list)
        for item in deck.iter_items():
            for cls in type(item).__mro__:
                groups[cls].append(item)
        self.of = lambda cls: groups.get(cls, [])
        self.raw_defs = unsupported_definitions(deck)

    # -- nodes ---------------------------------------------------------------

    def nodes(self) -> None:
        items = self.of(Nodes)
        rows = _Rows(items)
        ids = np.concatenate([it.ids for it in items]) if items else np.zeros(0, np.int64)
        x = np.concatenate([it.xyz for it in items]) if items else np.zeros((0, 3))
        dup = _first_duplicate(ids)
        if dup:
            item, line = rows.locate(dup[0])
            raise rows.error(dup[1], f"node {ids[dup[1]]} is defined twice (first at "
                             f"{item.source.file}:{line})")
        self.node_ids, self.x0 = ids, x
        self._order = np.argsort(ids)
        self._sorted = ids[self._order]

    def index(self, ids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Node indices of ``ids`` and a mask of ids that are not defined."""
        ids = np.asarray(ids, dtype=np.int64)
        if self._sorted.size == 0:
            return np.zeros(ids.shape, np.int64), np.ones(ids.shape, bool)
        pos = np.clip(np.searchsorted(self._sorted, ids), 0, self._sorted.size - 1)
        missing = self._sorted[pos] != ids
        return self._order[pos], missing

    def node_list(self, ids: np.ndarray, item: KeywordItem, what: str,
                  lines: np.ndarray | list | None = None) -> np.ndarray:
        idx, missing = self.index(ids)
        if missing.any():
            k = int(np.flatnonzero(missing.ravel())[0])
            line = int(np.asarray(lines).ravel()[k]) if lines is not None and len(lines) else None
            raise _err(item, f"{what} refers to node {np.asarray(ids).ravel()[k]} which is "
                       "not defined", line)
        return idx

    # -- definitions -----------------------------------------------------------

    def curves(self) -> dict[int, m.Curve]:
        out = {}
        for lcid, c in _unique_ids(self.of(DefineCurve), "curve", "lcid").items():
            x = _or(c.sfa, 1.0) * (c.points[:, 0] + c.offa)
            y = _or(c.sfo, 1.0) * (c.points[:, 1] + c.offo)
            if np.any(np.diff(x) <= 0.0):
                raise _err(c, f"curve {lcid}: abscissa is not increasing after scaling "
                           f"(SFA={c.sfa:g})")
            out[lcid] = m.Curve(lcid, x, y, c.title, c.source)
        return out

    def materials(self, curves: dict[int, m.Curve]) -> dict[int, m.MaterialDef]:
        out = {}
        for mid, mat in _unique_ids(self.of(Material), "material", "mid").items():
            p = _material_params(mat)
            for key in ("LCID", "LCSS", "LCSR"):
                lc = int(p.get(key, 0.0))
                if lc and lc not in curves:
                    raise _err(mat, f"material {mid} refers to curve {lc} ({key}) which is "
                               "not defined")
            if mat.KIND == "rubber181" and not int(p["LCID"]):
                raise _err(mat, f"material {mid}: LC/TBID (the force-deflection curve) is "
                           "missing")
            if mat.KIND == "pwl024" and not int(p["LCSS"]) and mat.es1:
                raise _err(mat, f"material {mid}: the EPS/ES table is not supported; give "
                           "the hardening curve as LCSS")
            out[mid] = m.MaterialDef(mid, mat.KIND, mat.ro, p, mat.KEYWORD, mat.title,
                                     mat.source)
        return out

    def sections(self) -> dict[int, m.SectionDef]:
        out: dict[int, m.SectionDef] = {}
        items = (self.of(SectionSolid) + self.of(SectionShell) + self.of(SectionDiscrete)
                 + self.of(SectionBeam))
        for secid, s in _unique_ids(items, "section", "secid").items():
            if isinstance(s, SectionDiscrete):  # build.discrete reads the rest
                out[secid] = m.SectionDef(secid, "discrete", 0, {"DRO": float(s.dro)},
                                          s.title, s.source)
            elif isinstance(s, SectionBeam):  # [beams]
                out[secid] = beam_section_def(s)
            elif isinstance(s, SectionShell):
                t1 = s.t1
                params = {"T1": t1, "T2": _or(s.t2, t1), "T3": _or(s.t3, t1),
                          "T4": _or(s.t4, t1), "NIP": float(_or(s.nip, 2)),
                          "SHRF": _or(s.shrf, 1.0), "QR": s.qr}
                out[secid] = m.SectionDef(secid, "shell", int(_or(s.elform, 2)), params,
                                          s.title, s.source)
            else:
                out[secid] = m.SectionDef(secid, "solid", int(_or(s.elform, 1)), {}, s.title,
                                          s.source)
        return out

    def controls(self) -> m.Controls:
        c = m.Controls()
        for t in self.of(ControlTermination):
            c.end_time, c.dtmin = t.endtim, t.dtmin
            c.endmas = t.endmas if t.endmas > 0.0 else 1.0e8
        for t in self.of(ControlTimestep):
            c.tssfac, c.dt2ms, c.erode = _or(t.tssfac, 0.9), t.dt2ms, t.erode
        for sh in self.of(ControlShell):
            c.istupd = int(sh.istupd)
        hg = m.HourglassDef(hgid=0)
        for h in self.of(ControlHourglass):
            hg.ihq, hg.qm, hg.source = int(_or(h.ihq, 1)), _or(h.qh, 0.1), h.source
        for b in self.of(ControlBulkViscosity):
            hg.q1, hg.q2 = _or(b.q1, 1.5), _or(b.q2, 0.06)
        c.hourglass = hg
        for cc in self.of(ControlContact):
            c.slsfac = _or(cc.slsfac, 0.1)
            c.contact_sort_interval = int(_or(cc.nsbcs, 100))
            c.tiedprj = int(cc.tiedprj)
        return c

    def hourglass(self, ctrl: m.Controls) -> dict[int, m.HourglassDef]:
        d = ctrl.hourglass
        return {hgid: m.HourglassDef(hgid, int(_or(h.ihq, d.ihq)), _or(h.qm, 0.1),
                                     _or(h.q1 or 0.0, d.q1), _or(h.q2 or 0.0, d.q2), h.source)
                for hgid, h in _unique_ids(self.of(Hourglass), "hourglass", "hgid").items()}

    def parts(self, sections: dict, materials: dict, hourglass: dict) -> dict[int, m.PartDef]:
        out = {}
        items = self.of(Part) + self.of(PartInertia)
        for pid, p in _unique_ids(items, "part", "pid").items():
            for what, ident, known in (("section", p.secid, sections),
                                       ("material", p.mid, materials),
                                       ("hourglass", p.hgid, hourglass)):
                if (ident or what != "hourglass") and ident not in known:
                    raise _err(p, f"part {pid} refers to {what} {ident}"
                               + not_defined(self.raw_defs, what, ident))
            out[pid] = m.PartDef(pid, p.secid, p.mid, p.hgid, p.title, p.source)
        return out

    # -- elements --------------------------------------------------------------

    def elements(self, cls: type, kind: str, parts: dict, sections: dict) -> list:
        items = self.of(cls)
        if not items:
            return []
        rows = _Rows(items)
        ids = np.concatenate([it.ids for it in items])
        pids = np.concatenate([it.pids for it in items])
        dup = _first_duplicate(ids)
        if dup:
            item, line = rows.locate(dup[0])
            raise rows.error(dup[1], f"element {ids[dup[1]]} is defined twice (first at "
                             f"{item.source.file}:{line})")
        conn_ids = np.concatenate([it.conn for it in items])
        conn, missing = self.index(conn_ids)
        if missing.any():
            r, k = (int(v[0]) for v in np.nonzero(missing))
            raise rows.error(r, f"element {ids[r]} refers to node {conn_ids[r, k]} which is "
                             "not defined")
        upids, first = np.unique(pids, return_index=True)
        for pid, r in zip(upids.tolist(), first.tolist()):
            if pid not in parts:
                raise rows.error(r, f"element {ids[r]} refers to part {pid}"
                                 + not_defined(self.raw_defs, "part", pid))
            sec = sections[parts[pid].secid]
            if sec.kind != kind:
                raise rows.error(r, f"element {ids[r]} is a {kind} but part {pid} has "
                                 f"*SECTION_{sec.kind.upper()} {sec.secid}")
        thick = None
        if kind == "shell":
            thick = np.zeros((ids.size, 4))
            for it, lo in zip(items, rows.offsets[:-1].tolist()):
                if it.thickness is not None:
                    thick[lo:lo + len(it.ids)] = it.thickness
        order = np.argsort(pids, kind="stable")
        bounds = np.searchsorted(pids[order], upids, side="left").tolist() + [ids.size]
        groups = []
        for k, pid in enumerate(upids.tolist()):
            sel = order[bounds[k]:bounds[k + 1]]
            c = conn[sel].astype(np.int32)
            if kind == "solid":
                groups.append(m.SolidGroup(pid, ids[sel].copy(), c))
            else:
                sp = sections[parts[pid].secid].params
                t_sec = np.array([sp["T1"], sp["T2"], sp["T3"], sp["T4"]])
                t = thick[sel]
                t = np.where(t > 0.0, t, t_sec[None, :])
                groups.append(m.ShellGroup(pid, ids[sel].copy(), c, t))
        return groups

    def extra_mass(self, n: int) -> np.ndarray:
        mass = np.zeros(n)
        for it in self.of(MassElements):
            idx = self.node_list(it.nids, it, "mass element", it.row_lines)
            np.add.at(mass, idx, it.mass)
        return mass

    # -- sets --------------------------------------------------------------------

    def sets(self, parts: dict) -> tuple[dict, dict, dict]:
        node_sets: dict[int, np.ndarray] = {}
        for sid, s in _unique_ids(self.of(SetNodeList) + self.of(SetNodeListGenerate),
                                  "node set", "sid").items():
            if isinstance(s, SetNodeListGenerate):
                idx, missing = self.index(s.expand())
                node_sets[sid] = idx[~missing].astype(np.int64)
            else:
                node_sets[sid] = self.node_list(s.nodes, s, f"node set {sid}", s.id_lines)
        part_sets: dict[int, list[int]] = {}
        for sid, s in _unique_ids(self.of(SetPartList) + self.of(SetPartListGenerate),
                                  "part set", "sid").items():
            if isinstance(s, SetPartListGenerate):
                part_sets[sid] = [p for p in s.expand().tolist() if p in parts]
                continue
            for k, pid in enumerate(s.parts.tolist()):
                if pid not in parts:
                    raise _err(s, f"part set {sid} refers to part {pid} which is not defined",
                               int(s.id_lines[k]) if s.id_lines is not None else None)
            part_sets[sid] = [int(p) for p in s.parts.tolist()]
        seg_sets: dict[int, np.ndarray] = {}
        for sid, s in _unique_ids(self.of(SetSegment), "segment set", "sid").items():
            lines = np.repeat(s.segment_lines, 4) if s.segment_lines else None
            seg_sets[sid] = self.node_list(s.segments, s, f"segment set {sid}",
                                           lines).astype(np.int32)
        return node_sets, part_sets, seg_sets


def _material_params(mat: Material) -> dict[str, float]:
    """MaterialDef.params (keys of MATERIAL_PARAMS) of a material keyword."""
    keys = m.MATERIAL_PARAMS[mat.KIND]
    p = {k: float(getattr(mat, k.lower())) for k in keys}
    if mat.KIND == "rubber181":
        for k in ("SGL", "SW", "ST"):
            p[k] = _or(p[k], 1.0)
    return p


def build_model(deck: Deck) -> m.Model:
    """Resolve a :class:`Deck` into a :class:`Model` (DeckError on bad references)."""
    b = _Builder(deck)
    b.nodes()
    curves = b.curves()
    materials = b.materials(curves)
    sections = b.sections()
    controls = b.controls()
    hourglass = b.hourglass(controls)
    parts = b.parts(sections, materials, hourglass)
    solids = b.elements(SolidElements, "solid", parts, sections)
    shells = b.elements(ShellElements, "shell", parts, sections)
    n = b.node_ids.size
    model = m.Model(node_ids=b.node_ids, node_x0=b.x0, node_extra_mass=b.extra_mass(n),
                    node_v0=np.zeros((n, 3)), node_w0=np.zeros((n, 3)), parts=parts,
                    sections=sections, materials=materials, hourglass=hourglass, curves=curves,
                    solid_groups=solids, shell_groups=shells, controls=controls,
                    title=deck.title, unsupported=deck.unsupported)
    model.node_sets, model.part_sets, model.segment_sets = b.sets(parts)
    model.spcs = _spcs(b, model)
    model.prescribed = _prescribed(b, model)
    model.part_inertia = _part_inertia(b, model)
    model.contacts = _contacts(b, model)
    model.tied_contacts = tied_contacts(b.of(TiedContact), model, len(model.contacts) + 1)
    model.output = _outputs(b, model)
    build_mechanics(b, model)
    initial_velocities(b, model)  # after the beams and springs: their parts' nodes
    return model


# ---------------------------------------------------------------------------
# Boundary and initial conditions, contacts, output


_node_set = node_set
_no_cid = no_cid


def _spcs(b: _Builder, model: m.Model) -> list[m.NodalSPC]:
    out = []
    for it in b.of(Nodes):
        if it.tc is None and it.rc is None:
            continue
        zero = np.zeros_like(it.ids)
        codes = np.column_stack([zero if it.tc is None else it.tc,
                                 zero if it.rc is None else it.rc])
        sel = np.flatnonzero(codes.any(axis=1))
        bad = sel[((codes[sel] < 0) | (codes[sel] > 7)).any(axis=1)]
        if bad.size:
            r = int(bad[0])
            raise _err(it, f"node {it.ids[r]}: TC/RC must be 0-7", _Rows([it]).locate(r)[1])
        dofs = np.zeros((sel.size, 6), dtype=bool)
        for col in (0, 1):
            for code, axes in _AXES.items():
                rows = np.flatnonzero(codes[sel, col] == code)
                for a in axes:
                    dofs[rows, 3 * col + a] = True
        out.append(m.NodalSPC(b.index(it.ids[sel])[0], dofs, it.source))
    items = b.of(BoundarySpcNode)
    for it in items:
        _no_cid(it, it.cid)
    if items:
        nodes = np.concatenate([b.node_list([it.nid], it, "SPC") for it in items])
        out.append(m.NodalSPC(nodes, np.array([it.dofs() for it in items], dtype=bool),
                              items[0].source))
    for it in b.of(BoundarySpcSet):
        _no_cid(it, it.cid)
        nodes = _node_set(model, it.nsid, it)
        out.append(m.NodalSPC(nodes, np.tile(np.array(it.dofs(), bool), (nodes.size, 1)),
                              it.source))
    return out


def _prescribed(b: _Builder, model: m.Model) -> list[m.PrescribedMotion]:
    out = []
    nodal_pids = {it.pid for it in b.of(ConstrainedNodalRigidBodyKeyword)}
    for it in b.of(PrescribedMotionKeyword):
        if it.dof not in _MOTION_DOFS:
            raise _err(it, f"DOF={it.dof} is not supported (1, 2, 3 translations; 5, 6, 7 "
                       "rotations)")
        if it.vad not in (0, 1, 2):
            raise _err(it, f"VAD={it.vad} is not supported (0 velocity, 1 acceleration, "
                       "2 displacement)")
        if it.lcid not in model.curves:
            raise _err(it, f"prescribed motion refers to curve {it.lcid} which is not defined")
        kw = dict(dof=it.dof, vad=it.vad, lcid=it.lcid, sf=_or(it.sf, 1.0), birth=it.birth,
                  death=_or(it.death, 1.0e28), source=it.source)
        if isinstance(it, PrescribedMotionRigid):
            if it.pid in nodal_pids:  # a nodal rigid body (build.rigid_constraints)
                out.append(m.PrescribedMotion("rigid", pid=it.pid, **kw))
                continue
            if it.pid not in model.parts:
                raise _err(it, f"prescribed motion refers to part {it.pid} which is not defined")
            if model.material_of(it.pid).kind != "rigid":
                raise _err(it, f"part {it.pid} is not rigid (*BOUNDARY_PRESCRIBED_MOTION_RIGID "
                           "needs a *MAT_RIGID part)")
            out.append(m.PrescribedMotion("rigid", pid=it.pid, **kw))
        elif isinstance(it, PrescribedMotionSet):
            out.append(m.PrescribedMotion("nodes", nodes=_node_set(model, it.nsid, it), **kw))
        else:
            out.append(m.PrescribedMotion("nodes", nodes=b.node_list([it.nid], it,
                                                                     "prescribed motion"), **kw))
    return out


def _part_inertia(b: _Builder, model: m.Model) -> dict[int, m.PartInertia]:
    out = {}
    for it in b.of(PartInertia):
        if it.ircs not in (0, 1) or (it.ircs and it.cid):
            raise _err(it, f"IRCS={it.ircs}, CID={it.cid}: give the tensor in global axes "
                       "(IRCS=0) or principal moments about XL..ZLIP (IRCS=1, CID=0)")
        xc = np.array([it.xc, it.yc, it.zc])
        if it.nodeid:
            xc = model.node_x0[b.node_list([it.nodeid], it, "NODEID")[0]].copy()
        inertia = np.array([[it.ixx, it.ixy, it.ixz], [it.ixy, it.iyy, it.iyz],
                            [it.ixz, it.iyz, it.izz]])
        if it.ircs:  # principal moments about local axes (model.rigid_bodies)
            try:
                inertia = local_axes_inertia([it.ixx, it.iyy, it.izz], [it.xl, it.yl, it.zl],
                                             [it.xlip, it.ylip, it.zlip])
            except ValueError as exc:
                raise _err(it, f"IRCS=1: {exc}") from None
        out[it.pid] = m.PartInertia(it.pid, xc, it.tm, inertia, np.array([it.vtx, it.vty, it.vtz]),
                                    np.array([it.vrx, it.vry, it.vrz]), it.source)
    return out


_SURFACE_TYPES = {0: "segment set", 1: "shell element set", 2: "part set", 3: "part",
                  4: "node set", 5: "all", 6: "part set excluded", 7: "branch id"}
_CONTACT_KINDS = {"AUTOMATIC_SURFACE_TO_SURFACE": "surface_to_surface",
                  "AUTOMATIC_NODES_TO_SURFACE": "nodes_to_surface",
                  "AUTOMATIC_SINGLE_SURFACE": "single_surface"}


def _surface(c: Contact, model: m.Model, sid: int, typ: int, name: str,
             main: bool) -> m.SurfaceRef:
    if typ == 5 or (c.type.endswith("SINGLE_SURFACE") and sid == 0):
        return m.SurfaceRef("all")
    ref = None if (typ == 4 and main) else defined_surface(model, sid, typ)
    if ref is not None:
        return ref
    what = _SURFACE_TYPES.get(typ)
    if typ in (0, 2, 3) or (typ == 4 and not main):
        raise _err(c, f"contact refers to {what} {sid} ({name}={typ}) which is not defined")
    raise _err(c, f"{name}={typ}" + (f" ({what})" if what else "") + " is not supported "
               "(0 segment set, 2 part set, 3 part, " + ("" if main else "4 node set, ") +
               "5 all)")


def _contacts(b: _Builder, model: m.Model) -> list[m.ContactDef]:
    out = []
    for k, c in enumerate(b.of(Contact), start=1):
        if c.sboxid or c.mboxid:
            raise _err(c, "SBOXID/MBOXID (contact boxes) are not supported")
        slave = _surface(c, model, c.ssid, c.sstyp, "SSTYP", False)
        master = None if c.type.endswith("SINGLE_SURFACE") else \
            _surface(c, model, c.msid, c.mstyp, "MSTYP", True)
        soft = int(c.soft or 0)
        if soft not in (0, 1, 2):
            raise _err(c, f"SOFT={soft} is not supported (0, 1, 2)")
        out.append(m.ContactDef(
            cid=c.cid if c.cid else k, kind=_CONTACT_KINDS[c.type], slave=slave, master=master,
            fs=c.fs, fd=c.fd, dc=c.dc, vdc=c.vdc, soft=min(soft, 1),
            sofscl=_or(c.sofscl or 0.0, 0.1),
            sfs=_or(c.sfs, 1.0), sfm=_or(c.sfm, 1.0), sst=c.sst, mst=c.mst, title=c.heading,
            source=c.source))
    return out


def _outputs(b: _Builder, model: m.Model) -> m.OutputRequests:
    out = m.OutputRequests()
    for d in b.of(DatabaseAscii):
        if d.name.lower() in OUTPUT_DATABASES:
            out.intervals[d.name.lower()] = d.dt
    for d in b.of(DatabaseBinaryD3plot):
        out.d3plot_dt = d.dt
    for d in b.of(DatabaseBinaryD3dump):
        out.d3dump_cycles = max(int(round(d.cycl)), 0)
    nodes = []
    for h in b.of(DatabaseHistoryNode):
        nodes.append(b.node_list(h.ids, h, "history", h.id_lines))
    for h in b.of(DatabaseHistoryNodeSet):
        for k, sid in enumerate(h.ids.tolist()):
            if sid not in model.node_sets:
                raise _err(h, f"history refers to node set {sid} which is not defined",
                           int(h.id_lines[k]) if h.id_lines is not None else None)
            nodes.append(model.node_sets[sid])
    if nodes:
        out.history_nodes = np.concatenate(nodes).astype(np.int64)
    return out
