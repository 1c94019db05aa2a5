"""The rigid hub of the lateral impacts and where it starts.

:func:`hub_mesh` meshes a closed cylinder of shells (the flat face, an
O-grid disc, toward the body; the side; the back). :func:`first_touch`
finds, for a hub of radius R travelling along ``direction`` on an axis
through a point, how far downstream its face first meets a surface (the
body's contact surface as triangles) and :func:`axis_hit` where the axis
itself meets it, so the hub can start a real gap from the skin.
:func:`hub_keywords` adds the hub's nodes, shells, part, *PART_INERTIA (the
impactor mass exactly, the initial velocity), *MAT_RIGID (CMO = 1 guidance),
*SECTION_SHELL and *INITIAL_VELOCITY_GENERATION to a deck. :func:`free_ids`
gives the first free ids of a deck. Units mm, kg, ms (velocity mm/ms = m/s).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.hollow.spatial import quads_to_triangles
from hollowbody.io.keyword import (
    Contact,
    Deck,
    DefineCurve,
    ElementBeam,
    ElementDiscrete,
    InitialVelocityGeneration,
    MassElements,
    Material,
    MatRigid,
    Nodes,
    Part,
    PartInertia,
    SectionShell,
    SetSegment,
    ShellElements,
    SolidElements,
    TiedContact,
)

#: Hub shell thickness (mm): the contact surface lies half of it in front of the face.
HUB_T = 1.0
#: Steel of the rigid hub (GPa; kg/mm^3): the contact stiffness uses E; the mass is
#: given by *PART_INERTIA.
HUB_E, HUB_PR, HUB_RHO = 210.0, 0.3, 7.85e-6
#: Element edge on the hub (mm, about).
HUB_ELEMENT = 12.0


def frame(direction: np.ndarray) -> np.ndarray:
    """(3, 3) rows e1, e2, d: d the unit travel direction, e2 the global vertical made
    perpendicular to d (global y when d is vertical), e1 = e2 x d."""
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    up = np.array([0.0, 0.0, 1.0])
    if abs(d @ up) > 0.99:
        up = np.array([0.0, 1.0, 0.0])
    e2 = up - (up @ d) * d
    e2 /= np.linalg.norm(e2)
    return np.vstack([np.cross(e2, d), e2, d])


def hub_mesh(radius: float, length: float, size: float = HUB_ELEMENT
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A closed cylinder of quads in its local frame: the face (an O-grid disc) at
    w = 0, normal +w (the travel direction), the back at w = -length.

    Returns nodes (n, 3) local (u, v, w) mm, quads (q, 4) 0-based with outward
    normals, and ``face`` (q,) bool for the quads of the face.
    """
    n = max(2, int(np.ceil(0.5 * np.pi * radius / size / 2.0)) * 2)  # quads per square side
    h = 0.5 * radius  # half-width of the inner square
    rings = max(1, int(round((radius - h) / size)))
    along = max(1, int(round(length / size)))
    nb = 4 * n

    def square(i: np.ndarray, j: np.ndarray) -> np.ndarray:
        return np.stack([-h + 2.0 * h * i / n, -h + 2.0 * h * j / n], axis=-1)

    # the inner square's boundary, counter-clockwise from the corner (h, -h)
    k = np.arange(n)
    edge = np.concatenate([square(np.full(n, n), k), square(n - k, np.full(n, n)),
                           square(np.zeros(n), n - k), square(k, np.zeros(n))])
    theta = -0.25 * np.pi + 2.0 * np.pi * np.arange(nb) / nb
    rim = radius * np.column_stack([np.cos(theta), np.sin(theta)])
    quads: list[np.ndarray] = []  # (q, 4, 2) in (u, v)
    i, j = (a.ravel() for a in np.meshgrid(np.arange(n), np.arange(n), indexing="ij"))
    quads.append(np.stack([square(i, j), square(i + 1, j), square(i + 1, j + 1),
                           square(i, j + 1)], axis=1))
    t = np.linspace(0.0, 1.0, rings + 1)
    ring = [(1.0 - s) * edge + s * rim for s in t]
    b = np.arange(nb)
    for r in range(rings):
        a0, a1 = ring[r], ring[r + 1]
        quads.append(np.stack([a0[b], a1[b], a1[(b + 1) % nb], a0[(b + 1) % nb]], axis=1))
    disc = np.concatenate(quads)
    face = np.concatenate([disc, np.zeros(disc.shape[:2] + (1,))], axis=2)
    back = np.concatenate([disc, np.full(disc.shape[:2] + (1,), -length)], axis=2)
    ws = np.linspace(0.0, -length, along + 1)
    side = []
    for q in range(along):
        p = [np.column_stack([rim, np.full(nb, ws[q])]),
             np.column_stack([rim, np.full(nb, ws[q + 1])])]
        side.append(np.stack([p[0][b], p[1][b], p[1][(b + 1) % nb], p[0][(b + 1) % nb]],
                             axis=1))
    allq = np.concatenate([face, back, *side])
    is_face = np.zeros(allq.shape[0], dtype=bool)
    is_face[:face.shape[0]] = True
    # outward normals: the hub is convex, so outward means away from its centre
    c = np.array([0.0, 0.0, -0.5 * length])
    nrm = np.cross(allq[:, 2] - allq[:, 0], allq[:, 3] - allq[:, 1])
    flip = np.einsum("ij,ij->i", nrm, allq.mean(axis=1) - c) < 0.0
    allq[flip] = allq[flip][:, ::-1]
    key = np.round(allq.reshape(-1, 3) * 1.0e6).astype(np.int64)
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    nodes = allq.reshape(-1, 3)[first[order]]
    return nodes, rank[inv.ravel()].reshape(-1, 4), is_face


# ---------------------------------------------------------------------------
# where the hub meets a surface


def _local(tris: np.ndarray, point: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Triangles (t, 3, 3) in the frame of :func:`frame` with origin ``point``."""
    return (np.asarray(tris, float) - np.asarray(point, float)) @ frame(direction).T


def _ray_hits(loc: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """Smallest w where rays along +w at (u, v) points uv (k, 2) cross the local
    triangles loc (t, 3, 3); +inf where a ray misses them all."""
    out = np.full(uv.shape[0], np.inf)
    a, b, c = loc[:, 0], loc[:, 1], loc[:, 2]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    ok = np.abs(det) > 1e-12
    a, b, c, det = a[ok], b[ok], c[ok], det[ok]
    if not det.size:
        return out
    lo = np.minimum(np.minimum(a[:, :2], b[:, :2]), c[:, :2])
    hi = np.maximum(np.maximum(a[:, :2], b[:, :2]), c[:, :2])
    for s in range(0, uv.shape[0], 256):
        p = uv[s:s + 256]
        inside = ((p[:, None, 0] >= lo[None, :, 0] - 1e-9) & (p[:, None, 0] <= hi[None, :, 0]
                  + 1e-9) & (p[:, None, 1] >= lo[None, :, 1] - 1e-9)
                  & (p[:, None, 1] <= hi[None, :, 1] + 1e-9))
        r, t = np.nonzero(inside)
        if not r.size:
            continue
        q = p[r]
        l1 = ((b[t, 0] - q[:, 0]) * (c[t, 1] - q[:, 1])
              - (c[t, 0] - q[:, 0]) * (b[t, 1] - q[:, 1])) / det[t]
        l2 = ((c[t, 0] - q[:, 0]) * (a[t, 1] - q[:, 1])
              - (a[t, 0] - q[:, 0]) * (c[t, 1] - q[:, 1])) / det[t]
        l3 = 1.0 - l1 - l2
        hit = (l1 >= -1e-9) & (l2 >= -1e-9) & (l3 >= -1e-9)
        w = l1 * a[t, 2] + l2 * b[t, 2] + l3 * c[t, 2]
        w = np.where(hit, w, np.inf)
        np.minimum.at(out, s + r, w)
    return out


def axis_hit(tris: np.ndarray, point: np.ndarray, direction: np.ndarray) -> float | None:
    """Signed distance (mm) along ``direction`` from ``point`` to where the line through
    it first meets the triangles (t, 3, 3) coming from upstream; None when it misses."""
    w = _ray_hits(_local(tris, point, direction), np.zeros((1, 2)))[0]
    return None if not np.isfinite(w) else float(w)


def first_touch(tris: np.ndarray, point: np.ndarray, direction: np.ndarray,
                radius: float, rim_points: int = 720) -> tuple[float, np.ndarray] | None:
    """Where a flat disc of ``radius`` (mm) centred on the axis through ``point``,
    normal to ``direction``, first meets the triangles (t, 3, 3) when it comes from
    upstream: (w, p) with w the signed distance (mm) along the axis from ``point`` to
    the disc's plane at first contact and p (3,) the touched point; None if the disc's
    path misses them.

    Exact up to the rim sampling: on each triangle the distance along the axis is
    linear, so its smallest value over the triangle's part within the disc's path lies
    at a vertex inside the path, where an edge crosses the path's cylinder, or on the
    rim (``rim_points`` rays, 0.65 mm apart on a 75 mm rim).
    """
    loc = _local(tris, point, direction)
    cands: list[tuple[np.ndarray, np.ndarray]] = []  # (w (k,), uv (k, 2))
    v = loc.reshape(-1, 3)
    inside = np.hypot(v[:, 0], v[:, 1]) <= radius
    cands.append((v[inside, 2], v[inside, :2]))
    for i0, i1 in ((0, 1), (1, 2), (2, 0)):
        p0, p1 = loc[:, i0], loc[:, i1]
        d = p1 - p0
        qa = d[:, 0] ** 2 + d[:, 1] ** 2
        qb = 2.0 * (p0[:, 0] * d[:, 0] + p0[:, 1] * d[:, 1])
        qc = p0[:, 0] ** 2 + p0[:, 1] ** 2 - radius**2
        disc = qb**2 - 4.0 * qa * qc
        ok = (qa > 1e-12) & (disc >= 0.0)
        for sgn in (-1.0, 1.0):
            s = np.full(qa.shape, -1.0)
            s[ok] = (-qb[ok] + sgn * np.sqrt(disc[ok])) / (2.0 * qa[ok])
            m = (s >= 0.0) & (s <= 1.0)
            pts = p0[m] + s[m, None] * d[m]
            cands.append((pts[:, 2], pts[:, :2]))
    ang = 2.0 * np.pi * np.arange(rim_points) / rim_points
    rim = radius * np.column_stack([np.cos(ang), np.sin(ang)])
    cands.append((_ray_hits(loc, rim), rim))
    w = np.concatenate([c[0] for c in cands])
    uv = np.concatenate([c[1] for c in cands])
    if not w.size or not np.isfinite(w.min()):
        return None
    k = int(np.argmin(w))
    f = frame(direction)
    hit = np.asarray(point, float) + uv[k, 0] * f[0] + uv[k, 1] * f[1] + w[k] * f[2]
    return float(w[k]), hit


def segment_triangles(seg: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Triangles (t, 3, 3) mm of contact segments seg (s, 4) node indices (triangles
    have N4 == N3) at coordinates x (n, 3): each quad split into two."""
    return x[quads_to_triangles(np.asarray(seg))]


# ---------------------------------------------------------------------------
# keywords


@dataclass
class FreeIds:
    """First free ids of a deck: node, element, part, material, section, curve, set,
    contact (each above the deck's largest, rounded up)."""

    node: int
    element: int
    part: int
    material: int
    section: int
    curve: int
    set: int
    contact: int


def _up(largest: int, step: int) -> int:
    return (max(largest, 0) // step + 1) * step


def free_ids(deck: Deck) -> FreeIds:
    """Ids above every id of ``deck`` (includes followed): nodes and elements from the
    next multiple of 10,000 (+1), the others from the next multiple of 100."""
    big = dict.fromkeys(("node", "element", "part", "material", "section", "curve", "set",
                         "contact"), 0)

    def bump(kind: str, v: object) -> None:
        a = np.asarray(v, dtype=np.int64).ravel()
        if a.size:
            big[kind] = max(big[kind], int(a.max()))

    for it in deck.iter_items():
        if isinstance(it, Nodes):
            bump("node", it.ids)
        elif isinstance(it, (SolidElements, ShellElements, MassElements, ElementBeam)):
            bump("element", it.ids)
        elif isinstance(it, ElementDiscrete):
            bump("element", it.eid)
        elif isinstance(it, (Part, PartInertia)):
            bump("part", it.pid)
        elif isinstance(it, Material):
            bump("material", it.mid)
        elif type(it).__name__.startswith("Section"):
            bump("section", it.secid)
        elif isinstance(it, DefineCurve):
            bump("curve", it.lcid)
        elif type(it).__name__.startswith("Set") or isinstance(it, SetSegment):
            bump("set", it.sid)
        elif isinstance(it, (Contact, TiedContact)) and it.cid:
            bump("contact", it.cid)
    return FreeIds(node=_up(big["node"], 10000) + 1, element=_up(big["element"], 10000) + 1,
                   part=_up(big["part"], 100), material=_up(big["material"], 100),
                   section=_up(big["section"], 100), curve=_up(big["curve"], 100),
                   set=_up(big["set"], 100), contact=_up(big["contact"], 100))


#: *MAT_RIGID CON1 code of the held global translations (x 0, y 1, z 2).
CON1 = {(): 0, (0,): 1, (1,): 2, (2,): 3, (0, 1): 4, (1, 2): 5, (0, 2): 6, (0, 1, 2): 7}


@dataclass
class Hub:
    """The hub as placed: part id, node ids (n,), the node at the face's centre (on the
    axis), face centre (3,) mm, unit direction (3,), node coordinates (n, 3) mm, held
    translations (global axes) and its mass kg."""

    pid: int
    node_ids: np.ndarray
    centre_node: int
    face_centre: np.ndarray
    direction: np.ndarray
    xyz: np.ndarray
    held: tuple[int, ...]
    mass: float


def hub_keywords(deck: Deck, ids: FreeIds, face_centre: np.ndarray, direction: np.ndarray,
                 speed: float, mass: float, diameter: float, length: float,
                 title: str = "impactor hub") -> Hub:
    """Add the hub to ``deck``: nodes, shells, *PART_INERTIA, *SECTION_SHELL (``HUB_T``),
    *MAT_RIGID and *INITIAL_VELOCITY_GENERATION. The face (radius diameter / 2) is
    centred on ``face_centre`` facing ``direction``.

    *PART_INERTIA gives the mass exactly (TM = ``mass`` kg; centre of the cylinder;
    inertia of a solid cylinder of that mass) and the initial velocity (``speed`` m/s
    along ``direction``; *INITIAL_VELOCITY_GENERATION on the part with IRIGID = 1 says
    the same, for readers that take rigid-body velocities from it). *MAT_RIGID CMO = 1
    holds every rotation and the global translations ``direction`` has no component
    along: the hub is guided, as the tests' pendulum or ram, and free along its path.
    """
    d = np.asarray(direction, float) / np.linalg.norm(direction)
    f = frame(d)
    r = 0.5 * diameter
    local, quads, _ = hub_mesh(r, length)
    xyz = np.asarray(face_centre, float) + local @ f
    nid = ids.node + np.arange(local.shape[0])
    deck.add_nodes(nid, xyz)
    deck.add_shells(ids.element + np.arange(quads.shape[0]), ids.part, nid[quads])
    held = tuple(int(k) for k in np.flatnonzero(np.abs(d) < 1e-9))
    c = np.asarray(face_centre, float) - 0.5 * length * d
    i_perp = mass * (3.0 * r**2 + length**2) / 12.0
    inertia = f.T @ np.diag([i_perp, i_perp, 0.5 * mass * r**2]) @ f
    v = speed * d
    deck.add(PartInertia(pid=ids.part, secid=ids.section, mid=ids.material, title=title,
                         xc=c[0], yc=c[1], zc=c[2], tm=mass, ixx=inertia[0, 0],
                         ixy=inertia[0, 1], ixz=inertia[0, 2], iyy=inertia[1, 1],
                         iyz=inertia[1, 2], izz=inertia[2, 2], vtx=v[0], vty=v[1], vtz=v[2]))
    deck.add(SectionShell(secid=ids.section, elform=2, nip=2, t1=HUB_T, t2=HUB_T, t3=HUB_T,
                          t4=HUB_T, title=title))
    deck.add(MatRigid(mid=ids.material, ro=HUB_RHO, e=HUB_E, pr=HUB_PR, cmo=1.0,
                      con1=float(CON1[held]), con2=7.0, title=title))
    deck.add(InitialVelocityGeneration(id=ids.part, styp=2, vx=float(v[0]), vy=float(v[1]),
                                       vz=float(v[2]), irigid=1))
    (k,) = np.flatnonzero(np.linalg.norm(local, axis=1) < 1e-9)  # the O-grid's centre
    return Hub(ids.part, nid, int(nid[k]), np.asarray(face_centre, float), d, xyz, held,
               mass)
