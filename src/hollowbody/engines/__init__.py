"""Hand-off of a deck to an external engine (OpenRadioss, LS-DYNA) and the results back.

hollowbody's own solver is the embedded default; models that outgrow one
machine run on OpenRadioss (open source, MPI + OpenMP) or LS-DYNA (licensed,
SMP or MPP). This package finds an installed engine
(:mod:`~hollowbody.engines.discovery`), builds the command lines of a run
(:mod:`~hollowbody.engines.commands`), prepares the deck each engine reads
(:mod:`~hollowbody.engines.radioss_deck`), runs them
(:mod:`~hollowbody.engines.runner`) and reads the engine's own files back into
hollowbody's ``glstat.csv``, ``rcforc.csv``, ``nodout.csv`` and ``summary.json``
(:mod:`~hollowbody.engines.lsdyna_status`, :mod:`~hollowbody.engines.lsdyna_ascii`,
:mod:`~hollowbody.engines.lsdyna_binout`, :mod:`~hollowbody.engines.radioss_listing`,
:mod:`~hollowbody.engines.results`). See ``docs/engines.md``.

Layer: above the solver (the column layout of the history files is the
solver's), beside :mod:`hollowbody.api`; it never imports the scenarios,
calibration or the command line.
"""

ENGINES = ("hollowbody", "openradioss", "lsdyna")
