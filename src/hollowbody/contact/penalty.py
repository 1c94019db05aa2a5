"""Node-to-segment penalty contact forces with Coulomb friction (numba kernels).

A pass's pairs come from :mod:`hollowbody.contact.detect` (node, segment,
contact point x_p with shape functions N_a, normal n, penetration g). Every
pass of a contact is detected first; the weights of all its springs on each
node (:func:`scatter_weights`) then bound the spring stiffness of this cycle.

Stiffness: SOFT=0 ``k = SLSFAC min(k_node, k_seg)`` (PENOPT=1); SOFT=1 the
larger of that and ``SOFSCL m* / (2 dtc^2)`` (m* the smaller nodal / segment
mass, dtc the reference step). Then, whatever the option, k is capped so that
no node the spring acts on exceeds ``(omega dt)^2 = 0.5`` with all its
contact springs of this cycle together (row-sum bound, see
:func:`~hollowbody.contact.law.deep_stiffness`): a fine surface pressed on a
coarse one puts many springs on each of the coarse segment's nodes, and
without the cap their sum makes the contact unstable.

Normal force: the spring force grows with the penetration *increment*
(:func:`~hollowbody.contact.law.spring_force`): on the same segment as last
cycle by k (g - g_prev); a node that moves on to another segment keeps its
force and adds the approach of this step; a fresh contact starts from the
approach of this step (a node found already deep -- entering sideways over a
segment's edge in a fold -- is held, not fired out; initial penetrations at
the first call push apart); always ``0 <= F <= k g``. A contact whose normal
turned against last cycle's counts as fresh (spring, stiffening and friction
forces are not carried over).
A force law in the total form ``k g`` makes energy out of every such jump.
Deeper than ``g1 = stiffen * G`` (G = reach + release depth, the penetration
at which the node would be released) the tangent stiffness rises
incrementally to the stability cap at the current step (see
:mod:`hollowbody.contact.law`); across a change of segment it too grows by
the approach of the step only. So the force a node can carry before release
follows the stiffening of the material under it (whose wave speed sets dt) and
the speed of the impact, without exceeding the explicit stability limit.
Minus the optional VDC damping ``c v_n`` (never adhesive). Friction by an
elastic trial with the spring k::

    f* = f_t(old, rotated into the current tangent plane) - k * v_t * dt
    mu = FD + (FS - FD) * exp(-DC * |v_t|)
    f_t = f* if |f*| <= mu F_n else mu F_n f* / |f*|

(v_t the tangential velocity of the node relative to the contact point;
f_t is stored per node between cycles). The pair force F = F_n n' + f_t acts
on the node and -N_a F on the segment's nodes: momentum is conserved exactly.

Per-node results are computed in parallel (``prange`` over nodes, each writes
only its own row), then scattered serially (race-free). No allocation in the
loops.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from hollowbody.contact.detect import CHUNK
from hollowbody.contact.law import (
    DT_FLOOR,
    STIFFEN_FRACTION,
    deep_stiffness,
    penalty_force,
    spring_force,
    stable_stiffness,
)


@njit(cache=True)
def _force_range(i0, i1, act, v, dt, dtc, nodes, n_k, n_mass, seg, s_k, s_mass, params, mloc,
                 wsum, imm, ft, nprev, oseg, ow, ogap, gold, sold, orel, of, ofd, ofn, odel):
    """Forces of the rows act[i0:i1] of a pass (body of :func:`force_pass`)."""
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
    cap = params[10]
    for ii in range(i0, i1):
        i = act[ii]
        s = oseg[i]
        if s < 0:
            ft[i, 0] = 0.0
            ft[i, 1] = 0.0
            ft[i, 2] = 0.0
            of[i, 0] = 0.0
            of[i, 1] = 0.0
            of[i, 2] = 0.0
            ofd[i] = 0.0
            ofn[i] = 0.0
            odel[i] = 0.0
            continue
        nd = nodes[i]
        prev = sold[i]
        gprev = gold[i]
        bgap = ogap[i]
        brel = orel[i]
        bnx = nprev[i, 0]
        bny = nprev[i, 1]
        bnz = nprev[i, 2]
        bw0 = ow[i, 0]
        bw1 = ow[i, 1]
        bw2 = ow[i, 2]
        bw3 = ow[i, 3]
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
        a = seg[s, 0]
        b = seg[s, 1]
        c = seg[s, 2]
        dd = seg[s, 3]
        # the largest stiffness every node of the pair stays stable with, all the
        # springs on it this cycle together (the step floored at DT_FLOOR of the
        # reference step: a collapsing element, which ends the run anyway, does not
        # drive the force up)
        dts = max(dt, DT_FLOOR * dtc)
        kcap = stable_stiffness(nd, a, b, c, dd, bw0, bw1, bw2, bw3, mloc, wsum, cap, dts)
        if 0.0 < kcap < k:
            k = kcap
        # relative velocity node - contact point
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
        # the first call of a run: an initial penetration counts as this step's
        # approach (it pushes apart); later a fresh contact gets only its approach
        dn = -bgap if params[11] > 0.0 and prev < 0 else vn * dt
        if prev < 0:  # a new contact (or one turned over): nothing carried
            ofd[i] = 0.0
            ft[i, 0] = 0.0
            ft[i, 1] = 0.0
            ft[i, 2] = 0.0
        elif prev != s:
            # moved on to another segment: the stiffening grows by this step's approach,
            # like the spring, not by the difference of the two segments' gaps
            gprev = bgap + dn
        kd = 0.0
        if bgap > g1:
            kd = deep_stiffness(nd, a, b, c, dd, bw0, bw1, bw2, bw3, mloc, wsum, deep, dts)
        fn, fdn = penalty_force(bgap, gprev, ofd[i], k, kd, g1, 0.5 * (brel - g1))
        ofd[i] = fdn
        fb = spring_force(bgap, gprev if prev == s else bgap, ofn[i], k, dn, prev == s,
                          prev >= 0)
        fn += fb - k * bgap
        ofn[i] = fb
        # penetration not pushed back from: the node is released that much deeper
        odel[i] = min(bgap - fb / k, brel) if k > 0.0 else 0.0
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
def force_pass(act, v, dt, dtc, nodes, n_k, n_mass, seg, s_k, s_mass, params, mloc, wsum, imm,
               ft, nprev, oseg, ow, ogap, gold, sold, orel, of, ofd, ofn, odel):
    """Pair forces of the nodes act of one pass, after :mod:`~hollowbody.contact.detect`.

    act (m,) int32 rows (:func:`active_rows`); v (L, 3) float64 mm/ms (local
    rows, t^{n+1/2}); dt, dtc: ms (step, SOFT=1 reference step; dtc <= 0
    disables the mass-based stiffness). nodes (ns,) int32 rows of v; n_k (ns,)
    kN/mm node stiffness (SOFT=0, scale factor applied, 0 = unknown); n_mass
    (ns,) kg (inf for rigid-body nodes); seg (S, 4) int32; s_k, s_mass (S,) as
    for nodes. params (12,) float64: slsfac, soft (0/1), sofscl, fs, fd, dc,
    vdc, friction on, start of the stiffened zone (fraction of the penetration
    at release), its stability limit of all springs on a node
    (:data:`~hollowbody.contact.law.STIFFEN_LIMIT`), the cap of every spring
    (:data:`~hollowbody.contact.law.CAP_LIMIT`), 1 at the first call of a run
    (a fresh contact's whole gap counts as its approach: initial penetrations
    push apart; 0 later: a fresh contact gets only the approach of its step).
    mloc (L,) kg nodal masses of the rows (rigid-body nodes: the body's mass
    per node; fixed nodes: inf);
    wsum (L,) summed weights of this cycle's springs per row
    (:func:`scatter_weights`); imm (L,) int8 1 for rows that no contact force
    can move (rigid-body and fixed nodes): a pair of such rows only gets the
    stiffened zone even when params[8] >= 1 disables it. From detection (in):
    nprev (ns, 3) normal, oseg (ns,) int32 segment or -1, ow (ns, 4), ogap, gold,
    orel (ns,) mm, sold (ns,) int32. State (in/out): ft (ns, 3) kN friction, ofd
    (ns,) kN stiffening force, ofn (ns,) kN spring force. Out: of (ns, 3) kN
    force on the node, odel (ns,) mm the penetration the spring does not push
    back from (gap - F / k, at most the penetration at release), by which the
    node's release from this segment is deferred (detection, next cycle).
    """
    ns = act.shape[0]
    nch = (ns + CHUNK - 1) // CHUNK
    for c in prange(nch):
        _force_range(c * CHUNK, min(ns, (c + 1) * CHUNK), act, v, dt, dtc, nodes, n_k, n_mass,
                     seg, s_k, s_mass, params, mloc, wsum, imm, ft, nprev, oseg, ow, ogap, gold,
                     sold, orel, of, ofd, ofn, odel)


@njit(cache=True)
def force_pass_serial(act, v, dt, dtc, nodes, n_k, n_mass, seg, s_k, s_mass, params, mloc, wsum,
                      imm, ft, nprev, oseg, ow, ogap, gold, sold, orel, of, ofd, ofn, odel):
    """Serial :func:`force_pass` (small passes: no thread start-up)."""
    _force_range(0, act.shape[0], act, v, dt, dtc, nodes, n_k, n_mass, seg, s_k, s_mass, params,
                 mloc, wsum, imm, ft, nprev, oseg, ow, ogap, gold, sold, orel, of, ofd, ofn, odel)


@njit(cache=True)
def scatter_weights(act, nodes, seg, oseg, ow, wsum):
    """Add the weight of every spring of the rows act of one pass to wsum (L,):
    1 on the node, N_a on the segment's corners (see
    :func:`~hollowbody.contact.law.deep_stiffness`)."""
    for ii in range(act.shape[0]):
        i = act[ii]
        s = oseg[i]
        if s < 0:
            continue
        wsum[nodes[i]] += 1.0
        wsum[seg[s, 0]] += ow[i, 0]
        wsum[seg[s, 1]] += ow[i, 1]
        wsum[seg[s, 2]] += ow[i, 2]
        if seg[s, 3] != seg[s, 2]:
            wsum[seg[s, 3]] += ow[i, 3]


@njit(cache=True)
def scatter_pass(act, nodes, seg, oseg, ow, of, f, fsum):
    """Add the pair forces of the rows act (:func:`active_rows`) of one pass into
    f (L, 3) kN (serial, race-free).

    Node gets +F, the segment's corners -N_a F. fsum (3,) accumulates the
    sum of F (force on the pass's nodes).
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


@njit(cache=True, inline="always")
def _spread(e0, e1, e2, a0, a1, a2, b0, b1, b2):
    """One displacement (e0, e1, e2) into the box a (min) / b (max) per axis;
    returns it updated."""
    return min(a0, e0), min(a1, e1), min(a2, e2), max(b0, e0), max(b1, e1), max(b2, e2)


@njit(cache=True)
def gather(x, v, nodes, xl, vl, xsort, xnear):
    """Copy global rows x[nodes], v[nodes] into xl, vl (L, 3); return squared
    bounds (mm^2) on how far the nodes moved *along any one axis, relative to one
    common translation* since the last sort (positions xsort (L, 3)) and since the
    last near-list filter (xnear (L, 3)): the squared half of the largest side of
    the displacements' box.

    Two nodes i, j approach along axis k by at most |u_ik - u_jk| <= b_k - a_k, the
    side of the displacements' box along k (the translation c is its centre). The
    lists are made with axis-aligned boxes enlarged by a margin m, so they stay
    complete while every side is below m (bound below (m/2)^2); the Euclidean
    approach is then below sqrt(3) m (the far lists' distance cut takes that).
    An axis at a time counts what the boxes need: walls folding in every direction
    (the crushed hollow block) move about as far along each axis, sqrt(3) less than
    along the box's diagonal.
    """
    if nodes.shape[0] == 0:
        return 0.0, 0.0
    a0 = a1 = a2 = c0 = c1 = c2 = np.inf  # boxes since the sort (a, b), the filter (c, d)
    b0 = b1 = b2 = d0 = d1 = d2 = -np.inf
    for i in range(nodes.shape[0]):
        g = nodes[i]
        for k in range(3):
            xl[i, k] = x[g, k]
            vl[i, k] = v[g, k]
        a0, a1, a2, b0, b1, b2 = _spread(
            xl[i, 0] - xsort[i, 0], xl[i, 1] - xsort[i, 1], xl[i, 2] - xsort[i, 2],
            a0, a1, a2, b0, b1, b2)
        c0, c1, c2, d0, d1, d2 = _spread(
            xl[i, 0] - xnear[i, 0], xl[i, 1] - xnear[i, 1], xl[i, 2] - xnear[i, 2],
            c0, c1, c2, d0, d1, d2)
    hs = 0.5 * max(b0 - a0, b1 - a1, b2 - a2)
    hn = 0.5 * max(d0 - c0, d1 - c1, d2 - c2)
    return hs * hs, hn * hn


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
