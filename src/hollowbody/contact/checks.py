"""Set-up checks of a contact side: degenerate segments and massless nodes.

Generated meshes (a hollowized part clipped to a curved boundary, a mesher's
slivers) can hold segments that cannot take part in penalty contact:

* zero area (collinear or coincident corners; area <= ``AREA_TOL`` times the
  side's median segment area, or not finite): no normal, no projection;
* zero thickness shells (thickness <= 0 and no SST / MST override): no
  contact surface and no mass;
* zero mass: every corner is a deformable node without mass, so no force
  on them means anything (and SOFT=1 / damping divide by it).

Slave nodes without mass (and not on a rigid body) are left out for the
same reason. :func:`clean_surface` drops them and says so in one message
per contact side, naming the first elements / nodes. Set-up only (numpy).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from hollowbody.contact.surface import SEG_SHELL, SEG_SOLID, Surface, segment_normals
from hollowbody.model.model import Model

#: A segment whose area is at most this fraction of the side's median is degenerate.
AREA_TOL = 1.0e-10
#: How many element / node ids a message names.
_NAMED = 8


def segment_elements(surf: Surface, model: Model) -> tuple[np.ndarray, np.ndarray]:
    """Element id and part id under each segment of surf, (s,) int64 each (-1: none)."""
    eid = np.full(surf.n_segments, -1, np.int64)
    pid = np.full(surf.n_segments, -1, np.int64)
    for kind, groups in ((SEG_SOLID, model.solid_groups), (SEG_SHELL, model.shell_groups)):
        sel = np.nonzero((surf.seg_kind == kind) & (surf.seg_group >= 0)
                         & (surf.seg_elem >= 0))[0]
        for gi in np.unique(surf.seg_group[sel]):
            m = sel[surf.seg_group[sel] == gi]
            g = groups[int(gi)]
            eid[m] = np.asarray(g.elem_ids, dtype=np.int64)[surf.seg_elem[m]]
            pid[m] = g.pid
    return eid, pid


def _names(ids: list[str]) -> str:
    more = f" and {len(ids) - _NAMED} more" if len(ids) > _NAMED else ""
    return ", ".join(ids[:_NAMED]) + more


def clean_surface(surf: Surface, model: Model, node_mass: np.ndarray, rigid_node: np.ndarray,
                  thickness_override: float, label: str, x0: np.ndarray | None = None
                  ) -> tuple[Surface, list[str]]:
    """Drop degenerate segments and massless slave nodes (see module docstring).

    surf: one side; node_mass (n,) kg; rigid_node (n,) bool; thickness_override
    mm (SST / MST, > 0 replaces shell thicknesses); label names the side in
    messages ("contact 3 slave side"). Returns the cleaned surface (the same
    object when nothing is dropped) and the warning messages (empty or one).
    x0: (n, 3) mm initial coordinates (None: ``model.node_x0``).
    """
    x0 = model.node_x0 if x0 is None else x0
    seg = surf.seg
    reasons: list[str] = []
    keep = np.ones(surf.n_segments, bool)
    if surf.n_segments:
        xs = x0[seg]
        _, area = segment_normals(seg, x0)
        finite = np.all(np.isfinite(xs.reshape(seg.shape[0], -1)), axis=1) & np.isfinite(area)
        ref = float(np.median(area[finite])) if finite.any() else 0.0
        flat = ~finite | (area <= AREA_TOL * ref) | (area <= 0.0)
        thin = np.zeros_like(flat)
        if thickness_override <= 0.0:
            thin = (surf.seg_kind == SEG_SHELL) & ~(surf.seg_thick > 0.0)
        corner_mass = np.where(rigid_node[seg], np.inf, node_mass[seg])
        light = ~(corner_mass > 0.0).any(axis=1)
        eid, pid = segment_elements(surf, model)

        def name(i: int) -> str:
            if eid[i] >= 0:
                kind = "shell" if surf.seg_kind[i] == SEG_SHELL else "solid"
                return f"{kind} {eid[i]} (part {pid[i]})"
            return "segment " + "-".join(str(int(model.node_ids[q])) for q in seg[i])

        for mask, why in ((flat, "zero area"), (thin & ~flat, "zero thickness"),
                          (light & ~flat & ~thin, "zero mass")):
            idx = np.nonzero(mask)[0]
            if idx.size:
                reasons.append(f"{idx.size} with {why}: {_names([name(i) for i in idx])}")
        keep = ~(flat | thin | light)
    nmass = np.where(rigid_node[surf.nodes], np.inf, node_mass[surf.nodes])
    keep_node = nmass > 0.0
    if not keep_node.all():
        ids = [str(int(model.node_ids[q])) for q in surf.nodes[~keep_node]]
        reasons.append(f"{len(ids)} massless node(s) left out as slaves: node {_names(ids)}")
    if not reasons:
        return surf, []
    out = replace(surf, seg=surf.seg[keep], seg_kind=surf.seg_kind[keep],
                  seg_thick=surf.seg_thick[keep], seg_group=surf.seg_group[keep],
                  seg_elem=surf.seg_elem[keep], nodes=surf.nodes[keep_node],
                  node_thick=surf.node_thick[keep_node])
    dropped = int((~keep).sum())
    head = (f"{label}: {dropped} degenerate segment(s) left out" if dropped
            else f"{label}: checked")
    return out, [head + " (" + "; ".join(reasons) + ")"]
