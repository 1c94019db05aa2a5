"""Meshes of the block test's rigid impactor surfaces (the block itself:
:func:`hollowbody.mesh.standing_block`).

All functions return plain arrays: node coordinates (n, 3) float64 mm and
connectivities as 0-based indices into them (LS-DYNA node order), so the
caller assigns ids.
"""

from __future__ import annotations

import numpy as np


def _disc_ogrid(radius: float, n: int, rings: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Quad mesh of a disc (z = 0) as an O-grid.

    A square core of n x n quads, then ``rings`` rings mapping the square's
    boundary to the circle. Returns (nodes (k, 3), quads (q, 4), rim (4n,)
    indices of the circle's nodes in counter-clockwise order).
    """
    a = 0.5 * radius  # half side of the core square
    g = np.linspace(-a, a, n + 1)
    cy, cx = np.meshgrid(g, g, indexing="ij")
    nodes = [np.column_stack([cx.ravel(), cy.ravel(), np.zeros(cx.size)])]
    quads = []
    for j in range(n):
        for i in range(n):
            p = j * (n + 1) + i
            quads.append([p, p + 1, p + n + 2, p + n + 1])
    # square boundary loop, counter-clockwise, 4n nodes
    loop = ([(0, i) for i in range(n)] + [(j, n) for j in range(n)]
            + [(n, i) for i in range(n, 0, -1)] + [(j, 0) for j in range(n, 0, -1)])
    inner = np.array([j * (n + 1) + i for j, i in loop])
    sq = nodes[0][inner, :2]
    ang = np.arctan2(sq[:, 1], sq[:, 0])
    circ = radius * np.column_stack([np.cos(ang), np.sin(ang)])
    count = nodes[0].shape[0]
    prev = inner
    for r in range(1, rings + 1):
        s = r / rings
        pts = (1.0 - s) * sq + s * circ
        idx = np.arange(count, count + pts.shape[0])
        nodes.append(np.column_stack([pts, np.zeros(pts.shape[0])]))
        count += pts.shape[0]
        m = len(prev)
        for q in range(m):
            quads.append([prev[q], idx[q], idx[(q + 1) % m], prev[(q + 1) % m]])
        prev = idx
    return np.vstack(nodes), np.array(quads, dtype=np.int64), prev


def cylinder_impactor_mesh(diameter: float = 90.0, edge_radius: float = 5.0, height: float = 20.0,
                           h: float = 4.0) -> tuple[np.ndarray, np.ndarray]:
    """Surface of a flat-faced cylinder whose face edge is rounded.

    The face lies in z = 0 (its flat part has radius ``diameter/2 -
    edge_radius``), the rounded edge is a quarter torus of radius
    ``edge_radius`` and the side wall rises to z = ``height``. Normals point
    out of the body (-z on the face). Element size about ``h`` mm. Returns
    (nodes (k, 3) mm, quads (q, 4) int64).
    """
    r_out = 0.5 * diameter
    r_flat = r_out - edge_radius
    if r_flat <= 0.0:
        raise ValueError("edge radius must be smaller than the impactor radius")
    n = max(2, int(np.ceil(np.pi * r_flat / 2.0 / h / 2.0)) * 2)  # core divisions
    rings = max(2, int(np.ceil((r_flat - 0.5 * r_flat) / h)))
    nodes, quads, rim = _disc_ogrid(r_flat, n, rings)
    ang = np.arctan2(nodes[rim, 1], nodes[rim, 0])
    k_arc = max(2, int(np.ceil(0.5 * np.pi * edge_radius / h)))
    k_side = max(1, int(np.ceil((height - edge_radius) / h))) if height > edge_radius else 0
    profile = [(r_flat + edge_radius * np.sin(t), edge_radius * (1.0 - np.cos(t)))
               for t in np.linspace(0.0, 0.5 * np.pi, k_arc + 1)[1:]]
    profile += [(r_out, edge_radius + (height - edge_radius) * s)
                for s in np.linspace(0.0, 1.0, k_side + 1)[1:]]
    all_nodes = [nodes]
    count = nodes.shape[0]
    prev = rim
    quads = [quads]
    m = rim.size
    for rad, z in profile:
        pts = np.column_stack([rad * np.cos(ang), rad * np.sin(ang), np.full(m, z)])
        idx = np.arange(count, count + m)
        all_nodes.append(pts)
        count += m
        quads.append(np.array([[prev[q], idx[q], idx[(q + 1) % m], prev[(q + 1) % m]]
                               for q in range(m)], dtype=np.int64))
        prev = idx
    quads_all = np.vstack(quads)
    # the O-grid is counter-clockwise seen from +z: normal +z; flip to point out (-z)
    quads_all = quads_all[:, ::-1].copy()
    return np.vstack(all_nodes), quads_all


def sphere_impactor_mesh(diameter: float = 90.0, h: float = 4.0) -> tuple[np.ndarray, np.ndarray]:
    """Closed quad surface of a sphere (cube projected on the sphere), lowest point at z = 0.

    Normals point outwards. Returns (nodes (k, 3) mm, quads (q, 4) int64).
    """
    r = 0.5 * diameter
    n = max(2, int(np.ceil(0.5 * np.pi * r / h)))
    g = np.linspace(-1.0, 1.0, n + 1)
    pts: dict[tuple[int, int, int], int] = {}
    coords: list[np.ndarray] = []
    quads = []

    def node(p: np.ndarray) -> int:
        key = tuple(np.round(p * n).astype(int))
        if key not in pts:
            pts[key] = len(coords)
            coords.append(p)
        return pts[key]

    for axis in range(3):
        for sign in (-1.0, 1.0):
            u_ax, v_ax = [a for a in range(3) if a != axis]
            for j in range(n):
                for i in range(n):
                    ids = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[axis] = sign
                        p[u_ax] = g[i + di]
                        p[v_ax] = g[j + dj]
                        ids.append(node(p))
                    # orient outwards: (u x v) . axis * sign must be > 0
                    e_u, e_v = np.eye(3)[u_ax], np.eye(3)[v_ax]
                    if np.cross(e_u, e_v)[axis] * sign < 0:
                        ids = ids[::-1]
                    quads.append(ids)
    cube = np.array(coords)
    # equal-angle-ish projection of the cube onto the sphere
    sph = cube / np.linalg.norm(cube, axis=1)[:, None] * r
    sph[:, 2] += r
    return sph, np.array(quads, dtype=np.int64)
