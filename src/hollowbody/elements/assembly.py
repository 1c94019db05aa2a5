"""Race-free assembly of per-element nodal forces into the global force array.

Element kernels write their nodal forces into their own slots of a work array
``fwork`` (e, 8, 3). Two ways to add them to ``f`` (n, 3):

* :func:`scatter_add` -- serial loop over elements (simple, no set-up);
* :class:`NodeGather` -- a node -> (element, corner) CSR map built once; a
  parallel loop over the group's distinct nodes sums their slots.

The runtime picks the gather when numba runs more than one thread and the
group is large (measured faster there; see benchmarks/bench_solid.py).
Units: kN.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange


@njit(cache=True)
def scatter_add(conn, fwork, f):
    """f[conn[e, a]] += fwork[e, a] for every element e and corner a (serial)."""
    for e in range(conn.shape[0]):
        for a in range(8):
            n = conn[e, a]
            f[n, 0] += fwork[e, a, 0]
            f[n, 1] += fwork[e, a, 1]
            f[n, 2] += fwork[e, a, 2]


@njit(cache=True, parallel=True)
def _gather_add(nodes, ptr, slots, fflat, f):
    for k in prange(nodes.shape[0]):
        sx = 0.0
        sy = 0.0
        sz = 0.0
        for j in range(ptr[k], ptr[k + 1]):
            s = slots[j]
            sx += fflat[s, 0]
            sy += fflat[s, 1]
            sz += fflat[s, 2]
        n = nodes[k]
        f[n, 0] += sx
        f[n, 1] += sy
        f[n, 2] += sz


class NodeGather:
    """CSR map from the distinct nodes of a group to their element slots.

    nodes (k,) int64 node indices; ptr (k + 1,) int64; slots (8 e,) int64 flat
    indices ``8 * e + a`` into ``fwork.reshape(-1, 3)``, grouped by node.
    """

    def __init__(self, conn: np.ndarray) -> None:
        flat = np.asarray(conn, dtype=np.int64).ravel()
        order = np.argsort(flat, kind="stable")
        sorted_nodes = flat[order]
        self.nodes, counts = np.unique(sorted_nodes, return_counts=True)
        self.ptr = np.zeros(self.nodes.size + 1, dtype=np.int64)
        np.cumsum(counts, out=self.ptr[1:])
        self.slots = order.astype(np.int64)

    def add(self, fwork: np.ndarray, f: np.ndarray) -> None:
        """f[node] += sum of the node's slots of fwork (e, 8, 3)."""
        _gather_add(self.nodes, self.ptr, self.slots, fwork.reshape(-1, 3), f)
