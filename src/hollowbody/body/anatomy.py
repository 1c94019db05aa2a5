"""The pedestrian's meshes, part by part, in the posture of a :class:`Skeleton`.

Every region is built in its segment's local frame (origin at the proximal
joint, local z from the distal to the proximal joint, x anterior) and placed
by the frame, so a posture is only a set of frames and joint centres.

- Limb segments (thigh, shank, upper arm, forearm; :func:`limb`): a layered
  tube (:mod:`hollowbody.body.tube`): bone shell tube on the inner ring
  (deformable cortical bone between two rigid end rows, the epiphyses that
  carry the joints), skeletal muscle hexahedra, skin shells on the outer ring;
  bone, muscle and skin share nodes. The flesh tapers linearly from the
  proximal to the distal end (elliptic sections) and stops ``JOINT_GAP`` mm
  short of each joint centre.
- Trunk (:func:`trunk`): one layered tube from the hip joints' height to C7:
  the spine's shell tube (five rigid zones T1, T8, T12, L3, sacrum, split at
  the levels of :data:`hollowbody.body.skeleton.SPINE_ZONES`) behind the
  centre, thoracic or abdominal organ hexahedra, the rib cage (from T12/L1 up;
  :func:`rib_cage_roles`) or the pelvis shell (rigid, below L5/S1) on an inner
  ring, subcutaneous fat (gluteal flesh below L5/S1) and skin.
- Head, neck, hands and feet (:func:`rigid_shell`): closed rigid shells
  (ellipsoids, a cylinder, boxes) whose mass and inertia are given by
  *PART_INERTIA.

Dimensions are fractions of the stature (:data:`LIMB_SHAPES`, :data:`TRUNK_SHAPE`,
stated engineering choices sized so the flesh carries most of each segment's
de Leva mass; the rigid pieces carry the rest). Units mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.body.skeleton import SPINE_ZONES, Skeleton
from hollowbody.body.tube import Ellipses, layered_tube, stations

#: Gap (mm) between a segment's flesh end and its joint centre.
JOINT_GAP = 12.0
#: Limb flesh (fractions of stature): ML and AP semi-axes at the proximal end,
#: distal/proximal taper, lateral offset of the flesh centre at the proximal end,
#: bone mid-surface radius, cortical thickness (mm, at 1,753 mm); ``power`` p of the
#: taper profile 1 + (taper - 1) u^p along the flesh (u = 0 proximal, 1 distal;
#: default 1, linear): the shank's calf keeps its width and narrows to the ankle
#: (p = 3), which puts its transverse inertia near de Leva's.
LIMB_SHAPES = {
    "thigh": dict(a=0.051, b=0.068, taper=0.60, offset=0.003, bone_r=0.0068, bone_t=5.0),
    "shank": dict(a=0.030, b=0.034, taper=0.45, offset=0.0, bone_r=0.0057, bone_t=4.0,
                  power=3.0),
    "upper_arm": dict(a=0.029, b=0.029, taper=0.80, offset=0.0, bone_r=0.0057, bone_t=3.5),
    "forearm": dict(a=0.027, b=0.024, taper=0.65, offset=0.0, bone_r=0.0046, bone_t=2.5),
}
#: Trunk sections (fractions of stature): half-width a and half-depth b at
#: MIDH, OMPH, XYPH, CERV; spine shell radius and its posterior offset (fraction of b).
#: The half-width at MIDH (0.088) is below half of Winter's hip breadth (0.191 H),
#: which is measured over the greater trochanters (the thighs' tops): with it the
#: lower trunk's moments of inertia are de Leva's.
TRUNK_SHAPE = dict(a=(0.088, 0.085, 0.092, 0.080), b=(0.058, 0.062, 0.060, 0.052),
                   spine_r=0.012, spine_back=0.30, fat=0.85)
RIB_T = 2.0   # mm, rib-cage shell (ribs, intercostal layers, costal cartilage, sternum)
#: Costal cartilage: the rib rows' elements within this angle (deg, parametric angle
#: of the trunk's section ellipse) of the anterior mid-line, beside the sternum.
CARTILAGE_ANGLE = 45.0
#: Sternum: the column of rib-cage elements on the anterior mid-line (half-width as a
#: fraction of stature; at least the one column centred on it), from XYPH up.
STERNUM_HALF_WIDTH = 0.011
BONE_T_PELVIS = 3.0
SKIN_T = 1.0


@dataclass
class PartMesh:
    """One part: ``kind`` solid or shell, ``conn`` 0-based global node indices,
    ``segment`` per element (de Leva segment names, sides suffixed), material key,
    shell thickness, rigid flag, and (rigid shells with given inertia) the
    *PART_INERTIA record (mass kg, centre (3,), inertia (3, 3) kg mm^2)."""

    name: str
    region: str
    kind: str
    material: str
    conn: np.ndarray
    segment: np.ndarray
    thickness: float = 0.0
    rigid: bool = False
    inertia: tuple[float, np.ndarray, np.ndarray] | None = None
    pid: int = 0


@dataclass
class BodyMesh:
    """Nodes (n, 3) mm and parts, in the order added (pids 1, 2, ...)."""

    x: list[np.ndarray] = field(default_factory=list)
    parts: list[PartMesh] = field(default_factory=list)
    n: int = 0

    def add_nodes(self, xyz: np.ndarray) -> int:
        """Append nodes; returns the index of the first."""
        first = self.n
        self.x.append(np.asarray(xyz, float).reshape(-1, 3))
        self.n += self.x[-1].shape[0]
        return first

    def add_part(self, part: PartMesh) -> PartMesh:
        part.pid = len(self.parts) + 1
        self.parts.append(part)
        return part

    def coords(self) -> np.ndarray:
        """(n, 3) all nodes."""
        return np.vstack(self.x) if self.x else np.zeros((0, 3))

    def part(self, name: str) -> PartMesh:
        for p in self.parts:
            if p.name == name:
                return p
        raise KeyError(f"no part {name!r}")


def place(local: np.ndarray, origin: np.ndarray, frame: np.ndarray) -> np.ndarray:
    """Global coordinates of local points (n, 3): origin + local @ frame (rows x, y, z)."""
    return origin + local @ frame


def limb(body: BodyMesh, sk: Skeleton, segment: str, side: str, mesh: float,
         scale: float = 1.0) -> dict[str, PartMesh]:
    """Bone, epiphyses, muscle and skin of one limb segment (``scale`` multiplies the
    flesh semi-axes). Returns the parts by role."""
    from hollowbody.body.skeleton import SEGMENT_AXES

    h = sk.stature
    s = LIMB_SHAPES[segment]
    prox, dist = SEGMENT_AXES[segment]
    p0, p1 = sk.point(f"{prox}_{side}"), sk.point(f"{dist}_{side}")
    length = float(np.linalg.norm(p1 - p0))
    frame = sk.frames[f"{segment}_{side}"]
    lateral = 1.0 if side == "l" else -1.0  # local y is global left in standing
    zs, _ = stations([-length + JOINT_GAP, -JOINT_GAP], mesh)
    nz = zs.size - 1
    u = (zs - zs[-1]) / (zs[0] - zs[-1])  # 0 proximal .. 1 distal
    taper = 1.0 + (s["taper"] - 1.0) * u ** s.get("power", 1.0)
    a = scale * s["a"] * h * taper
    b = scale * s["b"] * h * taper
    off = lateral * s["offset"] * h * (1.0 - u)
    rb = s["bone_r"] * h
    outer = Ellipses(np.zeros(nz + 1), off, b, a)  # local x: AP (b), local y: ML (a)
    inner = Ellipses.constant(nz + 1, rb, rb)
    perim = np.pi * (a[-1] + b[-1])
    nt = int(np.clip(2 * round(perim / mesh / 2), 8, 12))
    radial = max(2, int(round((0.5 * (a[-1] + b[-1]) - rb) / mesh)))
    tube = layered_tube(zs, inner, outer, np.linspace(0.0, 1.0, radial + 1), nt)
    first = body.add_nodes(place(tube.nodes(), p0, frame))
    name = f"{segment}_{side}"
    region = "leg" if segment in ("thigh", "shank") else "arm"
    region = f"{region}_{side}"
    rows = np.arange(nz)
    tag = np.full(0, name)

    def seg(n: int) -> np.ndarray:
        return np.full(n, name, dtype=object) if n else tag

    bone_rows = rows[1:-1] if nz > 2 else rows[:0]
    out = {}
    c = tube.quads(0, bone_rows) + first
    out["bone"] = body.add_part(PartMesh(f"{name} bone", region, "shell", "cortical", c,
                                         seg(len(c)), s["bone_t"]))
    for end, r in (("proximal", rows[-1:]), ("distal", rows[:1])):
        c = tube.quads(0, r) + first
        out[end] = body.add_part(PartMesh(f"{name} {end} epiphysis", region, "shell",
                                          "rigid", c, seg(len(c)), s["bone_t"], rigid=True))
    c = tube.hexes(rows, np.arange(radial)) + first
    out["muscle"] = body.add_part(PartMesh(f"{name} muscle", region, "solid", "muscle", c,
                                           seg(len(c))))
    c = tube.quads(radial, rows) + first
    out["skin"] = body.add_part(PartMesh(f"{name} skin", region, "shell", "skin", c,
                                         seg(len(c)), SKIN_T))
    return out


def trunk(body: BodyMesh, sk: Skeleton, mesh: float, scale: float = 1.0
          ) -> dict[str, PartMesh]:
    """The trunk's parts by role (``scale`` multiplies the section semi-axes)."""
    h = sk.stature
    t = TRUNK_SHAPE
    names = ["MIDH", "L5S1", "L3L4", "T12L1", "T9T10", "T4T5", "C7T1"]
    zb = [float(sk.point(n)[2]) for n in names]
    z0 = zb[0]
    zs, owner = stations([z - z0 for z in zb], mesh)
    key = [sk.point(n)[2] - z0 for n in ("MIDH", "OMPH", "XYPH", "CERV")]
    a = scale * h * np.interp(zs, key, t["a"])
    b = scale * h * np.interp(zs, key, t["b"])
    nz = zs.size - 1
    rs = t["spine_r"] * h
    back = -t["spine_back"] * b
    outer = Ellipses(np.zeros(nz + 1), np.zeros(nz + 1), b, a)
    inner = Ellipses(back, np.zeros(nz + 1), np.full(nz + 1, rs), np.full(nz + 1, rs))
    nt = int(max(12, 4 * round(np.pi * (a.mean() + b.mean()) / mesh / 4)))
    depth = float(np.mean(0.5 * (a + b)))
    n_org = max(2, int(round(t["fat"] * depth / mesh)))
    frac = np.concatenate([np.linspace(0.0, t["fat"], n_org + 1), [1.0]])
    tube = layered_tube(zs, inner, outer, frac, nt, theta0=np.pi / nt)
    first = body.add_nodes(place(tube.nodes(), sk.point("MIDH") - np.array([0, 0, 0.0]),
                                 np.eye(3)))
    # thirds of de Leva's trunk by element row (XYPH and OMPH are stations)
    z_mid = 0.5 * (zs[:-1] + zs[1:])
    zo, zx = key[1], key[2]
    third = np.where(z_mid >= zx, "upper_trunk", np.where(z_mid >= zo, "middle_trunk",
                                                          "lower_trunk")).astype(object)
    rows = np.arange(nz)
    out: dict[str, PartMesh] = {}

    def rows_seg(r: np.ndarray, per_row: int) -> np.ndarray:
        return np.repeat(third[r], per_row)

    def add(key_: str, part: PartMesh) -> None:
        if part.conn.shape[0]:
            out[key_] = body.add_part(part)

    discs: list[np.ndarray] = []
    for zone, _, _ in SPINE_ZONES:
        zid = {"T1": 5, "T8": 4, "T12": 3, "L3": 2, "sacrum": 0}[zone]
        r = rows[(owner == zid) | ((owner == 1) & (zone == "sacrum"))]
        if zone != "sacrum":  # the zone's lowest row: a deformable disc between bodies
            discs.append(r[:1])
            r = r[1:]
        c = tube.quads(0, r) + first
        add(f"spine_{zone}", PartMesh(f"spine {zone}", "trunk", "shell", "rigid", c,
                                      rows_seg(r, nt), 4.0, rigid=True))
    r = np.concatenate(discs)
    add("discs", PartMesh("intervertebral discs", "trunk", "shell", "disc",
                          tube.quads(0, r) + first, rows_seg(r, nt), 4.0))
    thorax = rows[owner >= 3]
    abdomen = rows[(owner == 1) | (owner == 2)]
    pelvis = rows[owner == 0]
    c = tube.quads(n_org, thorax) + first
    seg = rows_seg(thorax, nt)
    theta = np.pi / nt + 2.0 * np.pi * (np.arange(nt) + 0.5) / nt  # element centres
    half = STERNUM_HALF_WIDTH * h / float(np.mean(a[thorax]))  # rad, arc / half-width
    role = rib_cage_roles(thorax.size, theta, half, z_mid[thorax] >= zx)
    for key_, r_, mat, label in (("ribs", "rib", "cortical", "ribs"),
                                 ("intercostal", "intercostal", "intercostal",
                                  "intercostal layers"),
                                 ("costal_cartilage", "cartilage", "costal_cartilage",
                                  "costal cartilage"),
                                 ("sternum", "sternum", "cortical", "sternum")):
        m = role.ravel() == r_
        add(key_, PartMesh(label, "trunk", "shell", mat, c[m], seg[m], RIB_T))
    c = tube.quads(n_org, pelvis) + first
    add("pelvis", PartMesh("pelvis", "trunk", "shell", "rigid", c, rows_seg(pelvis, nt),
                           BONE_T_PELVIS, rigid=True))
    per = n_org * nt
    for key_, r, mat, label in (("thoracic_organs", thorax, "thoracic_organs",
                                 "thoracic organs"),
                                ("abdominal_organs", np.concatenate([pelvis, abdomen]),
                                 "abdominal_organs", "abdominal and pelvic organs")):
        c = tube.hexes(r, np.arange(n_org)) + first
        add(key_, PartMesh(label, "trunk", "solid", mat, c, rows_seg(r, per)))
    for key_, r, mat, label in (("fat_thorax", thorax, "fat", "subcutaneous fat, thorax"),
                                ("fat_abdomen", abdomen, "fat", "subcutaneous fat, abdomen"),
                                ("gluteal", pelvis, "muscle", "gluteal flesh")):
        c = tube.hexes(r, np.array([n_org])) + first
        add(key_, PartMesh(label, "trunk", "solid", mat, c, rows_seg(r, nt)))
    c = tube.quads(n_org + 1, rows) + first
    add("skin", PartMesh("trunk skin", "trunk", "shell", "skin", c, rows_seg(rows, nt),
                         SKIN_T))
    return out


def rib_cage_roles(n_rows: int, theta: np.ndarray, sternum_half: float,
                   sternum_rows: np.ndarray) -> np.ndarray:
    """(n_rows, nt) role of each rib-cage shell: ``rib``, ``intercostal``,
    ``cartilage`` or ``sternum``; rows bottom to top, ``theta`` (nt,) element centre
    angles (rad, 0 = anterior).

    The human rib cage is ribs, curved bones about as high as the spaces between them,
    joined by the intercostal muscles and membranes, and in front by the costal
    cartilages to the sternum. At the model's mesh the rows of the cage's shell take
    those roles in turn: rows alternate rib / intercostal from the top one down (half
    the height is bone, at any mesh); a rib row's elements within
    :data:`CARTILAGE_ANGLE` of the anterior mid-line are costal cartilage; the
    column(s) on the mid-line (within ``sternum_half`` rad, at least the nearest one)
    are the sternum in the rows where ``sternum_rows`` (n_rows,) is true (XYPH up).
    Without this the cage was one continuous bone shell, which carries a lateral load
    by membrane action round and along the chest, far stiffer than ribs that bend.
    """
    ang = np.abs((np.asarray(theta) + np.pi) % (2.0 * np.pi) - np.pi)
    rib_row = (n_rows - 1 - np.arange(n_rows)) % 2 == 0
    role = np.where(rib_row[:, None], "rib", "intercostal").astype(object)
    role = np.broadcast_to(role, (n_rows, ang.size)).copy()
    front = ang < np.radians(CARTILAGE_ANGLE)
    role[rib_row[:, None] & front[None, :]] = "cartilage"
    mid = (ang <= sternum_half) | (ang == ang.min())
    role[np.asarray(sternum_rows, bool)[:, None] & mid[None, :]] = "sternum"
    return role


def closed_shell(shape: str, semi: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """A closed quad surface around the origin: ``box`` or ``ellipsoid`` of semi-axes
    (3,) mm, n x n quads per cube face; returns (nodes (m, 3), quads (q, 4) 0-based),
    normals outward."""
    g = np.linspace(-1.0, 1.0, n + 1)
    pts, quads = [], []
    base = 0
    for axis in range(3):
        for sgn in (1.0, -1.0):
            u, v = np.meshgrid(g, g, indexing="ij")
            p = np.zeros(u.shape + (3,))
            p[..., axis] = sgn
            p[..., (axis + 1) % 3] = u
            p[..., (axis + 2) % 3] = v
            pts.append(p.reshape(-1, 3))
            i, j = (a.ravel() for a in np.meshgrid(np.arange(n), np.arange(n), indexing="ij"))
            q = np.column_stack([i * (n + 1) + j, (i + 1) * (n + 1) + j,
                                 (i + 1) * (n + 1) + j + 1, i * (n + 1) + j + 1]) + base
            quads.append(q if sgn > 0 else q[:, ::-1])
            base += (n + 1) ** 2
    p = np.vstack(pts)
    key = np.round(p * n * 4).astype(np.int64)
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    p = p[first[order]]
    q = rank[inv.ravel()[np.vstack(quads)]]
    if shape == "ellipsoid":
        p = p / np.linalg.norm(p, axis=1)[:, None]
    return p * semi, q


def rigid_shell(body: BodyMesh, name: str, region: str, segment: str, shape: str,
                centre: np.ndarray, semi: np.ndarray, frame: np.ndarray, n: int,
                mass: float, com: np.ndarray, inertia: np.ndarray, t: float = 2.0
                ) -> PartMesh:
    """A closed rigid shell part (skin surface for contact) with given mass (kg), centre of
    mass (3,) mm and inertia (3, 3) kg mm^2 about it (global axes)."""
    p, q = closed_shell(shape, np.asarray(semi, float), n)
    first = body.add_nodes(place(p, centre, frame))
    return body.add_part(PartMesh(name, region, "shell", "rigid", q + first,
                                  np.full(q.shape[0], segment, dtype=object), t, rigid=True,
                                  inertia=(mass, np.asarray(com, float),
                                           np.asarray(inertia, float))))
