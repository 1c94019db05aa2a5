"""The segment tests: what each one is, where it comes from, what data it has.

Units: speeds in m/s (= mm/ms), masses in kg, lengths in mm, times in ms.

Sources:

- **Viano 1989**: D.C. Viano, "Biomechanical responses and injuries in blunt
  lateral impact", 33rd Stapp Car Crash Conference, SAE 892432. A 23.4 kg,
  150 mm rigid hub; thorax and abdomen struck 30 degrees forward of pure
  lateral (thorax centred at the level of the xiphoid process, abdomen 75 mm
  below it), the pelvis purely lateral, centred on the greater trochanter.
  Specimen curves and corridors ship with hollowbody
  (:mod:`hollowbody.rating.viano1989`, Apache-2.0 digitisation).
- **Shoulder**: the lateral glenohumeral impacts of Bolte et al. 2000
  ("Shoulder response characteristics and injury due to lateral glenohumeral
  joint impacts", Stapp Car Crash Journal 44, 2000-01-SC18: 3.5 to 7.0 m/s)
  and Koh et al. 2005 (150 mm, 23.4 kg hub at 4.5 m/s, through the humeral
  head). The paper uses a 23 kg impactor. No digitised data with a licence
  that allows shipping them were found: the case runs and reports its
  response, and is rated only against a corridor the user gives.
- **Bending**: the dynamic three-point bending of the whole thigh and leg
  (Kerrigan et al. 2004, "Dynamic response corridors of the human thigh and
  leg in non-midpoint three-point bending", SAE 2004-01-1603; corridors in
  Ivarsson et al. 2004), loaded lateral-medial at mid-span at 1.5 m/s as the
  paper does. No corridor data ship (same reason): rated hollow against solid,
  and against a corridor the user gives.
"""

from __future__ import annotations

from dataclasses import dataclass, field

VIANO = ("Viano D.C. (1989), Biomechanical responses and injuries in blunt lateral "
         "impact, SAE 892432")
SHOULDER = ("Bolte et al. (2000), Shoulder response characteristics and injury due to "
            "lateral glenohumeral joint impacts, SAE 2000-01-SC18; Koh et al. (2005)")
KERRIGAN = ("Kerrigan et al. (2004), Dynamic response corridors of the human thigh and "
            "leg in non-midpoint three-point bending, SAE 2004-01-1603")


@dataclass(frozen=True)
class Case:
    """One segment test.

    Attributes
    ----------
    name : str
        Command-line name (``thorax``, ``leg-bending``, ...).
    kind : str
        ``impact`` (free rigid hub on the standing body, gravity on) or
        ``bending`` (limb segment, prescribed impactor).
    speeds : tuple of float
        Impact speeds of the tests [m/s].
    end_time : dict
        Simulated time per speed [ms] (the length of the test data).
    impactor_mass : float
        kg (bending: the impactor is driven, its mass does not matter).
    impactor_diameter : float
        mm (the hub's face; bending: the loading cylinder's diameter).
    oblique_deg : float
        Angle of the impact direction forward of pure lateral [deg].
    location : str
        Where the impactor's axis aims, in words (the docs and the report).
    source : str
        Citation.
    data : str
        ``viano1989`` when hollowbody ships the test data, else ``""``.
    quantities : tuple of str
        Signals the case reports: ``force`` (force-time), ``force_deflection``,
        ``moment_deflection``.
    """

    name: str
    kind: str
    speeds: tuple[float, ...]
    end_time: dict[float, float]
    impactor_mass: float
    impactor_diameter: float
    oblique_deg: float
    location: str
    source: str
    data: str = ""
    quantities: tuple[str, ...] = ("force", "force_deflection")
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def region(self) -> str:
        """The body region (``thorax``, ``thigh``, ...)."""
        return self.name.split("-")[0]


CASES: dict[str, Case] = {c.name: c for c in (
    Case("thigh-bending", "bending", (1.5,), {1.5: 30.0}, 0.0, 50.0, 0.0,
         "mid-span of the thigh, lateral-medial", KERRIGAN,
         quantities=("force", "force_deflection", "moment_deflection")),
    Case("leg-bending", "bending", (1.5,), {1.5: 30.0}, 0.0, 50.0, 0.0,
         "mid-span of the leg (shank), lateral-medial", KERRIGAN,
         quantities=("force", "force_deflection", "moment_deflection")),
    Case("pelvis", "impact", (5.2, 9.8), {5.2: 40.0, 9.8: 40.0}, 23.4, 150.0, 0.0,
         "greater trochanter, pure lateral; struck-side forearm and hand removed, "
         "their mass at the elbow", VIANO, "viano1989", quantities=("force",)),
    Case("abdomen", "impact", (4.8, 6.8, 9.4), {4.8: 60.0, 6.8: 50.0, 9.4: 40.0}, 23.4,
         150.0, 30.0, "75 mm below the xiphoid process, 30 deg forward of lateral",
         VIANO, "viano1989"),
    Case("thorax", "impact", (4.4, 6.5, 9.5), {4.4: 60.0, 6.5: 50.0, 9.5: 40.0}, 23.4,
         150.0, 30.0, "level of the xiphoid process, 30 deg forward of lateral",
         VIANO, "viano1989"),
    Case("shoulder", "impact", (4.4, 7.0), {4.4: 40.0, 7.0: 40.0}, 23.0, 150.0, 0.0,
         "glenohumeral joint centre (humeral head), pure lateral", SHOULDER),
)}

#: The order of ``--all`` and of the report.
ORDER = ("thigh-bending", "leg-bending", "pelvis", "abdomen", "thorax", "shoulder")


def case(name: str) -> Case:
    """The case called ``name``; ValueError listing the cases otherwise."""
    try:
        return CASES[name]
    except KeyError:
        raise ValueError(f"unknown case {name!r}; the cases are: {', '.join(ORDER)}") from None


def speeds_of(c: Case, speed: float | None) -> tuple[float, ...]:
    """The speeds to run: all of the case's, or ``speed`` (any positive value)."""
    if speed is None:
        return c.speeds
    if not speed > 0.0:
        raise ValueError(f"--speed must be positive (got {speed:g} m/s)")
    return (float(speed),)


def end_time_of(c: Case, speed: float) -> float:
    """Simulated time [ms] at ``speed``: the test's, or that of the nearest test speed."""
    near = min(c.end_time, key=lambda s: abs(s - speed))
    return c.end_time[near]
