"""Node-segment pairs left out of a contact: mesh neighbours in contact at t = 0.

Thick shells that meet at a junction (the walls of a hollow structure, a
shell folded tighter than its thickness) overlap by construction: a node of
one wall is closer than half the summed thicknesses to the neighbouring
wall's segments. Those pairs would push the structure apart at t = 0. A pair
(node, segment) is excluded for the whole run when, in the initial
configuration,

* the node is within contact distance of the segment, and
* the node is joined to the segment through the mesh: the shortest path
  along segment edges from the node to a corner of the segment is at most
  ``GEODESIC_FACTOR`` times the contact distance.

Pairs initially in contact but not joined that way (two separate surfaces
meshed overlapping) are kept and reported (``n_initial_penetrations``):
their contact pushes them apart. Segments that contain the node are always
left out by the broad phase.

Tied contacts join the mesh too: the wall edges of a hollowized part are not
merged with its boundary shells but tied to them (*CONTACT_TIED_...), so a
tied node is joined (path length 0, the links of
:func:`hollowbody.contact.tied.links.tie_links`) to the corners of the master
segments it lies on, and junctions across a tie are left out like junctions of
shared nodes.
"""

from __future__ import annotations

import heapq

import numpy as np
from numba import njit
from scipy import sparse

from hollowbody.contact.geometry import project_segment

#: Path length (in contact distances) within which an initial overlap is a
#: mesh junction and ignored.
GEODESIC_FACTOR = 3.0


@njit(cache=True)
def initial_contacts(x, nodes, n_thick, seg, s_thick, s_depth, s_two, ptr, cand, out):
    """out[q] = contact distance of candidate pair q if in contact at x, else 0."""
    for i in range(nodes.shape[0]):
        nd = nodes[i]
        for q in range(ptr[i], ptr[i + 1]):
            s = cand[q]
            out[q] = 0.0
            ok, inside, qx, qy, qz, nx, ny, nz, w0, w1, w2, w3 = project_segment(
                x[nd, 0], x[nd, 1], x[nd, 2], x, seg, s)
            if not (ok and inside):
                continue
            d = (x[nd, 0] - qx) * nx + (x[nd, 1] - qy) * ny + (x[nd, 2] - qz) * nz
            reach = 0.5 * (n_thick[i] + s_thick[s])
            if s_two[s] != 0:
                if abs(d) < reach:
                    out[q] = reach
            elif -s_depth[s] < d < reach:
                out[q] = max(reach, s_depth[s])


def edge_graph(segs: list[np.ndarray], x: np.ndarray, links: np.ndarray | None = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CSR graph of segment edges: ptr (L + 1,), nbr, length (mm) over rows of x.

    links: optional (k, 2) row pairs joined with length 0 (ties, see
    :mod:`hollowbody.contact.tied.links`).
    """
    e = []
    for seg in segs:
        if seg.shape[0]:
            for a in range(4):
                e.append(seg[:, [a, (a + 1) % 4]])
    nl = 0 if links is None else int(links.shape[0])
    if nl:
        e.append(np.asarray(links, dtype=np.int64).reshape(-1, 2))
    if not e:
        return np.zeros(x.shape[0] + 1, np.int64), np.zeros(0, np.int64), np.zeros(0)
    e = np.concatenate(e).astype(np.int64)
    zero = np.zeros(e.shape[0], bool)
    if nl:
        zero[-nl:] = True
    keep = e[:, 0] != e[:, 1]
    e, zero = e[keep], zero[keep]
    e = np.sort(e, axis=1)
    # one row per edge; a tie link wins over a mesh edge between the same nodes
    order = np.lexsort((~zero, e[:, 1], e[:, 0]))
    e, zero = e[order], zero[order]
    first = np.ones(e.shape[0], bool)
    first[1:] = np.any(e[1:] != e[:-1], axis=1)
    e, zero = e[first], zero[first]
    both = np.concatenate([e, e[:, ::-1]])
    zb = np.concatenate([zero, zero])
    order = np.lexsort((both[:, 1], both[:, 0]))
    both, zb = both[order], zb[order]
    ptr = np.zeros(x.shape[0] + 1, np.int64)
    np.add.at(ptr, both[:, 0] + 1, 1)
    ptr = np.cumsum(ptr)
    length = np.where(zb, 0.0, np.linalg.norm(x[both[:, 1]] - x[both[:, 0]], axis=1))
    return ptr, both[:, 1], length


def _within(src: int, radius: float, ptr, nbr, length) -> dict[int, float]:
    """Shortest path lengths from src to nodes closer than radius (Dijkstra)."""
    dist = {src: 0.0}
    heap = [(0.0, src)]
    while heap:
        d, u = heapq.heappop(heap)
        if d > dist.get(u, np.inf):
            continue
        for q in range(ptr[u], ptr[u + 1]):
            w = int(nbr[q])
            nd = d + float(length[q])
            if nd <= radius and nd < dist.get(w, np.inf):
                dist[w] = nd
                heapq.heappush(heap, (nd, w))
    return dist


def junction_exclusions(x0: np.ndarray, nodes: np.ndarray, n_thick: np.ndarray,
                        seg: np.ndarray, s_thick: np.ndarray, s_depth: np.ndarray,
                        s_two: np.ndarray, ptr: np.ndarray, cand: np.ndarray,
                        graph: tuple[np.ndarray, np.ndarray, np.ndarray]
                        ) -> tuple[np.ndarray, np.ndarray, int]:
    """Excluded pairs of one pass (see module docstring).

    x0: (L, 3) mm initial local coordinates; the pass arrays as in
    :func:`hollowbody.contact.detect.detect_pass`; ptr / cand: candidate
    pairs at x0 (capture distance, no margin); graph: :func:`edge_graph`.
    Returns ex_ptr (ns + 1,) int64, ex_seg int32 (CSR per node) and the
    number of initial contacts that are kept.
    """
    ns = nodes.shape[0]
    reach = np.zeros(cand.shape[0])
    initial_contacts(x0, nodes, n_thick, seg, s_thick, s_depth, s_two, ptr, cand, reach)
    hit = np.nonzero(reach > 0.0)[0]
    ex_ptr = np.zeros(ns + 1, np.int64)
    if hit.size == 0:
        return ex_ptr, np.zeros(0, np.int32), 0
    node_of = np.repeat(np.arange(ns), np.diff(ptr))
    gptr, nbr, length = graph
    pairs = []
    kept = 0
    for i in np.unique(node_of[hit]):
        qs = hit[node_of[hit] == i]
        radius = GEODESIC_FACTOR * float(reach[qs].max())
        dist = _within(int(nodes[i]), radius, gptr, nbr, length)
        for q in qs:
            s = int(cand[q])
            lim = GEODESIC_FACTOR * reach[q]
            if min(dist.get(int(c), np.inf) for c in seg[s]) <= lim:
                pairs.append((int(i), s))
            else:
                kept += 1
    if not pairs:
        return ex_ptr, np.zeros(0, np.int32), kept
    e = np.array(sorted(pairs), dtype=np.int64)
    np.add.at(ex_ptr, e[:, 0] + 1, 1)
    return np.cumsum(ex_ptr), e[:, 1].astype(np.int32), kept


def ring_exclusions(nodes: np.ndarray, seg: np.ndarray, n_rows: int
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Segments next to a node's own segments (sharing a corner with one), per node.

    Used by single-surface contact: a thick shell bent at an element edge
    brings a node within contact distance of the next segment, which is not
    contact. nodes (ns,) rows, seg (S, 4) rows of a (n_rows, 3) coordinate
    array. Returns CSR ptr (ns + 1,) int64, seg int32 (sorted per node).
    """
    nseg = seg.shape[0]
    rows = seg.ravel().astype(np.int64)
    cols = np.repeat(np.arange(nseg, dtype=np.int64), 4)
    inc = sparse.csr_matrix((np.ones(rows.size), (rows, cols)), shape=(n_rows, nseg))
    inc.data[:] = 1.0  # duplicates (triangles) summed: back to a pattern
    own = inc[nodes]
    ring = (own @ (inc.T @ inc)).tocsr()
    ring.data[:] = 1.0
    ring = (ring - own.multiply(10.0)).tocsr()  # drop the node's own segments
    ring.data = np.where(ring.data > 0.0, 1.0, 0.0)
    ring.eliminate_zeros()
    ring.sort_indices()
    return ring.indptr.astype(np.int64), ring.indices.astype(np.int32)


def merge_csr(p1: np.ndarray, s1: np.ndarray, p2: np.ndarray, s2: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """Union per row of two CSR lists of the same number of rows."""
    n = p1.shape[0] - 1
    r1 = np.repeat(np.arange(n), np.diff(p1))
    r2 = np.repeat(np.arange(n), np.diff(p2))
    rows = np.concatenate([r1, r2])
    cols = np.concatenate([s1, s2]).astype(np.int64)
    if rows.size == 0:
        return np.zeros(n + 1, np.int64), np.zeros(0, np.int32)
    key = np.unique(rows * (int(cols.max()) + 1) + cols)
    r = key // (int(cols.max()) + 1)
    c = key % (int(cols.max()) + 1)
    ptr = np.zeros(n + 1, np.int64)
    np.add.at(ptr, r + 1, 1)
    return np.cumsum(ptr), c.astype(np.int32)
