"""Race-free gather of per-element shell forces into nodal arrays.

Element kernels write their nodal contributions into a work array ``fe``
(e, 4, 6) (forces kN, moments kN*mm, corner order of the connectivity); the
gather then sums them per node, one node per thread, so no two threads write
the same node. The node -> element-corner map is built once per group.
"""

from __future__ import annotations

import numpy as np
from numba import get_num_threads, njit, prange

from hollowbody.elements.shell_bt_forces import CHUNK, PARALLEL_MIN


@njit(cache=True)
def _gather_range(lo, hi, fe, nodes, ptr, ref, f, moment, with_moment):
    for j in range(lo, hi):
        n = nodes[j]
        s0 = 0.0
        s1 = 0.0
        s2 = 0.0
        s3 = 0.0
        s4 = 0.0
        s5 = 0.0
        for p in range(ptr[j], ptr[j + 1]):
            r = ref[p]
            e = r // 4
            c = r - 4 * e
            s0 += fe[e, c, 0]
            s1 += fe[e, c, 1]
            s2 += fe[e, c, 2]
            s3 += fe[e, c, 3]
            s4 += fe[e, c, 4]
            s5 += fe[e, c, 5]
        f[n, 0] += s0
        f[n, 1] += s1
        f[n, 2] += s2
        if with_moment:
            moment[n, 0] += s3
            moment[n, 1] += s4
            moment[n, 2] += s5


@njit(cache=True, parallel=True)
def _gather_parallel(fe, nodes, ptr, ref, f, moment, with_moment):
    k = nodes.shape[0]
    nchunk = (k + 4 * CHUNK - 1) // (4 * CHUNK)
    for c in prange(nchunk):
        _gather_range(c * 4 * CHUNK, min(k, (c + 1) * 4 * CHUNK), fe, nodes, ptr, ref, f,
                      moment, with_moment)


def gather_node_forces(fe: np.ndarray, nodes: np.ndarray, ptr: np.ndarray, ref: np.ndarray,
                       f: np.ndarray, moment: np.ndarray, with_moment: bool) -> None:
    """Add element forces into nodal arrays, one node per thread (no races).

    fe (e,4,6); nodes (k,) int64 node indices used by the group; ptr (k+1,)
    int64 CSR offsets into ref (m,) int64 entries ``4 * element + corner``.
    f (n,3) kN += forces; moment (n,3) kN*mm += moments when ``with_moment``.
    """
    if nodes.shape[0] >= PARALLEL_MIN and get_num_threads() > 1:
        _gather_parallel(fe, nodes, ptr, ref, f, moment, with_moment)
    else:
        _gather_range(0, nodes.shape[0], fe, nodes, ptr, ref, f, moment, with_moment)


def node_gather_map(conn: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CSR map node -> element corners of ``conn`` (e, 4).

    Returns ``(nodes, ptr, ref)``: the sorted distinct node indices (k,) int64,
    offsets (k+1,) int64 and entries (4e,) int64 ``4 * element + corner``.
    A triangle's repeated node appears twice (both corners add).
    """
    flat = conn.reshape(-1).astype(np.int64)
    order = np.argsort(flat, kind="stable")
    nodes, counts = np.unique(flat[order], return_counts=True)
    ptr = np.zeros(nodes.size + 1, dtype=np.int64)
    np.cumsum(counts, out=ptr[1:])
    return nodes.astype(np.int64), ptr, order.astype(np.int64)
