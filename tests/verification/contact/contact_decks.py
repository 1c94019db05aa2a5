"""Small decks for the contact verification tests (built with the Deck API).

Units: mm, ms, kg, GPa.
"""

from __future__ import annotations

import numpy as np

from hollowbody.io.keyword import (
    BoundarySpcSet,
    Contact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseHistoryNode,
    Deck,
    DefineCurve,
    Hourglass,
    InitialVelocityGeneration,
    MatRigid,
    MatSimplifiedRubber,
    Part,
    SectionShell,
    SectionSolid,
    SetNodeList,
)
from hollowbody.mesh import standing_block
from hollowbody.tissues import tissue

#: First node / element id of the plate.
PLATE_ID0 = 100_001


def _plate(size: float, n: int, z: float) -> tuple[np.ndarray, np.ndarray]:
    """Square quad plate (edge ``size`` mm, n x n quads) centred on the z axis at height z."""
    g = np.linspace(-size / 2, size / 2, n + 1)
    yy, xx = np.meshgrid(g, g, indexing="ij")
    x = np.column_stack([xx.ravel(), yy.ravel(), np.full(xx.size, z)])
    j, i = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    p = (j * (n + 1) + i).ravel()
    return x, np.column_stack([p, p + n + 1, p + n + 2, p + 1])


def soft_block_and_rigid_plate(*, tissue_name: str = "fat", size: float = 60.0,
                               height: float = 30.0, mesh: float = 7.5,
                               plate_size: float = 45.0, plate_elem: float = 3.0,
                               plate_t: float = 4.0, plate_mass: float = 1.0,
                               speed: float = 20.0, end: float = 5.0,
                               friction: float = 0.2, soft: int = 1) -> Deck:
    """A MAT_181 tissue block (bottom fixed) struck on top by a rigid flat plate moving -z.

    The block is ``size`` x ``size`` x ``height`` mm (hexahedra of edge ``mesh``),
    with the block test's tissue law; the plate (``plate_size`` mm square,
    quads of about ``plate_elem`` mm, rigid shells ``plate_t`` mm thick, i.e.
    a contact offset of ``plate_t / 2``) weighs ``plate_mass`` kg and starts
    0.1 mm above its contact offset at ``speed`` mm/ms.
    *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE id 1, tissue slave, plate master.
    """
    t = tissue(tissue_name)
    xb, cb = standing_block((size, size, height), mesh)  # centred in x, y; on z = 0
    nplate = max(1, int(round(plate_size / plate_elem)))
    xp, qp = _plate(plate_size, nplate, height + 0.5 * plate_t + 0.1)
    bid = np.arange(1, xb.shape[0] + 1)
    pid_nodes = PLATE_ID0 + np.arange(xp.shape[0])
    deck = Deck()
    deck.title = f"{tissue_name} block and rigid plate"
    deck.add_nodes(bid, xb)
    deck.add_nodes(pid_nodes, xp)
    deck.add_solids(np.arange(1, cb.shape[0] + 1), 1, bid[cb])
    deck.add_shells(PLATE_ID0 + np.arange(qp.shape[0]), 2, pid_nodes[qp], thickness=plate_t)
    deck.add(Part(pid=1, secid=1, mid=1, hgid=1, title="tissue"))
    deck.add(Part(pid=2, secid=2, mid=2, title="plate"))
    deck.add(SectionSolid(secid=1))
    deck.add(SectionShell(secid=2, t1=plate_t, nip=2))
    deck.add(MatSimplifiedRubber(mid=1, ro=t.density, km=t.bulk_modulus, lcid=1))
    deck.add(DefineCurve(lcid=1, points=np.column_stack([t.strain, t.stress]).tolist()))
    deck.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    deck.add(MatRigid(mid=2, ro=plate_mass / (plate_size ** 2 * plate_t), e=210.0, pr=0.3,
                      cmo=1, con1=4, con2=7))
    deck.add(SetNodeList(sid=1, nodes=bid[xb[:, 2] < 1e-9].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    deck.add(InitialVelocityGeneration(id=2, styp=2, vz=-speed))
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=1, ssid=1, sstyp=3, msid=2,
                     mstyp=3, fs=friction, fd=friction, soft=soft))
    deck.add(ControlTermination(endtim=end))
    deck.add(ControlTimestep(tssfac=0.9))
    for name in ("GLSTAT", "RCFORC", "NODOUT"):
        deck.add(DatabaseAscii(name=name, dt=end / 200))
    deck.add(DatabaseHistoryNode(ids=[int(pid_nodes[0])]))
    return deck


def rigid_plate_on_fixed_base(*, size: float = 45.0, elem: float = 7.5,
                              base_t: float = 1.5, plate_t: float = 4.0,
                              plate_mass: float = 5.0, speed: float = 25.0,
                              end: float = 1.0) -> Deck:
    """A rigid plate (``plate_mass`` kg, ``speed`` mm/ms in -z) strikes a fixed base:
    an elastic shell plate (E 0.1 GPa, 1.5 mm) whose every node is held in x, y, z
    -- the hollow block's bottom wall. Shell-only surface-to-surface contact (no
    solid segments: the contact-wide stiffened zone is off), base slave, plate
    master; the plate starts 0.1 mm above the contact reach."""
    from hollowbody.io.keyword import MatElastic

    n = max(1, int(round(size / elem)))
    xb, qb = _plate(size, n, 0.0)
    xp, qp = _plate(size, n, 0.5 * (base_t + plate_t) + 0.1)
    bid = np.arange(1, xb.shape[0] + 1)
    pid_nodes = PLATE_ID0 + np.arange(xp.shape[0])
    deck = Deck()
    deck.title = "rigid plate on a fixed base"
    deck.add_nodes(bid, xb)
    deck.add_nodes(pid_nodes, xp)
    deck.add_shells(np.arange(1, qb.shape[0] + 1), 1, bid[qb], thickness=base_t)
    deck.add_shells(PLATE_ID0 + np.arange(qp.shape[0]), 2, pid_nodes[qp], thickness=plate_t)
    deck.add(Part(pid=1, secid=1, mid=1, title="base"))
    deck.add(Part(pid=2, secid=2, mid=2, title="plate"))
    deck.add(SectionShell(secid=1, t1=base_t, nip=3))
    deck.add(SectionShell(secid=2, t1=plate_t, nip=2))
    deck.add(MatElastic(mid=1, ro=5.45e-6, e=0.1, pr=0.3))
    deck.add(MatRigid(mid=2, ro=plate_mass / (size ** 2 * plate_t), e=210.0, pr=0.3,
                      cmo=1, con1=4, con2=7))
    deck.add(SetNodeList(sid=1, nodes=bid.tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    deck.add(InitialVelocityGeneration(id=2, styp=2, vz=-speed))
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=1, ssid=1, sstyp=3, msid=2,
                     mstyp=3, soft=1))
    deck.add(ControlTermination(endtim=end))
    deck.add(ControlTimestep(tssfac=0.9))
    for name in ("GLSTAT", "RCFORC", "NODOUT"):
        deck.add(DatabaseAscii(name=name, dt=end / 200))
    deck.add(DatabaseHistoryNode(ids=[int(pid_nodes[0])]))
    return deck


def flesh_tube_and_rigid_plate(*, r_in: float = 3.0, r_out: float = 15.0, n_around: int = 12,
                               length: float = 40.0, n_long: int = 4,
                               tissue_name: str = "muscle", plate_size: float = 60.0,
                               plate_n: int = 10, plate_t: float = 1.0,
                               plate_mass: float = 0.5, speed: float = 5.0, end: float = 3.0,
                               friction: float = 0.2, vdc: float = 20.0) -> Deck:
    """A flesh tube (an upper arm's muscle round its bone) struck across by a rigid plate.

    One layer of hexahedra between radii ``r_in`` and ``r_out`` mm (``n_around``
    around, ``n_long`` along the x axis, ``length`` mm), MAT_181 ``tissue_name``,
    the nodes of its lowest outer line held (it rests on a support); the bore is
    empty. The wedge-shaped elements have a small inner face: V / A of it is
    (r_out^2 - r_in^2) / (2 r_in) ~ 36 mm, so PENMAX (0.4) of it reaches past the
    outer face: a node at the outer face is within the release depth *behind*
    the bore's face of the same element. The plate (``plate_size`` mm square,
    ``plate_n`` x ``plate_n`` quads, rigid shells ``plate_t`` mm, ``plate_mass``
    kg) starts 0.1 mm above its contact reach at ``speed`` mm/ms in -z.
    *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE id 1 (flesh slave, plate master, SOFT 1,
    friction, VDC ``vdc`` %): the shoulder impact's hub contact, small.
    """
    t = tissue(tissue_name)
    th = np.linspace(0.0, 2.0 * np.pi, n_around, endpoint=False) + 0.5 * np.pi
    xs = np.linspace(-0.5 * length, 0.5 * length, n_long + 1)
    # node (k along, j radial 0 in / 1 out, i around)
    kk, jj, ii = np.meshgrid(np.arange(n_long + 1), np.arange(2), np.arange(n_around),
                             indexing="ij")
    r = np.where(jj == 0, r_in, r_out)
    xb = np.column_stack([xs[kk.ravel()], (r * np.cos(th[ii])).ravel(),
                          (r * np.sin(th[ii])).ravel()])

    def nid(k, j, i):
        return (k * 2 + j) * n_around + (i % n_around)

    conn = [[nid(k, 0, i), nid(k, 1, i), nid(k, 1, i + 1), nid(k, 0, i + 1),
             nid(k + 1, 0, i), nid(k + 1, 1, i), nid(k + 1, 1, i + 1), nid(k + 1, 0, i + 1)]
            for k in range(n_long) for i in range(n_around)]
    cb = np.array(conn)
    xp, qp = _plate(plate_size, plate_n, r_out + 0.5 * plate_t + 0.1)
    bid = np.arange(1, xb.shape[0] + 1)
    pid_nodes = PLATE_ID0 + np.arange(xp.shape[0])
    deck = Deck()
    deck.title = f"{tissue_name} tube and rigid plate"
    deck.add_nodes(bid, xb)
    deck.add_nodes(pid_nodes, xp)
    deck.add_solids(np.arange(1, cb.shape[0] + 1), 1, bid[cb])
    deck.add_shells(PLATE_ID0 + np.arange(qp.shape[0]), 2, pid_nodes[qp], thickness=plate_t)
    deck.add(Part(pid=1, secid=1, mid=1, hgid=1, title="flesh"))
    deck.add(Part(pid=2, secid=2, mid=2, title="plate"))
    deck.add(SectionSolid(secid=1))
    deck.add(SectionShell(secid=2, t1=plate_t, nip=2))
    deck.add(MatSimplifiedRubber(mid=1, ro=t.density, km=t.bulk_modulus, lcid=1))
    deck.add(DefineCurve(lcid=1, points=np.column_stack([t.strain, t.stress]).tolist()))
    deck.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    deck.add(MatRigid(mid=2, ro=plate_mass / (plate_size ** 2 * plate_t), e=210.0, pr=0.3,
                      cmo=1, con1=4, con2=7))
    low = np.isclose(xb[:, 2], -r_out)
    deck.add(SetNodeList(sid=1, nodes=bid[low].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    deck.add(InitialVelocityGeneration(id=2, styp=2, vz=-speed))
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=1, ssid=1, sstyp=3, msid=2,
                     mstyp=3, fs=friction, fd=friction, vdc=vdc, soft=1))
    deck.add(ControlTermination(endtim=end))
    deck.add(ControlTimestep(tssfac=0.9))
    for name in ("GLSTAT", "RCFORC", "NODOUT"):
        deck.add(DatabaseAscii(name=name, dt=end / 200))
    deck.add(DatabaseHistoryNode(ids=[int(pid_nodes[0])]))
    return deck
