"""Runs of the beam cantilever of :mod:`hollowbody.testing.beams` for the tests.

Default beam: L = 100 mm, 5 x 5 mm square section, steel (E = 200 GPa,
nu = 0.3, rho = 7.85e-6 kg/mm^3): L/h = 20, EI = 200 * 52.083 kN mm^2, axial
wave speed c = sqrt(E / rho) = 5048 mm/ms, first bending frequency
(Euler-Bernoulli) 0.4076 kHz.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hollowbody.api import load_model
from hollowbody.solver.energies import kinetic_energy
from hollowbody.testing.beams import EndLoad, cantilever_deck
from hollowbody.testing.engine import EngineRun

E, NU, RHO, L = 200.0, 0.3, 7.85e-6, 100.0
B = H = 5.0
I_S = B * H ** 3 / 12.0  # about s (bending in the x-z plane)
A = B * H
C = math.sqrt(E / RHO)
#: first bending frequency of the Euler-Bernoulli cantilever, kHz
F1 = 1.875 ** 2 * math.sqrt(E * I_S / (RHO * A * L ** 4)) / (2.0 * math.pi)


def engine(tmp: Path, **deck) -> EngineRun:
    """An EngineRun of :func:`cantilever_deck` written to ``tmp``."""
    path = tmp / "beam.k"
    path.write_text(cantilever_deck(**deck))
    return EngineRun(load_model(path))


def smooth(t: float, t_ramp: float) -> float:
    """0 -> 1 over t_ramp ms (half cosine), 1 after."""
    return 0.5 * (1.0 - math.cos(math.pi * min(t, t_ramp) / t_ramp))


def run_until(run: EngineRun, t_end: float, each=None) -> None:  # noqa: ANN001
    """Step ``run`` to ``t_end`` ms, calling ``each(run)`` after every cycle."""
    while run.t < t_end:
        run.step()
        if each is not None:
            each(run)


def energy_sum(run: EngineRun) -> tuple[float, float, float]:
    """(internal, kinetic, external work) J of the run."""
    ie = sum(rt.internal_energy for rt in run.plan.elements)
    ext = sum(getattr(t, "external_work", 0.0) for t in run.plan.terms)
    return ie, kinetic_energy(run.plan, run.state), ext


def add_load(run: EngineRun, node: int, **kw) -> EndLoad:  # noqa: ANN003
    """Append an :class:`EndLoad` on ``node`` to the run's force terms."""
    term = EndLoad(node, **kw)
    run.plan.terms.append(term)
    return term


def zero_crossing_period(t: np.ndarray, z: np.ndarray) -> float:
    """Mean period (ms) of z(t) from its crossings of its mean (linear interpolation)."""
    z = z - z.mean()
    s = np.sign(z)
    k = np.nonzero(s[1:] != s[:-1])[0]
    tc = t[k] - z[k] * (t[k + 1] - t[k]) / (z[k + 1] - z[k])
    return 2.0 * float(np.mean(np.diff(tc)))
