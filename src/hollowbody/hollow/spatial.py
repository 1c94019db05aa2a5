"""Spatial queries on one part's mesh for the solid -> hollow conversion.

A uniform bucket grid (dense, CSR item lists) over bounding boxes, and three
numba kernels on it:

- :meth:`TetLocator.inside`: is a point inside the union of tetrahedra
  (barycentric test with a small tolerance, so points on element faces and
  on the part's boundary count as inside);
- :meth:`TriangleSurface.distance`: distance from points to a triangulated
  surface (exact point-triangle distance, searched within a radius);
- :meth:`TriangleSurface.ray_hits`: does a ray segment hit the surface.

Used once per conversion, never in a time loop. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

#: Largest number of buckets of one grid (the bucket size grows beyond it).
MAX_BUCKETS = 2_000_000


@dataclass
class BucketGrid:
    """Dense uniform grid; ``items[start[b]:start[b + 1]]`` are the items of bucket b.

    lo: (3,) mm grid corner; size: bucket edge mm; dims: (3,) int64 buckets per axis.
    """

    lo: np.ndarray
    size: float
    dims: np.ndarray
    start: np.ndarray
    items: np.ndarray


def build_buckets(box_lo: np.ndarray, box_hi: np.ndarray, size: float) -> BucketGrid:
    """Register every box (m, 3) lo/hi (mm) in all buckets it overlaps."""
    size = float(max(size, 1e-9))
    if box_lo.shape[0] == 0:
        return BucketGrid(np.zeros(3), size, np.ones(3, np.int64), np.zeros(2, np.int64),
                          np.zeros(0, np.int64))
    lo = box_lo.min(axis=0) - 1e-6 * size
    hi = box_hi.max(axis=0) + 1e-6 * size
    while True:
        dims = np.maximum(np.ceil((hi - lo) / size).astype(np.int64), 1)
        if int(np.prod(dims)) <= MAX_BUCKETS:
            break
        size *= 1.5
    i0 = np.clip(((box_lo - lo) / size).astype(np.int64), 0, dims - 1)
    i1 = np.clip(((box_hi - lo) / size).astype(np.int64), 0, dims - 1)
    n = i1 - i0 + 1
    cnt = n[:, 0] * n[:, 1] * n[:, 2]
    item = np.repeat(np.arange(box_lo.shape[0], dtype=np.int64), cnt)
    local = np.arange(int(cnt.sum()), dtype=np.int64) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    nyz = np.repeat(n[:, 1] * n[:, 2], cnt)
    nz = np.repeat(n[:, 2], cnt)
    li, rem = local // nyz, local % nyz
    lj, lk = rem // nz, rem % nz
    bucket = (((np.repeat(i0[:, 0], cnt) + li) * dims[1] + np.repeat(i0[:, 1], cnt) + lj)
              * dims[2] + np.repeat(i0[:, 2], cnt) + lk)
    order = np.argsort(bucket, kind="stable")
    start = np.searchsorted(bucket[order], np.arange(int(np.prod(dims)) + 1))
    return BucketGrid(lo, size, dims, start.astype(np.int64), item[order])


# ---------------------------------------------------------------------------
# kernels


@njit(cache=True)
def _locate(p, x0, minv, lo, size, dims, start, items, tol, out):
    for q in range(p.shape[0]):
        b = np.empty(3, np.int64)
        ok = True
        for k in range(3):
            v = int(np.floor((p[q, k] - lo[k]) / size))
            if v < 0 or v >= dims[k]:
                ok = False
            b[k] = v
        out[q] = False
        if not ok:
            continue
        key = (b[0] * dims[1] + b[1]) * dims[2] + b[2]
        for s in range(start[key], start[key + 1]):
            t = items[s]
            d0 = p[q, 0] - x0[t, 0]
            d1 = p[q, 1] - x0[t, 1]
            d2 = p[q, 2] - x0[t, 2]
            l1 = minv[t, 0, 0] * d0 + minv[t, 0, 1] * d1 + minv[t, 0, 2] * d2
            l2 = minv[t, 1, 0] * d0 + minv[t, 1, 1] * d1 + minv[t, 1, 2] * d2
            l3 = minv[t, 2, 0] * d0 + minv[t, 2, 1] * d1 + minv[t, 2, 2] * d2
            if l1 >= -tol and l2 >= -tol and l3 >= -tol and 1.0 - l1 - l2 - l3 >= -tol:
                out[q] = True
                break


@njit(cache=True)
def _point_triangle_d2(p, a, b, c):
    """Squared distance from p to triangle abc (Ericson's region test)."""
    ab = b - a
    ac = c - a
    ap = p - a
    d1 = ab @ ap
    d2 = ac @ ap
    if d1 <= 0.0 and d2 <= 0.0:
        return ap @ ap
    bp = p - b
    d3 = ab @ bp
    d4 = ac @ bp
    if d3 >= 0.0 and d4 <= d3:
        return bp @ bp
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        v = d1 / (d1 - d3)
        r = ap - v * ab
        return r @ r
    cp = p - c
    d5 = ab @ cp
    d6 = ac @ cp
    if d6 >= 0.0 and d5 <= d6:
        return cp @ cp
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        w = d2 / (d2 - d6)
        r = ap - w * ac
        return r @ r
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        r = bp - w * (c - b)
        return r @ r
    den = 1.0 / (va + vb + vc)
    v = vb * den
    w = vc * den
    r = ap - v * ab - w * ac
    return r @ r


@njit(cache=True)
def _distance(p, tri, lo, size, dims, start, items, radius, out):
    reach = int(np.ceil(radius / size))
    for q in range(p.shape[0]):
        best = radius * radius
        c = np.empty(3, np.int64)
        for k in range(3):
            c[k] = int(np.floor((p[q, k] - lo[k]) / size))
        for i in range(max(c[0] - reach, 0), min(c[0] + reach + 1, dims[0])):
            for j in range(max(c[1] - reach, 0), min(c[1] + reach + 1, dims[1])):
                for l in range(max(c[2] - reach, 0), min(c[2] + reach + 1, dims[2])):
                    key = (i * dims[1] + j) * dims[2] + l
                    for s in range(start[key], start[key + 1]):
                        t = items[s]
                        d2 = _point_triangle_d2(p[q], tri[t, 0], tri[t, 1], tri[t, 2])
                        if d2 < best:
                            best = d2
        out[q] = np.sqrt(best)


@njit(cache=True)
def _segment_hits_triangle(px, py, pz, dx, dy, dz, length, tri, t):
    """Moller-Trumbore: segment p + s d, 0 <= s <= length, meets triangle t (closed)."""
    ax, ay, az = tri[t, 0, 0], tri[t, 0, 1], tri[t, 0, 2]
    e1x, e1y, e1z = tri[t, 1, 0] - ax, tri[t, 1, 1] - ay, tri[t, 1, 2] - az
    e2x, e2y, e2z = tri[t, 2, 0] - ax, tri[t, 2, 1] - ay, tri[t, 2, 2] - az
    pvx, pvy, pvz = dy * e2z - dz * e2y, dz * e2x - dx * e2z, dx * e2y - dy * e2x
    det = e1x * pvx + e1y * pvy + e1z * pvz
    scale = np.sqrt((e1x * e1x + e1y * e1y + e1z * e1z) * (e2x * e2x + e2y * e2y + e2z * e2z))
    if abs(det) <= 1e-12 * scale:
        return False
    tx, ty, tz = px - ax, py - ay, pz - az
    u = (tx * pvx + ty * pvy + tz * pvz) / det
    if u < -1e-9 or u > 1.0 + 1e-9:
        return False
    qx, qy, qz = ty * e1z - tz * e1y, tz * e1x - tx * e1z, tx * e1y - ty * e1x
    v = (dx * qx + dy * qy + dz * qz) / det
    if v < -1e-9 or u + v > 1.0 + 1e-9:
        return False
    sp = (e2x * qx + e2y * qy + e2z * qz) / det
    return -1e-9 * length <= sp <= length * (1.0 + 1e-9)


@njit(cache=True)
def _ray_hits(p, dirs, length, tri, lo, size, dims, start, items, out):
    """out[q, r]: segment p[q] + s dirs[r], 0 <= s <= length, hits a triangle."""
    for q in range(p.shape[0]):
        px, py, pz = p[q, 0], p[q, 1], p[q, 2]
        for r in range(dirs.shape[0]):
            dx, dy, dz = dirs[r, 0], dirs[r, 1], dirs[r, 2]
            i0x = max(int(np.floor((min(px, px + length * dx) - lo[0]) / size)), 0)
            i1x = min(int(np.floor((max(px, px + length * dx) - lo[0]) / size)), dims[0] - 1)
            i0y = max(int(np.floor((min(py, py + length * dy) - lo[1]) / size)), 0)
            i1y = min(int(np.floor((max(py, py + length * dy) - lo[1]) / size)), dims[1] - 1)
            i0z = max(int(np.floor((min(pz, pz + length * dz) - lo[2]) / size)), 0)
            i1z = min(int(np.floor((max(pz, pz + length * dz) - lo[2]) / size)), dims[2] - 1)
            hit = False
            for i in range(i0x, i1x + 1):
                for j in range(i0y, i1y + 1):
                    for l in range(i0z, i1z + 1):
                        key = (i * dims[1] + j) * dims[2] + l
                        for s in range(start[key], start[key + 1]):
                            if _segment_hits_triangle(px, py, pz, dx, dy, dz, length, tri,
                                                      items[s]):
                                hit = True
                                break
                        if hit:
                            break
                    if hit:
                        break
                if hit:
                    break
            out[q, r] = hit


# ---------------------------------------------------------------------------
# public wrappers


class TetLocator:
    """Point location in a set of tetrahedra.

    x: (n, 3) mm node coordinates; tets: (t, 4) node indices. Tetrahedra
    with (nearly) zero volume are ignored. ``tol``: barycentric tolerance
    (points within about ``tol`` x element size outside an element count as
    inside, so points on faces are inside).
    """

    def __init__(self, x: np.ndarray, tets: np.ndarray, tol: float = 1e-7) -> None:
        xt = x[tets]  # (t, 4, 3)
        m = np.stack([xt[:, 1] - xt[:, 0], xt[:, 2] - xt[:, 0], xt[:, 3] - xt[:, 0]], axis=2)
        det = np.linalg.det(m)
        ext = np.ptp(xt, axis=1).max(axis=1)
        keep = np.abs(det) > 1e-10 * np.maximum(ext, 1e-300) ** 3
        xt, m = xt[keep], m[keep]
        self.x0 = np.ascontiguousarray(xt[:, 0])
        self.minv = np.ascontiguousarray(np.linalg.inv(m)) if xt.shape[0] else np.zeros((0, 3, 3))
        self.tol = float(tol)
        lo, hi = xt.min(axis=1), xt.max(axis=1)
        size = float(np.mean(hi - lo)) * 1.5 if xt.shape[0] else 1.0
        self.grid = build_buckets(lo, hi, size)

    def inside(self, p: np.ndarray) -> np.ndarray:
        """(k,) bool: points p (k, 3) mm inside (or on) the tetrahedra."""
        p = np.ascontiguousarray(np.asarray(p, dtype=np.float64).reshape(-1, 3))
        out = np.zeros(p.shape[0], dtype=np.bool_)
        g = self.grid
        if p.shape[0] and self.x0.shape[0]:
            _locate(p, self.x0, self.minv, g.lo, g.size, g.dims, g.start, g.items, self.tol,
                    out)
        return out


def quads_to_triangles(conn: np.ndarray) -> np.ndarray:
    """(e, 4) quads (triangles with N4 == N3) -> (t, 3) triangles (split on 1-3)."""
    t1 = conn[:, [0, 1, 2]]
    quad = conn[:, 3] != conn[:, 2]
    t2 = conn[quad][:, [0, 2, 3]]
    return np.vstack([t1, t2])


class TriangleSurface:
    """A triangulated surface: tri (t, 3, 3) mm vertex coordinates; ``size``: bucket edge mm."""

    def __init__(self, tri: np.ndarray, size: float | None = None) -> None:
        self.tri = np.ascontiguousarray(np.asarray(tri, dtype=np.float64).reshape(-1, 3, 3))
        lo, hi = self.tri.min(axis=1), self.tri.max(axis=1)
        if size is None:
            size = 1.5 * float(np.mean(hi - lo)) if self.tri.shape[0] else 1.0
        self.grid = build_buckets(lo, hi, max(size, 1e-6))

    @classmethod
    def from_shells(cls, x: np.ndarray, conn: np.ndarray, size: float | None = None
                    ) -> TriangleSurface:
        """Surface of shell elements: x (n, 3) mm, conn (e, 4) indices."""
        return cls(x[quads_to_triangles(conn)], size)

    def distance(self, p: np.ndarray, radius: float) -> np.ndarray:
        """(k,) mm distance from p (k, 3) to the surface, capped at ``radius``."""
        p = np.ascontiguousarray(np.asarray(p, dtype=np.float64).reshape(-1, 3))
        out = np.full(p.shape[0], float(radius))
        g = self.grid
        if p.shape[0] and self.tri.shape[0]:
            _distance(p, self.tri, g.lo, g.size, g.dims, g.start, g.items, float(radius), out)
        return out

    def ray_hits(self, p: np.ndarray, dirs: np.ndarray, length: float) -> np.ndarray:
        """(k, r) bool: the segment from p (k, 3) along unit dirs (r, 3) of ``length`` mm
        hits the surface (end points included)."""
        p = np.ascontiguousarray(np.asarray(p, dtype=np.float64).reshape(-1, 3))
        d = np.ascontiguousarray(np.asarray(dirs, dtype=np.float64).reshape(-1, 3))
        out = np.zeros((p.shape[0], d.shape[0]), dtype=np.bool_)
        g = self.grid
        if p.shape[0] and self.tri.shape[0]:
            _ray_hits(p, d, float(length), self.tri, g.lo, g.size, g.dims, g.start, g.items,
                      out)
        return out
