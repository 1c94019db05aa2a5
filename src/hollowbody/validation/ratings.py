"""Rate a test run's curves: against the cadaver data, and hollow against solid.

For each quantity of a case (:attr:`hollowbody.validation.cases.Case.quantities`):

- **test data** (the Viano 1989 cases, at the test speeds): the reference curve
  is the mean of the specimen curves (force-time; :meth:`Corridor.from_specimens`
  over the range all specimens cover), or the corridor's mid-line where there
  are no specimen curves (force-deflection); the experimental corridor is
  CORA's inner corridor and its fraction-inside is reported;
- **a corridor the user gives** (``--corridor``): rated the same way, its
  mid-line as the reference;
- **hollow against solid**: the solid run is the reference (the paper's
  THUMS-HS against THUMS comparison).

CORA with CORAplus' defaults (interval of evaluation from the reference: 3 %
to 7.5 % of its peak, extended by 20 %), ISO/TS 18571 on the range both
curves cover, both on a 0.1 ms (or 0.1 mm) grid. The model force is CFC 180
filtered (:mod:`hollowbody.validation.signals`); the test curves are used as
digitised. A rating that cannot be computed (a curve that never rises, no
overlap) is kept with its reason instead of a number.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from hollowbody.rating import viano1989
from hollowbody.rating.cora import CoraParameters, cora
from hollowbody.rating.corridors import Corridor
from hollowbody.rating.iso18571 import IsoParameters, iso18571
from hollowbody.rating.signals import CurveError
from hollowbody.validation.cases import Case
from hollowbody.validation.signals import Signals

#: Axis labels per quantity.
LABELS = {"force": ("time [ms]", "force [kN]"),
          "force_deflection": ("deflection [mm]", "force [kN]"),
          "moment_deflection": ("deflection [mm]", "moment [kN*mm]")}
#: The Viano data's name of each quantity.
_VIANO_KIND = {"force": "force_time", "force_deflection": "force_deflection"}


@dataclass
class TestData:
    """What a quantity of a case is rated against (any part may be missing)."""

    corridor: Corridor | None
    specimens: list[tuple[np.ndarray, np.ndarray]]
    specimen_names: list[str]
    reference: tuple[np.ndarray, np.ndarray] | None
    reference_label: str
    source: str


@dataclass
class Rating:
    """One curve rated against one reference; numbers are None when ``error`` says why."""

    quantity: str
    against: str
    cora: float | None = None
    cora_corridor: float | None = None
    cora_cross: float | None = None
    iso: float | None = None
    iso_grade: str | None = None
    inside: float | None = None
    window: tuple[float, float] | None = None
    error: str | None = None

    def to_dict(self) -> dict:
        """Plain JSON values."""
        return asdict(self)

    def short(self) -> str:
        """``force vs test: CORA 0.71 ISO 0.65`` or the reason there is none."""
        head = f"{self.quantity} vs {self.against}"
        if self.error:
            return f"{head}: not rated ({self.error})"
        txt = f"{head}: CORA {self.cora:.2f} ISO {self.iso:.2f}"
        if self.inside is not None:
            txt += f", {100 * self.inside:.0f} % in corridor"
        return txt


def _midline(c: Corridor) -> tuple[np.ndarray, np.ndarray]:
    x = np.asarray(c.x, dtype=float)
    keep = np.concatenate([[True], np.diff(x) > 0.0])
    return x[keep], (0.5 * (c.lower + c.upper))[keep]


def reference_data(case: Case, speed: float, quantity: str,
              user_corridor: Corridor | None = None) -> TestData | None:
    """The data ``quantity`` of ``case`` at ``speed`` is rated against, or None."""
    if user_corridor is not None:
        return TestData(user_corridor, [], [], _midline(user_corridor), "corridor mid-line",
                        "user corridor")
    if case.data != "viano1989" or quantity not in _VIANO_KIND:
        return None
    if not any(abs(speed - s) < 1e-9 for s in case.speeds):
        return None
    corridor = None
    try:
        corridor = viano1989.load_corridor(case.region, speed, _VIANO_KIND[quantity])
    except (ValueError, KeyError):
        corridor = None
    specimens: list[tuple[np.ndarray, np.ndarray]] = []
    names: list[str] = []
    if quantity == "force":
        for sp in viano1989.load_specimens(case.region, speed):
            specimens.append((sp.time, sp.force))
            names.append(sp.name)
    reference, label = None, ""
    if len(specimens) >= 2:
        mean = Corridor.from_specimens(specimens)
        reference, label = (mean.x, mean.center), f"specimen mean (n={len(specimens)})"
    elif corridor is not None:
        reference, label = _midline(corridor), "corridor mid-line"
    if corridor is None and reference is None:
        return None
    return TestData(corridor, specimens, names, reference, label, case.source)


def rate(x: np.ndarray, y: np.ndarray, ref: tuple[np.ndarray, np.ndarray],
         quantity: str, against: str, corridor: Corridor | None = None) -> Rating:
    """CORA and ISO/TS 18571 of the curve (x, y) against ``ref`` (and ``corridor``)."""
    out = Rating(quantity, against)
    try:
        c = cora(ref[0], ref[1], x, y, CoraParameters(), corridor)
        i = iso18571(ref[0], ref[1], x, y, IsoParameters())
    except CurveError as err:
        out.error = str(err).split("\n")[0]
        return out
    out.cora, out.cora_corridor, out.cora_cross = c.total, c.corridor, c.cross_correlation
    out.iso, out.iso_grade = i.overall, i.grade
    out.window = (c.t_start, c.t_end)
    if corridor is not None:
        inside = corridor.fraction_inside(x, y)
        out.inside = float(inside) if np.isfinite(inside) else None
    return out


def rate_run(case: Case, speed: float, sig: Signals, solid: Signals | None = None,
             user_corridor: Corridor | None = None) -> list[Rating]:
    """Every rating of one run: each quantity against the test data (when there are
    any) and, for a hollow run with its solid twin, against the solid run."""
    out: list[Rating] = []
    for q in case.quantities:
        x, y = sig.curve(q)
        data = reference_data(case, speed, q, user_corridor)
        if data is not None and data.reference is not None:
            out.append(rate(x, y, data.reference, q, "test", data.corridor))
        if solid is not None:
            out.append(rate(x, y, solid.curve(q), q, "solid"))
    return out
