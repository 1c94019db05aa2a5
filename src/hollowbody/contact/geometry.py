"""Closest-point projection of a node onto a contact segment (numba).

Triangles (N4 == N3) are projected exactly (barycentric coordinates).
Quadrilaterals are treated as the bilinear surface
``x(xi, eta) = sum_a N_a(xi, eta) x_a`` and projected with Newton's method
on the two orthogonality conditions ``(x(xi, eta) - x_s) . x_,xi = 0`` and
``(x(xi, eta) - x_s) . x_,eta = 0`` (the full Jacobian, including the
``x_,xi,eta`` term of warped quads); the normal at the projection is
``x_,xi x x_,eta / |...|``.

Every function returns plain floats (no allocation) so it can be called in
parallel loops.
"""

from __future__ import annotations

import math

from numba import njit

#: Tolerance on the natural / barycentric coordinates for "inside" (a node
#: exactly over a shared edge is accepted by both segments).
INSIDE_TOL = 1.0e-2
_NEWTON_ITERS = 8
#: Last Newton step (|d xi| + |d eta|) below which a projection counts as converged
_CONVERGED = 1.0e-6


@njit(cache=True, inline="always")
def project_triangle(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz):
    """Project point p onto triangle abc.

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, wa, wb, wc): ok False for
    a degenerate triangle; inside when all barycentric weights >= -INSIDE_TOL;
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
    inside = wa >= -INSIDE_TOL and s >= -INSIDE_TOL and t >= -INSIDE_TOL
    return (True, inside, ax + rx, ay + ry, az + rz, nx, ny, nz, wa, s, t)


@njit(cache=True)
def project_quad(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, xi0=0.0,
                 eta0=0.0):
    """Project point p onto the bilinear quadrilateral with corners 0..3 (scalars, mm),
    Newton from natural coordinates (xi0, eta0) (default the centre; the contact
    kernel starts a node's last contact segment from its last contact point).

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, w0, w1, w2, w3): ok False
    when the Newton iteration breaks down; inside when |xi|, |eta| <= 1 +
    INSIDE_TOL and the iteration converged (else xp is not the foot of the
    normal through p, and p may be far from the segment although (p - xp) . n
    is small: a folded wall segment); xp the point x(xi, eta); n the unit normal
    there; w the bilinear shape functions (sum 1).
    """
    # x(xi, eta) = c0 + xi c1 + eta c2 + xi eta c3
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
    xi = xi0
    eta = eta0
    ok = False
    # parallelogram (x_,xi,eta = 0): the map is affine, one Newton step is exact
    affine = (c3x * c3x + c3y * c3y + c3z * c3z) <= 1.0e-24 * (
        c1x * c1x + c1y * c1y + c1z * c1z + c2x * c2x + c2y * c2y + c2z * c2z)
    tx = ty = tz = sx = sy = sz = 0.0
    rx = ry = rz = 0.0
    step = 0.0
    for _ in range(_NEWTON_ITERS):
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
    lim = 1.0 + INSIDE_TOL
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
                    eta0=0.0):
    """Project p onto a segment given by its corner coordinates (tri: N4 == N3).

    Returns (ok, inside, xpx, xpy, xpz, nx, ny, nz, w0, w1, w2, w3).
    """
    if tri:
        ok, inside, qx, qy, qz, nx, ny, nz, wa, wb, wc = project_triangle(
            px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2)
        return ok, inside, qx, qy, qz, nx, ny, nz, wa, wb, wc, 0.0
    return project_quad(px, py, pz, x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3, xi0, eta0)


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
