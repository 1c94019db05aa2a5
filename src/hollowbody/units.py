"""Units and conventions of hollowbody (the one place that defines them).

Every number inside hollowbody (decks, API, files) uses the consistent system
of THUMS and VIVA+:

======== ============ ===================================
quantity unit         note
======== ============ ===================================
length   mm
time     ms
mass     kg
force    kN
stress   GPa          1 MPa = 0.001 GPa (= kN/mm^2)
energy   J            = kN*mm
velocity mm/ms        = m/s
density  kg/mm^3      water = 1.0e-6
======== ============ ===================================

Voigt order is ``xx, yy, zz, xy, yz, zx``; tension is positive; strain vectors
carry engineering shear strains (gamma = 2 * epsilon).

Human-facing output may use MPa or km/h but must label the unit; use the
converters below rather than literal factors.
"""

from __future__ import annotations

#: Voigt component order of every stress/strain vector.
VOIGT = ("xx", "yy", "zz", "xy", "yz", "zx")

MPA_PER_GPA = 1000.0
KMH_PER_MM_PER_MS = 3.6  # 1 mm/ms = 1 m/s = 3.6 km/h
DENSITY_WATER = 1.0e-6  # kg/mm^3


def mpa_to_gpa(value_mpa: float) -> float:
    """Stress in MPa -> GPa (deck units)."""
    return value_mpa / MPA_PER_GPA


def gpa_to_mpa(value_gpa: float) -> float:
    """Stress in GPa (deck units) -> MPa."""
    return value_gpa * MPA_PER_GPA


def kmh_to_mm_per_ms(speed_kmh: float) -> float:
    """Speed in km/h -> mm/ms (= m/s)."""
    return speed_kmh / KMH_PER_MM_PER_MS


def mm_per_ms_to_kmh(speed: float) -> float:
    """Speed in mm/ms (= m/s) -> km/h."""
    return speed * KMH_PER_MM_PER_MS
