"""A rigid cylindrical impactor placed against a body's surface.

- :func:`cylinder_mesh`: a shell tube (quads) about an axis;
- :func:`surface_of`: the contact surface of parts of a built model (exterior
  faces of their solids and their shells, with each segment's contact
  thickness), as the contact sees it;
- :func:`ray_hit`: where a ray from inside a limb leaves its surface;
- :func:`first_contact_travel`: how far a cylinder moving along a direction
  travels before its face touches the surface (the surface sampled on a grid
  finer than 0.5 mm, each point offset by half its segment's contact
  thickness, as a two-sided shell contact does).

Units mm. The cylinder is infinite along its axis for the travel: callers make
it longer than the body it strikes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.hollow.spatial import quads_to_triangles
from hollowbody.model.model import Model, SurfaceRef

#: Largest spacing (mm) of the sample points on a surface segment.
SAMPLE_STEP = 0.5


@dataclass
class Surface:
    """Segments (s, 4) of node indices (triangles: N4 == N3), contact thickness (s,) mm
    and the initial coordinates (n, 3) mm of the model they index."""

    seg: np.ndarray
    thick: np.ndarray
    x: np.ndarray


def surface_of(model: Model, pids: list[int]) -> Surface:
    """The contact surface of parts ``pids`` of ``model`` (solid faces: thickness 0)."""
    from hollowbody.contact.surface import build_surface

    s = build_surface(SurfaceRef("parts", pids=list(pids)), model)
    return Surface(np.asarray(s.seg, dtype=np.int64), np.asarray(s.seg_thick, float),
                   np.asarray(model.node_x0, float))


def frame(direction: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """(3, 3) rows: the cylinder's axis, the travel direction, and their cross product
    (unit; ``axis`` is made normal to ``direction``); ValueError when parallel."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    a = np.asarray(axis, float) - float(np.dot(axis, d)) * d
    if np.linalg.norm(a) < 1e-6 * np.linalg.norm(axis):
        raise ValueError("the impactor axis is parallel to the travel direction")
    a = a / np.linalg.norm(a)
    return np.vstack([a, d, np.cross(a, d)])


def cylinder_mesh(centre: np.ndarray, axis: np.ndarray, radius: float, length: float,
                  n_around: int = 36, size: float = 10.0) -> tuple[np.ndarray, np.ndarray]:
    """Shell tube of mid-surface ``radius`` and ``length`` centred on ``centre`` about the
    unit ``axis``: (nodes (n, 3) mm, quads (q, 4) 0-based), about ``size`` mm along."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    e1 = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    n_along = max(1, int(np.ceil(length / size)))
    th = 2.0 * np.pi * np.arange(n_around) / n_around
    s = np.linspace(-0.5 * length, 0.5 * length, n_along + 1)
    ss, tt = (v.ravel() for v in np.meshgrid(s, th, indexing="ij"))
    nodes = (np.asarray(centre, float) + ss[:, None] * a
             + radius * (np.cos(tt)[:, None] * e1 + np.sin(tt)[:, None] * e2))
    k, i = (v.ravel() for v in np.meshgrid(np.arange(n_along), np.arange(n_around),
                                           indexing="ij"))

    def n(kk: np.ndarray, ii: np.ndarray) -> np.ndarray:
        return kk * n_around + ii % n_around

    return nodes, np.column_stack([n(k, i), n(k, i + 1), n(k + 1, i + 1), n(k + 1, i)])


def quad_areas(nodes: np.ndarray, quads: np.ndarray) -> np.ndarray:
    """(q,) mm^2 areas of planar-ish quads (half the cross product of the diagonals)."""
    p = nodes[quads]
    return 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]), axis=1)


def ray_hit(surface: Surface, origin: np.ndarray, direction: np.ndarray) -> np.ndarray | None:
    """The farthest point (3,) mm where the ray ``origin + t direction`` (t > 0) crosses
    the surface's mid-surface (quads as two triangles each way), or None."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    o = np.asarray(origin, float)
    best = None
    for tris in (quads_to_triangles(surface.seg),
                 quads_to_triangles(surface.seg[:, [1, 2, 3, 0]])):
        p0, p1, p2 = (surface.x[tris[:, k]] for k in range(3))
        e1, e2 = p1 - p0, p2 - p0
        h = np.cross(d, e2)
        det = np.einsum("ij,ij->i", e1, h)
        ok = np.abs(det) > 1e-12
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s = o - p0
        u = inv * np.einsum("ij,ij->i", s, h)
        q = np.cross(s, e1)
        v = inv * (q @ d)
        t = inv * np.einsum("ij,ij->i", e2, q)
        hit = ok & (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1.0 + 1e-9) & (t > 0.0)
        if hit.any():
            tm = float(t[hit].max())
            best = tm if best is None else max(best, tm)
    return None if best is None else o + best * d


def sample_points(surface: Surface, keep: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Points (k, 3) mm on the segments (bilinear grids no coarser than
    :data:`SAMPLE_STEP`, edges and corners included) and their segments' contact
    thickness (k,); ``keep`` (s,) bool selects segments."""
    seg, thick = surface.seg, surface.thick
    if keep is not None:
        seg, thick = seg[keep], thick[keep]
    if seg.shape[0] == 0:
        return np.zeros((0, 3)), np.zeros(0)
    p = surface.x[seg]  # (s, 4, 3); a triangle's N4 == N3
    edge = np.linalg.norm(p - np.roll(p, -1, axis=1), axis=2).max(axis=1)
    per_edge = np.ceil(edge / SAMPLE_STEP).astype(int) + 1  # points along an edge
    pts, ts = [], []
    for n in np.unique(per_edge):
        sel = np.flatnonzero(per_edge == n)
        r = np.linspace(0.0, 1.0, n)
        u, v = (g.ravel() for g in np.meshgrid(r, r, indexing="ij"))
        w = np.column_stack([(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v])  # (m, 4)
        pts.append(np.einsum("mk,skc->smc", w, p[sel]).reshape(-1, 3))
        ts.append(np.repeat(thick[sel], w.shape[0]))
    return np.vstack(pts), np.concatenate(ts)


def first_contact_travel(surface: Surface, centre: np.ndarray, direction: np.ndarray,
                         axis: np.ndarray, radius: float, half_length: float
                         ) -> tuple[float, np.ndarray]:
    """(travel mm, surface point (3,) mm): how far a cylinder of contact radius
    ``radius`` (its face), axis ``axis`` through ``centre``, moving along ``direction``,
    goes before its face meets the surface offset by half the segments' contact
    thickness; only the part of the surface within ``half_length`` of the centre
    along the axis and ahead of the centre counts (start the cylinder clear of
    the surface). ValueError when the cylinder's path misses the surface."""
    f = frame(direction, axis)
    rel = surface.x - centre
    reach = radius + 0.5 * surface.thick.max(initial=0.0)
    w_seg = (rel @ f[2])[surface.seg]
    a_seg = (rel @ f[0])[surface.seg]
    seg_near = ((w_seg.min(axis=1) < reach) & (w_seg.max(axis=1) > -reach)
                & (a_seg.min(axis=1) <= half_length) & (a_seg.max(axis=1) >= -half_length))
    pts, th = sample_points(surface, seg_near)
    r = pts - centre
    a_c, u, w = r @ f[0], r @ f[1], r @ f[2]
    rc = radius + 0.5 * th
    hit = (np.abs(w) < rc) & (np.abs(a_c) <= half_length) & (u > 0.0)
    if not hit.any():
        raise ValueError("the impactor's path misses the surface")
    travel = u[hit] - np.sqrt(rc[hit] ** 2 - w[hit] ** 2)
    k = int(np.argmin(travel))
    return float(travel[k]), pts[hit][k]
