"""Parameter space of the hollow-structure calibration: names, bounds, rounding.

The calibrated parameters are material and section values of the hollow
block's shell walls (human-facing units, labelled):

=========== ====== ============== ===================== ==========================
name        unit   default bounds BlockConfig field     meaning
=========== ====== ============== ===================== ==========================
E           MPa    10 .. 400      ``hollow_E``          wall Young's modulus
yield       MPa    0.5 .. 40      ``hollow_yield``      wall yield stress
etan        MPa    0 .. 50        ``hollow_etan``       wall tangent modulus
thickness   mm     0.5 .. 3       ``thickness``         wall thickness
=========== ====== ============== ===================== ==========================

The default bounds bracket the paper's fits (muscle E 100 MPa / yield 4 MPa,
fat 50 / 2 MPa, 1.5 mm walls) by a factor of 4-10 on each side (yield up to 40 MPa:
the first muscle calibration on our solid curve ended at 19 MPa, against the old
upper bound of 20). Parameters
that are not calibrated keep the block's defaults (etan 0 MPa, thickness
1.5 mm) or a value fixed by the caller.

Every candidate is evaluated at its parameters rounded to
:data:`SIGNIFICANT_DIGITS` significant digits; the rounded values are the
cache key (two candidates closer than that are the same run).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from hollowbody.errors import UserInputError

#: name -> (unit, default lower bound, default upper bound, BlockConfig field)
PARAMETERS: dict[str, tuple[str, float, float, str]] = {
    "E": ("MPa", 10.0, 400.0, "hollow_E"),
    "yield": ("MPa", 0.5, 40.0, "hollow_yield"),
    "etan": ("MPa", 0.0, 50.0, "hollow_etan"),
    "thickness": ("mm", 0.5, 3.0, "thickness"),
}

#: Significant digits of the evaluated (rounded) parameter values.
SIGNIFICANT_DIGITS = 4

DEFAULT_NAMES = ("E", "yield")


def round_significant(value: float, digits: int = SIGNIFICANT_DIGITS) -> float:
    """``value`` rounded to ``digits`` significant digits (0 stays 0)."""
    v = float(value)
    if v == 0.0 or not math.isfinite(v):
        return v
    return round(v, digits - 1 - int(math.floor(math.log10(abs(v)))))


@dataclass(frozen=True)
class Parameter:
    """One calibrated parameter: name, unit and bounds [lower, upper] (its unit)."""

    name: str
    lower: float
    upper: float

    @property
    def unit(self) -> str:
        return PARAMETERS[self.name][0]

    @property
    def field(self) -> str:
        """The :class:`~hollowbody.scenarios.block.BlockConfig` field it sets."""
        return PARAMETERS[self.name][3]


@dataclass(frozen=True)
class ParameterSpace:
    """The ordered calibrated parameters (the GA's decision vector)."""

    parameters: tuple[Parameter, ...]

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.parameters)

    @property
    def lower(self) -> np.ndarray:
        """(n,) lower bounds."""
        return np.array([p.lower for p in self.parameters], dtype=float)

    @property
    def upper(self) -> np.ndarray:
        """(n,) upper bounds."""
        return np.array([p.upper for p in self.parameters], dtype=float)

    def __len__(self) -> int:
        return len(self.parameters)

    def rounded(self, x: Sequence[float]) -> dict[str, float]:
        """Decision vector (n,) -> {name: value rounded and clipped to its bounds}."""
        out = {}
        for p, v in zip(self.parameters, x):
            r = round_significant(min(max(float(v), p.lower), p.upper))
            out[p.name] = min(max(r, p.lower), p.upper)
        return out

    def key(self, params: Mapping[str, float]) -> str:
        """Cache key of rounded parameters, e.g. ``'E=123.4,yield=4.56'``."""
        return ",".join(f"{n}={round_significant(params[n])!r}" for n in self.names)

    def to_dict(self) -> dict:
        """JSON form: {name: {"unit", "lower", "upper"}} in order."""
        return {p.name: {"unit": p.unit, "lower": p.lower, "upper": p.upper}
                for p in self.parameters}


def make_space(names: Iterable[str] = DEFAULT_NAMES,
               bounds: Mapping[str, tuple[float, float]] | None = None) -> ParameterSpace:
    """Parameter space of ``names`` with default bounds overridden by ``bounds``.

    Raises :class:`UserInputError` for an unknown or repeated name, a bound for
    a parameter that is not calibrated, or lower >= upper.
    """
    names = list(names)
    if not names:
        raise UserInputError("no parameters to calibrate")
    bounds = dict(bounds or {})
    seen: set[str] = set()
    params = []
    for n in names:
        if n not in PARAMETERS:
            raise UserInputError(f"unknown parameter {n!r}; choose from "
                                 f"{', '.join(PARAMETERS)}")
        if n in seen:
            raise UserInputError(f"parameter {n!r} given twice")
        seen.add(n)
        unit, lo, hi, _ = PARAMETERS[n]
        lo, hi = bounds.pop(n, (lo, hi))
        if not (math.isfinite(lo) and math.isfinite(hi)) or lo >= hi:
            raise UserInputError(f"bounds of {n} must satisfy lower < upper (got {lo:g}:{hi:g} "
                                 f"{unit})")
        if lo < 0.0 or (n != "etan" and lo <= 0.0):
            raise UserInputError(f"lower bound of {n} must be "
                                 f"{'>= 0' if n == 'etan' else 'positive'} (got {lo:g} {unit})")
        params.append(Parameter(n, float(lo), float(hi)))
    if bounds:
        extra = sorted(bounds)
        raise UserInputError(f"bounds given for {', '.join(extra)}, which "
                             f"{'is' if len(extra) == 1 else 'are'} not calibrated "
                             f"(calibrated: {', '.join(names)})")
    return ParameterSpace(tuple(params))


def parse_names(text: str) -> list[str]:
    """``'E,yield'`` -> ['E', 'yield'] (names are checked by :func:`make_space`)."""
    names = [s.strip() for s in text.split(",") if s.strip()]
    if not names:
        raise UserInputError(f"--params needs names separated by commas (got {text!r})")
    return names


_BOUND = re.compile(r"^\s*([A-Za-z_]+)\s*=\s*([^:]+):([^:]+)\s*$")


def parse_bounds(items: Iterable[str]) -> dict[str, tuple[float, float]]:
    """``['E=20:300', 'yield=1:10']`` -> {'E': (20.0, 300.0), 'yield': (1.0, 10.0)}."""
    out: dict[str, tuple[float, float]] = {}
    for item in items:
        m = _BOUND.match(item)
        if not m:
            raise UserInputError(f"bad bounds {item!r}: expected NAME=LO:HI, e.g. E=20:300")
        name = m.group(1)
        try:
            lo, hi = float(m.group(2)), float(m.group(3))
        except ValueError:
            raise UserInputError(f"bad bounds {item!r}: LO and HI must be numbers") from None
        if name not in PARAMETERS:
            raise UserInputError(f"unknown parameter {name!r} in --bounds; choose from "
                                 f"{', '.join(PARAMETERS)}")
        if lo >= hi:
            raise UserInputError(f"bounds of {name} must satisfy LO < HI (got {item!r})")
        out[name] = (lo, hi)
    return out


def parse_speeds(text: str) -> tuple[float, ...]:
    """``'40,70'`` -> (40.0, 70.0) km/h; positive, no repeats."""
    try:
        speeds = tuple(float(s) for s in text.split(",") if s.strip())
    except ValueError:
        raise UserInputError(f"--speeds must be numbers in km/h separated by commas "
                             f"(got {text!r})") from None
    if not speeds:
        raise UserInputError("--speeds needs at least one speed (km/h)")
    if any(not math.isfinite(s) or s <= 0.0 for s in speeds):
        raise UserInputError(f"speeds must be positive km/h (got {text!r})")
    if len(set(speeds)) != len(speeds):
        raise UserInputError(f"speed given twice in {text!r}")
    return speeds
