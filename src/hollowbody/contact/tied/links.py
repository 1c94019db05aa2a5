"""Tied contacts as seen by the penalty contacts: mesh links across a tie.

A tie joins its slave nodes to the master surface as shared nodes would,
so the contacts' junction exclusions (:mod:`hollowbody.contact.exclusion`)
treat a tied node as joined, by a zero-length link, to the corners of the
master segments it lies on. Set-up only.
"""

from __future__ import annotations

import numpy as np

from hollowbody.contact.bucket import bucket_sort
from hollowbody.contact.exclusion import initial_contacts
from hollowbody.contact.surface import build_surface
from hollowbody.errors import UserInputError
from hollowbody.model.model import Model


def tie_links(x0: np.ndarray, nodes: np.ndarray, seg: np.ndarray, tol: float) -> np.ndarray:
    """Zero-length graph links of tied nodes to the master segments they lie on.

    x0 (L, 3) mm; nodes (m,) rows of the tied (slave) nodes; seg (S, 4) rows of
    the tie's master segments; tol mm: a node closer than tol to a segment
    (projection inside) lies on it. Returns (k, 2) int64 pairs (node, corner).
    """
    nodes = np.ascontiguousarray(nodes, dtype=np.int32)
    seg = np.ascontiguousarray(seg, dtype=np.int32).reshape(-1, 4)
    if nodes.size == 0 or seg.shape[0] == 0:
        return np.zeros((0, 2), np.int64)
    ptr, cand = bucket_sort(x0, nodes, seg, np.full(seg.shape[0], tol))
    reach = np.zeros(cand.shape[0])
    # two-sided, contact distance tol (node "thickness" 2 tol, segments 0)
    initial_contacts(x0, nodes, np.full(nodes.shape[0], 2.0 * tol), seg,
                     np.zeros(seg.shape[0]), np.zeros(seg.shape[0]),
                     np.ones(seg.shape[0], np.int8), ptr, cand, reach)
    hit = np.nonzero(reach > 0.0)[0]
    if hit.size == 0:
        return np.zeros((0, 2), np.int64)
    node_of = np.repeat(np.arange(nodes.shape[0]), np.diff(ptr))
    pairs = np.column_stack([np.repeat(nodes[node_of[hit]], 4), seg[cand[hit]].ravel()])
    return np.unique(pairs.astype(np.int64), axis=0)


def tied_links(model: Model, loc: np.ndarray, x0: np.ndarray,
               node_x0: np.ndarray | None = None) -> np.ndarray:
    """Zero-length exclusion-graph links (local rows) of the model's tied contacts.

    loc: (n,) int64 local row of each model node in a contact (-1: not in it);
    x0: (L, 3) mm initial coordinates of those rows; node_x0: (n, 3) mm initial
    coordinates of the model (None: ``model.node_x0``). Each tied (slave) node of
    a *CONTACT_TIED_... that is also a node of the contact is joined to the
    corners of the tie's master segments it lies on (within half the summed
    thicknesses, at least 0.1 of the segments' median size), see
    :func:`tie_links`. Returns (k, 2) int64 local row pairs.
    """
    out = [np.zeros((0, 2), np.int64)]
    for tie in getattr(model, "tied_contacts", None) or []:
        try:
            master = build_surface(tie.master, model, max(float(tie.mst), 0.0), x0=node_x0)
            slave = build_surface(tie.slave, model, max(float(tie.sst), 0.0), x0=node_x0)
        except UserInputError:
            continue  # reported by the tie itself
        seg = master.seg[np.all(loc[master.seg] >= 0, axis=1)]
        keep = loc[slave.nodes] >= 0
        nodes = loc[slave.nodes[keep]]
        if seg.shape[0] == 0 or nodes.size == 0:
            continue
        lseg = loc[seg]
        size = float(np.median(np.linalg.norm(x0[lseg[:, 2]] - x0[lseg[:, 0]], axis=1)))
        tmax = float(master.seg_thick.max(initial=0.0)) + float(
            slave.node_thick[keep].max(initial=0.0))
        out.append(tie_links(x0, nodes, lseg, max(0.5 * tmax, 0.1 * size, 1e-6)))
    return np.concatenate(out)
