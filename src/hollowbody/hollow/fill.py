"""Interior walls of a hollowized part: a cubic grid of shell walls clipped to the part.

The grid lives on a lattice of spacing ``h = cell / elements_per_edge`` in
the grid frame (global axes, or the part's principal axes). The cells are
centred on the part's bounding box; wall planes are the cell faces strictly
inside it (the part's own boundary surface is the outer wall, see
:mod:`hollowbody.hollow.boundary`); the two outer, partial cells of each
axis are divided into steps of about ``h`` that end on the bounding box.
On every wall plane the lattice squares are clipped to the part's volume by
marching squares:

1. every lattice node is classified inside / outside the part (point
   location in the part's tetrahedra; points on the boundary are inside);
2. on every lattice edge whose ends differ, the crossing with the part's
   boundary is found by bisection along the edge;
3. crossings closer than ``snap`` x the edge length to a lattice node are merged into that
   node; the node is moved onto the crossing when that keeps it on all its
   wall planes (a node on one plane always; on an intersection line only
   along the line), so no sliver elements appear and walls stay planar;
4. each lattice square becomes the polygon of its inside corners and edge
   crossings (a quadrilateral, a triangle, or a pentagon / hexagon split
   into a quadrilateral and a triangle / two quadrilaterals).

Crossings are shared by all walls through an edge, lattice nodes by all
walls through them, so walls meeting on an intersection line share nodes
(conforming). Wall nodes that coincide with the part's original boundary
nodes (within ``merge x h``) become those nodes; the other nodes on the
walls' free edges lie on (or within ``snap x h`` of) the boundary surface
and are returned as nodes to tie to it.

Approximations: features of the part thinner than one lattice step between
two lattice nodes are not seen (a wall may span a narrow notch); wall edges
follow the boundary as chords between crossings.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import cKDTree

from hollowbody.hollow.spatial import TetLocator, TriangleSurface

#: Marching-squares tokens: 0-3 corners (counter-clockwise), 4-7 edges (c0c1, c1c2, c2c3, c3c0).
_SADDLE_SPLIT = {5: [[0, 4, 7], [5, 2, 6]], 10: [[4, 1, 5], [6, 3, 7]]}


@dataclass
class WallMesh:
    """Interior walls of one part.

    x_new: (m, 3) mm coordinates of new nodes; conn: (w, 4) node indices in a
    combined space (``< n_orig``: original node index; ``>= n_orig``: new node
    ``n_orig + j``), triangles N4 == N3; axis: (w,) int8 wall normal axis in
    the grid frame; tied: (k,) combined indices of wall nodes to tie to the
    boundary surface, tie_gap: (k,) mm their distance to it; frame: (3, 3)
    grid axes as columns (global coordinates); planes: per grid axis the
    coordinates (mm, along that axis of the grid frame) of the interior wall
    planes; h: lattice step mm; cells: (3,) cells per axis; stats: counts.
    """

    x_new: np.ndarray
    conn: np.ndarray
    axis: np.ndarray
    tied: np.ndarray
    tie_gap: np.ndarray
    frame: np.ndarray
    planes: list
    h: float
    cells: np.ndarray
    stats: dict = field(default_factory=dict)


def grid_frame(x: np.ndarray, inertia: np.ndarray | None) -> np.ndarray:
    """Grid axes (3, 3) as columns: identity, or the principal axes of ``inertia`` (3, 3)
    (ascending moments, right-handed, each axis's largest component positive)."""
    if inertia is None:
        return np.eye(3)
    _, vec = np.linalg.eigh(inertia)
    for k in range(3):
        if vec[np.argmax(np.abs(vec[:, k])), k] < 0.0:
            vec[:, k] = -vec[:, k]
    if np.linalg.det(vec) < 0.0:
        vec[:, 2] = -vec[:, 2]
    return vec


def cell_counts(extent: np.ndarray, cell: float) -> np.ndarray:
    """Cells per axis covering ``extent`` (3,) mm: ceil(extent / cell), at least 1."""
    return np.maximum(np.ceil(extent / cell - 1e-9), 1).astype(np.int64)


def lattice_coordinates(lo: float, hi: float, cells: int, cell: float, k: int
                        ) -> tuple[np.ndarray, np.ndarray]:
    """Lattice coordinates along one axis and the indices of the interior wall planes.

    ``cells`` cells of edge ``cell`` centred on [lo, hi]; interior planes
    every ``cell``, ``k`` steps of ``cell / k`` between them; the two outer
    (partial) cells are divided into steps of about ``cell / k`` that end
    exactly at lo and hi, so flat faces of the part on its bounding box meet
    the lattice.
    """
    h = cell / k
    mid = 0.5 * (lo + hi)
    inner = mid + cell * (np.arange(1, cells) - 0.5 * cells)
    if cells == 1:
        m = max(1, int(round((hi - lo) / h)))
        return np.linspace(lo, hi, m + 1), np.zeros(0, dtype=np.int64)
    parts = []
    w0 = inner[0] - lo
    parts.append(np.linspace(lo, inner[0], max(1, int(round(w0 / h))) + 1)[:-1])
    for j in range(cells - 2):
        parts.append(inner[j] + h * np.arange(k))
    w1 = hi - inner[-1]
    parts.append(np.linspace(inner[-1], hi, max(1, int(round(w1 / h))) + 1))
    c = np.concatenate(parts)
    return c, np.searchsorted(c, inner - 1e-9 * cell)


def fill_walls(x: np.ndarray, tets: np.ndarray, part_nodes: np.ndarray,
               faces: np.ndarray, cell: float, elements_per_edge: int,
               frame: np.ndarray, snap: float = 0.25, merge: float = 0.05) -> WallMesh:
    """Interior walls of one part (see the module docstring).

    x: (n, 3) mm all node coordinates; tets: (t, 4) the part's tetrahedra;
    part_nodes: (p,) node indices of the part; faces: (f, 4) its boundary
    faces (node indices); frame: (3, 3) grid axes as columns.
    """
    k = int(elements_per_edge)
    h = cell / k
    n_orig = x.shape[0]
    locator = TetLocator(x, tets)
    u = x[part_nodes] @ frame
    ulo, uhi = u.min(axis=0), u.max(axis=0)
    cells = cell_counts(uhi - ulo, cell)
    coords, is_plane, planes = [], [], []
    for a in range(3):
        c_a, p_a = lattice_coordinates(float(ulo[a]), float(uhi[a]), int(cells[a]), cell, k)
        coords.append(c_a)
        flag = np.zeros(c_a.size, dtype=bool)
        flag[p_a] = True
        is_plane.append(flag)
        planes.append(c_a[p_a])
    dims = np.array([c.size for c in coords], dtype=np.int64)
    stride = np.array([dims[1] * dims[2], dims[2], 1], dtype=np.int64)

    def ijk(flat: np.ndarray) -> np.ndarray:
        return np.column_stack([flat // stride[0], (flat // stride[1]) % dims[1], flat % dims[2]])

    def position(flat: np.ndarray) -> np.ndarray:
        idx = ijk(flat)
        u_ = np.column_stack([coords[a][idx[:, a]] for a in range(3)])
        return u_ @ frame.T

    def on_plane(flat: np.ndarray) -> np.ndarray:
        idx = ijk(flat)
        return np.column_stack([is_plane[a][idx[:, a]] for a in range(3)])

    # -- wall squares of the interior planes -------------------------------
    quads, qaxis = [], []
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        ub, uc = np.meshgrid(np.arange(dims[b] - 1), np.arange(dims[c] - 1), indexing="ij")
        ub, uc = ub.ravel(), uc.ravel()
        for p in np.flatnonzero(is_plane[a]).tolist():
            base = p * stride[a] + ub * stride[b] + uc * stride[c]
            quads.append(np.column_stack([base, base + stride[b], base + stride[b] + stride[c],
                                          base + stride[c]]))
            qaxis.append(np.full(base.size, a, dtype=np.int8))
    if not quads:
        return _empty(frame, planes, h, cells)
    quads, qaxis = np.vstack(quads), np.concatenate(qaxis)
    lat, inv = np.unique(quads, return_inverse=True)
    status_lat = locator.inside(position(lat))
    status = status_lat[inv.reshape(quads.shape)]
    keep = status.any(axis=1)
    quads, qaxis, status = quads[keep], qaxis[keep], status[keep]

    # -- edges and crossings -------------------------------------------------
    b_ax, c_ax = (qaxis + 1) % 3, (qaxis + 2) % 3
    e_start = np.column_stack([quads[:, 0], quads[:, 1], quads[:, 3], quads[:, 0]])
    e_axis = np.column_stack([b_ax, c_ax, b_ax, c_ax]).astype(np.int64)
    e_diff = np.column_stack([status[:, 0] != status[:, 1], status[:, 1] != status[:, 2],
                              status[:, 2] != status[:, 3], status[:, 3] != status[:, 0]])
    e_id = e_start * 3 + e_axis
    cross_ids = np.unique(e_id[e_diff])
    c_start, c_axis = cross_ids // 3, cross_ids % 3
    c_end = c_start + stride[c_axis]
    start_in = locator.inside(position(c_start))
    n_in = np.where(start_in, c_start, c_end)
    n_out = np.where(start_in, c_end, c_start)
    lo, hi = position(n_in), position(n_out)
    for _ in range(36):
        mid = 0.5 * (lo + hi)
        ins = locator.inside(mid)
        lo[ins], hi[~ins] = mid[ins], mid[~ins]
    xc = 0.5 * (lo + hi)
    p_in = position(n_in)
    t_in = np.linalg.norm(xc - p_in, axis=1) / np.linalg.norm(position(n_out) - p_in, axis=1)

    # -- snapping ------------------------------------------------------------------
    target = np.where(t_in <= snap, n_in, np.where(t_in >= 1.0 - snap, n_out, -1))
    dist = np.minimum(t_in, 1.0 - t_in)
    cand = np.flatnonzero(target >= 0)
    # a node may move along the edge only if the edge lies in all its wall planes
    memb = on_plane(target[cand])
    movable = ~memb[np.arange(cand.size), c_axis[cand]] & (memb.sum(axis=1) < 3)
    mv = cand[movable]
    order = np.lexsort((dist[mv], target[mv]))
    mv = mv[order]
    first = np.ones(mv.size, dtype=bool)
    first[1:] = target[mv][1:] != target[mv][:-1]
    mv = mv[first]
    moved = dict(zip(target[mv].tolist(), xc[mv].tolist()))
    n_lat_total = int(np.prod(dims))
    cross_node = np.where(target >= 0, target, n_lat_total + np.arange(cross_ids.size))
    edge_node = np.full(e_id.shape, -1, dtype=np.int64)
    pos = np.searchsorted(cross_ids, e_id[e_diff])
    edge_node[e_diff] = cross_node[pos]

    # -- polygons ----------------------------------------------------------------
    case = (status * np.array([1, 2, 4, 8])).sum(axis=1)
    full = case == 15
    elems = [quads[full]]
    eaxis = [qaxis[full]]
    cut = np.flatnonzero(~full)
    saddle = cut[(case[cut] == 5) | (case[cut] == 10)]
    centre_in = dict(zip(saddle.tolist(), locator.inside(
        position(quads[saddle].ravel()).reshape(-1, 4, 3).mean(axis=1)
        if saddle.size else np.zeros((0, 3))).tolist()))
    node_xyz = _NodeCoords(position, moved, xc, n_lat_total)
    tri_q: list[list[int]] = []
    tri_axis: list[int] = []
    for q in cut.tolist():
        cs = int(case[q])
        tokens_list = (_SADDLE_SPLIT[cs] if cs in _SADDLE_SPLIT and not centre_in[q]
                       else [_walk(status[q])])
        for tokens in tokens_list:
            ids = [int(quads[q, t]) if t < 4 else int(edge_node[q, t - 4]) for t in tokens]
            poly = _dedupe(ids)
            for el in _split(poly, node_xyz):
                tri_q.append(el)
                tri_axis.append(int(qaxis[q]))
    if tri_q:
        elems.append(np.array(tri_q, dtype=np.int64))
        eaxis.append(np.array(tri_axis, dtype=np.int8))
    conn = np.vstack(elems)
    axis = np.concatenate(eaxis)

    # -- node table, quality filter, boundary-coincident walls ---------------------------
    used, cinv = np.unique(conn, return_inverse=True)
    xyz = node_xyz(used)
    conn = cinv.reshape(conn.shape)
    conn, axis = _drop_bad(conn, axis, xyz, h, snap, locator, frame)
    # -- merge with the part's boundary nodes ---------------------------------------
    bnodes = np.unique(faces)
    tree = cKDTree(x[bnodes])
    d, j = tree.query(xyz, distance_upper_bound=merge * h)
    hit = np.isfinite(d)
    comb = np.where(hit, bnodes[np.minimum(j, bnodes.size - 1)], -1)
    used2 = np.unique(conn)
    new_mask = np.zeros(xyz.shape[0], dtype=bool)
    new_mask[used2] = ~hit[used2]
    new_index = -np.ones(xyz.shape[0], dtype=np.int64)
    new_index[new_mask] = n_orig + np.arange(int(new_mask.sum()))
    comb = np.where(hit, comb, new_index)
    conn = comb[conn]
    conn, axis = _collapse(conn, axis)
    x_new = xyz[new_mask]
    # -- free edges -> tied nodes ------------------------------------------------------
    free = _free_edge_nodes(conn)
    free = free[free >= n_orig]
    surface = TriangleSurface.from_shells(x, faces, size=max(h, 1e-6))
    gap = surface.distance(x_new[free - n_orig], radius=h)
    on = gap <= max(snap, merge) * h * 1.0001 + 1e-9
    stats = {"lattice_nodes": int(lat.size), "crossings": int(cross_ids.size),
             "moved_nodes": len(moved), "merged_nodes": int(hit[used2].sum()),
             "free_edge_nodes": int(free.size), "unattached_free_nodes": int((~on).sum())}
    return WallMesh(x_new=x_new, conn=conn, axis=axis, tied=free[on], tie_gap=gap[on],
                    frame=frame, planes=planes, h=h, cells=cells, stats=stats)


class _NodeCoords:
    """Coordinates of provisional node ids: lattice nodes (moved ones moved) and crossings."""

    def __init__(self, position, moved: dict, xc: np.ndarray, n_lat: int) -> None:
        self.position, self.moved, self.xc, self.n_lat = position, moved, xc, n_lat

    def __call__(self, ids: np.ndarray) -> np.ndarray:
        ids = np.asarray(ids, dtype=np.int64)
        out = np.empty((ids.size, 3))
        lat = ids < self.n_lat
        out[lat] = self.position(ids[lat])
        out[~lat] = self.xc[ids[~lat] - self.n_lat]
        for r in np.flatnonzero(lat):
            m = self.moved.get(int(ids[r]))
            if m is not None:
                out[r] = m
        return out


def _walk(s: np.ndarray) -> list[int]:
    """Marching-squares polygon (tokens) of one square with corner flags s (4,)."""
    out = []
    for i in range(4):
        if s[i]:
            out.append(i)
        if s[i] != s[(i + 1) % 4]:
            out.append(4 + i)
    return out


def _dedupe(ids: list[int]) -> list[int]:
    out = [v for i, v in enumerate(ids) if v != ids[i - 1]] if len(ids) > 1 else list(ids)
    return out if len(set(out)) == len(out) else list(dict.fromkeys(out))


def _quality(pts: np.ndarray) -> float:
    """area / longest side (mm) of a convex polygon pts (m, 3); negative if not convex."""
    m = pts.shape[0]
    d = np.roll(pts, -1, axis=0) - pts  # edges (m, 3)
    c = pts - pts.mean(axis=0)
    n = np.cross(c, np.roll(c, -1, axis=0)).sum(axis=0)
    area2 = float(np.sqrt(n @ n))
    if area2 <= 0.0:
        return -1.0
    turns = np.cross(d, np.roll(d, -1, axis=0)) @ (n / area2)
    if turns.min() < -1e-9 * area2:
        return -1.0
    return 0.5 * area2 / float(np.sqrt((d * d).sum(axis=1).max())) if m else -1.0


def _split(poly: list[int], coords) -> list[list[int]]:
    """Shell elements (node id lists of 4, triangles N4 == N3) of a polygon of 3-6 nodes."""
    m = len(poly)
    if m < 3:
        return []
    if m == 3:
        return [[poly[0], poly[1], poly[2], poly[2]]]
    xyz = coords(np.array(poly))
    if m == 4 and _quality(xyz) > 0.0:
        return [list(poly)]
    best, best_q = None, -np.inf
    if m == 4:
        options = [([0, 1, 2], [0, 2, 3]), ([1, 2, 3], [1, 3, 0])]
    elif m == 5:
        options = [([r, (r + 1) % 5, (r + 2) % 5, (r + 3) % 5], [r, (r + 3) % 5, (r + 4) % 5])
                   for r in range(5)]
    else:
        options = [([r, r + 1, r + 2, r + 3], [r, r + 3, (r + 4) % 6, (r + 5) % 6])
                   for r in range(3)]
    for parts in options:
        q = min(_quality(xyz[list(p)]) for p in parts)
        if q > best_q:
            best, best_q = parts, q
    out = []
    for p in best:  # type: ignore[union-attr]
        ids = [poly[i] for i in p]
        out.append(ids if len(ids) == 4 else ids + [ids[2]])
    return out


def _element_geometry(conn: np.ndarray, xyz: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(area (w,) mm^2, area / longest side (w,) mm) of shells conn (w, 4)."""
    xe = xyz[conn]
    area = 0.5 * np.linalg.norm(np.cross(xe[:, 2] - xe[:, 0], xe[:, 3] - xe[:, 1]), axis=1)
    sides = np.linalg.norm(xe - np.roll(xe, -1, axis=1), axis=2).max(axis=1)
    return area, area / np.maximum(sides, 1e-300)


def _drop_bad(conn: np.ndarray, axis: np.ndarray, xyz: np.ndarray, h: float, snap: float,
              locator: TetLocator, frame: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Drop slivers and walls lying on the part's boundary (one side outside)."""
    _, length = _element_geometry(conn, xyz)
    ok = length > 0.02 * snap * h
    xe = xyz[conn]
    tri = conn[:, 3] == conn[:, 2]
    centre = np.where(tri[:, None], xe[:, :3].mean(axis=1), xe.mean(axis=1))
    normal = frame.T[axis]
    eta = 1e-3 * h
    ok &= locator.inside(centre + eta * normal) & locator.inside(centre - eta * normal)
    return conn[ok], axis[ok]


def _collapse(conn: np.ndarray, axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Elements whose nodes merged: quads with one repeated node -> triangles; fewer than
    3 distinct nodes -> dropped."""
    s = np.sort(conn, axis=1)
    nd = 1 + (s[:, 1:] != s[:, :-1]).sum(axis=1)
    out = conn.copy()
    quad = conn[:, 3] != conn[:, 2]
    fix = np.flatnonzero((nd == 3) & quad)
    for r in fix:
        row = _dedupe(conn[r].tolist())
        out[r] = row + [row[2]] if len(row) == 3 else out[r]
    keep = nd >= 3
    return out[keep], axis[keep]


def _free_edge_nodes(conn: np.ndarray) -> np.ndarray:
    """Nodes on edges used by exactly one element (sorted unique)."""
    nxt = np.roll(conn, -1, axis=1)
    e = np.stack([conn, nxt], axis=2).reshape(-1, 2)
    e = e[e[:, 0] != e[:, 1]]
    e = np.sort(e, axis=1)
    u, cnt = np.unique(e, axis=0, return_counts=True)
    return np.unique(u[cnt == 1])


def _empty(frame: np.ndarray, planes: list, h: float, cells: np.ndarray) -> WallMesh:
    z = np.zeros(0, dtype=np.int64)
    return WallMesh(np.zeros((0, 3)), np.zeros((0, 4), np.int64), np.zeros(0, np.int8), z,
                    np.zeros(0), frame, planes, h, cells, {})
