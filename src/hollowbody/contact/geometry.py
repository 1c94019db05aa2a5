"""Closest-point projection onto a segment (numba): the one used by contact and ties.

A segment is a 4-node facet, triangles stored with ``N4 == N3``. Its points
are given by natural coordinates (u, v):

* quadrilaterals: the bilinear surface ``x(xi, eta) = sum_a N_a(xi, eta) x_a``
  on [-1, 1]^2, ``N_a = (1 + xi xi_a)(1 + eta eta_a) / 4`` (LS-DYNA corner
  order); projected with Newton's method on the two orthogonality conditions
  ``(x(xi, eta) - x_s) . x_,xi = 0`` and ``(x(xi, eta) - x_s) . x_,eta = 0``
  (the full Jacobian, including the ``x_,xi,eta`` term of warped quads);
* triangles: the linear map ``x(r, s) = (1 - r - s) x_1 + r x_2 + s x_3``,
  projected exactly (barycentric coordinates r, s).

The normal at the projection is ``x_,u x x_,v / |...|``. Only a converged
Newton iteration is a foot point: a projection that did not converge (a
strongly warped, folded segment) is never reported inside.

* :func:`project_segment` / :func:`project_corners` (contact): the foot of the
  normal through the node, its normal, the shape-function weights, and
  whether it lies on the segment (within :data:`INSIDE_TOL`);
* :func:`closest_point` (tied contacts, set-up): the point of the segment
  closest to the node, clamped to the segment: the foot point when it lies
  on the segment, else the closest point of the (straight) edges.

Every projection returns plain floats (no allocation) so it can be called in
parallel loops.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: Tolerance on the natural / barycentric coordinates for "inside" (a node
#: exactly over a shared edge is accepted by both segments).
INSIDE_TOL = 1.0e-2
_NEWTON_ITERS = 8
#: Last Newton step (|d xi| + |d eta|) below which a projection counts as converged
_CONVERGED = 1.0e-6
#: Newton iterations of :func:`closest_point` (set-up only: a generous budget)
CLOSEST_ITERS = 30
#: Tolerance on the natural coordinates of :func:`closest_point`'s "on the segment"
_ON_SEGMENT = 1.0e-10

_XI = (-1.0, 1.0, 1.0, -1.0)
_ETA = (-1.0, -1.0, 1.0, 1.0)


@njit(cache=True)
def shape_weights(u: float, v: float, tri: bool, out: np.ndarray) -> None:
    """Shape-function values (4,) at natural coordinates (u, v) into ``out``."""
    if tri:
        out[0] = 1.0 - u - v
        out[1] = u
        out[2] = v
        out[3] = 0.0
    else:
        for a in range(4):
            out[a] = 0.25 * (1.0 + u * _XI[a]) * (1.0 + v * _ETA[a])


@njit(cache=True)
def tangents(xs: np.ndarray, u: float, v: float, tri: bool, g: np.ndarray) -> None:
    """Tangents g[0] = dx/du, g[1] = dx/dv (2, 3) mm of segment corners xs (4, 3) mm."""
    for k in range(3):
        if tri:
            g[0, k] = xs[1, k] - xs[0, k]
            g[1, k] = xs[2, k] - xs[0, k]
        else:
            g0 = 0.0
            g1 = 0.0
            for a in range(4):
                g0 += 0.25 * _XI[a] * (1.0 + v * _ETA[a]) * xs[a, k]
                g1 += 0.25 * _ETA[a] * (1.0 + u * _XI[a]) * xs[a, k]
            g[0, k] = g0
            g[1, k] = g1


@njit(cache=True, inline="always")
def project_triangle(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz, tol=INSIDE_TOL):
    """Project point p onto triangle abc.

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, wa, wb, wc): ok False for
    a degenerate triangle; inside when all barycentric weights >= -tol;
    xp the projection onto the triangle's plane; n the unit normal
    ((b - a) x (c - a)); w the barycentric weights (sum 1).
    """
    e1x, e1y, e1z = bx - ax, by - ay, bz - az
    e2x, e2y, e2z = cx - ax, cy - ay, cz - az
    nx = e1y * e2z - e1z * e2y
    ny = e1z * e2x - e1x * e2z
    nz = e1x * e2y - e1y * e2x
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    # den = |e1|^2 |e2|^2 - (e1 . e2)^2 = nn^2 exactly; computed as nn^2 it has no
    # cancellation (a sliver triangle could give 0 the other way round)
    den = nn * nn
    if not den > 0.0:
        return False, False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    nx /= nn
    ny /= nn
    nz /= nn
    rx, ry, rz = px - ax, py - ay, pz - az
    d = rx * nx + ry * ny + rz * nz
    rx -= d * nx
    ry -= d * ny
    rz -= d * nz
    d00 = e1x * e1x + e1y * e1y + e1z * e1z
    d01 = e1x * e2x + e1y * e2y + e1z * e2z
    d11 = e2x * e2x + e2y * e2y + e2z * e2z
    d20 = rx * e1x + ry * e1y + rz * e1z
    d21 = rx * e2x + ry * e2y + rz * e2z
    s = (d11 * d20 - d01 * d21) / den
    t = (d00 * d21 - d01 * d20) / den
    wa = 1.0 - s - t
    inside = wa >= -tol and s >= -tol and t >= -tol
    return (True, inside, ax + rx, ay + ry, az + rz, nx, ny, nz, wa, s, t)


@njit(cache=True, inline="always")
def _quad_coefficients(x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3):
    """Coefficients of x(xi, eta) = c0 + xi c1 + eta c2 + xi eta c3 of the bilinear
    quadrilateral with corners 0..3 (mm): (c0x, c0y, c0z, c1x, ..., c3z)."""
    c0x = 0.25 * (x0 + x1 + x2 + x3)
    c0y = 0.25 * (y0 + y1 + y2 + y3)
    c0z = 0.25 * (z0 + z1 + z2 + z3)
    c1x = 0.25 * (-x0 + x1 + x2 - x3)
    c1y = 0.25 * (-y0 + y1 + y2 - y3)
    c1z = 0.25 * (-z0 + z1 + z2 - z3)
    c2x = 0.25 * (-x0 - x1 + x2 + x3)
    c2y = 0.25 * (-y0 - y1 + y2 + y3)
    c2z = 0.25 * (-z0 - z1 + z2 + z3)
    c3x = 0.25 * (x0 - x1 + x2 - x3)
    c3y = 0.25 * (y0 - y1 + y2 - y3)
    c3z = 0.25 * (z0 - z1 + z2 - z3)
    return c0x, c0y, c0z, c1x, c1y, c1z, c2x, c2y, c2z, c3x, c3y, c3z


@njit(cache=True, inline="always")
def _quad_newton(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, xi0, eta0,
                 iters):
    """Newton iteration for the foot of the normal through p on the bilinear
    quadrilateral with corners 0..3 (mm), from (xi0, eta0), at most ``iters`` steps.

    Returns (ok, xi, eta, step): ok False when the iteration breaks down (singular
    matrix); step the last |d xi| + |d eta| (0 once below 1e-10, or for a
    parallelogram, where one step is exact). The iterates are held in [-3, 3]^2.
    """
    # x(xi, eta) = c0 + xi c1 + eta c2 + xi eta c3
    (c0x, c0y, c0z, c1x, c1y, c1z, c2x, c2y, c2z, c3x, c3y,
     c3z) = _quad_coefficients(x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3)
    xi = xi0
    eta = eta0
    ok = False
    # parallelogram (x_,xi,eta = 0): the map is affine, one Newton step is exact
    affine = (c3x * c3x + c3y * c3y + c3z * c3z) <= 1.0e-24 * (
        c1x * c1x + c1y * c1y + c1z * c1z + c2x * c2x + c2y * c2y + c2z * c2z)
    tx = ty = tz = sx = sy = sz = 0.0
    rx = ry = rz = 0.0
    step = 0.0
    for _ in range(iters):
        tx = c1x + eta * c3x  # x_,xi
        ty = c1y + eta * c3y
        tz = c1z + eta * c3z
        sx = c2x + xi * c3x  # x_,eta
        sy = c2y + xi * c3y
        sz = c2z + xi * c3z
        rx = c0x + xi * c1x + eta * c2x + xi * eta * c3x - px
        ry = c0y + xi * c1y + eta * c2y + xi * eta * c3y - py
        rz = c0z + xi * c1z + eta * c2z + xi * eta * c3z - pz
        f1 = rx * tx + ry * ty + rz * tz
        f2 = rx * sx + ry * sy + rz * sz
        j11 = tx * tx + ty * ty + tz * tz
        j22 = sx * sx + sy * sy + sz * sz
        j12 = tx * sx + ty * sy + tz * sz + (rx * c3x + ry * c3y + rz * c3z)
        det = j11 * j22 - j12 * j12
        if det <= 1.0e-12 * j11 * j22:
            # fall back to the Gauss-Newton (positive definite) matrix
            j12 = tx * sx + ty * sy + tz * sz
            det = j11 * j22 - j12 * j12
            if det <= 0.0:
                ok = False
                break
        dxi = (j22 * f1 - j12 * f2) / det
        deta = (j11 * f2 - j12 * f1) / det
        xi -= dxi
        eta -= deta
        if xi > 3.0:
            xi = 3.0
        elif xi < -3.0:
            xi = -3.0
        if eta > 3.0:
            eta = 3.0
        elif eta < -3.0:
            eta = -3.0
        ok = True
        step = abs(dxi) + abs(deta)
        if affine or step < 1.0e-10:
            step = 0.0
            break
    return ok, xi, eta, step


@njit(cache=True, inline="always")
def project_quad(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, xi0=0.0,
                 eta0=0.0, tol=INSIDE_TOL):
    """Project point p onto the bilinear quadrilateral with corners 0..3 (scalars, mm),
    Newton from natural coordinates (xi0, eta0) (default the centre; the contact
    kernel starts a node's last contact segment from its last contact point).

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, w0, w1, w2, w3): ok False
    when the Newton iteration breaks down; inside when |xi|, |eta| <= 1 + tol
    (default INSIDE_TOL) and the iteration converged (else xp is not the foot of
    the normal through p, and p may be far from the segment although (p - xp) . n
    is small: a folded wall segment); xp the point x(xi, eta); n the unit normal
    there; w the bilinear shape functions (sum 1).
    """
    ok, xi, eta, step = _quad_newton(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3,
                                     z3, xi0, eta0, _NEWTON_ITERS)
    (c0x, c0y, c0z, c1x, c1y, c1z, c2x, c2y, c2z, c3x, c3y,
     c3z) = _quad_coefficients(x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3)
    if not ok:
        return False, False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    tx = c1x + eta * c3x
    ty = c1y + eta * c3y
    tz = c1z + eta * c3z
    sx = c2x + xi * c3x
    sy = c2y + xi * c3y
    sz = c2z + xi * c3z
    nx = ty * sz - tz * sy
    ny = tz * sx - tx * sz
    nz = tx * sy - ty * sx
    nn = math.sqrt(nx * nx + ny * ny + nz * nz)
    if not nn > 0.0:
        return False, False, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    lim = 1.0 + tol
    # not converged (a strongly warped, folded segment): xp is no foot point, and
    # d = (p - xp) . n is not the distance (it can be small for a node far away)
    inside = abs(xi) <= lim and abs(eta) <= lim and step < _CONVERGED
    w0 = 0.25 * (1.0 - xi) * (1.0 - eta)
    w1 = 0.25 * (1.0 + xi) * (1.0 - eta)
    w2 = 0.25 * (1.0 + xi) * (1.0 + eta)
    w3 = 0.25 * (1.0 - xi) * (1.0 + eta)
    return (True, inside, c0x + xi * c1x + eta * c2x + xi * eta * c3x,
            c0y + xi * c1y + eta * c2y + xi * eta * c3y,
            c0z + xi * c1z + eta * c2z + xi * eta * c3z,
            nx / nn, ny / nn, nz / nn, w0, w1, w2, w3)


@njit(cache=True, inline="always")
def project_corners(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, tri, xi0=0.0,
                    eta0=0.0, tol=INSIDE_TOL):
    """Project p onto a segment given by its corner coordinates (tri: N4 == N3);
    ``tol``: the "inside" tolerance (barycentric weights, natural coordinates).

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, w0, w1, w2, w3).
    """
    if tri:
        ok, inside, qx, qy, qz, nx, ny, nz, wa, wb, wc = project_triangle(
            px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, tol)
        return ok, inside, qx, qy, qz, nx, ny, nz, wa, wb, wc, 0.0
    return project_quad(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, xi0, eta0,
                        tol)


@njit(cache=True)
def project_segment(px, py, pz, x, seg, s):
    """Project p onto segment s of seg (S, 4) int32 rows of x (n, 3) (triangles N4 == N3).

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, w0, w1, w2, w3).
    """
    a = seg[s, 0]
    b = seg[s, 1]
    c = seg[s, 2]
    d = seg[s, 3]
    return project_corners(px, py, pz, x[a, 0], x[a, 1], x[a, 2], x[b, 0], x[b, 1], x[b, 2],
                           x[c, 0], x[c, 1], x[c, 2], x[d, 0], x[d, 1], x[d, 2], c == d)


@njit(cache=True)
def segment_point(xs: np.ndarray, u: float, v: float, tri: bool, w: np.ndarray,
                  out: np.ndarray) -> None:
    """The point x(u, v) (3,) mm of segment corners xs (4, 3) mm into ``out``; w (4,)
    work array (the shape-function weights on return)."""
    shape_weights(u, v, tri, w)
    for k in range(3):
        out[k] = w[0] * xs[0, k] + w[1] * xs[1, k] + w[2] * xs[2, k] + w[3] * xs[3, k]


@njit(cache=True)
def _dist2(xs: np.ndarray, u: float, v: float, tri: bool, p: np.ndarray, w: np.ndarray,
           q: np.ndarray) -> float:
    segment_point(xs, u, v, tri, w, q)
    return (q[0] - p[0]) ** 2 + (q[1] - p[1]) ** 2 + (q[2] - p[2]) ** 2


@njit(cache=True)
def _edge_param(a: np.ndarray, b: np.ndarray, p: np.ndarray) -> float:
    """Parameter t in [0, 1] of the point of the straight edge a-b closest to p."""
    d0 = b[0] - a[0]
    d1 = b[1] - a[1]
    d2 = b[2] - a[2]
    dd = d0 * d0 + d1 * d1 + d2 * d2
    if dd <= 0.0:
        return 0.0
    t = ((p[0] - a[0]) * d0 + (p[1] - a[1]) * d1 + (p[2] - a[2]) * d2) / dd
    return min(max(t, 0.0), 1.0)


@njit(cache=True)
def foot_point(xs: np.ndarray, tri: bool, p: np.ndarray) -> tuple[bool, float, float]:
    """Natural coordinates of the foot of the normal through p (3,) mm on segment
    corners xs (4, 3) mm: (found, u, v), found only for a converged projection
    (triangles: exact barycentric coordinates; quadrilaterals: the Newton iteration
    of :func:`project_quad`, :data:`CLOSEST_ITERS` steps from the centre)."""
    if tri:
        ok, _, _, _, _, _, _, _, _, r, s = project_triangle(
            p[0], p[1], p[2], xs[0, 0], xs[0, 1], xs[0, 2], xs[1, 0], xs[1, 1], xs[1, 2],
            xs[2, 0], xs[2, 1], xs[2, 2])
        return ok, r, s
    ok, xi, eta, step = _quad_newton(
        p[0], p[1], p[2], xs[0, 0], xs[0, 1], xs[0, 2], xs[1, 0], xs[1, 1], xs[1, 2],
        xs[2, 0], xs[2, 1], xs[2, 2], xs[3, 0], xs[3, 1], xs[3, 2], 0.0, 0.0, CLOSEST_ITERS)
    return ok and step < _CONVERGED, xi, eta


@njit(cache=True)
def closest_point(xs: np.ndarray, tri: bool, p: np.ndarray) -> tuple[float, float, float]:
    """Natural coordinates (u, v) of the point of segment corners xs (4, 3) mm closest
    to p (3,) mm, and the squared distance (mm^2).

    The converged foot point (:func:`foot_point`) when it lies on the segment (to
    1e-10 in u, v; then clamped onto it), else, or when an edge is closer (a warped
    segment), the closest point of the segment's straight edges.
    """
    w = np.zeros(4)
    q = np.zeros(3)
    best_u, best_v, best = 0.0, 0.0, np.inf
    found, u, v = foot_point(xs, tri, p)
    eps = _ON_SEGMENT
    if found:
        inside = (u >= -eps and v >= -eps and u + v <= 1.0 + eps) if tri else \
            (abs(u) <= 1.0 + eps and abs(v) <= 1.0 + eps)
        if inside:
            if tri:
                u, v = min(max(u, 0.0), 1.0), min(max(v, 0.0), 1.0)
            else:
                u, v = min(max(u, -1.0), 1.0), min(max(v, -1.0), 1.0)
            best_u, best_v, best = u, v, _dist2(xs, u, v, tri, p, w, q)
    n_edges = 3 if tri else 4
    for k in range(n_edges):
        t = _edge_param(xs[k], xs[(k + 1) % n_edges], p)
        if tri:
            if k == 0:
                eu, ev = t, 0.0
            elif k == 1:
                eu, ev = 1.0 - t, t
            else:
                eu, ev = 0.0, 1.0 - t
        else:
            if k == 0:
                eu, ev = -1.0 + 2.0 * t, -1.0
            elif k == 1:
                eu, ev = 1.0, -1.0 + 2.0 * t
            elif k == 2:
                eu, ev = 1.0 - 2.0 * t, 1.0
            else:
                eu, ev = -1.0, 1.0 - 2.0 * t
        d2 = _dist2(xs, eu, ev, tri, p, w, q)
        if best == np.inf or d2 < best - 1e-14 * max(best, 1.0):
            best_u, best_v, best = eu, ev, d2
    return best_u, best_v, best
