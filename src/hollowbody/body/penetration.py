"""Initial penetrations between the pedestrian's body segments, and below the floor.

The body's segments are separate meshes joined by joints; a posture must not
start with one segment's surface inside another's. For every pair of
segments that do not share a joint (adjacent segments overlap at their joint
by design, as the flesh of a human body model is continuous there), the
nodes of segment A are tested

- inside B's soft-tissue solids (point location in B's hexahedra split into
  tetrahedra, :class:`hollowbody.hollow.spatial.TetLocator`), and
- within ``thickness`` mm of B's surface shells (skin and rigid shells: the
  distance a contact of that thickness would find at t = 0,
  :class:`hollowbody.hollow.spatial.TriangleSurface`),

and every node is tested against the floor (z < -tol). Units mm.
"""

from __future__ import annotations

from itertools import permutations

import numpy as np

from hollowbody.body.anatomy import BodyMesh
from hollowbody.hollow.boundary import solid_tets
from hollowbody.hollow.spatial import TetLocator, TriangleSurface

#: Segment groups that share a joint and meet there (their overlap at the joint is
#: allowed; the shoulder is not among them: the arm hangs clear of the trunk).
ADJACENT = {("trunk", "thigh"), ("trunk", "head"),
            ("thigh", "shank"), ("shank", "foot"), ("upper_arm", "forearm"),
            ("forearm", "hand")}


def group_of(segment: str) -> str:
    """Penetration group of a segment label (trunk thirds are one trunk)."""
    return "trunk" if segment.endswith("trunk") else segment


def _adjacent(a: str, b: str) -> bool:
    sa, sb = a[-2:], b[-2:]
    base_a = a[:-2] if sa in ("_l", "_r") else a
    base_b = b[:-2] if sb in ("_l", "_r") else b
    if sa in ("_l", "_r") and sb in ("_l", "_r") and sa != sb:
        return False
    return (base_a, base_b) in ADJACENT or (base_b, base_a) in ADJACENT


def penetrations(mesh: BodyMesh, thickness: float = 1.0, floor: float = 0.0,
                 tol: float = 1e-6) -> dict:
    """Count the initial penetrations: ``{"pairs": [{a, b, inside, near}], "below_floor":
    n, "total": n}`` (pairs listed only where a count is not zero)."""
    x = mesh.coords()
    nodes: dict[str, set] = {}
    solids: dict[str, list] = {}
    shells: dict[str, list] = {}
    for p in mesh.parts:
        g = group_of(str(p.segment[0]))
        nodes.setdefault(g, set()).update(np.unique(p.conn).tolist())
        (solids if p.kind == "solid" else shells).setdefault(g, []).append(p.conn)
    pts = {g: np.array(sorted(v)) for g, v in nodes.items()}
    locs = {g: TetLocator(x, solid_tets(np.vstack(c))) for g, c in solids.items()}
    surfs = {g: TriangleSurface.from_shells(x, np.vstack(c)) for g, c in shells.items()}
    pairs = []
    for a, b in permutations(sorted(pts), 2):
        if _adjacent(a, b):
            continue
        pa = x[pts[a]]
        inside = int(locs[b].inside(pa).sum()) if b in locs else 0
        near = int((surfs[b].distance(pa, 2.0 * thickness) < thickness).sum()) \
            if b in surfs else 0
        if inside or near:
            pairs.append({"a": a, "b": b, "inside": inside, "near": near})
    below = int((x[:, 2] < floor - tol).sum())
    total = below + sum(p["inside"] + p["near"] for p in pairs)
    return {"pairs": pairs, "below_floor": below, "total": total}
