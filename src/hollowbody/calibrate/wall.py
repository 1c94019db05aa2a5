"""The hollow walls a calibration found: its best parameters with the block's defaults.

A calibration varies some wall parameters (:mod:`hollowbody.calibrate.space`)
and may fix others; :func:`effective_wall` gives the complete wall (every
parameter of :data:`WALL_UNITS` that has a value), as the study re-runs it and
the reports print it.
"""

from __future__ import annotations

#: Hollow wall values used when a parameter is neither calibrated nor fixed (the block's).
WALL_DEFAULTS = {"etan": 0.0, "thickness": 1.5}
WALL_UNITS = {"E": "MPa", "yield": "MPa", "etan": "MPa", "thickness": "mm"}


def effective_wall(data: dict) -> dict[str, float] | None:
    """Best wall parameters of a calibration with fixed/default values filled in."""
    best = data.get("best_parameters")
    if best is None:
        return None
    fixed = data.get("simulator", {}).get("fixed", {}) or {}
    values = {**WALL_DEFAULTS, **fixed, **best}
    return {k: float(values[k]) for k in WALL_UNITS if k in values}


#: BlockConfig fields of the walls' hourglass control that a calibration records in its
#: simulator options (a study of calibrated walls must run them with the same control).
WALL_CONTROL_FIELDS = ("wall_hourglass_ihq", "wall_hourglass_qh")


#: BlockConfig fields of the walls' geometry that a calibration records in its simulator
#: options when they are not the block's (a study of calibrated walls builds the same).
WALL_GEOMETRY_FIELDS = ("cell",)


def _recorded(data: dict, names: tuple[str, ...]) -> dict:
    """The fields ``names`` a calibration recorded in its simulator options."""
    options = (data.get("simulator") or {}).get("options") or {}
    return {k: options[k] for k in names if k in options}


def wall_geometry(data: dict) -> dict:
    """The walls' geometry a calibration ran with, when not the block's ({} otherwise)."""
    return _recorded(data, WALL_GEOMETRY_FIELDS)


def wall_control(data: dict) -> dict:
    """The walls' hourglass control a calibration ran with ({} for the block's default)."""
    return _recorded(data, WALL_CONTROL_FIELDS)


#: BlockConfig fields of the solid reference's hourglass control
SOLID_CONTROL_FIELDS = ("hourglass_ihq", "hourglass_qh")
#: the solid block's *HOURGLASS (IHQ, QM) of calibrations that do not record theirs: they
#: were made when the block's default was the stiffness form IHQ 4, QM 0.05 (a calibration
#: run with that control records none either)
LEGACY_SOLID_HOURGLASS = (4, 0.05)


def solid_control(data: dict) -> dict:
    """The solid reference's hourglass control a calibration ran with (BlockConfig fields
    ``hourglass_ihq`` and ``hourglass_qh``)."""
    sim = data.get("simulator", {}) or {}
    ihq, qm = sim.get("solid_hourglass") or LEGACY_SOLID_HOURGLASS
    return {"hourglass_ihq": int(ihq), "hourglass_qh": float(qm)}
