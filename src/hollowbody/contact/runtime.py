"""ContactRuntime: one *CONTACT_AUTOMATIC_... definition during a run.

The solver creates one :class:`ContactRuntime` per :class:`ContactDef` and
calls :meth:`ContactRuntime.add_forces` once per cycle with the new
coordinates. Kinds:

* ``nodes_to_surface``: one pass, slave nodes against master segments;
* ``surface_to_surface``: two passes (slave nodes vs master segments, master
  nodes vs slave segments), symmetric;
* ``single_surface``: one pass, every node of the surface against every
  segment of it except the segments that contain the node and the segments
  next to those (sharing a corner with one): a thick shell bent at an element
  edge is not in contact with itself.

In every kind, node-segment pairs that are already in contact at t = 0 and
joined through the mesh (shell T-junctions, thick shells meeting at an
angle, surfaces of different parts sharing nodes) are left out for the whole
run, see :mod:`hollowbody.contact.exclusion`; nodes of the model's tied
contacts count as joined to the segments they are tied to.

Degenerate segments and massless nodes are left out at set-up with one
warning per side (:mod:`hollowbody.contact.checks`). A node pushed through a
surface (behind the segment it was in contact with by more than the release
depth, see :mod:`hollowbody.contact.law`) is counted (``n_pass_through``) and
reported: :meth:`ContactRuntime.pop_events` returns the warnings not yet
reported (set-up messages; the first ``MAX_EVENTS`` pass-through events with
node id, segment element id and time; all are counted).

All node and segment references are translated to a compact local numbering
(the nodes of this contact only); coordinates and velocities are gathered
into work arrays each cycle, forces scattered back. Every work array is
allocated here, none per cycle (the bucket sort, every
``controls.contact_sort_interval`` cycles, allocates its CSR lists).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
from numba import get_num_threads, njit

from hollowbody.contact.bucket import bucket_sort, dynamic_blocks
from hollowbody.contact.checks import clean_surface, segment_elements
from hollowbody.contact.detect import detect_pass, detect_pass_serial
from hollowbody.contact.exclusion import (
    edge_graph,
    junction_exclusions,
    merge_csr,
    ring_exclusions,
)
from hollowbody.contact.frames import (
    SLAB_COLS,
    segment_frames,
    segment_frames_of,
    segment_frames_of_parallel,
)
from hollowbody.contact.kinematic_step import max_speed2, passes_step, work_arrays
from hollowbody.contact.law import CAP_LIMIT, STIFFEN_FRACTION, STIFFEN_LIMIT
from hollowbody.contact.nearlist import (
    distance_cut,
    distance_cut_parallel,
    keep_current,
    near_filter,
    near_filter_parallel,
)
from hollowbody.contact.penalty import (
    active_rows,
    count_through,
    finish,
    force_pass,
    force_pass_serial,
    gather,
    scatter_pass,
    scatter_weights,
)
from hollowbody.contact.stiffness import (
    node_effective_mass,
    node_stiffness,
    segment_mass,
    segment_stiffness,
)
from hollowbody.contact.surface import (
    SEG_SOLID,
    Surface,
    build_surface,
    model_surface,
)
from hollowbody.contact.tied.links import tied_links
from hollowbody.errors import UserInputError
from hollowbody.model.model import ContactDef, Model

#: Release depth, as a fraction of the element depth V / A behind a solid face
#: (LS-DYNA's PENMAX default for automatic contacts is 0.4) or of sqrt(A) of a shell.
PENMAX = 0.4
#: A threaded kernel costs a wake-up of the waiting threads per call: ~2 us while
#: they spin, 60-140 us when they sleep (passive wait) on the shared two-core machine
#: of BENCHMARKS.md. So a pass runs its per-cycle kernels (frames, detection, forces,
#: kinematic limit) threaded only from ``parallel_min_rows`` active rows (nodes with
#: near pairs or a contact). This default is for sleeping threads: the hollow block's
#: passes (at most 3,182 active rows of 5,209 nodes) were slower threaded than serial
#: there (2 threads, idle machine, 100 km/h: contact 4.7-6.5 s against 4.5-5.1 s on
#: one thread). A run whose threads spin briefly before they sleep lowers it
#: (hollowbody.solver.threads.per_cycle_min_rows: 256; contact 3.2 s against 4.3 s).
PARALLEL_MIN_ROWS = 4096
#: The near filter and the bucket sort run threaded (blocks of nodes, each written
#: into its own part of the lists) for passes of at least this many nodes plus far
#: pairs: the crushed hollow block's self-contact (5,209 nodes, ~105,000 far pairs)
#: sorts in 3.6 ms and filters in ~0.5 ms on one thread, above a wake-up (BENCHMARKS.md).
PARALLEL_MIN_NODES = 16384
#: Blocks of rows per thread in the threaded near filter.
FILTER_BLOCKS_PER_THREAD = 2
#: Re-sort when the nodes have moved this fraction of the bucket margin along an axis
#: relative to one common translation (:func:`hollowbody.contact.penalty.gather`).
_RESORT_FRACTION = 0.5
_SQRT3 = math.sqrt(3.0)
#: Largest bucket-sort margin and the near-list margin, as fractions of the
#: median segment size (see ContactRuntime._sort and hollowbody.contact.nearlist)
FAR_MARGIN = 0.5
NEAR_MARGIN = 0.1
#: Pass-through events reported one by one (the rest are counted only).
MAX_EVENTS = 20


class _Pass:
    """Arrays of one node-vs-segment pass (local numbering), see detect_pass / force_pass.

    ``STATE_FIELDS``: what a restart must save and put back for the run to continue
    bit for bit: the far and near lists and their segment lists (rebound with a
    new length at every sort / filter: put back by assignment, not in place; fact
    and act are views of work buffers until the next filter), the filter's stamps,
    the per-node contact history (last segment, weights, force, gap, normal,
    friction force, stiffening and spring force, held penetration, entry flag,
    pass-through segment) and
    which segments are alive (erosion). The segment frames and boxes are recomputed
    before they are read (every cycle / filter) and are not state, nor are the
    detection's hand-overs to the force pass (gold, sold, orel).
    """

    STATE_FIELDS: ClassVar[tuple[str, ...]] = (
        "ptr", "cand", "sact", "nptr", "ncand", "fact", "act", "_mark",
        "ft", "nprev", "oseg", "ow", "of", "ogap", "ofd", "ofn", "odel", "oentry", "othru",
        "seg_alive")

    def __init__(self, nodes, n_thick, n_k, n_mass, seg, s_thick, s_k, s_mass, s_depth,
                 s_two, sign: float) -> None:
        self.nodes = np.ascontiguousarray(nodes, dtype=np.int32)
        self.n_thick = np.ascontiguousarray(n_thick, dtype=np.float64)
        self.n_k = np.ascontiguousarray(n_k, dtype=np.float64)
        self.n_mass = np.ascontiguousarray(n_mass, dtype=np.float64)
        self.seg = np.ascontiguousarray(seg, dtype=np.int32).reshape(-1, 4)
        self.s_thick = np.ascontiguousarray(s_thick, dtype=np.float64)
        self.s_k = np.ascontiguousarray(s_k, dtype=np.float64)
        self.s_mass = np.ascontiguousarray(s_mass, dtype=np.float64)
        self.s_depth = np.ascontiguousarray(s_depth, dtype=np.float64)
        self.s_two = np.ascontiguousarray(s_two, dtype=np.int8)
        self.sign = sign
        ns, nseg = self.nodes.shape[0], self.seg.shape[0]
        tmax = float(self.n_thick.max()) if ns else 0.0
        #: (S,) mm farthest a node can be from a segment and still be in contact
        self.capture = np.maximum(self.s_depth, 0.5 * (tmax + self.s_thick))
        self.ex_ptr = np.zeros(ns + 1, np.int64)
        self.ex_seg = np.zeros(0, np.int32)
        self.cen = np.zeros((nseg, 3))
        self.nrm = np.zeros((nseg, 3))
        self.rad2 = np.zeros(nseg)
        self.warp = np.zeros(nseg)
        self.slab = np.zeros((nseg, SLAB_COLS))
        #: (k,) int32 the segments in the far lists (ptr / cand), set after each sort
        self.sact = np.zeros(0, np.int32)
        #: near lists (hollowbody.contact.nearlist): CSR nptr / ncand, and fact the
        #: segments in them (the only frames the kernels read)
        self.nptr = np.zeros(ns + 1, np.int64)
        self.ncand = np.zeros(0, np.int32)
        self.fact = np.zeros(0, np.int32)
        #: (m,) int32 rows the kernels treat until the next filter (active_rows)
        self.act = np.zeros(0, np.int32)
        self._act_buf = np.zeros(ns, np.int32)
        self._nsact = np.zeros(nseg, np.int32)
        self._mark = np.zeros(nseg, np.int64)
        self._lo = np.zeros((nseg, 3))
        self._hi = np.zeros((nseg, 3))
        self.ptr = np.zeros(ns + 1, np.int64)
        self.cand = np.zeros(0, np.int32)
        #: pairs of the last bucket sort before the distance cut (a size hint, not state)
        self.n_box_pairs = 0
        self.ft = np.zeros((ns, 3))
        self.nprev = np.zeros((ns, 3))
        self.oseg = np.full(ns, -1, np.int32)
        self.ow = np.zeros((ns, 4))
        self.of = np.zeros((ns, 3))
        self.ogap = np.zeros(ns)
        self.ofd = np.zeros(ns)
        self.ofn = np.zeros(ns)
        self.odel = np.zeros(ns)
        # detection -> force pass of the same cycle: last gap, last segment, release gap
        self.gold = np.zeros(ns)
        self.sold = np.full(ns, -1, np.int32)
        self.orel = np.zeros(ns)
        self.oentry = np.zeros(ns, np.int8)
        self.othru = np.full(ns, -1, np.int32)
        self.fsum = np.zeros(3)
        #: (S,) element id and part id under each segment (-1: none), for messages
        self.seg_eid = np.full(nseg, -1, np.int64)
        self.seg_pid = np.full(nseg, -1, np.int64)
        #: (S,) bool: False for segments of deleted (eroded, failed) elements
        self.seg_alive = np.ones(nseg, dtype=bool)
        self._kin_dt, self._kin_row = work_arrays(ns)
        #: mm: narrowest contact band of the pass (None: to be computed)
        self.kin_band: float | None = None


class ContactRuntime:
    """Penalty contact of one :class:`ContactDef` (see module docstring).

    node_mass: (n,) kg lumped nodal masses (rigid-part nodes: their nodal
    share); rigid_node: (n,) bool, True for nodes of rigid parts (SOFT=1 and
    damping then use the deformable side's mass); fixed_node: (n,) bool, nodes
    with every translation held by an SPC (None: none); rigid_share: (n,) kg, a
    rigid body's mass divided by its node count on its nodes (None: rigid nodes
    are left out of the stiffened zone's stability bound). Every contact has the
    stiffened zone; a pair in which every participant is rigid or fixed (a rigid
    impactor on a fixed base) keeps it, bounded by the rigid body's mass, when
    :meth:`set_stiffening` switches it off for the contact. x0: (n, 3) mm initial
    coordinates of the run (the tied contacts' ``node_x0``; None: the model's).

    After each :meth:`add_forces`: ``slave_force`` (3,) kN resultant contact
    force on the slave side, ``master_force`` = -slave_force (both zero for
    single-surface contact), ``energy`` J cumulative contact work (penalty
    springs + friction), ``n_active`` nodes in contact, ``time`` ms (sum of
    the steps passed), ``n_pass_through`` nodes pushed through a surface so
    far (events; ``pass_through_nodes`` the distinct node ids).

    ``STATE_FIELDS`` names what changes in time (a restart saves and puts back
    these and each pass's ``passes[i].STATE_FIELDS``): the results above, the
    pass-through records (a set and lists: saved as copies, put back by
    assignment), the reference positions of the last sort and filter and their
    margins, the previous positions, forces and node weights (contact work and
    the stiffened zone), the sort and filter counters and flags, and the
    critical step seen. The gathered coordinates and force work arrays are
    rewritten every cycle before they are read and are not state.
    """

    STATE_FIELDS: ClassVar[tuple[str, ...]] = (
        "time", "energy", "n_active", "slave_force", "master_force",
        "n_pass_through", "pass_through_nodes", "events", "_pending",
        "_xsort", "_xnear", "_margin", "_near_margin", "_xprev", "_fprev",
        "n_sorts", "_last_sort", "n_filters", "_refilter", "_first", "_dtc",
        "n_step_limited", "dt_kin_min")

    def __init__(self, cdef: ContactDef, model: Model, node_mass: np.ndarray,
                 rigid_node: np.ndarray, fixed_node: np.ndarray | None = None,
                 rigid_share: np.ndarray | None = None, x0: np.ndarray | None = None
                 ) -> None:
        self.cid = cdef.cid
        self.kind = cdef.kind
        self.cdef = cdef
        #: release depth of solid faces / element depth (see set_penmax)
        self.penmax = PENMAX
        #: per-cycle kernels threaded from this many active rows of a pass; the near
        #: filter and bucket sort from parallel_min_nodes nodes plus far pairs
        self.parallel_min_rows = PARALLEL_MIN_ROWS
        self.parallel_min_nodes = PARALLEL_MIN_NODES
        self.sort_interval = max(1, int(model.controls.contact_sort_interval or 100))
        n = model.n_nodes
        x0 = np.asarray(model.node_x0 if x0 is None else x0, dtype=np.float64)
        node_mass = np.asarray(node_mass, dtype=np.float64)
        rigid_node = np.asarray(rigid_node, dtype=bool)
        self._params = np.array([model.controls.slsfac, 1.0 if cdef.soft >= 1 else 0.0,
                                 cdef.sofscl, cdef.fs, cdef.fd, cdef.dc, cdef.vdc,
                                 1.0 if (cdef.fs > 0.0 or cdef.fd > 0.0) else 0.0,
                                 STIFFEN_FRACTION, STIFFEN_LIMIT,
                                 CAP_LIMIT, 0.0])
        self._node_ids = np.asarray(model.node_ids, dtype=np.int64)
        ms_cache: dict[float, Surface] = {}

        def msurf(t: float) -> Surface:
            if t not in ms_cache:
                ms_cache[t] = model_surface(model, t, x0)
            return ms_cache[t]

        slave = build_surface(cdef.slave, model, cdef.sst,
                              msurf(cdef.sst) if cdef.slave.kind in ("nodes", "segments")
                              else None, x0=x0)
        master = None
        if cdef.kind in ("nodes_to_surface", "surface_to_surface"):
            if cdef.master is None:
                raise UserInputError(f"contact {cdef.cid}: {cdef.kind} needs a master side")
            master = build_surface(cdef.master, model, cdef.mst,
                                   msurf(cdef.mst) if cdef.master.kind in ("nodes", "segments")
                                   else None, x0=x0)
            if master.n_segments == 0:
                raise UserInputError(f"contact {cdef.cid}: master side has no segments")
        elif cdef.kind != "single_surface":
            raise UserInputError(f"contact {cdef.cid}: unknown contact kind {cdef.kind!r}")
        #: set-up messages (degenerate segments, massless nodes left out)
        self.warnings: list[str] = []
        side = "surface" if master is None else "slave side"
        slave, w = clean_surface(slave, model, node_mass, rigid_node, cdef.sst,
                                 f"contact {cdef.cid} {side}", x0)
        self.warnings += w
        if master is not None:
            master, w = clean_surface(master, model, node_mass, rigid_node, cdef.mst,
                                      f"contact {cdef.cid} master side", x0)
            self.warnings += w
            if master.n_segments == 0:
                raise UserInputError(f"contact {cdef.cid}: master side has no valid segments")
        self.slave_surface = slave
        self.master_surface = master

        def side_arrays(surf: Surface, t_override: float):
            k_seg, depth = segment_stiffness(surf, model, x0)
            if surf.n_segments:
                k_node = node_stiffness(surf.nodes, surf.seg, k_seg, n)
            else:  # node set: stiffness of the model's segments through the node
                ms = msurf(t_override)
                k_ms, _ = segment_stiffness(ms, model, x0)
                k_node = node_stiffness(surf.nodes, ms.seg, k_ms, n)
            # release depth = penmax * depth (solids V / A, shells sqrt(A))
            return k_seg, depth, k_node

        sk, sdepth, snk = side_arrays(slave, cdef.sst)
        parts = [slave.nodes, slave.seg.ravel()]
        if master is not None:
            mk, mdepth, mnk = side_arrays(master, cdef.mst)
            parts += [master.nodes, master.seg.ravel()]
        self.nodes = np.unique(np.concatenate(parts).astype(np.int64))  # (L,) global
        loc = np.full(n, -1, np.int64)
        loc[self.nodes] = np.arange(self.nodes.shape[0])

        def mk_pass(nsurf: Surface, nk, ssurf: Surface, segk, sdep, sf_n, sf_s, sign):
            p = _Pass(loc[nsurf.nodes], nsurf.node_thick, sf_n * nk,
                      node_effective_mass(nsurf.nodes, node_mass, rigid_node),
                      loc[ssurf.seg], ssurf.seg_thick, sf_s * segk,
                      segment_mass(ssurf.seg, node_mass, rigid_node), sdep,
                      (ssurf.seg_kind != SEG_SOLID).astype(np.int8), sign)
            p.seg_eid, p.seg_pid = segment_elements(ssurf, model)
            return p

        self.passes: list[_Pass] = []
        if master is not None:
            self.passes.append(mk_pass(slave, snk, master, mk, mdepth, cdef.sfs, cdef.sfm, 1.0))
            if cdef.kind == "surface_to_surface" and slave.n_segments:
                self.passes.append(mk_pass(master, mnk, slave, sk, sdepth, cdef.sfm, cdef.sfs,
                                           -1.0))
        else:
            if slave.n_segments == 0:
                raise UserInputError(f"contact {cdef.cid}: single surface has no valid segments")
            self.passes.append(mk_pass(slave, snk, slave, sk, sdepth, cdef.sfs, cdef.sfs, 0.0))
        for p in self.passes:
            p.elem_depth = p.s_depth.copy()
        # every contact has the stiffened zone (law.py), shells and self-contacts too:
        # crushed walls stiffen as their step falls, and a SOFT=1 spring set from the
        # initial step let them push nodes through their folds (calibrated hollow
        # muscle block, 70 km/h: 71 pass-through events without it, 32 with it)
        self.set_penmax(PENMAX, exclusions=False)
        #: initial contacts between surfaces not joined by the mesh (they push apart)
        self.n_initial_penetrations = 0
        self._x0 = x0[self.nodes]
        self._links = tied_links(model, loc, self._x0, x0)
        self._exclude_junctions(self._x0)

        nl = self.nodes.shape[0]
        #: (L,) kg nodal masses of the contact's nodes (inf: rigid-body nodes)
        # rigid-body nodes count with their body's mass per node in the stiffened zone's
        # stability bound; fixed nodes (every translation held) are left out
        fixed = (np.zeros(n, dtype=bool) if fixed_node is None
                 else np.asarray(fixed_node, dtype=bool))
        share = (np.full(n, np.inf) if rigid_share is None
                 else np.asarray(rigid_share, dtype=np.float64))
        self._mloc = np.where(rigid_node[self.nodes], share[self.nodes],
                              np.where(fixed[self.nodes], np.inf, node_mass[self.nodes]))
        self._imm = (rigid_node | fixed)[self.nodes].astype(np.int8)
        self._wsum = np.zeros(nl)
        self._xl = np.zeros((nl, 3))
        self._vl = np.zeros((nl, 3))
        self._xsort = np.zeros((nl, 3))
        self._xprev = np.zeros((nl, 3))
        self._xnear = np.zeros((nl, 3))
        self._fl = np.zeros((nl, 3))
        self._fprev = np.zeros((nl, 3))
        self._margin = 0.0
        self._near_margin = 0.0
        self._refilter = True
        self.n_filters = 0
        self._last_sort = -1
        self._dtc = 0.0
        self._first = True
        self.n_sorts = 0
        self.time = 0.0
        self.n_pass_through = 0
        self.pass_through_nodes: set[int] = set()
        self.events: list[dict] = []
        self._pending: list[dict] = [{"kind": "contact_setup", "contact": self.cid,
                                      "time_ms": 0.0, "message": m} for m in self.warnings]
        self.slave_force = np.zeros(3)
        self.master_force = np.zeros(3)
        self.energy = 0.0
        self.n_active = 0
        #: the solver counts the cycles in which this contact's kinematic step limit
        #: (:meth:`kinematic_step`) set the step and keeps the smallest (ms)
        self.n_step_limited = 0
        self.dt_kin_min = np.inf
        self._kin_live: list[_Pass] = []

    # ------------------------------------------------------------------
    def set_stiffening(self, fraction: float) -> None:
        """Start of the stiffened zone as a fraction of the penetration at release
        (default :data:`~hollowbody.contact.law.STIFFEN_FRACTION`; >= 1 disables it)."""
        self._params[8] = float(fraction)

    def pop_events(self) -> list[dict]:
        """Warnings not yet returned, for the run log: each a dict with ``kind``,
        ``contact`` id, ``time_ms`` and ``message``.

        ``contact_setup``: degenerate segments / massless nodes left out (once,
        at the first call). ``contact_pass_through``: also ``node`` id and
        ``segment_element`` / ``segment_part`` (-1 when the segment has no
        element); the first MAX_EVENTS events of a run come one by one, then
        one entry saying that further events are only counted
        (``n_pass_through``).
        """
        new = self._pending
        self._pending = []
        return new

    def _event(self, ev: dict) -> None:
        self.events.append(ev)
        self._pending.append(ev)

    def _record_through(self, p: _Pass) -> None:
        for i in p.act[p.othru[p.act] >= 0]:
            nid = int(self._node_ids[self.nodes[p.nodes[i]]])
            self.n_pass_through += 1
            self.pass_through_nodes.add(nid)
            s = int(p.othru[i])
            eid, pid = int(p.seg_eid[s]), int(p.seg_pid[s])
            where = (f"the surface of element {eid} (part {pid})" if eid >= 0
                     else "a free contact segment")
            if len(self.events) < MAX_EVENTS:
                self._event({
                    "kind": "contact_pass_through", "contact": self.cid, "node": nid,
                    "time_ms": self.time, "segment_element": eid, "segment_part": pid,
                    "message": f"contact {self.cid}: node {nid} pushed through {where} at "
                               f"t={self.time:.6g} ms (deeper than the release depth)"})
            elif len(self.events) == MAX_EVENTS:
                self._event({
                    "kind": "contact_pass_through", "contact": self.cid, "node": nid,
                    "time_ms": self.time, "segment_element": eid, "segment_part": pid,
                    "message": f"contact {self.cid}: more than {MAX_EVENTS} nodes pushed "
                               f"through (latest node {nid} at t={self.time:.6g} ms); further "
                               "events are only counted (summary.json contact_pass_through)"})

    def set_penmax(self, penmax: float, exclusions: bool = True) -> None:
        """Release depth as a fraction of the segment's depth scale.

        A node deeper than ``penmax * V / A`` behind a solid face (LS-DYNA's
        automatic contacts: PENMAX, default 0.4), or than
        ``max(penmax * sqrt(A), reach)`` past a shell's mid-surface on the far
        side from where it came, is released. Call before the first
        :meth:`add_forces`.
        """
        self.penmax = float(penmax)
        for p in self.passes:
            p.s_depth = np.ascontiguousarray(self.penmax * p.elem_depth)
            tmax = float(p.n_thick.max()) if p.nodes.shape[0] else 0.0
            p.capture = np.maximum(p.s_depth, 0.5 * (tmax + p.s_thick))
            p.kin_band = None
        if exclusions:
            self._exclude_junctions(self._x0)
        self._first = True

    def _exclude_junctions(self, x0: np.ndarray) -> None:
        """Leave out mesh-neighbour pairs already in contact at t = 0 (see exclusion)."""
        graph = edge_graph([p.seg for p in self.passes], x0, self._links)
        self.n_initial_penetrations = 0
        for p in self.passes:
            if p.seg.shape[0] == 0:
                continue
            ptr, cand = bucket_sort(x0, p.nodes, p.seg, p.capture)
            p.ex_ptr, p.ex_seg, kept = junction_exclusions(
                x0, p.nodes, p.n_thick, p.seg, p.s_thick, p.s_depth, p.s_two, ptr, cand, graph)
            self.n_initial_penetrations += kept
            if p.sign == 0.0:  # single surface: also the segments next to the node's own
                rp, rs = ring_exclusions(p.nodes, p.seg, x0.shape[0])
                p.ex_ptr, p.ex_seg = merge_csr(p.ex_ptr, p.ex_seg, rp, rs)

    def _sort(self, dt: float, cycle: int) -> None:
        vmax = math.sqrt(max_speed2(self._vl))
        for p in self.passes:
            if p.seg.shape[0] == 0:
                continue
            segment_frames(self._xl, p.seg, p.cen, p.nrm, p.rad2, p.warp, p.slab, False)
        lseg = float(np.median(np.concatenate([2.0 * np.sqrt(p.rad2) for p in self.passes])))
        self._margin = min(max(2.0 * vmax * max(dt, 0.0) * self.sort_interval,
                               NEAR_MARGIN * lseg), FAR_MARGIN * lseg)
        self._near_margin = NEAR_MARGIN * lseg
        for p in self.passes:
            p.ptr, p.cand = bucket_sort(self._xl, p.nodes, p.seg, p.capture + self._margin,
                                        p.ex_ptr, p.ex_seg, self._threaded(p, lists=True),
                                        size_hint=p.n_box_pairs)
            p.n_box_pairs = p.cand.shape[0]
            # re-sorted when a side of the displacements' box reaches the margin: node and
            # segment approach by less than sqrt(3) margins in space (penalty.gather)
            cut = (self._xl, p.nodes, p.n_thick, p.s_thick, p.s_depth, p.s_two, p.cen, p.nrm,
                   p.rad2, p.warp, p.oseg, _SQRT3 * self._margin, p.ptr, p.cand)
            if self._threaded(p, lists=True):
                m = distance_cut_parallel(*cut, FILTER_BLOCKS_PER_THREAD * get_num_threads())
            else:
                m = distance_cut(*cut)
            p.cand = p.cand[:m]
            if not p.seg_alive.all():
                p.ptr, p.cand = _drop_dead(p.ptr, p.cand, p.seg_alive)
            p.ptr, p.cand = keep_current(p.ptr, p.cand, p.oseg, p.seg_alive)
        self._xsort[:] = self._xl
        self._last_sort = cycle
        self.n_sorts += 1

    def expire_lists(self) -> None:
        """Rebuild the candidate lists at the next :meth:`add_forces` (lists put back
        from a restart file of an older format, made for another re-sort bound). The
        forces do not change: the lists only have to be complete."""
        self._last_sort = -(1 << 62)

    def _threaded(self, p: _Pass, lists: bool = False) -> bool:
        """Use the threaded kernels for pass p when numba runs more than one thread.
        Per-cycle kernels: p has parallel_min_rows active rows. The kernels that make
        the lists (``lists``: near filter and bucket sort): p's nodes plus far pairs
        reach parallel_min_nodes."""
        if get_num_threads() < 2:
            return False
        if not lists:
            return p.act.shape[0] >= self.parallel_min_rows
        return p.nodes.shape[0] + int(p.cand.shape[0]) >= self.parallel_min_nodes

    def _filter(self) -> None:
        """Near lists of every pass from its far lists, at the current coordinates."""
        self.n_filters += 1
        for p in self.passes:
            if p.seg.shape[0] == 0:
                continue
            par = self._threaded(p, lists=True)
            args = (self._xl, p.nodes, p.seg, p.capture + self._near_margin, p.ptr, p.cand,
                    p.oseg, p.sact, p._lo, p._hi, p.nptr, p.ncand, p._mark, self.n_filters,
                    p._nsact)
            if par:
                with dynamic_blocks():
                    m = near_filter_parallel(*args, FILTER_BLOCKS_PER_THREAD * get_num_threads())
            else:
                m = near_filter(*args)
            p.fact = p._nsact[:m]
            p.act = p._act_buf[:active_rows(p.nptr, p.oseg, p._act_buf)]
            p.othru[:] = -1  # rows left out are not rewritten (events already reported)
        self._xnear[:] = self._xl
        self._refilter = False

    def deactivate_elements(self, pid: int, elem_ids: np.ndarray) -> int:
        """Take the segments of deleted elements (part ``pid``, element ids) out
        of the contact, as LS-DYNA does for eroded elements: no node is pushed
        by them any more (they are taken out of the candidate lists at once; a
        re-sort is not needed, since the lists stay complete without them).
        Returns how many segments were removed."""
        ids = np.asarray(elem_ids, dtype=np.int64)
        removed = 0
        for p in self.passes:
            hit = p.seg_alive & (p.seg_pid == pid) & np.isin(p.seg_eid, ids)
            if hit.any():
                p.seg_alive[hit] = False
                removed += int(hit.sum())
                # the lists stay complete without those segments: no re-sort
                p.ptr, p.cand = _drop_dead(p.ptr, p.cand, p.seg_alive)
                _release_dead(p)
                self._refilter = True
        return removed

    def add_forces(self, x: np.ndarray, v: np.ndarray, dt: float, cycle: int,
                   f: np.ndarray) -> None:
        """Add the contact forces at t^{n+1} into f.

        x: (n, 3) float64 mm coordinates at t^{n+1}; v: (n, 3) float64 mm/ms
        velocities at t^{n+1/2}; dt: ms, the step just taken (also the
        SOFT=1 reference); cycle: cycle number; f: (n, 3) float64 kN, added to.
        """
        self.time += dt
        md2, mdn2 = gather(x, v, self.nodes, self._xl, self._vl, self._xsort, self._xnear)
        if self._first:
            self._xprev[:] = self._xl
        if dt > 0.0 and (self._dtc <= 0.0 or dt > 1.05 * self._dtc):
            self._dtc = dt
        if (self._first or cycle - self._last_sort >= self.sort_interval
                or md2 > (_RESORT_FRACTION * self._margin) ** 2):
            self._sort(dt, cycle)
            for p in self.passes:
                p.sact = _listed(p.cand, p.seg.shape[0])
                p.ncand = np.empty(p.cand.shape[0], np.int32)
            self._refilter = True
        if self._refilter or mdn2 > (_RESORT_FRACTION * self._near_margin) ** 2:
            self._filter()
        # first call: initial penetrations push apart (spring_force)
        self._params[11] = 1.0 if self._first else 0.0
        self._first = False
        self._fl[:] = 0.0
        self._wsum[:] = 0.0
        self.slave_force[:] = 0.0
        n_act = 0
        live = [p for p in self.passes if p.seg.shape[0]]
        for p in live:  # every pair of this cycle first: the springs on each node
            par = self._threaded(p)
            (segment_frames_of_parallel if par else segment_frames_of)(
                self._xl, p.seg, p.fact, p.cen, p.nrm, p.rad2, p.warp, p.slab)
            (detect_pass if par else detect_pass_serial)(
                p.act, self._xl, p.nodes, p.n_thick, p.seg, p.s_thick, p.s_depth, p.s_two,
                p.cen, p.nrm, p.rad2, p.warp, p.slab, p.nptr, p.ncand, p.nprev, p.oseg, p.ow,
                p.ogap, p.oentry, p.othru, p.gold, p.sold, p.orel, p.odel)
            scatter_weights(p.act, p.nodes, p.seg, p.oseg, p.ow, self._wsum)
        self._kin_live = live
        for p in live:
            (force_pass if self._threaded(p) else force_pass_serial)(
                p.act, self._vl, dt, self._dtc, p.nodes, p.n_k, p.n_mass, p.seg, p.s_k,
                p.s_mass, self._params, self._mloc, self._wsum, self._imm, p.ft, p.nprev,
                p.oseg, p.ow, p.ogap, p.gold, p.sold, p.orel, p.of, p.ofd, p.ofn, p.odel)
            if count_through(p.act, p.othru):
                self._record_through(p)
            p.fsum[:] = 0.0
            n_act += scatter_pass(p.act, p.nodes, p.seg, p.oseg, p.ow, p.of, self._fl, p.fsum)
            self.slave_force += p.sign * p.fsum
        self.master_force[:] = -self.slave_force
        self.n_active = n_act
        self.energy += finish(self.nodes, self._fl, self._fprev, self._xl, self._xprev, f)

    def kinematic_step(self, dt_next: float) -> float:
        """This cycle's kinematic step limit (ms) over the passes, after
        :meth:`add_forces` (:func:`hollowbody.contact.kinematic_step.passes_step`).
        ``dt_next``: the step the solver would take (the pairs are visited only if the
        limit can be below it; inf otherwise)."""
        return passes_step(self._kin_live, self._xl, self._vl, dt_next, self._threaded)


def _release_dead(p: _Pass) -> None:
    """Nodes whose contact segment was just deleted let go of it: the next detection
    takes them as new contacts on whatever segment holds them (the stiffening starts
    from its first gap), and no pass-through is reported against the deleted one.
    Their side memory (``nprev``, for two-sided segments) is kept."""
    rows = np.nonzero(p.oseg >= 0)[0]
    rows = rows[~p.seg_alive[p.oseg[rows]]]
    if rows.size:
        p.oseg[rows] = -1
        p.ogap[rows] = 0.0
        p.odel[rows] = 0.0
        p.oentry[rows] = 0
        p.othru[rows] = -1


def _drop_dead(ptr: np.ndarray, cand: np.ndarray, alive: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray]:
    """Candidate lists (CSR ptr (ns+1,), cand) without the segments not ``alive``."""
    keep = alive[cand]
    kept_before = np.zeros(cand.size + 1, dtype=np.int64)
    np.cumsum(keep, out=kept_before[1:])
    return kept_before[ptr], np.ascontiguousarray(cand[keep])


@njit(cache=True)
def _listed(cand: np.ndarray, nseg: int) -> np.ndarray:
    """(k,) int32 ascending: the segments that appear in cand (of nseg)."""
    seen = np.zeros(nseg, dtype=np.bool_)
    k = 0
    for q in range(cand.shape[0]):
        s = cand[q]
        if not seen[s]:
            seen[s] = True
            k += 1
    out = np.empty(k, np.int32)
    k = 0
    for s in range(nseg):
        if seen[s]:
            out[k] = s
            k += 1
    return out
