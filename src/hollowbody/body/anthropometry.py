"""Segment inertia parameters of the average adult male (de Leva 1996), scaled.

Source: P. de Leva, "Adjustments to Zatsiorsky-Seluyanov's segment inertia
parameters", J. Biomech. 29(9):1223-1230, 1996: Table 1 (mean segment lengths
of the male sample, stature 1741 mm, mass 73.0 kg) and Table 4 (males:
segment mass as a fraction of body mass, centre of mass as a fraction of the
segment length from its first endpoint, radii of gyration as fractions of the
length about the sagittal, transverse and longitudinal axes through the
centre of mass). The endpoints are joint centres or landmarks: VERT vertex,
CERV cervicale (C7), XYPH xiphion, OMPH omphalion, MIDH mid-hip (between the
hip joint centres), SJC/EJC/WJC shoulder/elbow/wrist joint centres, MET3 third
metacarpale, HJC/KJC/AJC hip/knee/ankle joint centres, HEEL, TTIP toe tip.

Partition: de Leva's, for the whole body (head with neck; trunk split into
upper, middle and lower trunk; two arms and legs). VIVA+ 50M, whose total
(1,753 mm, 76.75 kg) is the default pedestrian, cuts the body differently
(its torso is 51 % of the mass, de Leva's trunk 43 %, because VIVA+ puts the
gluteal region and the upper thigh flesh in the torso; its thigh is 8 kg,
de Leva's 10.9 kg at 76.75 kg): :data:`VIVA_50M_TARGETS` lists its segment
masses so that a report can show both, but the model follows de Leva.

Scaling (:func:`segments`): lengths with stature, masses with body mass,
moments of inertia m (r L)^2. Units: mm, kg, kg*mm^2.
"""

from __future__ import annotations

from dataclasses import dataclass

#: Stature (mm) and mass (kg) of de Leva's male sample (Table 1).
DE_LEVA_STATURE = 1741.0
DE_LEVA_MASS = 73.0
#: The default pedestrian: average adult male of VIVA+ 50M.
DEFAULT_STATURE = 1753.0
DEFAULT_MASS = 76.75

#: VIVA+ 50M segment mass targets (kg) as given for the default pedestrian; their
#: partition differs from de Leva's (see the module docstring).
VIVA_50M_TARGETS = {"head": 4.42, "neck": 1.16, "torso": 39.4, "thorax": 19.5,
                    "upper_extremities": 7.7, "lower_extremities": 23.5, "thigh": 8.0,
                    "lower_leg": 3.0}


@dataclass(frozen=True)
class SegmentParameters:
    """One row of de Leva's tables (males).

    length: mm at the sample's stature; mass: fraction of body mass; com:
    fraction of the length from ``proximal``; r_sagittal, r_transverse,
    r_longitudinal: radii of gyration as fractions of the length; count: 1 or 2
    (one per side).
    """

    name: str
    proximal: str
    distal: str
    length: float
    mass: float
    com: float
    r_sagittal: float
    r_transverse: float
    r_longitudinal: float
    count: int = 1


#: de Leva (1996), males: Table 1 lengths, Table 4 inertia parameters.
DE_LEVA_MALE: tuple[SegmentParameters, ...] = (
    SegmentParameters("head", "VERT", "CERV", 242.9, 0.0694, 0.5002, 0.303, 0.315, 0.261),
    SegmentParameters("upper_trunk", "CERV", "XYPH", 242.1, 0.1596, 0.5066, 0.505, 0.320,
                      0.465),
    SegmentParameters("middle_trunk", "XYPH", "OMPH", 215.5, 0.1633, 0.4502, 0.482, 0.383,
                      0.468),
    SegmentParameters("lower_trunk", "OMPH", "MIDH", 145.7, 0.1117, 0.6115, 0.615, 0.551,
                      0.587),
    SegmentParameters("upper_arm", "SJC", "EJC", 281.7, 0.0271, 0.5772, 0.285, 0.269, 0.158, 2),
    SegmentParameters("forearm", "EJC", "WJC", 268.9, 0.0162, 0.4574, 0.276, 0.265, 0.121, 2),
    SegmentParameters("hand", "WJC", "MET3", 86.2, 0.0061, 0.7900, 0.628, 0.513, 0.401, 2),
    SegmentParameters("thigh", "HJC", "KJC", 422.2, 0.1416, 0.4095, 0.329, 0.329, 0.149, 2),
    SegmentParameters("shank", "KJC", "AJC", 440.3, 0.0433, 0.4395, 0.251, 0.246, 0.102, 2),
    SegmentParameters("foot", "HEEL", "TTIP", 258.1, 0.0137, 0.4415, 0.257, 0.245, 0.124, 2),
)
#: The whole trunk (CERV-MIDH) of Table 4, for comparison with the sum of its thirds.
DE_LEVA_TRUNK = SegmentParameters("trunk", "CERV", "MIDH", 603.3, 0.4346, 0.5138, 0.328,
                                  0.306, 0.169)


@dataclass(frozen=True)
class Segment:
    """A segment of a body of given stature and mass.

    length mm; mass kg (one segment, not the pair); com mm from the proximal
    endpoint along the segment; inertia (3,) kg*mm^2 about the centre of mass:
    sagittal, transverse, longitudinal axes.
    """

    name: str
    proximal: str
    distal: str
    length: float
    mass: float
    com: float
    inertia: tuple[float, float, float]
    count: int


def segments(stature: float = DEFAULT_STATURE, mass: float = DEFAULT_MASS,
             table: tuple[SegmentParameters, ...] = DE_LEVA_MALE) -> dict[str, Segment]:
    """Segments of a body of ``stature`` mm and ``mass`` kg, scaled from ``table``.

    Raises ValueError for a non-positive stature or mass.
    """
    if stature <= 0.0 or mass <= 0.0:
        raise ValueError(f"stature and mass must be positive (got {stature:g} mm, "
                         f"{mass:g} kg)")
    k = stature / DE_LEVA_STATURE
    out = {}
    for p in table:
        length = p.length * k
        m = p.mass * mass
        radii = (p.r_sagittal, p.r_transverse, p.r_longitudinal)
        out[p.name] = Segment(p.name, p.proximal, p.distal, length, m, p.com * length,
                              tuple(m * (r * length) ** 2 for r in radii), p.count)
    return out


def total_mass_fraction(table: tuple[SegmentParameters, ...] = DE_LEVA_MALE) -> float:
    """Sum of the segments' mass fractions, both sides counted (1 up to rounding)."""
    return sum(p.mass * p.count for p in table)
