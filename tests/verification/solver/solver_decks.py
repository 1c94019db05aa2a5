"""Small decks for the solver verification tests (built with the Deck API)."""

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
    MatElastic,
    MatRigid,
    Part,
    PrescribedMotionSet,
    SectionShell,
    SectionSolid,
    SetNodeList,
)
from hollowbody.mesh import standing_block


def plate(size: float, n: int, z: float) -> tuple[np.ndarray, np.ndarray]:
    """Square quad plate centred on the z axis at height z: nodes, quads (normal -z)."""
    g = np.linspace(-size / 2, size / 2, n + 1)
    yy, xx = np.meshgrid(g, g, indexing="ij")
    x = np.column_stack([xx.ravel(), yy.ravel(), np.full(xx.size, z)])
    j, i = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    p = (j * (n + 1) + i).ravel()
    quads = np.column_stack([p, p + n + 1, p + n + 2, p + 1])
    return x, quads


def cube_and_plate(*, e: float = 0.01, pr: float = 0.3, h: float = 5.0, n: int = 4,
                   plate_mass: float = 1.0, speed: float = 5.0, end: float = 2.0,
                   friction: float = 0.0, ihq: int = 4, qh: float = 0.05,
                   fixed_bottom: bool = True, dtmin: float = 0.0, erode: int = 0,
                   gap: float = 0.1, crush: float = 0.0) -> Deck:
    """An elastic cube (n^3 hexes of edge h) struck on top by a rigid plate moving -z.

    crush > 0: instead, the cube's top nodes are driven down by ``crush`` mm
    over the run (prescribed displacement, VAD=2), which inverts elements.
    """
    side = n * h
    xb, cb = standing_block((side, side, side), h)
    xp, qp = plate(1.5 * side, 6, side + 0.5 + gap)
    nb = xb.shape[0]
    bid = np.arange(1, nb + 1)
    pid_nodes = 10001 + np.arange(xp.shape[0])
    deck = Deck()
    deck.title = "cube and plate"
    deck.add_nodes(bid, xb)
    deck.add_nodes(pid_nodes, xp)
    deck.add_solids(np.arange(1, cb.shape[0] + 1), 1, bid[cb])
    deck.add_shells(10001 + np.arange(qp.shape[0]), 2, pid_nodes[qp], thickness=1.0)
    area = (1.5 * side) ** 2
    deck.add(Part(pid=1, secid=1, mid=1, hgid=1, title="cube"))
    deck.add(Part(pid=2, secid=2, mid=2, title="plate"))
    deck.add(SectionSolid(secid=1))
    deck.add(SectionShell(secid=2, t1=1.0))
    deck.add(MatElastic(mid=1, ro=1.0e-6, e=e, pr=pr))
    deck.add(MatRigid(mid=2, ro=plate_mass / area, e=210.0, pr=0.3, cmo=1, con1=4, con2=7))
    deck.add(Hourglass(hgid=1, ihq=ihq, qm=qh))
    if fixed_bottom:
        deck.add(SetNodeList(sid=1, nodes=bid[xb[:, 2] < 1e-9].tolist()))
        deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    deck.add(InitialVelocityGeneration(id=2, styp=2, vz=-speed))
    if crush > 0.0:
        deck.add(SetNodeList(sid=2, nodes=bid[xb[:, 2] > side - 1e-9].tolist()))
        deck.add(DefineCurve(lcid=1, points=[[0.0, 0.0], [end, -crush]]))
        deck.add(PrescribedMotionSet(nsid=2, dof=3, vad=2, lcid=1))
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=1, ssid=1, sstyp=3, msid=2,
                     mstyp=3, fs=friction, fd=friction, soft=1))
    deck.add(ControlTermination(endtim=end, dtmin=dtmin))
    deck.add(ControlTimestep(tssfac=0.9, erode=erode))
    for name in ("GLSTAT", "RCFORC", "NODOUT", "SPCFORC", "MATSUM"):
        deck.add(DatabaseAscii(name=name, dt=end / 200))
    deck.add(DatabaseHistoryNode(ids=[int(pid_nodes[0])]))
    return deck


def crushed_column(n: int = 3, h: float = 5.0, crush: float = 30.0, end: float = 1.0,
                   erode: int = 0, dtmin: float = 0.0) -> Deck:
    """A column of n hexahedra (edge h), bottom nodes fixed, top nodes driven down by
    ``crush`` mm over ``end`` ms (every node of the top face prescribed, so the top
    element's volume is exactly h^2 (h - u) until the column's top passes the next layer)."""
    xb, cb = standing_block((h, h, n * h), h)
    ids = np.arange(1, xb.shape[0] + 1)
    deck = Deck()
    deck.title = "crushed column"
    deck.add_nodes(ids, xb)
    deck.add_solids(np.arange(1, cb.shape[0] + 1), 7, ids[cb])
    deck.add(Part(pid=7, secid=1, mid=1, hgid=1, title="column"))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=1.0e-6, e=0.01, pr=0.3))
    deck.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    deck.add(SetNodeList(sid=1, nodes=ids[xb[:, 2] < 1e-9].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    deck.add(SetNodeList(sid=2, nodes=ids[xb[:, 2] > n * h - 1e-9].tolist()))
    deck.add(DefineCurve(lcid=1, points=[[0.0, 0.0], [end, -crush]]))
    deck.add(PrescribedMotionSet(nsid=2, dof=3, vad=2, lcid=1))
    deck.add(ControlTermination(endtim=end, dtmin=dtmin))
    deck.add(ControlTimestep(tssfac=0.9, erode=erode))
    deck.add(DatabaseAscii(name="GLSTAT", dt=end / 100))
    return deck


def crushed_strip(n: int = 3, h: float = 5.0, crush: float = 30.0, end: float = 1.0,
                  erode: int = 0, dtmin: float = 0.0, dt2ms: float = 0.0,
                  istupd: int = 0) -> Deck:
    """A vertical strip of n square shells (edge h, in the xz plane, part 8,
    elastic-plastic MAT_003), bottom nodes fixed, top nodes driven down by
    ``crush`` mm over ``end`` ms: crushed in its own plane, elements collapse.
    dt2ms: *CONTROL_TIMESTEP DT2MS; istupd: *CONTROL_SHELL ISTUPD."""
    from hollowbody.io.keyword import ControlShell, MatPlasticKinematic

    zs = np.arange(n + 1) * h
    x = np.array([[xx, 0.0, z] for z in zs for xx in (0.0, h)])
    ids = np.arange(1, x.shape[0] + 1)
    quads = np.array([[2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2] for k in range(n)])
    deck = Deck()
    deck.title = "crushed shell strip"
    deck.add_nodes(ids, x)
    deck.add_shells(np.arange(1, n + 1), 8, ids[quads], thickness=1.0)
    deck.add(Part(pid=8, secid=1, mid=1, title="strip"))
    deck.add(SectionShell(secid=1, elform=2, nip=5, t1=1.0))
    deck.add(MatPlasticKinematic(mid=1, ro=1.0e-6, e=0.1, pr=0.3, sigy=0.004, etan=0.0,
                                 beta=1.0))
    deck.add(SetNodeList(sid=1, nodes=ids[x[:, 2] < 1e-9].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1, dofrx=1, dofry=1, dofrz=1))
    deck.add(SetNodeList(sid=2, nodes=ids[x[:, 2] > n * h - 1e-9].tolist()))
    deck.add(DefineCurve(lcid=1, points=[[0.0, 0.0], [end, -crush]]))
    deck.add(PrescribedMotionSet(nsid=2, dof=3, vad=2, lcid=1))
    deck.add(ControlTermination(endtim=end, dtmin=dtmin))
    deck.add(ControlTimestep(tssfac=0.9, erode=erode, dt2ms=dt2ms))
    if istupd:
        deck.add(ControlShell(istupd=istupd))
    deck.add(DatabaseAscii(name="GLSTAT", dt=end / 100))
    return deck
