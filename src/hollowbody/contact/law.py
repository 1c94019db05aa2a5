"""Normal force law of the penalty contact: release depth, stiffened zone, pass-through.

Numba functions called per node-segment pair by
:mod:`hollowbody.contact.penalty` (no allocation). With g the penetration
(gap) of a node, reach = (t_node + t_seg) / 2 and the release depth D behind
the segment (:func:`release_depth`), the node is in contact for
0 < g < G = reach + D and released beyond. The force (:func:`penalty_force`)
is the spring force (:func:`spring_force`: incremental, at most ``k g``, k
capped by :func:`stable_stiffness`) up to ``g1 = STIFFEN_FRACTION * G``; deeper, the tangent
stiffness rises, incrementally, to the nodal stability bound at the current
step (:func:`deep_stiffness`). Why: with SOFT=1 the spring k is set from the
initial step; a crushed soft tissue is one to two orders of magnitude
stiffer (and its step that much shorter), so with k alone a node can carry
only k G before it is released and pushed through the surface. A node
released behind the segment it came from is a pass-through
(:func:`pushed_through`), which the runtime reports.
"""

from __future__ import annotations

from numba import njit

from hollowbody.contact.geometry import project_corners

#: Default start of the stiffened zone, as a fraction of the penetration at
#: release (params[8]; a value >= 1 disables it).
STIFFEN_FRACTION = 0.5
#: (omega dt)^2 allowed for all contact springs on a node, the bound every spring
#: stiffness is capped to (:func:`stable_stiffness`): by Weyl's inequality the
#: eigenvalues of element and contact stiffness add at most, and elements use up
#: to (2 TSSFAC)^2 = 3.24 of the central-difference limit 4 at TSSFAC 0.9.
CAP_LIMIT = 1.5
#: (omega dt)^2 allowed for all contact springs on a node in the stiffened zone
#: (params[9]); with the elements' (omega dt)^2 <= (2 TSSFAC)^2 = 3.24 the sum
#: stays below the central-difference limit 4.
STIFFEN_LIMIT = 0.5
#: The stiffened zone follows the time step down to this fraction of the
#: reference step dtc (at most a 400-fold stiffening): below, a collapsing
#: element (which ends the run anyway) does not drive the contact force up.
DT_FLOOR = 0.05
#: A contact whose first gap is at most this fraction of the penetration at
#: release came from outside; only such a node's release behind its segment
#: is a pass-through (a node caught deep at once -- sliding over an edge, a
#: fold -- was never on the outer side).
ENTRY_FRACTION = 0.5
#: "Inside" tolerance (natural coordinates of a quad, barycentric weights of a
#: triangle) within which a node keeps the segment it was in contact with last
#: cycle when no segment has it inside (:mod:`hollowbody.contact.detect`): behind
#: a convex edge of the surface a node projects onto neither face. Dropped and
#: found again it would start as a fresh contact (:func:`spring_force`) and lose
#: its force. 0.2 is 0.5 mm on a 5 mm quad: a node 1 mm behind the middle of a
#: 50-degree edge.
HOLD_TOL = 0.2
#: Loose "inside" test (smallest shape function) for the pass-through check on
#: the previous segment: a node pushed through near an edge still counts.
_THRU_MIN_WEIGHT = -0.1


@njit(cache=True, inline="always")
def release_depth(s_depth, reach, two):
    """Depth (mm) behind a segment (behind its mid-surface for shells) at which a
    node is released: s_depth (penmax times the element depth), and for
    two-sided segments at least the contact reach (half the summed thicknesses)."""
    if two and s_depth < reach:
        return reach
    return s_depth


@njit(cache=True, inline="always")
def penalty_force(gap, gap_prev, fd_prev, k, kd, g1, ramp):
    """Normal penalty force (kN) at penetration gap (mm): returns (F_n, F_d).

    ``F_n = k gap + F_d`` (k kN/mm). F_d, the stiffening force, is zero up to
    the depth g1 (mm); deeper it grows incrementally with the extra stiffness
    ``r(e) k_x``, ``k_x = max(0, kd - k)`` (kd kN/mm, the stiffened zone's
    tangent stiffness at the current step, see :func:`deep_stiffness`),
    e = gap - g1, ramped in as r(e) = min(1, e / ramp) so that the force law
    has no kink (a kink crossed within a step costs the central-difference
    scheme energy accuracy)::

        F_d = clamp(F_d,prev + r(e_mid) k_x (e - e_prev), 0, F_total(e))
        F_total(e) = k_x e^2 / (2 ramp)  (e <= ramp),  k_x (e - ramp / 2)  (beyond)

    e_prev from gap_prev, the last cycle's gap on the same segment (the
    kernel passes the gap itself for a fresh contact, whose stiffening starts
    from there, and ``gap + v_n dt`` for a node that moved on to another
    segment: its F_d grows by the approach of its step, as the spring's, not
    by the difference of two segments' gaps, which made the force jump), e_mid
    the mean of both. Incremental, so a falling time step (rising kd)
    stiffens the next increments but never makes the force jump at a fixed
    gap (the total form F_total with k_x(dt) would inject energy whenever dt
    falls with the node deep in the zone, and feed a collapsing step back
    into the force); a rising step lowers the cap (a drop: dissipative).
    """
    if gap <= g1 or kd <= k:
        return k * gap, 0.0
    kx = kd - k
    e = gap - g1
    ep = gap_prev - g1
    if ep < 0.0:
        ep = 0.0
    # ramp: the extra stiffness rises linearly over the first `ramp` mm (no kink)
    em = 0.5 * (e + ep)
    r = em / ramp if ramp > 0.0 and em < ramp else 1.0
    fd = fd_prev + r * kx * (e - ep)
    cap = kx * (e - 0.5 * ramp) if e > ramp else 0.5 * kx * e * e / ramp
    if fd < 0.0:
        fd = 0.0
    elif fd > cap:
        fd = cap
    return k * gap + fd, fd


@njit(cache=True, inline="always")
def spring_force(gap, gap_prev, f_prev, k, dn, same, held):
    """Spring part of the normal force (kN) at penetration gap (mm), incremental.

    ``same``: in contact with the same segment last cycle (gap_prev mm its gap
    then, f_prev kN the spring force then): ``F = f_prev + k (gap - gap_prev)``.
    ``held`` but not same (the node moved on to another segment, whose gap may
    differ from the last one's by a fold's angle): ``F = f_prev - k dn`` with
    dn = v_n dt (mm) the normal relative motion of this step (negative when
    approaching). A fresh contact: ``F = k max(0, -dn)``, the penetration made
    by this step's approach (a node arriving through the face within one step
    has ``gap <= -dn``: ``F = k gap``). Always ``0 <= F <= k gap``. The caller
    passes ``dn = -gap`` at the first call of a run, so that initial
    penetrations between surfaces not joined by the mesh push apart.

    Why: with the total form ``k gap`` every jump of the gap at a fixed position
    (a change of segment across a fold, a rise of k) is a jump of the force,
    and the node is pushed out with more energy than it came in with; in
    folding shell walls this made the contact energy negative (hollow block,
    40 km/h: -23 J of 309 J). Incremental, k may change from cycle to cycle
    (the stability cap follows the springs on each node) without a force jump;
    a drop of k lowers the bound ``k gap`` (dissipative, never generative).
    A fresh contact found deep -- a node entering a segment's contact zone
    sideways, over its edge, in a fold -- is held where it is: with ``k gap``
    its spring starts with ``k gap^2 / 2`` of energy from nothing, which it
    gives to the node on the way out (axial crush of the circular aluminium
    tube D/t 30, shell drilling factor 0: 2749 fresh self-contacts created
    651 J so, contact energy -549 J, -17.5 % of the total; now +116 J).
    """
    if same:
        f = f_prev + k * (gap - gap_prev)
    elif held:
        f = f_prev - k * dn
    else:
        f = -k * dn
    top = k * gap
    if f > top:
        return top
    if f < 0.0:
        return 0.0
    return f


@njit(cache=True, inline="always")
def stable_stiffness(nd, a, b, c, d, w0, w1, w2, w3, mloc, wsum, limit, dt):
    """Largest spring stiffness (kN/mm) of the pair node nd - segment (a, b, c, d)
    (shape functions w at the contact point) that keeps every movable node j of
    the pair within ``(omega dt)^2 = limit`` with all its contact springs of this
    cycle together (0: no bound, every participant immovable).

    Row-sum (Gershgorin) bound of the pair stiffness ``k u u^T`` over the movable
    participants, u = (1, -w): row j is ``k |u_j| S`` with S the sum of |u| over
    them (2 for a node on a deformable segment, 1 against a rigid or fixed one);
    with W_j the summed weights of this cycle's springs on j,
    ``k W_j S / m_j <= limit / dt^2``. mloc (L,) kg (inf: rigid or fixed),
    wsum (L,) -, dt ms.
    """
    s = 0.0
    if mloc[nd] < 1.0e300:
        s += 1.0
    if w0 > 0.0 and mloc[a] < 1.0e300:
        s += w0
    if w1 > 0.0 and mloc[b] < 1.0e300:
        s += w1
    if w2 > 0.0 and mloc[c] < 1.0e300:
        s += w2
    if w3 > 0.0 and d != c and mloc[d] < 1.0e300:
        s += w3
    m = mloc[nd] / max(wsum[nd], 1.0)
    if w0 > 0.0:
        m = min(m, mloc[a] / max(wsum[a], w0))
    if w1 > 0.0:
        m = min(m, mloc[b] / max(wsum[b], w1))
    if w2 > 0.0:
        m = min(m, mloc[c] / max(wsum[c], w2))
    if w3 > 0.0 and d != c:
        m = min(m, mloc[d] / max(wsum[d], w3))
    dt2 = dt * dt
    if m >= 1.0e300 or not dt2 > 0.0 or s <= 0.0:
        return 0.0
    return limit * m / (s * dt2)


@njit(cache=True, inline="always")
def deep_stiffness(nd, a, b, c, d, w0, w1, w2, w3, mloc, wsum, limit, dt):
    """Tangent stiffness (kN/mm) of the stiffened zone for the pair node nd - segment
    (a, b, c, d) with shape functions w at the contact point.

    The largest stiffness for which no participating node j (the node, the
    segment's corners with w > 0; rigid ones, mloc = inf, left out) exceeds
    ``(omega dt)^2 = limit`` from all its contact springs together, by the
    row-sum (Gershgorin) bound of the pair stiffness ``k u u^T``,
    u = (1, -w): ``2 k W_j / m_j <= limit / dt^2`` with W_j the summed weights
    of the springs on j in this cycle (at least 1). mloc (L,) kg,
    wsum (L,) -, dt ms. 0 when every participant is rigid.
    """
    m = mloc[nd] / max(wsum[nd], 1.0)
    if w0 > 0.0:
        m = min(m, mloc[a] / max(wsum[a], 1.0))
    if w1 > 0.0:
        m = min(m, mloc[b] / max(wsum[b], 1.0))
    if w2 > 0.0:
        m = min(m, mloc[c] / max(wsum[c], 1.0))
    if w3 > 0.0 and d != c:
        m = min(m, mloc[d] / max(wsum[d], 1.0))
    dt2 = dt * dt
    if m >= 1.0e300 or not dt2 > 0.0:
        return 0.0
    return 0.5 * limit * m / dt2


@njit(cache=True)
def pushed_through(px, py, pz, tn, x, seg, s_thick, s_depth, s_two, s, mx, my, mz, extra):
    """s if the node at p (thickness tn) is behind segment s, the one it was in
    contact with last cycle (with contact normal m, zero if unknown), by more
    than the release depth (plus extra mm, the penetration held, see
    :func:`spring_force`), else -1."""
    a = seg[s, 0]
    b = seg[s, 1]
    c = seg[s, 2]
    dd = seg[s, 3]
    ok, inside, qx, qy, qz, nx, ny, nz, w0, w1, w2, w3 = project_corners(
        px, py, pz, x[a, 0], x[a, 1], x[a, 2], x[b, 0], x[b, 1], x[b, 2],
        x[c, 0], x[c, 1], x[c, 2], x[dd, 0], x[dd, 1], x[dd, 2], c == dd)
    if not ok:
        return -1
    wmin = min(w0, w1, w2) if c == dd else min(w0, w1, w2, w3)
    if wmin < _THRU_MIN_WEIGHT:
        return -1  # slid off the segment
    d = (px - qx) * nx + (py - qy) * ny + (pz - qz) * nz
    two = s_two[s] != 0
    if two:
        al = nx * mx + ny * my + nz * mz
        if al > -0.5 and al < 0.5:
            return -1  # side unknown
        if al < 0.0:
            d = -d
    reach = 0.5 * (tn + s_thick[s])
    if d <= -(release_depth(s_depth[s], reach, two) + extra):
        return s
    return -1
