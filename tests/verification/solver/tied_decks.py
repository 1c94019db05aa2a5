"""Small decks with tied contacts (built with the Deck API) for the tied-contact tests."""

from __future__ import annotations

import numpy as np

from hollowbody.io.keyword import (
    BoundarySpcSet,
    ControlContact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    Deck,
    DefineCurve,
    Hourglass,
    InitialVelocity,
    InitialVelocityGeneration,
    MatElastic,
    MatRigid,
    Part,
    PrescribedMotionSet,
    SectionShell,
    SectionSolid,
    SetNodeList,
    SetPartList,
    SetSegment,
    TiedContact,
)
from hollowbody.mesh import standing_block

#: bar material: E (GPa), density (kg/mm^3); bar wave speed c = sqrt(E / rho) mm/ms
E_BAR, RHO_BAR = 0.1, 1.0e-6
SIDE = 10.0  # bar cross-section (mm)


def two_bars(*, length: float = 50.0, n_fine: int = 4, n_coarse: int = 3, v0: float = 1.0,
             end: float = 0.3, gap: float = 0.0, offset: bool = False, pr: float = 0.0,
             shift: tuple[float, float] = (0.0, 0.0), ramp: float = 0.0) -> tuple[Deck, dict]:
    """Two elastic bars along x tied end to end across a non-matching interface.

    Bar 1 (part 1, x in [0, L]): n_fine x n_fine elements across, cubes; bar 2
    (part 2, x in [L + gap, 2 L + gap]): n_coarse x n_coarse, cubes. Bar 1's end
    face nodes (slave node set 1) are tied to part 2 (*CONTACT_TIED_NODES_TO_SURFACE,
    ``_OFFSET`` when ``offset``). Bar 1 moves at v0 (mm/ms) along +x, bar 2 is at
    rest: a compressive wave of stress rho c v0 / 2 runs into each bar. With
    ``ramp`` > 0 (ms) both bars start at rest and bar 1's left end is driven at
    v0 reached linearly over ``ramp`` (prescribed velocity): a wave of stress
    rho c v0 runs through bar 1 and, across the tie, into bar 2. ``shift``
    (mm, y and z) moves bar 2 sideways (the tie then covers part of the face).
    Returns the deck and a dict of node ids per bar and the slave ids.
    """
    h1, h2 = SIDE / n_fine, SIDE / n_coarse
    x1, c1 = standing_block((length, SIDE, SIDE), h1)
    x2, c2 = standing_block((length, SIDE, SIDE), h2)
    x1 = x1 + np.array([0.5 * length, 0.0, 0.0])
    x2 = x2 + np.array([1.5 * length + gap, shift[0], shift[1]])
    id1 = np.arange(1, x1.shape[0] + 1)
    id2 = 100001 + np.arange(x2.shape[0])
    deck = Deck()
    deck.title = "two bars tied across a non-matching interface"
    deck.add_nodes(id1, x1)
    deck.add_nodes(id2, x2)
    deck.add_solids(np.arange(1, c1.shape[0] + 1), 1, id1[c1])
    deck.add_solids(100001 + np.arange(c2.shape[0]), 2, id2[c2])
    for pid in (1, 2):
        deck.add(Part(pid=pid, secid=1, mid=1, hgid=1, title=f"bar {pid}"))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=RHO_BAR, e=E_BAR, pr=pr))
    deck.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    slaves = id1[np.abs(x1[:, 0] - length) < 1e-9]
    deck.add(SetNodeList(sid=1, nodes=slaves.tolist(), title="bar 1 end face"))
    deck.add(TiedContact(type="TIED_NODES_TO_SURFACE", offset="OFFSET" if offset else "",
                         cid=7, heading="bar 1 -> bar 2", ssid=1, sstyp=4, msid=2, mstyp=3,
                         sst=-max(2.0 * gap, 0.0) if gap else 0.0))
    if ramp > 0.0:
        left = id1[np.abs(x1[:, 0]) < 1e-9]
        deck.add(SetNodeList(sid=2, nodes=left.tolist(), title="bar 1 loaded end"))
        deck.add(DefineCurve(lcid=1, points=[[0.0, 0.0], [ramp, v0], [100.0 * end, v0]]))
        deck.add(PrescribedMotionSet(nsid=2, dof=1, vad=0, lcid=1))
    else:
        deck.add(InitialVelocityGeneration(id=1, styp=2, vx=v0))
    deck.add(ControlTermination(endtim=end))
    deck.add(ControlTimestep(tssfac=0.9))
    deck.add(DatabaseAscii(name="GLSTAT", dt=end / 100.0))
    return deck, {"bar1": id1, "bar2": id2, "slaves": slaves, "x1": x1, "x2": x2}


def rotating_plate(*, kind: str = "SHELL_EDGE", height: float = 0.0, offset: str = "",
                   omega: float = 0.3, velocity: tuple[float, float, float] = (1.0, -2.0, 0.5),
                   end: float = 5.0) -> Deck:
    """A rigid square plate (part 1, 20 x 20 mm, 2 x 2 shells, z = 0) translating and
    spinning about the x axis through its centre, with a small deformable shell
    (part 2, 10 x 10 mm at z = ``height``, corners at (+-5, +-5)) whose four nodes
    (101-104) are tied to the plate (``*CONTACT_TIED_<kind>_TO_SURFACE[_<offset>]``).
    The shell sets the time step; its nodes must follow the rigid motion exactly.
    """
    g = np.linspace(-10.0, 10.0, 3)
    yy, xx = np.meshgrid(g, g, indexing="ij")
    xp = np.column_stack([xx.ravel(), yy.ravel(), np.zeros(9)])
    pid = np.arange(1, 10)
    quads = np.array([[1, 2, 5, 4], [2, 3, 6, 5], [4, 5, 8, 7], [5, 6, 9, 8]])
    deck = Deck()
    deck.title = "rigid plate with a tied shell"
    deck.add_nodes(pid, xp)
    deck.add_shells([1, 2, 3, 4], 1, quads, thickness=1.0)
    xs = np.array([[-5.0, -5.0, height], [5.0, -5.0, height], [5.0, 5.0, height],
                   [-5.0, 5.0, height]])
    deck.add_nodes([101, 102, 103, 104], xs)
    deck.add_shells([101], 2, [[101, 102, 103, 104]], thickness=0.5)
    deck.add(Part(pid=1, secid=1, mid=1, title="rigid plate"))
    deck.add(Part(pid=2, secid=2, mid=2, title="tied shell"))
    deck.add(SectionShell(secid=1, t1=1.0))
    deck.add(SectionShell(secid=2, t1=0.5, nip=3))
    deck.add(MatRigid(mid=1, ro=2.5e-3, e=210.0, pr=0.3))
    deck.add(MatElastic(mid=2, ro=1.0e-6, e=0.01, pr=0.3))
    deck.add(SetNodeList(sid=1, nodes=[101, 102, 103, 104]))
    deck.add(SetPartList(sid=3, parts=[1]))
    deck.add(TiedContact(type=f"TIED_{kind}_TO_SURFACE", offset=offset, cid=1, ssid=1,
                         sstyp=4, msid=3, mstyp=2, sst=-2.0 * abs(height) - 0.1))
    deck.add(InitialVelocityGeneration(id=1, styp=2, omega=omega, vx=velocity[0],
                                       vy=velocity[1], vz=velocity[2], nx=1.0))
    deck.add(ControlTermination(endtim=end))
    deck.add(ControlContact(tiedprj=0))
    deck.add(DatabaseAscii(name="GLSTAT", dt=end / 50.0))
    return deck


def t_junction(*, kind: str = "SHELL_EDGE", tied: bool = True, v_tip: float = 1.0,
               end: float = 5.0, e: float = 1.0) -> tuple[Deck, np.ndarray]:
    """A vertical elastic wall (part 2, x in [-5, 5], z in [0, 20] at y = 0, 2 x 4
    shells) standing on a base plate (part 1, 20 x 20 mm at z = 0, 3 x 3 shells,
    every DOF fixed) whose mesh does not match the wall's: with ``tied`` the wall's
    bottom nodes are tied to the base (``*CONTACT_TIED_<kind>_TO_SURFACE``), else
    they are clamped (every DOF fixed: the reference). The wall's top nodes start
    moving at ``v_tip`` along y (mm/ms); E = ``e`` GPa (the clamped wall's first
    bending period is about 2.5 ms at 1 GPa). Returns the deck and the wall's node ids.
    """
    g = np.linspace(-10.0, 10.0, 4)
    yy, xx = np.meshgrid(g, g, indexing="ij")
    xb = np.column_stack([xx.ravel(), yy.ravel(), np.zeros(16)])
    bid = np.arange(1, 17)
    j, i = (a.ravel() for a in np.meshgrid(np.arange(3), np.arange(3), indexing="ij"))
    qb = np.column_stack([j * 4 + i, j * 4 + i + 1, (j + 1) * 4 + i + 1, (j + 1) * 4 + i]) + 1
    xw_x, xw_z = np.meshgrid(np.linspace(-5.0, 5.0, 3), np.linspace(0.0, 20.0, 5))
    xw = np.column_stack([xw_x.ravel(), np.zeros(15), xw_z.ravel()])
    wid = 101 + np.arange(15)
    k, i = (a.ravel() for a in np.meshgrid(np.arange(4), np.arange(2), indexing="ij"))
    qw = wid[np.column_stack([k * 3 + i, k * 3 + i + 1, (k + 1) * 3 + i + 1, (k + 1) * 3 + i])]
    deck = Deck()
    deck.title = "wall on a base plate"
    deck.add_nodes(bid, xb)
    deck.add_nodes(wid, xw)
    deck.add_shells(np.arange(1, 10), 1, qb, thickness=1.0)
    deck.add_shells(100 + np.arange(1, 9), 2, qw, thickness=1.0)
    deck.add(Part(pid=1, secid=1, mid=1, title="base"))
    deck.add(Part(pid=2, secid=1, mid=1, title="wall"))
    deck.add(SectionShell(secid=1, t1=1.0, nip=3))
    deck.add(MatElastic(mid=1, ro=1.0e-6, e=e, pr=0.3))
    deck.add(SetNodeList(sid=1, nodes=bid.tolist()))
    bottom = wid[:3]
    deck.add(SetNodeList(sid=2, nodes=bottom.tolist()))
    deck.add(SetNodeList(sid=3, nodes=wid[-3:].tolist()))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1, dofrx=1, dofry=1, dofrz=1))
    if tied:
        deck.add(TiedContact(type=f"TIED_{kind}_TO_SURFACE", cid=1, ssid=2, sstyp=4, msid=1,
                             mstyp=3))
    else:
        deck.add(BoundarySpcSet(nsid=2, dofx=1, dofy=1, dofz=1, dofrx=1, dofry=1, dofrz=1))
    deck.add(InitialVelocity(nsid=3, vy=v_tip))
    deck.add(ControlTermination(endtim=end))
    deck.add(DatabaseAscii(name="GLSTAT", dt=end / 50.0))
    return deck, wid


def two_blocks(*, n_fine: int = 4, n_coarse: int = 2, side: float = 10.0,
               master: str = "part") -> Deck:
    """Two elastic cubes side by side along x sharing the face x = side, meshed
    independently (part 1: n_fine^3 elements, part 2: n_coarse^3) and tied there:
    part 1's face nodes (node set 1) to part 2 (MSTYP 3), or to the segment set 2 of
    part 2's face when ``master="segments"``. For the constant-stress patch test."""
    x1, c1 = standing_block((side, side, side), side / n_fine)
    x2, c2 = standing_block((side, side, side), side / n_coarse)
    x1 = x1 + np.array([0.5 * side, 0.5 * side, 0.0])
    x2 = x2 + np.array([1.5 * side, 0.5 * side, 0.0])
    id1 = np.arange(1, x1.shape[0] + 1)
    id2 = 1001 + np.arange(x2.shape[0])
    deck = Deck()
    deck.title = "two blocks tied across a non-matching face"
    deck.add_nodes(id1, x1)
    deck.add_nodes(id2, x2)
    deck.add_solids(np.arange(1, c1.shape[0] + 1), 1, id1[c1])
    deck.add_solids(1001 + np.arange(c2.shape[0]), 2, id2[c2])
    for pid in (1, 2):
        deck.add(Part(pid=pid, secid=1, mid=1, hgid=1))
    deck.add(SectionSolid(secid=1))
    deck.add(MatElastic(mid=1, ro=RHO_BAR, e=E_BAR, pr=0.3))
    deck.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    deck.add(SetNodeList(sid=1, nodes=id1[np.abs(x1[:, 0] - side) < 1e-9].tolist()))
    msid, mstyp = 2, 3
    if master == "segments":
        face = c2[np.all(np.abs(x2[c2[:, [0, 3, 7, 4]], 0] - side) < 1e-9, axis=1)]
        deck.add(SetSegment(sid=2, segments=id2[face[:, [0, 3, 7, 4]]].tolist()))
        msid, mstyp = 2, 0
    deck.add(TiedContact(type="TIED_NODES_TO_SURFACE", cid=1, ssid=1, sstyp=4, msid=msid,
                         mstyp=mstyp))
    deck.add(ControlTermination(endtim=1.0))
    return deck
