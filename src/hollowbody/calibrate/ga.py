"""Real-coded genetic algorithm (pymoo GA) driven by ask-and-tell, resumable by replay.

Settings (defaults): population 16, generations 20 (the initial random
population is generation 1, so a run evaluates at most population x
generations candidates), binary tournament selection, simulated binary
crossover (SBX, probability 0.9, distribution index 15), polynomial mutation
(distribution index 20, each variable with probability 1/n), duplicate
elimination, (mu + lambda) survival with ``population`` offspring per
generation. Decision variables are the parameters in their own units between
their bounds.

The run is reproducible: pymoo draws every random number from the algorithm's
generator, seeded with ``seed``. A checkpoint therefore only needs the
decision vectors and fitness values of every completed generation:
:meth:`GeneticSearch.replay` rebuilds the algorithm by asking and telling them
again (no evaluation), and checks that each asked generation equals the stored
one (a different pymoo version that breaks this is reported, not ignored).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from hollowbody.calibrate.space import ParameterSpace


class ReplayError(RuntimeError):
    """A checkpoint's generations cannot be replayed (GA settings or pymoo changed)."""


@dataclass(frozen=True)
class GASettings:
    """population >= 2, generations >= 1 (including the initial one), seed."""

    population: int = 16
    generations: int = 20
    seed: int = 1
    crossover_prob: float = 0.9
    crossover_eta: float = 15.0
    mutation_eta: float = 20.0

    def __post_init__(self) -> None:
        if self.population < 2:
            raise ValueError(f"population must be at least 2 (got {self.population})")
        if self.generations < 1:
            raise ValueError(f"generations must be at least 1 (got {self.generations})")

    def to_dict(self) -> dict:
        return asdict(self)


class GeneticSearch:
    """pymoo GA over ``space`` with explicit ask/tell; ``generation`` counts tells."""

    def __init__(self, space: ParameterSpace, settings: GASettings) -> None:
        from pymoo.algorithms.soo.nonconvex.ga import GA
        from pymoo.core.problem import Problem
        from pymoo.core.termination import NoTermination
        from pymoo.operators.crossover.sbx import SBX
        from pymoo.operators.mutation.pm import PM

        self.space = space
        self.settings = settings
        problem = Problem(n_var=len(space), n_obj=1, xl=space.lower, xu=space.upper)
        self.algorithm = GA(pop_size=settings.population, n_offsprings=settings.population,
                            crossover=SBX(prob=settings.crossover_prob,
                                          eta=settings.crossover_eta),
                            mutation=PM(eta=settings.mutation_eta),
                            eliminate_duplicates=True)
        self.algorithm.setup(problem, seed=int(settings.seed), termination=NoTermination(),
                             verbose=False)
        self.generation = 0
        self._pending = None

    def ask(self) -> np.ndarray:
        """Decision vectors (m, n) of the next generation (m <= population)."""
        self._pending = self.algorithm.ask()
        return np.asarray(self._pending.get("X"), dtype=float)

    def tell(self, fitness: np.ndarray) -> None:
        """Fitness (m,) of the vectors returned by the last :meth:`ask`."""
        from pymoo.core.evaluator import Evaluator
        from pymoo.problems.static import StaticProblem

        if self._pending is None:
            raise RuntimeError("tell() without ask()")
        f = np.asarray(fitness, dtype=float).reshape(-1, 1)
        Evaluator().eval(StaticProblem(self.algorithm.problem, F=f), self._pending)
        self.algorithm.tell(infills=self._pending)
        self._pending = None
        self.generation += 1

    def replay(self, generations: list[dict]) -> None:
        """Re-ask and re-tell stored generations ``[{"X": (m, n), "F": (m,)}, ...]``."""
        for g, gen in enumerate(generations, start=1):
            x = self.ask()
            xs = np.asarray(gen["X"], dtype=float)
            if x.shape != xs.shape or not np.allclose(x, xs, rtol=1e-12, atol=0.0):
                raise ReplayError(f"generation {g} of the checkpoint does not replay: the GA "
                                  "settings or the pymoo version differ from the run that "
                                  "wrote it")
            self.tell(np.asarray(gen["F"], dtype=float))

    def best(self) -> tuple[np.ndarray, float] | None:
        """(x (n,), fitness) of the best candidate so far, or None before the first tell."""
        opt = self.algorithm.opt
        if opt is None or len(opt) == 0:
            return None
        return np.asarray(opt[0].X, dtype=float), float(opt[0].F[0])
