"""Node-to-segment penalty contact with Coulomb friction (numba kernels).

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

Normal force ``F_n = k g`` up to ``g1 = stiffen * G`` (G = reach + release
depth, the penetration at which the node would be released); deeper, the
tangent stiffness rises incrementally to the largest value that keeps every
node the spring acts on stable at the *current* step with all its contact
springs together, ``(omega dt)^2 <= 0.5`` (see :mod:`hollowbody.contact.law`).
So the force a node can carry before release follows the stiffening of the
material under it (whose wave speed sets dt) and the speed of the impact,
without exceeding the explicit stability limit. Minus the optional VDC
damping ``c v_n`` (never adhesive). Friction by an elastic trial with the
spring k::

    f* = f_t(old, rotated into the current tangent plane) - k * v_t * dt
    mu = FD + (FS - FD) * exp(-DC * |v_t|)
    f_t = f* if |f*| <= mu F_n else mu F_n f* / |f*|

(v_t the tangential velocity of the node relative to the contact point;
f_t is stored per node between cycles). The pair force F = F_n n' + f_t acts
on the node and -N_a F on the segment's nodes: momentum is conserved exactly.

Pass-through detection: a node that was in contact with segment s in the
previous cycle, had entered that contact from outside (first gap at most
``ENTRY_FRACTION`` of the penetration at release) and is now behind s (on
the side opposite to the one it was pushed to) by more than the release
depth has been pushed through the surface; its row of ``othru`` gets s
(else -1), see :class:`~hollowbody.contact.runtime.ContactRuntime`.

Per-node results are computed in parallel (``prange`` over nodes, each writes
only its own row), then scattered serially (race-free). No allocation in the
loops.
"""

from __future__ import annotations

import math

from numba import njit, prange

from hollowbody.contact.geometry import project_corners
from hollowbody.contact.law import (
    DT_FLOOR,
    ENTRY_FRACTION,
    STIFFEN_FRACTION,
    deep_stiffness,
    penalty_force,
    pushed_through,
    release_depth,
)

#: Nodes per parallel work item: array arguments cost an incref/decref per call,
#: so kernels are called per chunk, not per item; small enough that the nodes in
#: contact (the costly ones, clustered in the numbering) spread over the threads.
_CHUNK = 64
#: mm: slack of the bound |d| >= |(p - cen) . n| - 1.05 warp (the segment lies
#: within +-warp of its mean plane, and within +-1.0201 warp when its natural
#: coordinates reach 1 + INSIDE_TOL; at a converged foot point |d| = |p - x_p|),
#: for round-off and the Newton tolerance: a candidate whose bound is beyond the
#: best distance so far cannot win and is not projected.
_BOUND_EPS = 1.0e-6


@njit(cache=True)
def _nodes_range(i0, i1, act, x, v, dt, dtc, nodes, n_thick, n_k, n_mass, seg, s_thick, s_k,
                 s_mass, s_depth, s_two, cen, nrm, rad2, warp, ptr, cand, params, mloc, wprev,
                 imm, ft, nprev, oseg, ow, of, ogap, ofd, oentry, othru):
    """Contact of the rows act[i0:i1] of a pass (body of :func:`contact_pass`)."""
    slsfac = params[0]
    soft = params[1]
    sofscl = params[2]
    fs = params[3]
    fd = params[4]
    dc = params[5]
    vdc = params[6]
    fric = params[7] > 0.0
    stiffen = params[8]
    deep = params[9]
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
            # largest |d| that can be accepted: a node not in contact last cycle (no
            # remembered normal) meets a two-sided segment only within its reach
            lim = reach if (two and fresh) else max(reach, rel)
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
                    if de >= reach or de <= -rel:
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
                if d >= reach or d <= -rel:
                    continue
                gap = reach - d
            if ad < best_ad or (ad == best_ad and s < best):  # ties: lowest segment
                best_ad = ad
                best = s
                bgap = gap
                brel = reach + rel
                bnx = nx
                bny = ny
                bnz = nz
                bw0 = w0
                bw1 = w1
                bw2 = w2
                bw3 = w3
        # a fresh contact starts the stiffening from its first gap (no increment)
        gprev = ogap[i] if prev >= 0 else bgap
        othru[i] = -1
        if prev >= 0 and prev != best and oentry[i] != 0:
            othru[i] = pushed_through(px, py, pz, tn, x, seg, s_thick, s_depth, s_two, prev,
                                       mx, my, mz)
        oseg[i] = best
        if best < 0:
            ft[i, 0] = 0.0
            ft[i, 1] = 0.0
            ft[i, 2] = 0.0
            of[i, 0] = 0.0
            of[i, 1] = 0.0
            of[i, 2] = 0.0
            ogap[i] = 0.0
            ofd[i] = 0.0
            oentry[i] = 0
            nprev[i, 0] = 0.0
            nprev[i, 1] = 0.0
            nprev[i, 2] = 0.0
            continue
        if prev < 0:  # entered from outside: shallow first gap
            oentry[i] = 1 if bgap <= ENTRY_FRACTION * brel else 0
        nprev[i, 0] = bnx
        nprev[i, 1] = bny
        nprev[i, 2] = bnz
        s = best
        ow[i, 0] = bw0
        ow[i, 1] = bw1
        ow[i, 2] = bw2
        ow[i, 3] = bw3
        ogap[i] = bgap
        # stiffness: SOFT=0 minimum of node and segment (PENOPT=1), SOFT=1 max with mass-based
        kn = n_k[i]
        ks = s_k[s]
        if kn > 0.0 and ks > 0.0:
            k0 = slsfac * min(kn, ks)
        else:
            k0 = slsfac * max(kn, ks)
        mn = n_mass[i]
        ms = s_mass[s]
        mstar = min(mn, ms)
        k = k0
        if dtc * dtc > 0.0 and mstar < 1.0e300:
            k1 = 0.5 * mstar / (dtc * dtc)
            if soft > 0.0:
                k = max(k0, sofscl * k1)
            elif k0 <= 0.0:
                k = 0.1 * k1  # no element behind either side: SOFT=1 default scale
        # relative velocity node - contact point
        a = seg[s, 0]
        b = seg[s, 1]
        c = seg[s, 2]
        dd = seg[s, 3]
        vrx = v[nd, 0] - (bw0 * v[a, 0] + bw1 * v[b, 0] + bw2 * v[c, 0] + bw3 * v[dd, 0])
        vry = v[nd, 1] - (bw0 * v[a, 1] + bw1 * v[b, 1] + bw2 * v[c, 1] + bw3 * v[dd, 1])
        vrz = v[nd, 2] - (bw0 * v[a, 2] + bw1 * v[b, 2] + bw2 * v[c, 2] + bw3 * v[dd, 2])
        vn = vrx * bnx + vry * bny + vrz * bnz
        g1 = stiffen * brel
        if (stiffen >= 1.0 and imm[nd] != 0 and (bw0 <= 0.0 or imm[a] != 0)
                and (bw1 <= 0.0 or imm[b] != 0) and (bw2 <= 0.0 or imm[c] != 0)
                and (bw3 <= 0.0 or dd == c or imm[dd] != 0)):
            # nothing in the pair can be set in motion but a rigid body (a rigid
            # impactor on a fixed base): the stiffened zone holds the body
            g1 = STIFFEN_FRACTION * brel
        kd = 0.0
        if bgap > g1:
            # the step, floored at DT_FLOOR of the reference step: a collapsing
            # element (which ends the run anyway) does not drive the force up
            kd = deep_stiffness(nd, a, b, c, dd, bw0, bw1, bw2, bw3, mloc, wprev, deep,
                                max(dt, DT_FLOOR * dtc))
        fn, fdn = penalty_force(bgap, gprev, ofd[i], k, kd, g1, 0.5 * (brel - g1))
        ofd[i] = fdn
        if vdc > 0.0 and mstar < 1.0e300:
            inv = 0.0
            if 0.0 < mn < 1.0e300:
                inv += 1.0 / mn
            if 0.0 < ms < 1.0e300:
                inv += 1.0 / ms
            omega = math.sqrt(k * inv)
            fn -= 0.01 * vdc * 2.0 * mstar * omega * vn
            if fn < 0.0:
                fn = 0.0
        fx = fn * bnx
        fy = fn * bny
        fz = fn * bnz
        if fric:
            vtx = vrx - vn * bnx
            vty = vry - vn * bny
            vtz = vrz - vn * bnz
            # old tangential force rotated into the current tangent plane
            ox = ft[i, 0]
            oy = ft[i, 1]
            oz = ft[i, 2]
            omag = math.sqrt(ox * ox + oy * oy + oz * oz)
            on = ox * bnx + oy * bny + oz * bnz
            ox -= on * bnx
            oy -= on * bny
            oz -= on * bnz
            pmag = math.sqrt(ox * ox + oy * oy + oz * oz)
            if pmag > 0.0:
                sc = omag / pmag
                ox *= sc
                oy *= sc
                oz *= sc
            tx = ox - k * vtx * dt
            ty = oy - k * vty * dt
            tz = oz - k * vtz * dt
            vt = math.sqrt(vtx * vtx + vty * vty + vtz * vtz)
            mu = fd + (fs - fd) * math.exp(-dc * vt)
            fyld = mu * fn
            tm = math.sqrt(tx * tx + ty * ty + tz * tz)
            if tm > fyld:
                sc = fyld / tm if tm > 0.0 else 0.0
                tx *= sc
                ty *= sc
                tz *= sc
            ft[i, 0] = tx
            ft[i, 1] = ty
            ft[i, 2] = tz
            fx += tx
            fy += ty
            fz += tz
        of[i, 0] = fx
        of[i, 1] = fy
        of[i, 2] = fz


@njit(cache=True, parallel=True)
def contact_pass(act, x, v, dt, dtc, nodes, n_thick, n_k, n_mass, seg, s_thick, s_k, s_mass,
                 s_depth, s_two, cen, nrm, rad2, warp, ptr, cand, params, mloc, wprev, imm, ft,
                 nprev, oseg, ow, of, ogap, ofd, oentry, othru):
    """Detect contact and compute the pair force of the nodes act of one pass.

    act (m,) int32: the rows of ``nodes`` to treat (:func:`active_rows`: rows with a
    candidate or in contact). Any other row has no candidate and no contact
    state, and treating it would only write the zeros it already holds.
    x, v: (L, 3) float64 mm, mm/ms (local rows); dt, dtc: ms (step, SOFT=1
    reference step; dtc <= 0 disables the mass-based stiffness).
    nodes (ns,) int32 rows of x; n_thick (ns,) mm; n_k (ns,) kN/mm node
    stiffness (SOFT=0, scale factor applied, 0 = unknown); n_mass (ns,) kg
    (inf for rigid-body nodes).
    seg (S, 4) int32 rows of x; s_thick, s_k, s_mass as for nodes; s_depth
    (S,) mm release depth; s_two (S,) int8 1 = two-sided.
    cen, nrm, rad2, warp: :func:`~hollowbody.contact.frames.segment_frames`;
    ptr (ns + 1,) int64, cand int32:
    candidate segments per node.
    params (10,) float64: slsfac, soft (0/1), sofscl, fs, fd, dc, vdc, friction on,
    start of the stiffened zone (fraction of the penetration at release), its
    stability limit (:data:`~hollowbody.contact.law.STIFFEN_LIMIT`). mloc (L,) kg
    nodal masses of the rows of x (rigid-body nodes: the body's mass per node; fixed nodes:
    inf), wprev (L,) summed spring weights per row in the last cycle
    (:func:`scatter_pass`), imm (L,) int8 1 for rows that no contact force can move
    (rigid-body and fixed nodes): a pair of such rows only gets the stiffened zone even
    when params[8] >= 1 disables it.
    ft (ns, 3) kN friction state, nprev (ns, 3) contact normal of the last
    cycle (zero when not in contact; two-sided side memory) (in/out);
    oseg (ns,) int32 segment in contact or -1, ogap (ns,) mm penetration and
    ofd (ns,) kN stiffening force (:func:`~hollowbody.contact.law.penalty_force`), oentry (ns,) int8
    1 when the contact began shallow (:data:`~hollowbody.contact.law.ENTRY_FRACTION`) (in: last
    cycle's, out: this one's). Outputs: ow (ns, 4) shape functions, of (ns, 3) kN
    force on the node, othru (ns,) int32 segment the node was pushed
    through this cycle or -1.
    """
    ns = act.shape[0]
    nch = (ns + _CHUNK - 1) // _CHUNK
    for c in prange(nch):
        _nodes_range(c * _CHUNK, min(ns, (c + 1) * _CHUNK), act, x, v, dt, dtc, nodes, n_thick,
                     n_k, n_mass, seg, s_thick, s_k, s_mass, s_depth, s_two, cen, nrm, rad2,
                     warp, ptr, cand, params, mloc, wprev, imm, ft, nprev, oseg, ow, of, ogap,
                     ofd, oentry, othru)


@njit(cache=True)
def contact_pass_serial(act, x, v, dt, dtc, nodes, n_thick, n_k, n_mass, seg, s_thick, s_k, s_mass,
                        s_depth, s_two, cen, nrm, rad2, warp, ptr, cand, params, mloc, wprev,
                        imm, ft, nprev, oseg, ow, of, ogap, ofd, oentry, othru):
    """Serial :func:`contact_pass` (small passes: no thread start-up)."""
    _nodes_range(0, act.shape[0], act, x, v, dt, dtc, nodes, n_thick, n_k, n_mass, seg, s_thick,
                 s_k, s_mass, s_depth, s_two, cen, nrm, rad2, warp, ptr, cand, params, mloc,
                 wprev, imm, ft, nprev, oseg, ow, of, ogap, ofd, oentry, othru)


@njit(cache=True)
def scatter_pass(act, nodes, seg, oseg, ow, of, f, fsum, wsum):
    """Add the pair forces of the rows act (:func:`active_rows`) of one pass into
    f (L, 3) kN (serial, race-free).

    Node gets +F, the segment's corners -N_a F. fsum (3,) accumulates the
    sum of F (force on the pass's nodes); wsum (L,) the weight of every spring
    on each row (1 on the node, N_a on the corners; see
    :func:`~hollowbody.contact.law.deep_stiffness`).
    Returns the number of nodes in contact.
    """
    n = 0
    for ii in range(act.shape[0]):
        i = act[ii]
        s = oseg[i]
        if s < 0:
            continue
        n += 1
        nd = nodes[i]
        tri = seg[s, 3] == seg[s, 2]
        wsum[nd] += 1.0
        wsum[seg[s, 0]] += ow[i, 0]
        wsum[seg[s, 1]] += ow[i, 1]
        wsum[seg[s, 2]] += ow[i, 2]
        if not tri:
            wsum[seg[s, 3]] += ow[i, 3]
        for k in range(3):
            fk = of[i, k]
            f[nd, k] += fk
            fsum[k] += fk
            f[seg[s, 0], k] -= ow[i, 0] * fk
            f[seg[s, 1], k] -= ow[i, 1] * fk
            f[seg[s, 2], k] -= ow[i, 2] * fk
            if not tri:
                f[seg[s, 3], k] -= ow[i, 3] * fk
    return n


@njit(cache=True)
def gather(x, v, nodes, xl, vl, xsort, xnear):
    """Copy global rows x[nodes], v[nodes] into xl, vl (L, 3); return the largest
    squared displacements (mm^2) since the last sort (positions xsort (L, 3))
    and since the last near-list filter (xnear (L, 3))."""
    m = 0.0
    mn = 0.0
    for i in range(nodes.shape[0]):
        g = nodes[i]
        dd = 0.0
        dn = 0.0
        for k in range(3):
            xv = x[g, k]
            xl[i, k] = xv
            vl[i, k] = v[g, k]
            e = xv - xsort[i, k]
            dd += e * e
            e = xv - xnear[i, k]
            dn += e * e
        if dd > m:
            m = dd
        if dn > mn:
            mn = dn
    return m, mn


@njit(cache=True)
def finish(nodes, fl, fprev, xl, xprev, f):
    """Scatter fl (L, 3) into global f; return the increment of contact energy
    -1/2 (f_prev + f) . (x - x_prev) (J); roll fprev and xprev forward."""
    de = 0.0
    for i in range(nodes.shape[0]):
        g = nodes[i]
        for k in range(3):
            de -= 0.5 * (fprev[i, k] + fl[i, k]) * (xl[i, k] - xprev[i, k])
            f[g, k] += fl[i, k]
            fprev[i, k] = fl[i, k]
            xprev[i, k] = xl[i, k]
    return de



@njit(cache=True)
def count_through(act, othru):
    """Number of rows act of othru (ns,) int32 that name a segment (pass-through events)."""
    n = 0
    for ii in range(act.shape[0]):
        if othru[act[ii]] >= 0:
            n += 1
    return n


@njit(cache=True)
def active_rows(nptr, oseg, out):
    """Rows i of a pass with a near candidate (nptr[i + 1] > nptr[i]) or in contact
    (oseg[i] >= 0), ascending, into out (ns,) int32; returns their number. Until
    the next near filter no other row can come into contact."""
    m = 0
    for i in range(oseg.shape[0]):
        if nptr[i + 1] > nptr[i] or oseg[i] >= 0:
            out[m] = i
            m += 1
    return m
