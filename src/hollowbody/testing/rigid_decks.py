"""Small decks of rigid-body assemblies for tests, the example and docs.

:func:`assembly_deck`: three one-hexahedron *MAT_RIGID boxes merged into one body
by a chain of *CONSTRAINED_RIGID_BODIES (1 <- 2, 2 <- 3), two point-mass nodes
carried by it (*CONSTRAINED_EXTRA_NODES_NODE / _SET), and a nodal rigid body
(PID 100) of four point masses; everything starts with one rigid motion (a spin
of ``omega`` rad/ms about a non-principal axis plus a translation), then each
body flies freely. Nothing is deformable: the step comes from the rigid boxes'
*MAT_RIGID E, PR and density (E only sets the step here; it is lowered to 0.21
GPa so that a run of ~1000 cycles covers a few radians).

The point data (:data:`BOXES`, :data:`EXTRA`, :data:`NRB`) are exported so the
tests can compute the mass properties by hand. Units: mm, ms, kg.
"""

from __future__ import annotations

import numpy as np

from hollowbody.io.keyword import (
    ConstrainedExtraNodesNode,
    ConstrainedExtraNodesSet,
    ConstrainedNodalRigidBody,
    ConstrainedRigidBodies,
    ControlTermination,
    DatabaseAscii,
    Deck,
    InitialVelocityGeneration,
    MatRigid,
    Part,
    SectionSolid,
    SetNodeList,
)

#: pid: (lower corner (3,) mm, size (3,) mm, density kg/mm^3, first node id)
BOXES = {1: ((0.0, 0.0, 0.0), (20.0, 10.0, 6.0), 7.8e-6, 1),
         2: ((30.0, 0.0, 0.0), (10.0, 10.0, 10.0), 2.7e-6, 11),
         3: ((45.0, 0.0, 0.0), (5.0, 4.0, 4.0), 7.8e-6, 21)}
#: extra nodes: id: (position mm, mass kg, part it is carried by)
EXTRA = {31: ((10.0, 15.0, 3.0), 0.002, 1), 32: ((35.0, -5.0, 5.0), 0.003, 2)}
#: nodal rigid body 100: id: (position mm, mass kg)
NRB = {41: ((20.0, 30.0, 0.0), 0.004), 42: ((30.0, 30.0, 0.0), 0.002),
       43: ((20.0, 40.0, 2.0), 0.003), 44: ((22.0, 33.0, 8.0), 0.001)}
#: hexahedron corners in LS-DYNA order as offsets (0/1 per axis)
HEX = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)


def box_nodes(pid: int) -> tuple[np.ndarray, np.ndarray]:
    """(ids (8,), coordinates (8, 3) mm) of box ``pid``."""
    lo, size, _, first = BOXES[pid]
    return first + np.arange(8), np.asarray(lo) + HEX * np.asarray(size)


def assembly_deck(end: float = 20.0, omega: float = 0.1, nrb: bool = True,
                  extra: bool = True, merges: bool = True, rbdout_dt: float = 0.0) -> Deck:
    """The free-flying assembly (see the module docstring); ``end`` ms."""
    deck = Deck()
    deck.title = "free-flying rigid assembly"
    deck.add(SectionSolid(secid=1))
    for pid, (_, _, rho, _) in BOXES.items():
        ids, x = box_nodes(pid)
        deck.add_nodes(ids, x)
        deck.add_solids(np.array([pid]), pid, ids[None, :])
        deck.add(MatRigid(mid=pid, ro=rho, e=0.21, pr=0.3))
        deck.add(Part(pid=pid, secid=1, mid=pid, title=f"box {pid}"))
    if merges:
        deck.add(ConstrainedRigidBodies(pidm=1, pids=2))
        deck.add(ConstrainedRigidBodies(pidm=2, pids=3))
    if extra:
        ids = np.array(list(EXTRA))
        deck.add_nodes(ids, np.array([p for p, _, _ in EXTRA.values()]))
        deck.add_masses(ids, ids, np.array([m for _, m, _ in EXTRA.values()]))
        deck.add(ConstrainedExtraNodesNode(pid=EXTRA[32][2], nid=32))
        deck.add(SetNodeList(sid=31, nodes=[31]))
        deck.add(ConstrainedExtraNodesSet(pid=EXTRA[31][2], nsid=31))
    if nrb:
        ids = np.array(list(NRB))
        deck.add_nodes(ids, np.array([p for p, _ in NRB.values()]))
        deck.add_masses(100 + ids, ids, np.array([m for _, m in NRB.values()]))
        deck.add(SetNodeList(sid=100, nodes=ids.tolist()))
        deck.add(ConstrainedNodalRigidBody(pid=100, nsid=100))
    deck.add(InitialVelocityGeneration(id=0, omega=omega, vx=1.0, vy=-0.5, vz=0.2, xc=25.0,
                                       yc=10.0, zc=3.0, nx=1.0, ny=1.0, nz=0.3))
    deck.add(ControlTermination(endtim=end))
    if rbdout_dt:
        deck.add(DatabaseAscii(name="RBDOUT", dt=rbdout_dt))
        deck.add(DatabaseAscii(name="GLSTAT", dt=rbdout_dt))
    return deck
