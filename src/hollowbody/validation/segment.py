"""One limb segment cut from the open pedestrian, as a keyword deck of its own.

:func:`cut_segment` keeps the parts of one segment of a
:class:`~hollowbody.body.pedestrian.Body` (for a leg segment: the long bone's
shell tube, its two rigid end rows (the epiphyses) with the inertia carriers
merged into them (*PART_INERTIA, *CONSTRAINED_RIGID_BODIES; they hold the
epiphyses' mass: :mod:`hollowbody.body.inertia_fit`), the muscle and the skin),
their nodes and what they use of the materials, sections and tissue curves
(:func:`hollowbody.body.deck.materials`). Node, element, part, material and
section ids are those of the whole pedestrian deck (``hollowbody
pedestrian``), so a result can be traced back to the full model. Nothing
else is written: no joints, no gravity, no floor, no control or output cards
(the bending set-up adds its own). Units mm, kg.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.body import anatomy as an
from hollowbody.body.deck import material_id, materials, shell_sections
from hollowbody.body.pedestrian import Body
from hollowbody.io.keyword import ConstrainedRigidBodies, Deck, Part, PartInertia

#: Roles of a limb segment's parts (keys of ``Body.parts`` after ``<segment>_<side>_``).
ROLES = ("bone", "proximal", "distal", "muscle", "skin")


@dataclass
class Segment:
    """A cut segment: ``name`` (``thigh_l``), ``deck`` (nodes, elements, parts,
    materials), ``pids`` by role (:data:`ROLES`), the joint centres (3,) mm at its
    ``proximal_joint`` and ``distal_joint`` ends and ``elements`` counts by kind."""

    name: str
    deck: Deck
    pids: dict[str, int]
    proximal_joint: np.ndarray
    distal_joint: np.ndarray
    elements: dict[str, int]


def segment_parts(body: Body, segment: str, side: str = "l") -> dict[str, an.PartMesh]:
    """The parts of ``segment`` (thigh, shank, upper_arm, forearm) on ``side`` by role;
    KeyError naming the segment when the body has no such limb."""
    name = f"{segment}_{side}"
    missing = [r for r in ROLES if f"{name}_{r}" not in body.parts]
    if missing:
        raise KeyError(f"the body has no limb segment {name!r} (missing: {missing})")
    return {r: body.parts[f"{name}_{r}"] for r in ROLES}


def cut_segment(body: Body, segment: str, side: str = "l") -> Segment:
    """The deck of one limb segment of ``body`` (ids as in the whole pedestrian deck)."""
    from hollowbody.body.skeleton import SEGMENT_AXES

    parts = segment_parts(body, segment, side)
    keep = {p.pid for p in parts.values()}
    carriers = {body.carriers[parts[r].pid]: parts[r].pid for r in ("proximal", "distal")
                if parts[r].pid in body.carriers}
    keep |= set(carriers)
    x = body.mesh.coords()
    first_eid: dict[int, int] = {}
    eid = 1
    for p in body.mesh.parts:  # element ids numbered part by part, as pedestrian_deck
        first_eid[p.pid] = eid
        eid += p.conn.shape[0]
    ordered = [p for p in body.mesh.parts if p.pid in keep]
    nodes = np.unique(np.concatenate([p.conn.ravel() for p in ordered]))
    deck = Deck()
    deck.title = f"hollowbody open pedestrian: {segment}_{side} segment"
    materials(deck, body, ordered)
    deck.add_nodes(nodes + 1, x[nodes])
    secs = shell_sections(body)
    counts = {"solid": 0, "shell": 0}
    for p in ordered:
        ids = np.arange(first_eid[p.pid], first_eid[p.pid] + p.conn.shape[0])
        if p.kind == "solid":
            deck.add_solids(ids, p.pid, p.conn + 1)
        else:
            deck.add_shells(ids, p.pid, p.conn + 1)
        secid = 1 if p.kind == "solid" else secs[p.thickness]
        if p.pid in carriers:  # an inertia carrier: given mass properties, merged
            m, c, inertia = p.inertia
            deck.add(PartInertia(pid=p.pid, secid=secid, mid=material_id(p), title=p.name,
                                 xc=c[0], yc=c[1], zc=c[2], tm=m, ixx=inertia[0, 0],
                                 ixy=inertia[0, 1], ixz=inertia[0, 2], iyy=inertia[1, 1],
                                 iyz=inertia[1, 2], izz=inertia[2, 2]))
            deck.add(ConstrainedRigidBodies(pidm=carriers[p.pid], pids=p.pid))
            continue
        counts[p.kind] += p.conn.shape[0]
        deck.add(Part(pid=p.pid, secid=secid, mid=material_id(p),
                      hgid=1 if p.kind == "solid" else 0, title=p.name))
    prox, dist = SEGMENT_AXES[segment]
    sk = body.skeleton
    return Segment(f"{segment}_{side}", deck, {r: p.pid for r, p in parts.items()},
                   sk.point(f"{prox}_{side}"), sk.point(f"{dist}_{side}"), counts)
