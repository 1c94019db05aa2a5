"""Top-level Python API: read a deck and run it.

>>> from hollowbody.api import run_deck
>>> result = run_deck("block.k", "out")          # doctest: +SKIP
>>> result.status, result.summary["energy_ratio"]  # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

from hollowbody.model.model import Model
from hollowbody.solver.explicit import RunOptions, RunResult, run
from hollowbody.solver.verdict import Thresholds


def load_model(deck: str | Path, strict: bool = False) -> Model:
    """Read and validate a keyword deck into a :class:`Model` (DeckError on bad input)."""
    from hollowbody.build import build_model
    from hollowbody.io.keyword import read_deck

    return build_model(read_deck(Path(deck), strict=strict))


def _read_for_run(deck: str | Path, strict: bool) -> tuple[Model, tuple[Path, ...]]:
    """The model and the files it was read from (deck and includes). Unsupported
    keywords are not warned about: the run lists them in messages.log and summary.json."""
    import warnings

    from hollowbody.build import build_model
    from hollowbody.io.keyword import UnsupportedKeywordWarning, read_deck

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnsupportedKeywordWarning)
        d = read_deck(Path(deck), strict=strict)
    files = (Path(deck), *(Path(inc.deck.path) for inc in d.includes() if inc.deck.path))
    return build_model(d), files


def run_model(model: Model, out_dir: str | Path, end_time: float | None = None,
              erode: bool | None = None, vtk: bool = True, quiet: bool = True,
              label: str = "run", restart: str | Path | None = None,
              dump_cycles: int | None = None, dump_minutes: float = 0.0,
              keep_dumps: int = 0, dump_at_end: bool = False, overwrite: bool = False,
              inputs: tuple[Path, ...] = (), quality: Thresholds | None = None,
              threads: int | str | None = None, d3plot: bool | None = None) -> RunResult:
    """Run a model; outputs go to ``out_dir`` (created).

    restart: resume from this restart file, or ``"newest"`` for the newest
    ``d3dumpNN`` of ``out_dir``; dump_cycles: cycles between restart files
    (overrides *DATABASE_BINARY_D3DUMP); dump_minutes: minutes of wall time between
    restart files too (0: not by time); keep_dumps: keep only the newest K restart
    files (0: all); dump_at_end: a run that ends normally writes one too (to be
    continued to a later end time). An ``out_dir`` holding an earlier run
    is refused (UserInputError) unless ``overwrite``, which deletes that run's
    outputs first (never the ``inputs`` files); a restart resumes into it.
    quality: limits of the run's verdict (``summary["quality"]``; None: the defaults).
    threads: numba threads of the run, at most N or ``"auto"`` (see
    :mod:`hollowbody.solver.threads`); None keeps numba's current count.
    d3plot: write a d3plot for LS-PrePost (True), never (False), or when the deck has
    *DATABASE_BINARY_D3PLOT and lasso-python is installed (None).
    """
    return run(model, RunOptions(out_dir=Path(out_dir), end_time=end_time, erode=erode,
                                 vtk=vtk, quiet=quiet, label=label, restart=restart,
                                 dump_cycles=dump_cycles, dump_minutes=dump_minutes,
                                 keep_dumps=keep_dumps, dump_at_end=dump_at_end,
                                 overwrite=overwrite, inputs=tuple(inputs), quality=quality,
                                 threads=threads, d3plot=d3plot))


def run_deck(deck: str | Path, out_dir: str | Path, end_time: float | None = None,
             erode: bool | None = None, vtk: bool = True, quiet: bool = True,
             strict: bool = False, restart: str | Path | None = None,
             dump_cycles: int | None = None, dump_minutes: float = 0.0,
             keep_dumps: int = 0, dump_at_end: bool = False, overwrite: bool = False,
             quality: Thresholds | None = None,
             threads: int | str | None = None, d3plot: bool | None = None) -> RunResult:
    """Read ``deck`` and run it; see :func:`run_model` (the deck and its includes are
    the run's ``inputs``)."""
    model, files = _read_for_run(deck, strict)
    return run_model(model, out_dir, end_time=end_time, erode=erode, vtk=vtk, quiet=quiet,
                     label=Path(deck).name, restart=restart, dump_cycles=dump_cycles,
                     dump_minutes=dump_minutes, keep_dumps=keep_dumps,
                     dump_at_end=dump_at_end, overwrite=overwrite, inputs=files,
                     quality=quality, threads=threads, d3plot=d3plot)
