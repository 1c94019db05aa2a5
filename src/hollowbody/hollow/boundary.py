"""Geometry of one solid part: its tetrahedra, its boundary surface, its exact mass properties.

Solids are LS-DYNA hexahedra in the degenerate-hexahedron form (wedges
``N1 N2 N3 N4 N5 N5 N6 N6``, pyramids ``N1..N4 N5 N5 N5 N5``, tetrahedra
``N1 N2 N3 N4 N4 N4 N4 N4``). The boundary surface is every element face
used by exactly one element *of the part*: faces the part shares with other
parts (bones, organs, skin) are boundary too. Faces are oriented outward.
"""

from __future__ import annotations

import numpy as np

from hollowbody.model.mass import MassProperties

#: Faces of the hexahedron (0-based local nodes, LS-DYNA order).
HEX_FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
                      [3, 0, 4, 7]])
#: The hexahedron as 6 tetrahedra around the diagonal 0-6 (degenerate ones add nothing).
HEX_TETS = np.array([[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6],
                     [0, 5, 1, 6]])
#: Faces of a tetrahedron given by its 4 distinct nodes.
TET_FACES = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])


def distinct_sorted(conn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows sorted with repeated nodes pushed to the end: (sorted (e, 8), counts (e,))."""
    s = np.sort(conn, axis=1)
    new = np.ones_like(s, dtype=bool)
    new[:, 1:] = s[:, 1:] != s[:, :-1]
    counts = new.sum(axis=1)
    out = np.where(new, s, np.iinfo(np.int64).max)
    return np.sort(out, axis=1), counts


def solid_tets(conn: np.ndarray, owner: bool = False):
    """Tetrahedra (t, 4) node indices of the solids conn (e, 8); repeated-node tets dropped.

    Tetrahedra of the split keep the hexahedron's orientation (positive
    volume for a valid element). ``owner=True`` also returns the element row
    of each tetrahedron (t,).
    """
    t = conn[:, HEX_TETS].reshape(-1, 4)
    s = np.sort(t, axis=1)
    ok = (s[:, 1:] != s[:, :-1]).all(axis=1)
    if owner:
        return t[ok], np.repeat(np.arange(conn.shape[0]), len(HEX_TETS))[ok]
    return t[ok]


def tet_properties(x: np.ndarray, tets: np.ndarray, rho: float | np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass (t,) kg, centroid (t, 3) mm and second moment about the origin (t, 3, 3) kg mm^2
    of uniform tetrahedra (signed volumes, so the split of a hexahedron is exact)."""
    v = x[tets]  # (t, 4, 3)
    vol = np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                    v[:, 3] - v[:, 0]) / 6.0
    m = rho * vol
    s = v.sum(axis=1)
    second = (np.einsum("tai,taj->tij", v, v) + np.einsum("ti,tj->tij", s, s)) / 20.0
    return m, s / 4.0, m[:, None, None] * second


def solid_mass_properties(x: np.ndarray, conn: np.ndarray, rho: float) -> MassProperties:
    """Exact mass properties of uniform solids (continuous body, not lumped).

    x (n, 3) mm; conn (e, 8) node indices; rho kg/mm^3 (inverted elements count
    with their absolute volume). Returns mass kg,
    centre (3,) mm and inertia (3, 3) kg mm^2 about the centre.
    """
    tets, own = solid_tets(conn, owner=True)
    m, c, second = tet_properties(x, tets, rho)
    # inverted elements count with their absolute volume (as the solver's lumped masses)
    vol = np.zeros(conn.shape[0])
    np.add.at(vol, own, m)
    sign = np.where(vol[own] < 0.0, -1.0, 1.0)
    m, second = m * sign, second * sign[:, None, None]
    total = float(m.sum())
    if total <= 0.0:
        return MassProperties(0.0, np.zeros(3), np.zeros((3, 3)))
    xc = (m[:, None] * c).sum(axis=0) / total
    s = second.sum(axis=0) - total * np.outer(xc, xc)
    inertia = np.eye(3) * np.trace(s) - s
    return MassProperties(total, xc, inertia)


def element_faces(conn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """All faces of the solids: (faces (f, 4) node indices with triangles N4 == N3,
    owner (f,) element row). Collapsed faces are dropped; tetrahedra give their 4
    triangles (the degenerate-hexahedron face N1 N2 N3 N4 is not a tetrahedron face)."""
    e = conn.shape[0]
    faces = conn[:, HEX_FACES].reshape(-1, 4)
    owner = np.repeat(np.arange(e), 6)
    _, counts = distinct_sorted(conn)
    tet_rows = np.flatnonzero(counts == 4)
    keep_hex = np.repeat(counts != 4, 6)
    faces, owner = faces[keep_hex], owner[keep_hex]
    # cyclic compression of repeated nodes
    new = faces != np.roll(faces, 1, axis=1)
    nd = new.sum(axis=1)
    s = np.sort(faces, axis=1)
    ndist = 1 + (s[:, 1:] != s[:, :-1]).sum(axis=1)
    quad = (nd == 4) & (ndist == 4)
    tri = (nd == 3) & (ndist == 3)
    tri_nodes = faces[tri][new[tri]].reshape(-1, 3)
    out = [faces[quad], np.column_stack([tri_nodes, tri_nodes[:, 2]])]
    owners = [owner[quad], owner[tri]]
    if tet_rows.size:
        four = first_distinct(conn[tet_rows], 4)
        tf = four[:, TET_FACES].reshape(-1, 3)
        out.append(np.column_stack([tf, tf[:, 2]]))
        owners.append(np.repeat(tet_rows, 4))
    return np.vstack(out).astype(np.int64), np.concatenate(owners)


def first_distinct(rows: np.ndarray, k: int) -> np.ndarray:
    """The distinct nodes of each row (e, m) in row order -> (e, k); every row must have k."""
    eq = rows[:, :, None] == rows[:, None, :]
    first = ~np.tril(eq, -1).any(axis=2)
    return rows[first].reshape(-1, k)


def boundary_faces(x: np.ndarray, conn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Faces used by exactly one solid of ``conn`` (e, 8), oriented outward.

    Returns (faces (f, 4) node indices, triangles N4 == N3; owner (f,) element row).
    Outward: the face normal points away from the owning element's centroid.
    """
    faces, owner = element_faces(conn)
    key = faces.copy()
    key[:, 3] = np.where(faces[:, 3] == faces[:, 2], -1, faces[:, 3])  # triangles: N4 -> -1
    key = np.sort(key, axis=1)
    _, inv, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    single = counts[inv.reshape(-1)] == 1
    faces, owner = faces[single], owner[single]
    xf = x[faces]
    normal = np.cross(xf[:, 2] - xf[:, 0], xf[:, 3] - xf[:, 1])
    tri = faces[:, 3] == faces[:, 2]
    normal[tri] = np.cross(xf[tri, 1] - xf[tri, 0], xf[tri, 2] - xf[tri, 0])
    centre = np.where(tri[:, None], xf[:, :3].mean(axis=1), xf.mean(axis=1))
    ds, cnt = distinct_sorted(conn[owner])
    valid = ds < np.iinfo(np.int64).max
    xe = x[np.where(valid, ds, 0)]
    elem_c = (xe * valid[:, :, None]).sum(axis=1) / cnt[:, None]
    flip = np.einsum("ij,ij->i", normal, centre - elem_c) < 0.0
    f = faces.copy()
    fq = flip & ~tri
    f[fq] = faces[fq][:, [0, 3, 2, 1]]
    ft = flip & tri
    f[ft] = faces[ft][:, [0, 2, 1, 1]]
    return f, owner
