"""Small keyword decks of springs and dampers for the discrete-element tests, and a
driver that runs the solver's own cycle (set-up, State, start, step) on them."""

from __future__ import annotations

import numpy as np

from hollowbody.build import build_model
from hollowbody.io.keyword import read_deck_text
from hollowbody.solver.energies import energies
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import init_state
from hollowbody.solver.step import start, step


def f10(*values: object) -> str:
    """One card of 10-column fields."""
    return "".join(f"{v:>10}" for v in values)


def discrete_card(eid: int, pid: int, n1: int, n2: int, vid: int = 0, s: float = 1.0,
                  pf: int = 0, offset: float = 0.0) -> str:
    """An *ELEMENT_DISCRETE card (widths 8 8 8 8 8 16 8 16)."""
    return f"{eid:>8}{pid:>8}{n1:>8}{n2:>8}{vid:>8}{s:>16}{pf:>8}{offset:>16}"


def curve(lcid: int, points: list[tuple[float, float]]) -> str:
    return "*DEFINE_CURVE\n" + f10(lcid) + "\n" + "\n".join(
        f"{a:>20}{o:>20}" for a, o in points) + "\n"


def oscillator_deck(materials: list[str], *, mass: float = 1.0, v0: float = 1.0,
                    length: float = 100.0, end: float = 30.0, tssfac: float = 0.05,
                    dro: int = 0, extra: str = "", offset: float = 0.0) -> str:
    """Node 1 fixed, node 2 (mass ``mass`` kg) at x = ``length`` with initial velocity
    ``v0`` mm/ms along x, one discrete element per material card (part k+1, material
    k+1, section 1) between them. ``materials``: full *MAT keyword blocks whose MID is
    k+1. TSSFAC small so that the period error of the central difference is below
    0.1 % (the spring's own step at 0.9 would give 24 %)."""
    lines = ["*KEYWORD", "*CONTROL_TERMINATION", f10(end),
             "*CONTROL_TIMESTEP", f10(0.0, tssfac),
             "*NODE", f"{1:>8}{0.0:>16}{0.0:>16}{0.0:>16}",
             f"{2:>8}{length:>16}{0.0:>16}{0.0:>16}",
             "*BOUNDARY_SPC_NODE", f10(1, 0, 1, 1, 1, 1, 1, 1),
             "*BOUNDARY_SPC_NODE", f10(2, 0, 0, 1, 1, 1, 1, 1),
             "*ELEMENT_MASS", f"{1:>8}{2:>8}{mass:>16}",
             "*INITIAL_VELOCITY_NODE", f10(2, v0, 0.0, 0.0),
             "*SECTION_DISCRETE", f10(1, dro), f10(0.0, 0.0)]
    for k, mat in enumerate(materials):
        lines += ["*PART", f"spring {k + 1}", f10(k + 1, 1, k + 1), mat.rstrip("\n")]
    lines.append("*ELEMENT_DISCRETE")
    for k in range(len(materials)):
        lines.append(discrete_card(k + 1, k + 1, 1, 2, offset=offset))
    return "\n".join(lines) + "\n" + extra + "*END\n"


def load(text: str, name: str = "deck.k"):  # noqa: ANN201
    return build_model(read_deck_text(text, name))


class Driver:
    """The solver's own cycle on a model: ``run(t_end)`` records time, x, v of ``node``
    (index) and the energies at every cycle."""

    def __init__(self, model) -> None:  # noqa: ANN001
        self.model = model
        self.plan = assemble(model)
        self.state = init_state(model, self.plan)
        start(model, self.plan, self.state)
        self.rows: list[tuple] = []

    def run(self, t_end: float, node: int = 1, every: int = 1) -> np.ndarray:
        s = self.state
        while s.t < t_end:
            step(self.model, self.plan, s, s.dt_next)
            if s.cycle % every == 0:
                e = energies(self.plan, s)
                self.rows.append((s.t, *s.x[node], *s.v[node], e["kinetic"], e["internal"],
                                  e["total"], e["energy_ratio"], e["external_work"]))
        return np.array(self.rows)


def crossings(t: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Times where u changes sign from - to + (linear interpolation)."""
    k = np.nonzero((u[:-1] < 0.0) & (u[1:] >= 0.0))[0]
    return t[k] - u[k] * (t[k + 1] - t[k]) / (u[k + 1] - u[k])
