"""Time signals and force-displacement curves of runs: the SAE J211 CFC filter,
the :class:`~hollowbody.curves.force_displacement.ForceDisplacement` curve (from
history files, to CSV) and its plot.

Used by scenarios, calibration and reports alike, so it sits below all of them
(it reads histories through :mod:`hollowbody.io.results`).
"""
