"""Small decks and a cycle driver for the load and rigid-wall verification tests."""

from __future__ import annotations

import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    ControlTermination,
    Deck,
    DefineCurve,
    Hourglass,
    LoadBody,
    MatElastic,
    MatRigid,
    Part,
    PartInertia,
    SectionShell,
    SectionSolid,
)
from hollowbody.mesh import standing_block
from hollowbody.solver.energies import energies, kinetic_energy
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step

G = 9.81e-3  # mm/ms^2


def add_block(deck: Deck, *, pid: int, size: float, h: float, z0: float = 0.0,
              x0: float = 0.0, first_node: int = 1, first_elem: int = 1,
              rigid: bool = False, e: float = 0.01, pr: float = 0.3,
              ro: float = 1.0e-6, inertia_tm: float = 0.0) -> np.ndarray:
    """A cube of side ``size`` (hex edge h) standing on z = z0 centred on x = x0, as part
    ``pid`` (section and material ids = pid). ``inertia_tm`` > 0 (rigid only): a
    *PART_INERTIA part of that mass (kg), its inertia that of a uniform cube. Returns
    its node ids."""
    x, conn = standing_block((size, size, size), h)
    x = x + np.array([x0, 0.0, z0])
    ids = first_node + np.arange(x.shape[0])
    deck.add_nodes(ids, x)
    deck.add_solids(first_elem + np.arange(conn.shape[0]), pid, ids[conn])
    if inertia_tm > 0.0:
        i0 = inertia_tm * size ** 2 / 6.0
        deck.add(PartInertia(pid=pid, secid=pid, mid=pid, title=f"block {pid}", xc=x0,
                             yc=0.0, zc=z0 + size / 2, tm=inertia_tm, ixx=i0, iyy=i0,
                             izz=i0))
    else:
        deck.add(Part(pid=pid, secid=pid, mid=pid, hgid=1 if not rigid else 0,
                      title=f"block {pid}"))
    deck.add(SectionSolid(secid=pid))
    if rigid:
        deck.add(MatRigid(mid=pid, ro=ro, e=e, pr=pr))
    else:
        deck.add(MatElastic(mid=pid, ro=ro, e=e, pr=pr))
    return ids


def base_deck(end: float, g: float | None = G, lcid: int = 1) -> Deck:
    """Termination, hourglass 1 (IHQ 4) and, with ``g``, gravity in -z (curve ``lcid``
    constant 1, *LOAD_BODY_Z SF = g)."""
    deck = Deck()
    deck.add(ControlTermination(endtim=end))
    deck.add(Hourglass(hgid=1, ihq=4, qm=0.05))
    deck.add(SectionShell(secid=900, t1=1.0))
    if g is not None:
        deck.add(DefineCurve(lcid=lcid, points=[[0.0, 1.0], [1.0e6, 1.0]]))
        deck.add(LoadBody(axis="Z", lcid=lcid, sf=g))
    return deck


class Run:
    """A model stepped cycle by cycle (no output files)."""

    def __init__(self, deck: Deck) -> None:
        self.model = build_model(deck)
        self.plan = assemble(self.model)
        self.state = init_state(self.model, self.plan)
        start(self.model, self.plan, self.state)
        self.state.e0 = kinetic_energy(self.plan, self.state)

    def step(self, dt: float | None = None) -> None:
        step(self.model, self.plan, self.state, self.state.dt_next if dt is None else dt)

    def run_to(self, t_end: float, dt: float | None = None, every=None) -> None:  # noqa: ANN001
        while self.state.t < t_end - 1e-12:
            self.step(dt)
            if every is not None:
                every(self)

    def energies(self) -> dict[str, float]:
        return energies(self.plan, self.state)

    def index(self, nid: int) -> int:
        return int(np.flatnonzero(self.model.node_ids == nid)[0])
