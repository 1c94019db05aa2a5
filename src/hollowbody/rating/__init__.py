"""Objective curve rating: ISO/TS 18571, CORA, corridors and reference data.

Modules
-------
iso18571    ISO/TS 18571 rating (corridor, phase, magnitude, slope scores)
cora        CORA rating as in CORAplus 4 (corridor and cross-correlation method)
corridors   response corridors from polygons, bounds or specimen curves
plot        plots of a response against a corridor and specimen curves
viano1989   Viano (1989) lateral hub impact corridors and specimen curves
csvio       reading curves and corridors from CSV files
signals     curve checks and resampling shared by the methods
kernels     numba kernels (sliding cross-correlation, banded DTW)

Example
-------
>>> import numpy as np
>>> from hollowbody.rating import cora, iso18571
>>> t = np.linspace(0.0, 60.0, 601)                       # ms
>>> test = 3.0 * np.sin(np.pi * t / 60.0) ** 2             # kN
>>> sim = 3.3 * np.sin(np.pi * (t - 1.0) / 60.0) ** 2
>>> round(iso18571(t, test, t, sim).overall, 3) <= 1.0
True
"""

from hollowbody.rating.cora import CoraParameters, CoraResult, UserCorridors, cora
from hollowbody.rating.corridors import Corridor
from hollowbody.rating.iso18571 import IsoParameters, IsoResult, iso18571
from hollowbody.rating.signals import CurveError

__all__ = [
    "CoraParameters",
    "CoraResult",
    "Corridor",
    "CurveError",
    "IsoParameters",
    "IsoResult",
    "UserCorridors",
    "cora",
    "iso18571",
]
