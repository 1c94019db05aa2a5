"""Kinematics of the 8-node one-point hexahedron (Flanagan & Belytschko 1981).

Node order is LS-DYNA's: N1..N4 the bottom face counter-clockwise seen from
the top, N5..N8 above them. Reference coordinates of node ``a``:
``xi = (-1, 1, 1, -1, -1, 1, 1, -1)``, ``eta = (-1, -1, 1, 1, -1, -1, 1, 1)``,
``zeta = (-1, -1, -1, -1, 1, 1, 1, 1)``.

Uniform gradient. The element's volume-averaged shape-function gradient is
``b_a = (1/V) dV/dx_a`` where ``V`` is the exact volume of the trilinear
element. ``dV/dx_a`` (the component along x) is a bilinear form of the nodal
y and z coordinates; its closed form (FB 1981, eq. 79) is generated here from
the exact integral of ``det J`` and written out below. The y and z components
follow by cycling (x, y, z). Because ``V`` is linear in the x coordinates,
``V = sum_a x_a (dV/dx_a)_x`` exactly, and ``sum_a x_a (x) b_a = I``: every
linear velocity field is reproduced exactly, for any shape, including the
degenerate wedges and tetrahedra (repeated nodes simply add up).

Tetrahedra. LS-DYNA decks store a tetrahedron as ``N1 N2 N3 N4 N4 N4 N4 N4``.
As a trilinear map that pattern is *not* the tetrahedron (its bottom "face"
N1-N2-N3-N4 is a saddle through the volume and the exact volume is half the
tetrahedron's); :func:`canonical_connectivity` therefore rewrites elements
with four distinct nodes to ``N1 N2 N3 N3 N4 N4 N4 N4`` (a collapsed hex that
*is* the tetrahedron, same orientation). Wedges ``N1 N2 N3 N4 N5 N5 N6 N6``
are exact as given.

All functions marked "kernel" are numba functions on one element's local
arrays (no allocation); the others are vectorised helpers for set-up and tests.
Units: mm, mm/ms, mm^3.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: Flanagan-Belytschko hourglass base vectors h_alpha (4, 8): xi*eta,
#: eta*zeta, zeta*xi, xi*eta*zeta evaluated at the nodes.
HG_BASE = np.array([
    [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0],
    [1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0],
])

#: Node quadruples of the six faces (for the characteristic length).
HEX_FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4],
                      [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]], dtype=np.int64)

#: Element shape codes returned by :func:`canonical_connectivity`.
SHAPE_HEX, SHAPE_WEDGE, SHAPE_TET, SHAPE_OTHER = 0, 1, 2, 3

_TWELFTH = 1.0 / 12.0


def canonical_connectivity(conn: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Connectivity the kernels use, and the shape of every element.

    conn: (e, 8) int node indices as in the deck. Returns ``(conn_k, shape)``:
    conn_k (e, 8) int32 where every element with exactly four distinct nodes
    (a tetrahedron, whatever its degenerate pattern) is rewritten as
    ``u0 u1 u2 u2 u3 u3 u3 u3`` (distinct nodes in order of first appearance),
    other elements unchanged; shape (e,) int8: SHAPE_HEX (8 distinct nodes),
    SHAPE_WEDGE (6), SHAPE_TET (4) or SHAPE_OTHER.
    """
    conn = np.asarray(conn)
    conn_k = conn.astype(np.int32, copy=True)
    s = np.sort(conn, axis=1)
    distinct = 1 + np.count_nonzero(np.diff(s, axis=1), axis=1)
    shape = np.full(conn.shape[0], SHAPE_OTHER, dtype=np.int8)
    shape[distinct == 8] = SHAPE_HEX
    shape[distinct == 6] = SHAPE_WEDGE
    shape[distinct == 4] = SHAPE_TET
    for e in np.nonzero(distinct == 4)[0]:
        u: list[int] = []
        for n in conn[e]:
            if int(n) not in u:
                u.append(int(n))
        conn_k[e] = (u[0], u[1], u[2], u[2], u[3], u[3], u[3], u[3])
    return conn_k, shape


@njit(cache=True, inline="always", fastmath={"contract"})
def _dvdx_component(xe, j, k, out, i):
    """Kernel: out[:, i] = dV/dx_{a,i} from coordinate columns j, k of xe (8, 3)."""
    p0, p1, p2, p3 = xe[0, j], xe[1, j], xe[2, j], xe[3, j]
    p4, p5, p6, p7 = xe[4, j], xe[5, j], xe[6, j], xe[7, j]
    q0, q1, q2, q3 = xe[0, k], xe[1, k], xe[2, k], xe[3, k]
    q4, q5, q6, q7 = xe[4, k], xe[5, k], xe[6, k], xe[7, k]
    out[0, i] = (p1 * (-q2 - q3 + q4 + q5) + p2 * (q1 - q3)
                 + p3 * (q1 + q2 - q4 - q7) + p4 * (-q1 + q3 - q5 + q7)
                 + p5 * (-q1 + q4) + p7 * (q3 - q4)) * _TWELFTH
    out[1, i] = (p0 * (q2 + q3 - q4 - q5) + p2 * (-q0 - q3 + q5 + q6)
                 + p3 * (-q0 + q2) + p4 * (q0 - q5)
                 + p5 * (q0 - q2 + q4 - q6) + p6 * (-q2 + q5)) * _TWELFTH
    out[2, i] = (p0 * (-q1 + q3) + p1 * (q0 + q3 - q5 - q6)
                 + p3 * (-q0 - q1 + q6 + q7) + p5 * (q1 - q6)
                 + p6 * (q1 - q3 + q5 - q7) + p7 * (-q3 + q6)) * _TWELFTH
    out[3, i] = (p0 * (-q1 - q2 + q4 + q7) + p1 * (q0 - q2)
                 + p2 * (q0 + q1 - q6 - q7) + p4 * (-q0 + q7)
                 + p6 * (q2 - q7) + p7 * (-q0 + q2 - q4 + q6)) * _TWELFTH
    out[4, i] = (p0 * (q1 - q3 + q5 - q7) + p1 * (-q0 + q5)
                 + p3 * (q0 - q7) + p5 * (-q0 - q1 + q6 + q7)
                 + p6 * (-q5 + q7) + p7 * (q0 + q3 - q5 - q6)) * _TWELFTH
    out[5, i] = (p0 * (q1 - q4) + p1 * (-q0 + q2 - q4 + q6)
                 + p2 * (-q1 + q6) + p4 * (q0 + q1 - q6 - q7)
                 + p6 * (-q1 - q2 + q4 + q7) + p7 * (q4 - q6)) * _TWELFTH
    out[6, i] = (p1 * (q2 - q5) + p2 * (-q1 + q3 - q5 + q7)
                 + p3 * (-q2 + q7) + p4 * (q5 - q7)
                 + p5 * (q1 + q2 - q4 - q7) + p7 * (-q2 - q3 + q4 + q5)) * _TWELFTH
    out[7, i] = (p0 * (-q3 + q4) + p2 * (q3 - q6)
                 + p3 * (q0 - q2 + q4 - q6) + p4 * (-q0 - q3 + q5 + q6)
                 + p5 * (-q4 + q6) + p6 * (q2 + q3 - q4 - q5)) * _TWELFTH


@njit(cache=True, inline="always", fastmath={"contract"})
def hex8_volume_derivatives(xe, out):
    """Kernel: exact volume and its nodal derivatives.

    xe: (8, 3) float64 mm nodal coordinates (any origin); out: (8, 3) float64,
    filled with dV/dx_a (mm^2). Returns the volume V (mm^3, negative when the
    element is inverted). The uniform gradient is ``out / V``.
    """
    _dvdx_component(xe, 1, 2, out, 0)
    _dvdx_component(xe, 2, 0, out, 1)
    _dvdx_component(xe, 0, 1, out, 2)
    v = 0.0
    for a in range(8):
        v += xe[a, 0] * out[a, 0]
    return v


@njit(cache=True, inline="always", fastmath={"contract"})
def hex8_max_face_area(xe):
    """Kernel: largest face area (mm^2) of a hexahedron, xe (8, 3) mm.

    Face area = |d1 x d2| / 2 with the face diagonals d1, d2 (exact for planar
    quadrilaterals and for triangles, i.e. faces with a repeated node).
    """
    amax = 0.0
    for f in range(6):
        n0, n1, n2, n3 = HEX_FACES[f, 0], HEX_FACES[f, 1], HEX_FACES[f, 2], HEX_FACES[f, 3]
        d1x = xe[n2, 0] - xe[n0, 0]
        d1y = xe[n2, 1] - xe[n0, 1]
        d1z = xe[n2, 2] - xe[n0, 2]
        d2x = xe[n3, 0] - xe[n1, 0]
        d2y = xe[n3, 1] - xe[n1, 1]
        d2z = xe[n3, 2] - xe[n1, 2]
        cx = d1y * d2z - d1z * d2y
        cy = d1z * d2x - d1x * d2z
        cz = d1x * d2y - d1y * d2x
        a2 = cx * cx + cy * cy + cz * cz
        if a2 > amax:
            amax = a2
    return 0.5 * np.sqrt(amax)


@njit(cache=True, inline="always", fastmath={"contract"})
def velocity_gradient(ve, b, lg):
    """Kernel: lg (3, 3) = sum_a v_a (x) b_a (1/ms); ve, b (8, 3)."""
    for i in range(3):
        for j in range(3):
            s = 0.0
            for a in range(8):
                s += ve[a, i] * b[a, j]
            lg[i, j] = s


@njit(cache=True, inline="always", fastmath={"contract"})
def midpoint_velocity_gradient(lg, dt):
    """Kernel: velocity gradient in the mid-step configuration, in place.

    With ``L`` computed from the end-of-step gradients, and an increment that
    is affine over the element, ``L_mid = (I - dt/2 L)^-1 L`` exactly. With it a
    rigid rotation gives D = 0 exactly and, with :func:`hughes_winget`, the
    exact rotation of the stress (Hughes & Winget 1980). dt = 0 leaves L
    unchanged. lg: (3, 3) 1/ms.
    """
    h = 0.5 * dt
    if h == 0.0:
        return
    a00 = 1.0 - h * lg[0, 0]
    a01 = -h * lg[0, 1]
    a02 = -h * lg[0, 2]
    a10 = -h * lg[1, 0]
    a11 = 1.0 - h * lg[1, 1]
    a12 = -h * lg[1, 2]
    a20 = -h * lg[2, 0]
    a21 = -h * lg[2, 1]
    a22 = 1.0 - h * lg[2, 2]
    c00 = a11 * a22 - a12 * a21
    c01 = a02 * a21 - a01 * a22
    c02 = a01 * a12 - a02 * a11
    c10 = a12 * a20 - a10 * a22
    c11 = a00 * a22 - a02 * a20
    c12 = a02 * a10 - a00 * a12
    c20 = a10 * a21 - a11 * a20
    c21 = a01 * a20 - a00 * a21
    c22 = a00 * a11 - a01 * a10
    det = a00 * c00 + a01 * c10 + a02 * c20
    inv = 1.0 / det
    l00, l01, l02 = lg[0, 0], lg[0, 1], lg[0, 2]
    l10, l11, l12 = lg[1, 0], lg[1, 1], lg[1, 2]
    l20, l21, l22 = lg[2, 0], lg[2, 1], lg[2, 2]
    lg[0, 0] = (c00 * l00 + c01 * l10 + c02 * l20) * inv
    lg[0, 1] = (c00 * l01 + c01 * l11 + c02 * l21) * inv
    lg[0, 2] = (c00 * l02 + c01 * l12 + c02 * l22) * inv
    lg[1, 0] = (c10 * l00 + c11 * l10 + c12 * l20) * inv
    lg[1, 1] = (c10 * l01 + c11 * l11 + c12 * l21) * inv
    lg[1, 2] = (c10 * l02 + c11 * l12 + c12 * l22) * inv
    lg[2, 0] = (c20 * l00 + c21 * l10 + c22 * l20) * inv
    lg[2, 1] = (c20 * l01 + c21 * l11 + c22 * l21) * inv
    lg[2, 2] = (c20 * l02 + c21 * l12 + c22 * l22) * inv


@njit(cache=True, inline="always", fastmath={"contract"})
def hughes_winget(lg, dt, q):
    """Kernel: incremental rotation q (3, 3) = (I - A)^-1 (I + A), A = dt/2 W.

    W = skew(lg). Closed form of the Cayley transform of a skew matrix with
    axial vector w: ``Q = I + 2 (A + A^2) / (1 + |w|^2)``; exactly orthogonal.
    """
    h = 0.5 * dt
    w1 = h * 0.5 * (lg[2, 1] - lg[1, 2])
    w2 = h * 0.5 * (lg[0, 2] - lg[2, 0])
    w3 = h * 0.5 * (lg[1, 0] - lg[0, 1])
    # A = [[0, -w3, w2], [w3, 0, -w1], [-w2, w1, 0]]; A^2 = w w^T - |w|^2 I
    ww = w1 * w1 + w2 * w2 + w3 * w3
    s = 2.0 / (1.0 + ww)
    q[0, 0] = 1.0 + s * (w1 * w1 - ww)
    q[1, 1] = 1.0 + s * (w2 * w2 - ww)
    q[2, 2] = 1.0 + s * (w3 * w3 - ww)
    q[0, 1] = s * (-w3 + w1 * w2)
    q[1, 0] = s * (w3 + w1 * w2)
    q[0, 2] = s * (w2 + w1 * w3)
    q[2, 0] = s * (-w2 + w1 * w3)
    q[1, 2] = s * (-w1 + w2 * w3)
    q[2, 1] = s * (w1 + w2 * w3)


# ---------------------------------------------------------------------------
# Vectorised helpers (set-up, tests)


@njit(cache=True, fastmath={"contract"})
def _gradients_loop(conn, x, b, vol, amax):
    xe = np.empty((8, 3))
    bt = np.empty((8, 3))
    for e in range(conn.shape[0]):
        n0 = conn[e, 0]
        for a in range(8):
            n = conn[e, a]
            for i in range(3):
                xe[a, i] = x[n, i] - x[n0, i]
        v = hex8_volume_derivatives(xe, bt)
        vol[e] = v
        amax[e] = hex8_max_face_area(xe)
        inv = 1.0 / v if v != 0.0 else 0.0
        for a in range(8):
            for i in range(3):
                b[e, a, i] = bt[a, i] * inv


def hex8_gradients(conn: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Uniform gradients and exact volumes of a group.

    conn: (e, 8) int node indices (use :func:`canonical_connectivity` first for
    tetrahedra); x: (n, 3) float64 mm. Returns ``b`` (e, 8, 3) float64 1/mm
    (zero for an element of zero volume) and ``volume`` (e,) float64 mm^3.
    """
    conn = np.ascontiguousarray(conn, dtype=np.int64)
    x = np.ascontiguousarray(x, dtype=np.float64)
    e = conn.shape[0]
    b = np.empty((e, 8, 3))
    vol = np.empty(e)
    amax = np.empty(e)
    _gradients_loop(conn, x, b, vol, amax)
    return b, vol


def characteristic_lengths(conn: np.ndarray, x: np.ndarray,
                           shape: np.ndarray | None = None) -> np.ndarray:
    """Characteristic lengths L_e (e,) mm for the time step.

    Hexahedra and wedges: V / A_max (LS-DYNA's rule for solids);
    tetrahedra (shape SHAPE_TET): the smallest altitude 3 V / A_max.
    """
    conn = np.ascontiguousarray(conn, dtype=np.int64)
    x = np.ascontiguousarray(x, dtype=np.float64)
    e = conn.shape[0]
    b = np.empty((e, 8, 3))
    vol = np.empty(e)
    amax = np.empty(e)
    _gradients_loop(conn, x, b, vol, amax)
    length = vol / np.where(amax > 0.0, amax, np.inf)
    if shape is not None:
        length = np.where(shape == SHAPE_TET, 3.0 * length, length)
    return length
