"""Contact surfaces: segments (solid faces, shells) and the nodes on them.

A contact *segment* is a 4-node facet, triangles stored with ``N4 == N3``:

* the exterior faces of solid elements (faces used by exactly one element of
  the solids taken together), oriented with the outward normal, **one-sided**,
  contact thickness 0;
* shell elements, **two-sided** (the contact surface lies at +-t/2 around the
  mid-surface), contact thickness = the shell thickness (mean of the nodal
  thicknesses) or the SST / MST override of the contact.

Degenerate solids follow the LS-DYNA storage of :class:`~hollowbody.model.model.SolidGroup`:
a hexahedron face with 3 distinct nodes is a triangle, one with fewer than 3 is
dropped; an element with 4 distinct nodes is a tetrahedron and gets its 4
triangles explicitly (the ``N1 N2 N3 N4 N4 N4 N4 N4`` form would otherwise give
a folded quadrilateral). Faces shared by two solids of the same surface are
interior, also across parts.

All functions here are vectorised numpy, used at set-up only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.errors import UserInputError
from hollowbody.model.beams import section_constants
from hollowbody.model.model import Model, SurfaceRef

#: Faces of the 8-node hexahedron (LS-DYNA node order), outward for a
#: positive-volume element.
HEX_FACES = np.array([[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4],
                      [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]], dtype=np.int64)
#: Faces of a tetrahedron given by its 4 distinct nodes (orientation fixed later).
TET_FACES = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], dtype=np.int64)

SEG_SOLID = 0  #: segment is a face of a solid element (one-sided)
SEG_SHELL = 1  #: segment is a shell element (two-sided)
SEG_FREE = 2  #: user segment with no element under it (two-sided, thickness 0)


@dataclass
class Surface:
    """One side of a contact.

    seg: (s, 4) int32 global node indices, triangles with N4 == N3.
    seg_kind: (s,) int8 :data:`SEG_SOLID`, :data:`SEG_SHELL` or :data:`SEG_FREE`.
    seg_thick: (s,) float64 mm contact thickness (shells; 0 for solids).
    seg_group: (s,) int32 index into ``model.solid_groups`` (solid faces) or
    ``model.shell_groups`` (shells); -1 when there is no element.
    seg_elem: (s,) int64 element index inside that group (-1: none).
    nodes: (m,) int64 sorted unique global node indices (the candidates for
    penetrating the other side).
    node_thick: (m,) float64 mm contact thickness of each node (largest
    thickness of the shell segments around it; 0 on solids).
    """

    seg: np.ndarray
    seg_kind: np.ndarray
    seg_thick: np.ndarray
    seg_group: np.ndarray
    seg_elem: np.ndarray
    nodes: np.ndarray
    node_thick: np.ndarray

    @property
    def n_segments(self) -> int:
        return int(self.seg.shape[0])


# ---------------------------------------------------------------------------
# Geometry helpers


def segment_normals(seg: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals and areas of segments.

    seg: (s, 4) int node indices (N4 == N3 for triangles); x: (n, 3) mm.
    Returns normals (s, 3) (cross product of the diagonals, which for a
    triangle is the edge cross product) and areas (s,) mm^2.
    """
    xs = x[seg]
    c = np.cross(xs[:, 2] - xs[:, 0], xs[:, 3] - xs[:, 1])
    a2 = np.linalg.norm(c, axis=1)
    n = c / np.where(a2 > 0.0, a2, 1.0)[:, None]
    return n, 0.5 * a2


def segment_centroids(seg: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Centroids (s, 3) mm (mean of the distinct corner nodes)."""
    xs = x[seg]
    tri = seg[:, 3] == seg[:, 2]
    c = xs.mean(axis=1)
    c[tri] = xs[tri, :3].mean(axis=1)
    return c


def segment_max_diagonal(seg: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Longest diagonal (quads) or longest edge (triangles), (s,) mm."""
    xs = x[seg]
    d1 = np.linalg.norm(xs[:, 2] - xs[:, 0], axis=1)
    d2 = np.linalg.norm(xs[:, 3] - xs[:, 1], axis=1)
    e = [np.linalg.norm(xs[:, (i + 1) % 4] - xs[:, i], axis=1) for i in range(4)]
    tri = seg[:, 3] == seg[:, 2]
    out = np.maximum(d1, d2)
    out[tri] = np.maximum(np.maximum(e[0], e[1]), np.linalg.norm(xs[:, 0] - xs[:, 2], axis=1))[tri]
    return out


# ---------------------------------------------------------------------------
# Solid exterior faces


def _dedupe_cyclic(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Remove cyclically repeated nodes of (f, 4) faces.

    Returns (faces (f, 4) with triangles as a b c c, ndistinct (f,)).
    """
    keep = faces != np.roll(faces, 1, axis=1)
    nd = keep.sum(axis=1)
    # all four equal: keep is all False -> 1 distinct node
    nd[nd == 0] = 1
    out = faces.copy()
    tri = nd == 3
    if np.any(tri):
        ft = faces[tri]
        kt = keep[tri]
        # order of kept entries, stable
        order = np.argsort(~kt, axis=1, kind="stable")[:, :3]
        t3 = np.take_along_axis(ft, order, axis=1)
        out[tri] = np.column_stack([t3, t3[:, 2]])
    return out, nd


def solid_faces(conn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """All faces of solid elements, degenerate ones reduced.

    conn: (e, 8) int node indices (LS-DYNA degenerate-hexahedron storage).
    Returns faces (f, 4) int64 (triangles a b c c; faces with < 3 distinct
    nodes dropped) and elem (f,) int64 owning element. Orientation is the
    hexahedron's (outward for positive volume); see :func:`solid_exterior_faces`.
    """
    conn = np.asarray(conn, dtype=np.int64)
    e = conn.shape[0]
    if e == 0:
        return np.zeros((0, 4), np.int64), np.zeros(0, np.int64)
    s = np.sort(conn, axis=1)
    ndist = 1 + np.count_nonzero(np.diff(s, axis=1), axis=1)
    is_tet = ndist == 4
    faces_list = []
    elems_list = []
    other = np.nonzero(~is_tet)[0]
    if other.size:
        f = conn[other][:, HEX_FACES].reshape(-1, 4)
        el = np.repeat(other, 6)
        f, nd = _dedupe_cyclic(f)
        ok = nd >= 3
        faces_list.append(f[ok])
        elems_list.append(el[ok])
    tets = np.nonzero(is_tet)[0]
    if tets.size:
        ct = conn[tets]
        # distinct nodes in order of first appearance
        first = np.ones_like(ct, dtype=bool)
        for j in range(1, 8):
            first[:, j] = np.all(ct[:, j:j + 1] != ct[:, :j], axis=1)
        d4 = ct[first].reshape(-1, 4)
        f = d4[:, TET_FACES].reshape(-1, 3)
        faces_list.append(np.column_stack([f, f[:, 2]]))
        elems_list.append(np.repeat(tets, 4))
    return np.concatenate(faces_list), np.concatenate(elems_list)


def _orient_outward(faces: np.ndarray, elem: np.ndarray, conn: np.ndarray,
                    x: np.ndarray) -> np.ndarray:
    """Flip faces whose normal points into their element (in place copy)."""
    n, _ = segment_normals(faces, x)
    xc = x[conn[elem]].mean(axis=1)
    fc = segment_centroids(faces, x)
    inward = np.einsum("ij,ij->i", n, fc - xc) < 0.0
    out = faces.copy()
    tri = out[:, 3] == out[:, 2]
    qi = inward & ~tri
    ti = inward & tri
    out[qi] = out[qi][:, [0, 3, 2, 1]]
    out[ti] = out[ti][:, [0, 2, 1, 1]]
    return out


def solid_exterior_faces(conns: list[np.ndarray], x: np.ndarray
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exterior faces of a set of solid groups, oriented outward.

    conns: list of (e_g, 8) int connectivities (the groups taken together:
    a face shared by elements of two groups is interior); x: (n, 3) mm.
    Returns faces (f, 4) int32 (triangles a b c c), group (f,) int32 index
    into ``conns`` and elem (f,) int64 element index inside that group.
    """
    fl, gl, el = [], [], []
    for gi, conn in enumerate(conns):
        f, e = solid_faces(conn)
        if f.shape[0] == 0:
            continue
        f = _orient_outward(f, e, np.asarray(conn, dtype=np.int64), x)
        fl.append(f)
        gl.append(np.full(f.shape[0], gi, np.int32))
        el.append(e)
    if not fl:
        return np.zeros((0, 4), np.int32), np.zeros(0, np.int32), np.zeros(0, np.int64)
    faces = np.concatenate(fl)
    grp = np.concatenate(gl)
    elem = np.concatenate(el)
    key = np.sort(faces, axis=1)
    tri = faces[:, 3] == faces[:, 2]
    key[tri] = np.column_stack([np.full(tri.sum(), -1), np.sort(faces[tri, :3], axis=1)])
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    ext = cnt[inv.ravel()] == 1
    return faces[ext].astype(np.int32), grp[ext], elem[ext]


# ---------------------------------------------------------------------------
# Surfaces from a model


def _node_thickness(nodes: np.ndarray, seg: np.ndarray, seg_thick: np.ndarray,
                    n_total: int) -> np.ndarray:
    """Largest segment thickness around each node, (m,) mm."""
    t = np.zeros(n_total)
    if seg.shape[0]:
        np.maximum.at(t, seg.ravel(), np.repeat(seg_thick, 4))
    return t[nodes]


def _parts_surface(model: Model, pids: set[int], shell_thick_override: float,
                   x0: np.ndarray | None = None) -> Surface:
    sgroups = [i for i, g in enumerate(model.solid_groups) if g.pid in pids]
    hgroups = [i for i, g in enumerate(model.shell_groups) if g.pid in pids]
    faces, fg, fe = solid_exterior_faces([model.solid_groups[i].conn for i in sgroups],
                                         model.node_x0 if x0 is None else x0)
    fg = np.array([sgroups[i] for i in fg], dtype=np.int32) if fg.size else fg
    segs = [faces]
    kind = [np.full(faces.shape[0], SEG_SOLID, np.int8)]
    thick = [np.zeros(faces.shape[0])]
    grp = [fg]
    elem = [fe]
    for gi in hgroups:
        g = model.shell_groups[gi]
        c = np.asarray(g.conn, dtype=np.int32)
        tri = c[:, 3] == c[:, 2]
        t = np.where(tri, g.thickness[:, :3].mean(axis=1), g.thickness.mean(axis=1))
        if shell_thick_override > 0.0:
            t = np.full(c.shape[0], shell_thick_override)
        segs.append(c)
        kind.append(np.full(c.shape[0], SEG_SHELL, np.int8))
        thick.append(t.astype(np.float64))
        grp.append(np.full(c.shape[0], gi, np.int32))
        elem.append(np.arange(c.shape[0], dtype=np.int64))
    seg = np.concatenate(segs).astype(np.int32)
    st = np.concatenate(thick)
    nodes = np.unique(seg.ravel()).astype(np.int64)
    node_thick = _node_thickness(nodes, seg, st, model.n_nodes)
    beam_nodes, beam_thick = beam_contact_nodes(model, pids)
    if beam_nodes.size:  # beams: their nodes only, with the section's thickness
        t = np.zeros(model.n_nodes)
        t[nodes] = node_thick
        np.maximum.at(t, beam_nodes, beam_thick)
        nodes = np.union1d(nodes, beam_nodes).astype(np.int64)
        node_thick = t[nodes]
    return Surface(seg=seg, seg_kind=np.concatenate(kind), seg_thick=st,
                   seg_group=np.concatenate(grp).astype(np.int32),
                   seg_elem=np.concatenate(elem).astype(np.int64), nodes=nodes,
                   node_thick=node_thick)


def beam_contact_nodes(model: Model, pids: set[int]) -> tuple[np.ndarray, np.ndarray]:
    """Nodes (k,) of the beams of parts ``pids`` and their contact thickness (k,) mm.

    A beam takes part in a contact through its two nodes (N1, N2; no segment),
    with the diameter of its section as contact thickness, as LS-DYNA's
    automatic contacts treat beams: a tube's outer diameter TS, else the
    diameter of the circle of the section's area, sqrt(4 A / pi) (SST / MST apply
    to shells only, as in LS-DYNA). A node on several beams takes the largest.
    """
    ids, thick = [], []
    for g in model.beam_groups:
        if g.pid not in pids or g.conn.shape[0] == 0:
            continue
        sec = model.sections[model.parts[g.pid].secid]
        p = sec.params
        if sec.elform == 1 and int(p.get("CST", 0)) == 1:
            d = 0.5 * (p["TS1"] + p["TS2"])
        else:
            d = float(np.sqrt(4.0 * section_constants(sec.elform, p)[0] / np.pi))
        n = np.asarray(g.conn[:, :2], dtype=np.int64).ravel()
        ids.append(n)
        thick.append(np.full(n.size, d))
    if not ids:
        return np.zeros(0, np.int64), np.zeros(0)
    return np.concatenate(ids), np.concatenate(thick)


def model_surface(model: Model, shell_thick_override: float = 0.0,
                  x0: np.ndarray | None = None) -> Surface:
    """Surface of every part of the model (exterior solid faces + all shells); x0 (n, 3)
    mm the initial coordinates that orient the solid faces (None: ``model.node_x0``)."""
    return _parts_surface(model, set(model.parts) | {g.pid for g in model.solid_groups}
                          | {g.pid for g in model.shell_groups}, shell_thick_override, x0)


def _match_segments(given: np.ndarray, ref: Surface) -> np.ndarray:
    """Index into ref.seg of each given segment (same node set), -1 if none."""
    def keys(s: np.ndarray) -> np.ndarray:
        k = np.sort(s, axis=1).astype(np.int64)
        tri = s[:, 3] == s[:, 2]
        k[tri] = np.column_stack([np.full(tri.sum(), -1), np.sort(s[tri, :3], axis=1)])
        return k
    if ref.seg.shape[0] == 0 or given.shape[0] == 0:
        return np.full(given.shape[0], -1, np.int64)
    kr, kg = keys(ref.seg), keys(given)
    allk = np.concatenate([kr, kg])
    _, inv = np.unique(allk, axis=0, return_inverse=True)
    inv = inv.ravel()
    lookup = np.full(inv.max() + 1, -1, np.int64)
    # prefer the first reference segment of a key
    lookup[inv[:kr.shape[0]][::-1]] = np.arange(kr.shape[0])[::-1]
    return lookup[inv[kr.shape[0]:]]


def build_surface(ref: SurfaceRef, model: Model, shell_thick_override: float = 0.0,
                  model_surf: Surface | None = None, x0: np.ndarray | None = None) -> Surface:
    """Build the contact surface of one side of a contact.

    ref.kind ``"parts"`` / ``"all"``: exterior faces of the parts' solids and
    their shells; ``"segments"``: the given segments, matched to the model's
    solid faces / shells for orientation, thickness and stiffness (unmatched
    segments are kept as given, two-sided, thickness 0); ``"nodes"``: no
    segments, the node set only (thickness from shells through the node).
    ``shell_thick_override`` (mm, SST / MST; 0 = use the shell thickness)
    applies to shell segments and shell nodes only, as in LS-DYNA.
    ``model_surf`` (optional) is a cached :func:`model_surface`; ``x0`` (n, 3) mm
    the initial coordinates that orient solid faces outward (None:
    ``model.node_x0``; the run's set-up passes the tied contacts' coordinates).
    """
    kind = ref.kind
    if kind in ("parts", "all"):
        pids = set(ref.pids) if kind == "parts" else (
            set(model.parts) | {g.pid for g in model.solid_groups}
            | {g.pid for g in model.shell_groups})
        missing = [p for p in pids if p not in model.parts
                   and not any(g.pid == p for g in model.solid_groups + model.shell_groups)]
        if missing:
            raise UserInputError(f"contact surface refers to unknown part(s) {sorted(missing)}")
        return _parts_surface(model, pids, shell_thick_override, x0)
    ms = model_surf if model_surf is not None else model_surface(model, shell_thick_override,
                                                                 x0)
    if kind == "nodes":
        nodes = np.unique(np.asarray(ref.nodes if ref.nodes is not None else [],
                                     dtype=np.int64))
        nt = _node_thickness(nodes, ms.seg[ms.seg_kind == SEG_SHELL],
                             ms.seg_thick[ms.seg_kind == SEG_SHELL], model.n_nodes)
        if shell_thick_override > 0.0:
            nt = np.where(nt > 0.0, shell_thick_override, 0.0)
        z = np.zeros(0)
        return Surface(seg=np.zeros((0, 4), np.int32), seg_kind=z.astype(np.int8),
                       seg_thick=z, seg_group=z.astype(np.int32), seg_elem=z.astype(np.int64),
                       nodes=nodes, node_thick=nt)
    if kind == "segments":
        given = np.asarray(ref.segments, dtype=np.int32).reshape(-1, 4)
        idx = _match_segments(given, ms)
        hit = idx >= 0
        seg = given.copy()
        seg[hit] = ms.seg[idx[hit]]  # model orientation (outward for solids)
        skind = np.full(given.shape[0], SEG_FREE, np.int8)
        skind[hit] = ms.seg_kind[idx[hit]]
        st = np.zeros(given.shape[0])
        st[hit] = ms.seg_thick[idx[hit]]
        if shell_thick_override > 0.0:
            st[skind == SEG_SHELL] = shell_thick_override
        grp = np.full(given.shape[0], -1, np.int32)
        grp[hit] = ms.seg_group[idx[hit]]
        el = np.full(given.shape[0], -1, np.int64)
        el[hit] = ms.seg_elem[idx[hit]]
        nodes = np.unique(seg.ravel()).astype(np.int64)
        return Surface(seg=seg, seg_kind=skind, seg_thick=st, seg_group=grp, seg_elem=el,
                       nodes=nodes, node_thick=_node_thickness(nodes, seg, st, model.n_nodes))
    raise UserInputError(f"unknown contact surface kind {kind!r}")
