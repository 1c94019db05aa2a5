"""Calibration of hollow shell structures against solid soft tissue (paper section 2.1).

The public API::

    from hollowbody.calibrate import (CalibrationSettings, GASettings, FitnessSettings,
                                      make_space, calibrate, make_runner, BlockSimulator)

See docs/calibrate.md for the method (fitness definition, GA settings,
caching, checkpoints, parallel evaluation).
"""

from hollowbody.calibrate.driver import (
    CalibrationError,
    CalibrationResult,
    CalibrationSettings,
    calibrate,
)
from hollowbody.calibrate.fitness import FitnessSettings, curve_distance
from hollowbody.calibrate.ga import GASettings
from hollowbody.calibrate.runner import DaskRunner, SerialRunner, make_runner
from hollowbody.calibrate.simulate import BlockSimulator, RunOutcome
from hollowbody.calibrate.space import ParameterSpace, make_space
from hollowbody.calibrate.surrogate import SurrogateSimulator

__all__ = [
    "BlockSimulator",
    "CalibrationError",
    "CalibrationResult",
    "CalibrationSettings",
    "DaskRunner",
    "FitnessSettings",
    "GASettings",
    "ParameterSpace",
    "RunOutcome",
    "SerialRunner",
    "SurrogateSimulator",
    "calibrate",
    "curve_distance",
    "make_runner",
    "make_space",
]
