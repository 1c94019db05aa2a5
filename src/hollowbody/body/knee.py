"""The pedestrian's knee: rotational stiffness and translational (shear) springs.

The other joints of the pedestrian are *CONSTRAINED_JOINT_SPHERICAL (the two
segment ends tied at one point) with a joint stiffness. The knee is not tied:
its two nodes (one on the femur's distal end, one on the tibia's proximal end,
coincident at the knee joint centre at t = 0) are joined by

- the same *CONSTRAINED_JOINT_STIFFNESS_GENERALIZED as before (flexion,
  varus/valgus, axial rotation; :mod:`hollowbody.body.joints`), now naming no
  joint (JID 0): it puts a couple on the two rigid bodies and does not hold
  their positions;
- three translational *ELEMENT_DISCRETE springs between the two nodes along
  the shank's axes at t = 0 (*DEFINE_SD_ORIENTATION IOP 0, fixed vectors):
  anterior-posterior (x) and lateral (y) shear, *MAT_SPRING_NONLINEAR_ELASTIC
  with a linear range and an elastic stop; axial (z), *MAT_SPRING_ELASTIC,
  stiff (the condyles on the tibial plateau in compression, the ligaments and
  capsule in tension);
- three *MAT_DAMPER_VISCOUS along the same axes (a fraction of the critical
  damping of the lower leg on each spring).

Values (kN, mm, ms):

- lateral shear: :data:`SHEAR_STIFFNESS` 0.16 kN/mm up to :data:`SHEAR_STOP`
  15 mm (2.4 kN), the order of the knee shear measured in lateral impacts on
  PMHS legs by Kajzer et al. (Stapp Car Crash Conf. 1997, 973326, and SAE
  1999-01-0712): peak shear forces of about 2-3 kN at shear displacements of
  about 15 mm, where the ligaments failed; 15 mm is also the shear
  displacement at ligament failure that Arnoux et al. (LLMS model of the
  lower limb) derived from pure shearing tests. Past the stop the condyles
  meet the tibial eminence and the capsule is taut: :data:`STOP_STIFFNESS`, 10
  times the linear slope (a choice; the model has no ligament failure);
- anterior-posterior shear: the lateral curve (a choice; no impact data used);
- axial: :data:`AXIAL_STIFFNESS` 50 kN/mm, a choice five times the shank
  bone tube's own axial stiffness (E A / L = 15 GPa x 2 pi 10 mm x 4 mm / 440 mm
  = 8.6 kN/mm at the default body), so the knee adds little axial compliance
  to the leg (the body weight compresses it by 0.007 mm);
- damping: :data:`DAMPING_RATIO` 0.1 of 2 sqrt(k m) per spring, m the lower
  leg (shank and foot, de Leva's 5.7 % of the body mass), as the spherical
  joints' penalty springs carry 10 % of critical damping.

The spring directions are fixed in space (those of the shank at t = 0):
hollowbody's *DEFINE_SD_ORIENTATION supports fixed vectors only (IOP 0; the
node-defined and follower directions IOP 1-3 are not read, docs/discrete.md).
While the shank turns little (the first tens of ms of a lateral impact, when
the bumper loads the knee) the springs act along the shank's axes; after a
rotation alpha the shear spring's direction is alpha off the tibia's plateau.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.io.keyword import (
    Deck,
    DefineCurve,
    DefineSdOrientation,
    ElementDiscrete,
    MatDamperViscous,
    MatSpringElastic,
    MatSpringNonlinearElastic,
    Part,
    SectionDiscrete,
)

#: Linear shear stiffness, anterior-posterior and lateral (kN/mm).
SHEAR_STIFFNESS = 0.16
#: Shear displacement where the stop starts (mm).
SHEAR_STOP = 15.0
#: Slope of the shear curve past the stop (kN/mm).
STOP_STIFFNESS = 10.0 * SHEAR_STIFFNESS
#: Axial stiffness, compression and tension (kN/mm).
AXIAL_STIFFNESS = 50.0
#: Damping of each spring, fraction of 2 sqrt(k m_lower_leg).
DAMPING_RATIO = 0.1
#: Section id of the knee's discrete elements (solids use 1, shells 10..).
SECID = 2
#: Curve id of the shear force-deflection curve (the joint curves are 100..).
LCID_SHEAR = 90


@dataclass(frozen=True)
class Knee:
    """One knee: name, femur-side node n1, tibia-side node n2 (coincident), the
    shank's frame at t = 0 (3, 3) rows x (anterior), y (left), z (up the shank)."""

    name: str
    n1: int
    n2: int
    frame: np.ndarray


def shear_curve() -> list[list[float]]:
    """Shear force (kN) against deflection (mm): linear to +-SHEAR_STOP, then the stop's
    slope (the last segments; curves are extrapolated with their end slopes)."""
    f0 = SHEAR_STIFFNESS * SHEAR_STOP
    far = SHEAR_STOP + 10.0
    f1 = f0 + STOP_STIFFNESS * 10.0
    return [[-far, -f1], [-SHEAR_STOP, -f0], [0.0, 0.0], [SHEAR_STOP, f0], [far, f1]]


def shear_force(d: float | np.ndarray) -> float | np.ndarray:
    """The shear curve's force (kN) at deflection ``d`` (mm), end slopes beyond it."""
    d = np.asarray(d, float)
    lin = SHEAR_STIFFNESS * d
    past = np.sign(d) * (SHEAR_STIFFNESS * SHEAR_STOP
                         + STOP_STIFFNESS * (np.abs(d) - SHEAR_STOP))
    out = np.where(np.abs(d) <= SHEAR_STOP, lin, past)
    return float(out) if out.ndim == 0 else out


def lower_leg_mass(sk) -> float:  # noqa: ANN001 - Skeleton
    """Mass (kg) of one lower leg, shank and foot (de Leva's, scaled to the body)."""
    return float(sk.segments["shank"].mass + sk.segments["foot"].mass)


def dampers(lower_leg: float) -> tuple[float, float]:
    """(shear, axial) damping coefficients (kN ms/mm): DAMPING_RATIO of 2 sqrt(k m)
    with m = ``lower_leg`` kg, to 4 significant digits."""
    m = lower_leg
    return (float(f"{2.0 * DAMPING_RATIO * np.sqrt(SHEAR_STIFFNESS * m):.4g}"),
            float(f"{2.0 * DAMPING_RATIO * np.sqrt(AXIAL_STIFFNESS * m):.4g}"))


def knee_springs(d: Deck, knees: list[Knee], lower_leg: float, first_pid: int,
                 first_eid: int = 1, first_vid: int = 1) -> dict:
    """The knees' translational springs and dampers into ``d``.

    Parts ``first_pid`` .. + 3 (shear springs, axial springs, shear dampers, axial
    dampers; material id 1000 + pid), section :data:`SECID`, curve
    :data:`LCID_SHEAR`; per knee three *DEFINE_SD_ORIENTATION (the shank's x, y, z
    at t = 0) from ``first_vid`` and six elements from ``first_eid`` (springs x, y,
    z, dampers x, y, z; N1 femur side, N2 tibia side: a positive deflection is the
    tibia moving along +axis from the femur); dampers for a lower leg of ``lower_leg``
    kg (:func:`dampers`). Returns {knee name: element ids}, the
    part ids and the dampers.
    """
    if not knees:
        return {"elements": {}, "parts": {}, "damping": (0.0, 0.0)}
    c_s, c_a = dampers(lower_leg)
    pids = {k: first_pid + i for i, k in enumerate(("shear", "axial", "shear_damper",
                                                    "axial_damper"))}
    d.add(SectionDiscrete(secid=SECID, dro=0, title="knee springs and dampers"))
    d.add(DefineCurve(lcid=LCID_SHEAR, points=shear_curve(),
                      title="knee shear force [kN] vs displacement [mm]"))
    d.add(MatSpringNonlinearElastic(mid=1000 + pids["shear"], lcd=LCID_SHEAR,
                                    title="knee shear"))
    d.add(MatSpringElastic(mid=1000 + pids["axial"], k=AXIAL_STIFFNESS, title="knee axial"))
    d.add(MatDamperViscous(mid=1000 + pids["shear_damper"], dc=float(c_s),
                           title="knee shear damping"))
    d.add(MatDamperViscous(mid=1000 + pids["axial_damper"], dc=float(c_a),
                           title="knee axial damping"))
    for key, pid in pids.items():
        d.add(Part(pid=pid, secid=SECID, mid=1000 + pid, title=f"knee {key.replace('_', ' ')}"))
    eid, vid, out = first_eid, first_vid, {}
    for knee in knees:
        ids = []
        for axis in range(3):
            e = knee.frame[axis]
            d.add(DefineSdOrientation(vid=vid + axis, iop=0, xt=float(e[0]), yt=float(e[1]),
                                      zt=float(e[2]), title=f"{knee.name} {'xyz'[axis]}"))
        for kind in ("spring", "damper"):
            for axis in range(3):
                if kind == "spring":
                    pid = pids["axial"] if axis == 2 else pids["shear"]
                else:
                    pid = pids["axial_damper"] if axis == 2 else pids["shear_damper"]
                d.add(ElementDiscrete(eid=eid, pid=pid, n1=knee.n1, n2=knee.n2,
                                      vid=vid + axis))
                ids.append(eid)
                eid += 1
        vid += 3
        out[knee.name] = ids
    return {"elements": out, "parts": pids, "damping": (float(c_s), float(c_a))}
