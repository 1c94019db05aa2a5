"""Node-to-segment contact detection of a penalty pass (numba kernels).

One *pass* checks a list of nodes against a list of segments (the bucket
sort's candidates). For node s and the nearest candidate segment it is
inside of (closest-point projection x_p, unit normal n, shape functions
N_a at x_p; see :mod:`hollowbody.contact.geometry`), with d = (x_s - x_p) . n
and reach = (t_node + t_seg) / 2:

* one-sided (solid faces, outward n): contact when -depth < d < reach,
  penetration g = reach - d, force direction +n; ``depth`` is the release
  depth (``penmax`` times the depth V / A of the element under the face);
* two-sided (shells, free segments): a node arriving contacts when
  |d| < reach, g = reach - |d|, direction sign(d) n; while it stays in
  contact it keeps that side (the last contact normal is remembered), so a
  node pushed past the mid-surface is still pushed back,
  g = reach - sign * d up to the release depth behind the mid-surface,
  ``max(penmax * sqrt(A), reach)``: never less than the contact half
  thickness, else a node released inside the shell's own contact thickness
  would at once be caught from the far side and pushed through.

Before the projection a pair must pass cheap tests that only drop pairs which
cannot win: distance from the segment's mean plane, the bound from the best
pair so far, the circumscribed circle, and the segment's two slabs
(:func:`~hollowbody.contact.frames.slab_bound`: no foot point inside the
segment within the contact distance and the best distance so far).

The far face of a layer: a node behind a one-sided face is not in contact with
it when a nearer one-sided face that it is in front of faces the opposite way
(it is outside the layer there; the small inner face of a wedge-shaped flesh
element round a bone reaches past the outer face with PENMAX of its V / A).
A contact whose normal turns against last cycle's starts as a new contact
(``sold`` -1: nothing carried over, see :mod:`hollowbody.contact.penalty`).

Ties go to the lowest segment number. A node that projects onto no
candidate but lies within ``HOLD_TOL`` (natural coordinates) of the segment it
was in contact with last cycle keeps that segment: behind a convex edge of the
surface it projects onto neither face (see
:data:`~hollowbody.contact.law.HOLD_TOL`). Pass-through detection: a node that
was in contact with segment s in the previous cycle, had entered that
contact from outside (first gap at most ``ENTRY_FRACTION`` of the
penetration at release) and is now behind s (on the side opposite to the one
it was pushed to) by more than the release depth has been pushed through the
surface; its row of ``othru`` gets s (else -1), see
:class:`~hollowbody.contact.runtime.ContactRuntime`.

Detection runs for every pass of a contact before any force is computed
(:mod:`hollowbody.contact.penalty`), so that the force of each pair knows how
many springs act on each node in this very cycle. Per-node results are
computed in parallel (``prange`` over chunks of nodes, each row written only
by its own node); no allocation in the loops.
"""

from __future__ import annotations

from numba import njit, prange

from hollowbody.contact.frames import slab_bound
from hollowbody.contact.geometry import project_corners
from hollowbody.contact.law import ENTRY_FRACTION, HOLD_TOL, pushed_through, release_depth

#: Nodes per parallel work item: array arguments cost an incref/decref per call,
#: so kernels are called per chunk, not per item; small enough that the nodes in
#: contact (the costly ones, clustered in the numbering) spread over the threads.
CHUNK = 64
#: mm: slack of the bound |d| >= |(p - cen) . n| - 1.05 warp (the segment lies
#: within +-warp of its mean plane, and within +-1.0201 warp when its natural
#: coordinates reach 1 + INSIDE_TOL; at a converged foot point |d| = |p - x_p|),
#: for round-off and the Newton tolerance: a candidate whose bound is beyond the
#: best distance so far cannot win and is not projected.
_BOUND_EPS = 1.0e-6


@njit(cache=True)
def _detect_range(i0, i1, act, x, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm, rad2,
                  warp, slab, ptr, cand, nprev, oseg, ow, ogap, oentry, othru, gold, sold, orel,
                  odel):
    """Detection for the rows act[i0:i1] of a pass (body of :func:`detect_pass`)."""
    for ii in range(i0, i1):
        i = act[ii]
        nd = nodes[i]
        px = x[nd, 0]
        py = x[nd, 1]
        pz = x[nd, 2]
        tn = n_thick[i]
        mx = nprev[i, 0]
        my = nprev[i, 1]
        mz = nprev[i, 2]
        fresh = mx == 0.0 and my == 0.0 and mz == 0.0
        best = -1
        best_ad = 1.0e300
        bgap = 0.0
        brel = 0.0
        bnx = bny = bnz = 0.0
        bw0 = bw1 = bw2 = bw3 = 0.0
        breach = 0.0
        fad = 1.0e300
        fnx = fny = fnz = 0.0
        held = False
        hgap = hrel = 0.0
        hnx = hny = hnz = 0.0
        hw0 = hw1 = hw2 = hw3 = 0.0
        # the segment in contact last cycle first (when listed): its distance then
        # lets the bound below skip the projection onto most other candidates
        prev = oseg[i]
        qf = -1
        if prev >= 0:
            for q in range(ptr[i], ptr[i + 1]):
                if cand[q] == prev:
                    qf = q
                    break
        for k in range(-1 if qf >= 0 else 0, ptr[i + 1] - ptr[i]):
            if k < 0:
                q = qf
            else:
                q = ptr[i] + k
                if q == qf:
                    continue
            s = cand[q]
            reach = 0.5 * (tn + s_thick[s])
            two = s_two[s] != 0
            rel = release_depth(s_depth[s], reach, two)
            # the segment of last cycle holds the node deeper by the penetration it
            # was found with and is not pushed back from (odel, see spring_force)
            ext = odel[i] if s == prev else 0.0
            # largest |d| that can be accepted: a node not in contact last cycle (no
            # remembered normal) meets a two-sided segment only within its reach
            lim = reach if (two and fresh) else max(reach, rel + ext)
            rx = px - cen[s, 0]
            ry = py - cen[s, 1]
            rz = pz - cen[s, 2]
            dn = rx * nrm[s, 0] + ry * nrm[s, 1] + rz * nrm[s, 2]
            r2 = rad2[s]
            if abs(dn) > lim + warp[s]:
                continue
            if abs(dn) - 1.05 * warp[s] - _BOUND_EPS > best_ad:
                continue  # every point of s is farther than the best: it cannot win
            if rx * rx + ry * ry + rz * rz - dn * dn > 1.1 * r2:
                continue
            # no foot point within the contact distance and the best one so far (not
            # tested for last cycle's segment: always projected, its result is needed)
            if k >= 0 and slab_bound(s, rx, ry, rz, min(lim, best_ad), slab):
                continue
            a = seg[s, 0]
            b = seg[s, 1]
            c = seg[s, 2]
            dd = seg[s, 3]
            xi0 = 0.0
            eta0 = 0.0
            if k < 0:  # last cycle's segment: Newton from last cycle's contact point
                xi0 = ow[i, 1] + ow[i, 2] - ow[i, 0] - ow[i, 3]
                eta0 = ow[i, 2] + ow[i, 3] - ow[i, 0] - ow[i, 1]
            ok, inside, qx, qy, qz, nx, ny, nz, w0, w1, w2, w3 = project_corners(
                px, py, pz, x[a, 0], x[a, 1], x[a, 2], x[b, 0], x[b, 1], x[b, 2],
                x[c, 0], x[c, 1], x[c, 2], x[dd, 0], x[dd, 1], x[dd, 2], c == dd, xi0, eta0)
            over_edge = False
            if k < 0 and ok and not inside:
                # just off last cycle's segment: over a convex edge of the surface a
                # node behind it projects onto neither face; it stays in contact with
                # that segment (taken only if no segment has it inside)
                ok, inside, qx, qy, qz, nx, ny, nz, w0, w1, w2, w3 = project_corners(
                    px, py, pz, x[a, 0], x[a, 1], x[a, 2], x[b, 0], x[b, 1], x[b, 2],
                    x[c, 0], x[c, 1], x[c, 2], x[dd, 0], x[dd, 1], x[dd, 2], c == dd, xi0,
                    eta0, HOLD_TOL)
                over_edge = True
            if not (ok and inside):
                continue
            d = (px - qx) * nx + (py - qy) * ny + (pz - qz) * nz
            ad = abs(d)
            if two:
                # side: the one the node was pushed to last cycle when that
                # contact normal is about parallel to this segment's, else its side now
                al = nx * mx + ny * my + nz * mz
                if al > 0.5 or al < -0.5:
                    sg = 1.0 if al > 0.0 else -1.0
                    de = sg * d
                    if de >= reach or de <= -(rel + ext):
                        continue
                    gap = reach - de
                else:
                    if ad >= reach:
                        continue
                    gap = reach - ad
                    sg = 1.0 if d >= 0.0 else -1.0
                nx *= sg
                ny *= sg
                nz *= sg
            else:
                if d >= 0.0 and ad < fad and not over_edge:
                    # the nearest face the node is in front of (outside the body there)
                    fad = ad
                    fnx = nx
                    fny = ny
                    fnz = nz
                if d >= reach or d <= -(rel + ext):
                    continue
                gap = reach - d
            if over_edge:
                held = True
                hgap = gap
                hrel = reach + rel
                hnx = nx
                hny = ny
                hnz = nz
                hw0 = w0
                hw1 = w1
                hw2 = w2
                hw3 = w3
                continue
            if ad < best_ad or (ad == best_ad and s < best):  # ties: lowest segment
                best_ad = ad
                best = s
                bgap = gap
                breach = reach
                brel = reach + rel
                bnx = nx
                bny = ny
                bnz = nz
                bw0 = w0
                bw1 = w1
                bw2 = w2
                bw3 = w3
        if (best >= 0 and s_two[best] == 0 and bgap > breach and fad < best_ad
                and fnx * bnx + fny * bny + fnz * bnz < 0.0):
            # behind a face (a layer's inner face) while nearer to a face of the other
            # side of the layer that it is in front of: it is outside that layer, not
            # in it (the bore face of a flesh tube seen from its outer face)
            best = -1
        if best < 0 and held:
            best = prev
            bgap = hgap
            brel = hrel
            bnx = hnx
            bny = hny
            bnz = hnz
            bw0 = hw0
            bw1 = hw1
            bw2 = hw2
            bw3 = hw3
        # a contact whose normal turned against last cycle's is a new contact: the
        # force pushed the node the other way (a fold's opposite layer)
        first = prev
        if best >= 0 and prev >= 0 and bnx * mx + bny * my + bnz * mz < 0.0:
            first = -1
        # a fresh contact starts the stiffening from its first gap (no increment)
        gold[i] = ogap[i] if first >= 0 else bgap
        sold[i] = first
        othru[i] = -1
        if prev >= 0 and prev != best and oentry[i] != 0:
            othru[i] = pushed_through(px, py, pz, tn, x, seg, s_thick, s_depth, s_two, prev,
                                       mx, my, mz, odel[i])
        oseg[i] = best
        if best < 0:
            ogap[i] = 0.0
            oentry[i] = 0
            nprev[i, 0] = 0.0
            nprev[i, 1] = 0.0
            nprev[i, 2] = 0.0
            continue
        if first < 0:  # entered from outside: shallow first gap
            oentry[i] = 1 if bgap <= ENTRY_FRACTION * brel else 0
        nprev[i, 0] = bnx
        nprev[i, 1] = bny
        nprev[i, 2] = bnz
        ow[i, 0] = bw0
        ow[i, 1] = bw1
        ow[i, 2] = bw2
        ow[i, 3] = bw3
        ogap[i] = bgap
        orel[i] = brel


@njit(cache=True, parallel=True)
def detect_pass(act, x, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm, rad2, warp,
                slab, ptr, cand, nprev, oseg, ow, ogap, oentry, othru, gold, sold, orel, odel):
    """Find the contact segment of the nodes act of one pass.

    act (m,) int32: the rows of ``nodes`` to treat
    (:func:`~hollowbody.contact.penalty.active_rows`). x (L, 3) float64 mm
    (local rows); nodes (ns,) int32 rows of x; n_thick (ns,) mm; seg (S, 4)
    int32 rows of x; s_thick (S,) mm; s_depth (S,) mm release depth; s_two
    (S,) int8 1 = two-sided; cen, nrm, rad2, warp, slab:
    :func:`~hollowbody.contact.frames.segment_frames`; ptr (ns + 1,) int64,
    cand int32: candidate segments per node.
    In/out (last cycle's in, this cycle's out): nprev (ns, 3) contact normal
    (zero when not in contact; two-sided side memory), oseg (ns,) int32
    segment in contact or -1, ogap (ns,) mm penetration, oentry (ns,) int8 1
    when the contact began shallow. Out: ow (ns, 4) shape functions at the
    contact point, othru (ns,) int32 segment the node was pushed through or -1,
    and for the force pass gold (ns,) mm last cycle's gap (this one's for a
    fresh contact), sold (ns,) int32 last cycle's segment, orel (ns,) mm
    penetration at release. odel (ns,) mm (in): the part of last cycle's
    penetration the spring force does not push back from
    (:func:`~hollowbody.contact.law.spring_force`); the node is released from
    that segment that much deeper.
    """
    ns = act.shape[0]
    nch = (ns + CHUNK - 1) // CHUNK
    for c in prange(nch):
        _detect_range(c * CHUNK, min(ns, (c + 1) * CHUNK), act, x, nodes, n_thick, seg,
                      s_thick, s_depth, s_two, cen, nrm, rad2, warp, slab, ptr, cand, nprev, oseg,
                      ow, ogap, oentry, othru, gold, sold, orel, odel)


@njit(cache=True)
def detect_pass_serial(act, x, nodes, n_thick, seg, s_thick, s_depth, s_two, cen, nrm, rad2,
                       warp, slab, ptr, cand, nprev, oseg, ow, ogap, oentry, othru, gold, sold,
                       orel, odel):
    """Serial :func:`detect_pass` (small passes: no thread start-up)."""
    _detect_range(0, act.shape[0], act, x, nodes, n_thick, seg, s_thick, s_depth, s_two, cen,
                  nrm, rad2, warp, slab, ptr, cand, nprev, oseg, ow, ogap, oentry, othru, gold,
                  sold, orel, odel)
