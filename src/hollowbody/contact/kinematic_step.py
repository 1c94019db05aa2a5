"""Kinematic step limit of a penalty contact: no node crosses its contact band in one step.

A penalty contact can only push on a node it sees inside the contact band: for
a two-sided segment (shell) the ``reach = (t_node + t_seg) / 2`` on either side
of the mid-surface, for a one-sided (solid) face the ``reach`` in front of it
plus the release depth behind it. The element step does not know about
contacts: a heavy plate closing on soft tissue at 20-30 mm/ms moves 1-2 mm per
element step, as much as its 2 mm contact half thickness, so nodes land past
the mid-surface before the contact first sees them and are pushed out through
the far side; and the step that falls at first contact (the struck layer's
bulk viscosity) costs the central-difference scheme energy in proportion to
the force already acting (``-(dt_n^2 - dt_{n-1}^2) sum |f|^2 / (8 m)``).

The limit, per near pair (node, segment) whose node lies over the segment
(inside its circumscribed circle) and closes on it at ``w`` mm/ms (relative
velocity to the segment's mean nodal velocity along its normal, towards the
mid-surface of a two-sided segment, into a one-sided face), with ``D`` the
node's distance to the far edge of the band (the mid-surface, or the release
plane of a one-sided face) and ``B`` the band's width::

    dt_kin = max(alpha B, D - (1 - alpha) B) / w,    alpha = KIN_FRACTION = 0.5

A node outside the band lands at most ``alpha B`` inside it; a node inside
moves at most ``alpha B`` per step, so it is seen at least twice before it
reaches the mid-surface. Unlike the nodal rule ``(B - p) / (2 w)`` of
Radioss's interface step (which shrinks with the penetration p and can
collapse under a deep node) the travel allowed inside the band does not
shrink. It binds only where a contact closes fast on a coarse mesh; in a car
crash mesh (steps of ~1 us) it never does. The pairs are only visited when it
can bind: a closing speed is at most twice the largest nodal speed of the
contact, so no pair limits a step below ``KIN_FRACTION B_min / (2 v_max)``
(:func:`narrowest_band`, :func:`max_speed2`).

Units: mm, ms, mm/ms. Kernels: numba, no allocation in the loops.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numba import njit, prange

from hollowbody.contact.detect import CHUNK

#: Fraction of the contact band a node may cross per step (module docstring).
KIN_FRACTION = 0.5
#: Relative slack of the skip test ``travel > best * wmax``: a pair is skipped only when
#: its time at the fastest closing speed is above the best by more than round-off.
_BOUND_SLACK = 1.0 + 1.0e-12


@njit(cache=True)
def _pair_range(i0, i1, act, x, v, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm,
                rad2, ptr, cand, alpha, limit, wmax):
    """Smallest dt_kin (ms) below ``limit`` over the near pairs of rows act[i0:i1], and
    its row; (inf, -1) when none is below. ``wmax`` (mm/ms): a bound on every pair's
    closing speed; a pair whose travel needs at least the best time so far at that
    speed is not looked at further (its segment's velocity is not gathered)."""
    best = limit
    row = -1
    for ii in range(i0, i1):
        i = act[ii]
        nd = nodes[i]
        for j in range(ptr[i], ptr[i + 1]):
            s = cand[j]
            px = x[nd, 0] - cen[s, 0]
            py = x[nd, 1] - cen[s, 1]
            pz = x[nd, 2] - cen[s, 2]
            nx = nrm[s, 0]
            ny = nrm[s, 1]
            nz = nrm[s, 2]
            dist = px * nx + py * ny + pz * nz
            if px * px + py * py + pz * pz - dist * dist > rad2[s]:
                continue  # beside the segment, not over it
            reach = 0.5 * (n_thick[i] + s_thick[s])
            two = s_two[s] != 0
            if two:
                far = abs(dist)
                band = reach
            else:
                far = dist + s_depth[s]
                band = reach + s_depth[s]
            if band <= 0.0 or far < 0.0:
                continue
            travel = max(alpha * band, far - (1.0 - alpha) * band)
            if travel > best * wmax * _BOUND_SLACK:
                continue  # slower than the best so far even at the fastest closing speed
            a = seg[s, 0]
            b = seg[s, 1]
            c = seg[s, 2]
            d = seg[s, 3]
            if d == c:
                vx = (v[a, 0] + v[b, 0] + v[c, 0]) / 3.0
                vy = (v[a, 1] + v[b, 1] + v[c, 1]) / 3.0
                vz = (v[a, 2] + v[b, 2] + v[c, 2]) / 3.0
            else:
                vx = 0.25 * (v[a, 0] + v[b, 0] + v[c, 0] + v[d, 0])
                vy = 0.25 * (v[a, 1] + v[b, 1] + v[c, 1] + v[d, 1])
                vz = 0.25 * (v[a, 2] + v[b, 2] + v[c, 2] + v[d, 2])
            rate = (v[nd, 0] - vx) * nx + (v[nd, 1] - vy) * ny + (v[nd, 2] - vz) * nz
            if two:
                w = -rate if dist >= 0.0 else rate
            else:
                w = -rate
            if w <= 0.0:
                continue
            dtk = travel / w
            if dtk < best:
                best = dtk
                row = i
    if row < 0:
        return math.inf, -1
    return best, row


@njit(cache=True, parallel=True)
def approach_step(act, x, v, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm, rad2, ptr,
                  cand, alpha, out_dt, out_row, limit=math.inf, wmax=math.inf):
    """dt_kin of one pass (module docstring), threaded over chunks of rows.

    act (m,) int32 rows to treat; x, v (L, 3) float64 mm, mm/ms (local rows, v at
    the half step); nodes (ns,) int32 rows of x; n_thick (ns,) mm; seg (S, 4) int32;
    s_thick, s_depth (S,) mm; s_two (S,) int8 1 = two-sided; cen, nrm (S, 3), rad2
    (S,) mm^2: :func:`~hollowbody.contact.frames.segment_frames` (current for the
    segments of the near lists); ptr (ns + 1,) int64, cand int32: near lists;
    alpha: KIN_FRACTION. out_dt (>= chunks,) float64, out_row (>= chunks,) int64:
    work arrays. limit (ms): only steps below it are looked for (the step the solver
    would take); wmax (mm/ms): a bound on every closing speed (twice the largest nodal
    speed; inf: no pair is skipped). Returns (dt_kin ms, row of ``nodes``); (inf, -1)
    when no pair closes fast enough to need a step below ``limit``.
    """
    m = act.shape[0]
    nch = (m + CHUNK - 1) // CHUNK
    for ch in prange(nch):
        out_dt[ch], out_row[ch] = _pair_range(ch * CHUNK, min(m, (ch + 1) * CHUNK), act, x, v,
                                              nodes, n_thick, seg, s_thick, s_depth, s_two, cen,
                                              nrm, rad2, ptr, cand, alpha, limit, wmax)
    best = math.inf
    row = -1
    for ch in range(nch):
        if out_dt[ch] < best:
            best = out_dt[ch]
            row = out_row[ch]
    return best, row


@njit(cache=True)
def approach_step_serial(act, x, v, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm,
                         rad2, ptr, cand, alpha, out_dt, out_row, limit=math.inf,
                         wmax=math.inf):
    """Serial :func:`approach_step` (small passes: no thread start-up)."""
    return _pair_range(0, act.shape[0], act, x, v, nodes, n_thick, seg, s_thick, s_depth,
                       s_two, cen, nrm, rad2, ptr, cand, alpha, limit, wmax)


@njit(cache=True)
def max_speed2(v):
    """Largest squared speed (mm/ms)^2 of the rows of v (L, 3) float64 mm/ms."""
    best = 0.0
    for i in range(v.shape[0]):
        s = v[i, 0] * v[i, 0] + v[i, 1] * v[i, 1] + v[i, 2] * v[i, 2]
        if s > best:
            best = s
    return best


def narrowest_band(n_thick: np.ndarray, s_thick: np.ndarray, s_depth: np.ndarray,
                   s_two: np.ndarray) -> float:
    """Narrowest positive contact band (mm) a pair of the pass can have (inf: none):
    with the thinnest node, reach over two-sided segments, reach plus release depth
    over one-sided ones. Every pair's dt_kin is at least KIN_FRACTION times this over
    its closing speed, which is at most twice the largest nodal speed."""
    if n_thick.size == 0 or s_thick.size == 0:
        return np.inf
    band = 0.5 * (float(n_thick.min()) + s_thick) + np.where(s_two != 0, 0.0, s_depth)
    band = band[band > 0.0]
    return float(band.min()) if band.size else np.inf


def work_arrays(n_rows: int) -> tuple[np.ndarray, np.ndarray]:
    """Per-chunk work arrays of :func:`approach_step` for a pass of ``n_rows`` nodes."""
    n = max((n_rows + CHUNK - 1) // CHUNK, 1)
    return np.full(n, np.inf), np.full(n, -1, np.int64)


def passes_step(passes: Sequence, xl: np.ndarray, vl: np.ndarray, dt_next: float,
                threaded: Callable[[object], bool]) -> float:
    """dt_kin (ms) over the passes of a contact when it is below ``dt_next``; inf when
    no pair needs a step below it, at once when the bound ``KIN_FRACTION B_min /
    (2 v_max)`` is at least ``dt_next``. Pairs that cannot beat ``dt_next`` or the best
    so far even at the closing speed ``2 v_max`` are skipped before their segment's
    velocity is gathered.

    passes: the contact's passes with segments (``_Pass``: act, nodes, n_thick, seg,
    s_thick, s_depth, s_two, cen, nrm, rad2, nptr, ncand, kin_band, work arrays),
    detected this cycle; xl, vl (L, 3) mm, mm/ms: the contact's gathered coordinates
    and half-step velocities; threaded(p): use the threaded kernel for pass p.
    """
    if not passes:
        return math.inf
    for p in passes:
        if p.kin_band is None:
            p.kin_band = narrowest_band(p.n_thick, p.s_thick, p.s_depth, p.s_two)
    band = min(p.kin_band for p in passes)
    vmax = 2.0 * math.sqrt(max_speed2(vl))
    if not math.isfinite(band) or KIN_FRACTION * band >= vmax * dt_next:
        return math.inf
    best = math.inf
    for p in passes:  # only steps below dt_next and the passes' best so far are sought
        d, _ = (approach_step if threaded(p) else approach_step_serial)(
            p.act, xl, vl, p.nodes, p.n_thick, p.seg, p.s_thick, p.s_depth, p.s_two, p.cen,
            p.nrm, p.rad2, p.nptr, p.ncand, KIN_FRACTION, p._kin_dt, p._kin_row,
            min(best, dt_next), vmax)
        best = min(best, float(d))
    return best
