"""What a set-up builder returns: the deck and how to read the run's signals.

Both set-up builders (:mod:`hollowbody.validation.impact`,
:mod:`hollowbody.validation.bending`) return a :class:`Setup`. The runner
writes ``setup.json`` (:meth:`Setup.to_json`) beside the deck, so the signals
of a run can be read again later (:mod:`hollowbody.validation.signals`).
Units: mm, ms, kg, kN, m/s.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hollowbody.io.keyword import Deck


@dataclass
class Setup:
    """One test set-up on one model.

    Attributes
    ----------
    case, speed, tissue : str, float, str
        Case name, impact speed [m/s], ``solid``, ``hollow`` or ``user``.
    deck : Deck
        The main deck (with its includes) ready to be written and run.
    end_time : float
        Simulated time [ms].
    impactor_pid : int
        Part id of the rigid impactor.
    impactor_mass : float
        Its mass [kg].
    contact_id : int
        Id of the contact between the impactor and the body; its ``rcforc``
        rows give the force. The impactor is the *master* side.
    direction : (3,) floats
        Unit vector of the impactor's travel (global frame).
    impact_point : (3,) floats
        Point [mm] on the body's surface the impactor's axis aims at.
    contact_time : float
        Time [ms] at which the impactor's face reaches the body if it travels
        freely (the gap over the speed); time zero of the test curves.
    impactor_node : int or None
        A node of the impactor listed in *DATABASE_HISTORY_NODE (on its axis);
        its ``nodout`` displacement is the impactor's travel. When None the
        impactor part's ``rbdout`` rows are read instead (hollowbody's own
        runs only: the engines' results converters write glstat, rcforc and
        nodout).
    reference_node : int or None
        Node id (a *DATABASE_HISTORY_NODE) whose displacement along
        ``direction`` is subtracted from the impactor's to give the
        deflection (impacts: the spine or pelvis; bending: None).
    span, load_a, load_b : float or None
        Bending: distance between the supports and from each support to the
        load point [mm]; the moment at the load point is F a b / span.
    notes : list of str
        What the set-up did that a reader should know (deviations from the
        test, parts left out of the contact, masses moved).
    mesh : float or None
        The pedestrian's soft-tissue element size [mm] (None: a user's model);
        ``--resume`` refuses to continue these runs with another one.
    """

    case: str
    speed: float
    tissue: str
    deck: Deck
    end_time: float
    impactor_pid: int
    impactor_mass: float
    contact_id: int
    direction: tuple[float, float, float]
    impact_point: tuple[float, float, float]
    contact_time: float = 0.0
    impactor_node: int | None = None
    reference_node: int | None = None
    span: float | None = None
    load_a: float | None = None
    load_b: float | None = None
    notes: list[str] = field(default_factory=list)
    mesh: float | None = None

    def to_json(self) -> dict[str, Any]:
        """Everything but the deck, as plain JSON values."""
        out = {k: v for k, v in self.__dict__.items() if k != "deck"}
        out["direction"] = [float(v) for v in self.direction]
        out["impact_point"] = [float(v) for v in self.impact_point]
        return out

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> Setup:
        """The record back from :meth:`to_json` (with an empty deck)."""
        kw = dict(d)
        kw["direction"] = tuple(float(v) for v in kw["direction"])
        kw["impact_point"] = tuple(float(v) for v in kw["impact_point"])
        return cls(deck=Deck(), **kw)


def unit(v: Any) -> np.ndarray:
    """``v`` (3,) scaled to length 1; ValueError for a zero vector."""
    a = np.asarray(v, dtype=np.float64).reshape(3)
    n = float(np.linalg.norm(a))
    if n == 0.0:
        raise ValueError("a direction must not be the zero vector")
    return a / n
