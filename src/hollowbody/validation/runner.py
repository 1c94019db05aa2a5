"""Run a segment test end to end: set-up, deck, run, signals, ratings.

Folder layout under ``out``::

    <case>/<speed>ms/<tissue>/deck.k (+ includes), setup.json and the run's
                              outputs (glstat.csv, rcforc.csv, summary.json, ...)

:func:`run_case` returns one :class:`RunRecord` per (speed, tissue). A run
that fails keeps its record with the reason and where (element, part, time,
from the run's summary), so a report can say which did not end normally and
why; the other runs go on. ``dry_run`` writes the decks without running them.
Units: mm, ms, kg, kN, m/s.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hollowbody.errors import UserInputError
from hollowbody.rating.corridors import Corridor
from hollowbody.solver.step import INTERRUPT
from hollowbody.validation.cases import Case, end_time_of
from hollowbody.validation.ratings import Rating, rate_run
from hollowbody.validation.setup import Setup
from hollowbody.validation.signals import Signals, read_signals

TISSUES = ("solid", "hollow")
#: Restart files of a validation run: one every this many minutes of wall time, the
#: newest kept, one more at a normal end (``--resume`` continues or extends the run).
DUMP_MINUTES = 10.0


class ValidationInterrupted(KeyboardInterrupt):
    """A run was stopped by the user (Ctrl-C, SIGTERM): the validation stops too; the
    records made so far travel with it."""

    def __init__(self, records: list[RunRecord]) -> None:
        super().__init__("interrupted by the user")
        self.records = records


@dataclass
class RunRecord:
    """One run of a case: where, how it ended, its signals and ratings."""

    case: str
    speed: float
    tissue: str
    folder: Path
    status: str = "not run"
    reason: str = ""
    quality: str = ""
    quality_reasons: list[str] = field(default_factory=list)
    where: dict[str, Any] = field(default_factory=dict)
    wall_seconds: float | None = None
    resumed: int = 0
    setup_seconds: float | None = None
    cycles: int | None = None
    energy_ratio: float | None = None
    elements: dict[str, int] = field(default_factory=dict)
    peak_force: float | None = None
    peak_time: float | None = None
    setup: dict[str, Any] = field(default_factory=dict)
    ratings: list[Rating] = field(default_factory=list)
    signals: Signals | None = None

    @property
    def ok(self) -> bool:
        """Ended normally with quality ok."""
        return self.status == "normal termination" and self.quality == "ok"

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON values (without the signals)."""
        out = {k: v for k, v in self.__dict__.items() if k not in ("signals", "ratings")}
        out["folder"] = str(self.folder)
        out["ratings"] = [r.to_dict() for r in self.ratings]
        return out


def _builder(case: Case) -> Callable[..., Setup]:
    if case.kind == "impact":
        from hollowbody.validation.impact import impact_setup

        return impact_setup
    from hollowbody.validation.bending import bending_setup

    return bending_setup


def build_setup(case: Case, speed: float, tissue: str, mesh: float = 30.0,
                end_time: float | None = None, model: Path | None = None,
                landmarks: dict | None = None, landmarks_path: Path | None = None
                ) -> Setup:
    """The set-up of ``case`` at ``speed`` on the pedestrian (``tissue`` solid or
    hollow) or on the user's ``model`` with its ``landmarks``."""
    return _builder(case)(case.name, speed, tissue=tissue, mesh=mesh, end_time=end_time,
                          model=model, landmarks=landmarks, landmarks_path=landmarks_path)


def write_setup(s: Setup, folder: Path) -> Path:
    """Write the deck (with its includes) and ``setup.json`` into ``folder``; the
    main deck's path."""
    from hollowbody.io.keyword import write_deck

    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "deck.k"
    write_deck(s.deck, path, flatten=False)
    (folder / "setup.json").write_text(json.dumps(s.to_json(), indent=1) + "\n")
    return path


def _read_summary(rec: RunRecord) -> None:
    p = rec.folder / "summary.json"
    if not p.is_file():
        return
    d = json.loads(p.read_text())
    rec.status = d.get("status", rec.status)
    rec.reason = d.get("reason", "")
    rec.quality = d.get("quality", "")
    rec.quality_reasons = [q.get("message", str(q)) if isinstance(q, dict) else str(q)
                           for q in d.get("quality_reasons", [])]
    rec.where = {k[len("error_"):]: v for k, v in d.items() if k.startswith("error_")}
    rec.wall_seconds = d.get("wall_seconds_total", d.get("wall_seconds"))
    rec.resumed = len(d.get("resumed", []))
    rec.cycles = d.get("cycles")
    rec.energy_ratio = d.get("energy_ratio")
    rec.elements = {k: v for k, v in d.get("element_counts", {}).items() if v}


def _read_results(rec: RunRecord, s: Setup) -> None:
    try:
        sig = read_signals(rec.folder, s)
    except UserInputError as err:
        rec.reason = (rec.reason + "; " if rec.reason else "") + str(err)
        return
    rec.signals = sig
    t, f = sig.curve("force")
    if f.size:
        k = int(f.argmax())
        rec.peak_force, rec.peak_time = float(f[k]), float(t[k])


def load_setup(folder: Path) -> Setup:
    """The set-up record (``setup.json``) of a run folder."""
    return Setup.from_json(json.loads((Path(folder) / "setup.json").read_text()))


def _read_back(rec: RunRecord, s: Setup) -> None:
    """Fill ``rec`` from what its folder holds: the summary and, when the run wrote
    any, its signals."""
    _read_summary(rec)
    if (rec.folder / "rcforc.csv").is_file():
        _read_results(rec, s)


def _run_on_engine(s: Setup, deck: Path, work: Path, engine: str, np_: int,
                   threads: int | str | None, engine_path: str | None, quiet: bool) -> Path:
    """Run ``deck`` on an external engine in ``work``; the folder of its results."""
    from hollowbody.engines.runner import execute, plan_run

    if s.impactor_node is None:
        raise UserInputError(f"{s.case}: the set-up names no history node of the impactor, "
                             "which the results of an external engine need")
    nthreads = int(threads) if isinstance(threads, int) or str(threads).isdigit() else 1
    prep = plan_run(engine, deck, work, np_=np_, threads=nthreads, engine_path=engine_path,
                    end_time=s.end_time)
    execute(prep, quiet=quiet)
    return work


def _execute(rec: RunRecord, s: Setup, deck: Path, *, restart: bool, quiet: bool,
             threads: int | str | None, engine: str, np_: int, engine_path: str | None,
             dump_minutes: float) -> None:
    """Run ``deck`` into ``rec.folder`` (from t = 0, or from its newest restart file
    when ``restart``) and read what it wrote. A run stopped by the user raises
    :class:`KeyboardInterrupt` after its record is filled."""
    if engine == "hollowbody":
        from hollowbody.api import run_deck

        res = run_deck(deck, rec.folder, end_time=s.end_time, quiet=quiet, vtk=False,
                       overwrite=not restart, threads=threads,
                       restart="newest" if restart else None,
                       dump_minutes=dump_minutes, keep_dumps=1 if dump_minutes > 0 else 0,
                       dump_at_end=dump_minutes > 0)
        interrupted = res.status == INTERRUPT or res.stop_requested is not None
    else:
        rec.folder = _run_on_engine(s, deck, rec.folder / engine, engine, np_, threads,
                                    engine_path, quiet)
        interrupted = False
    _read_summary(rec)
    _read_results(rec, s)
    if interrupted:
        raise KeyboardInterrupt


def run_one(case: Case, speed: float, tissue: str, out: Path, *, mesh: float = 30.0,
            end_time: float | None = None, model: Path | None = None,
            landmarks: dict | None = None, landmarks_path: Path | None = None,
            dry_run: bool = False, quiet: bool = True, threads: int | str | None = None,
            engine: str = "hollowbody", np_: int = 1, engine_path: str | None = None,
            resume: bool = False, dump_minutes: float = DUMP_MINUTES,
            log: Callable[[str], None] = print) -> RunRecord:
    """Set up, write and (unless ``dry_run``) run one speed and tissue of ``case``.

    ``engine``: ``hollowbody`` (the embedded solver), ``lsdyna`` or ``openradioss``
    (run in ``<folder>/<engine>`` with ``np_`` ranks; their results are converted to
    the same histories, :mod:`hollowbody.engines`). ``resume``: a run already in its
    folder is kept, resumed from its newest restart file or extended to a later
    ``end_time`` (:mod:`hollowbody.validation.resume`) instead of started again.
    ``dump_minutes``: a restart file every this many minutes of wall time (0: none;
    hollowbody engine). A run stopped by the user raises :class:`KeyboardInterrupt`
    (:func:`run_case` then reads its record back from its folder)."""
    from hollowbody.solver.run_lock import RunLock
    from hollowbody.validation.resume import KEEP, RESUME, resume_action, update_end_time

    label = "user" if model is not None else tissue
    folder = out / case.name / f"{speed:g}ms" / label
    # held from the set-up to the last result read (a run still going on in this
    # folder, another validation's: refused before anything of it is touched)
    with RunLock(folder):
        rec = RunRecord(case.name, speed, label, folder)
        opts = dict(quiet=quiet, threads=threads, engine=engine, np_=np_,
                    engine_path=engine_path, dump_minutes=dump_minutes)
        if resume and engine == "hollowbody":
            action, why = resume_action(folder, end_time)
            if action in (KEEP, RESUME):
                kept = load_setup(folder)
                if model is None and kept.mesh is not None and abs(kept.mesh - mesh) > 1e-9:
                    raise UserInputError(f"--mesh {mesh:g} differs from the run in {folder} "
                                         f"({kept.mesh:g} mm): resume with --mesh {kept.mesh:g}, "
                                         "or use another --out")
                s = update_end_time(folder, end_time) if action == RESUME else kept
                rec.setup = s.to_json()
                log(f"{case.name} {speed:g} m/s {label}: {why}")
                if action == KEEP:
                    _read_back(rec, s)
                    return rec
                try:
                    _execute(rec, s, folder / "deck.k", restart=True, **opts)
                except UserInputError as err:  # e.g. a damaged restart file: say why
                    rec.status, rec.reason = "failed", str(err)
                return rec
            log(f"{case.name} {speed:g} m/s {label}: {why}")
            # started again: an earlier summary must not pass for this run's if it is stopped
            (folder / "summary.json").unlink(missing_ok=True)
        log(f"{case.name} {speed:g} m/s {label}: building the set-up")
        t0 = time.perf_counter()
        s = build_setup(case, speed, tissue, mesh, end_time, model, landmarks, landmarks_path)
        if model is None:
            s.mesh = float(mesh)  # recorded in setup.json: a resume checks it
        deck = write_setup(s, folder)
        rec.setup_seconds = time.perf_counter() - t0
        rec.setup = s.to_json()
        if dry_run:
            rec.status = "not run (dry run)"
            return rec
        log(f"{case.name} {speed:g} m/s {label}: running {s.end_time:g} ms on {engine} -> "
            f"{folder}")
        try:
            _execute(rec, s, deck, restart=False, **opts)
        except UserInputError as err:  # a deck the run refuses: keep the record, say why
            rec.status, rec.reason = "failed", str(err)
        return rec


def rate_records(records: list[RunRecord], corridor: Corridor | None = None) -> None:
    """Rate every record with signals against the test data and, hollow, against the
    solid run of the same case and speed among ``records``."""
    from hollowbody.validation.cases import CASES

    for r in records:
        if r.signals is None:
            continue
        solid = next((x for x in records if x.case == r.case and x.speed == r.speed
                      and x.tissue == "solid" and x is not r), None)
        twin = solid.signals if solid is not None and solid.signals is not None else None
        r.ratings = rate_run(CASES[r.case], r.speed, r.signals, twin, corridor)


def run_case(case: Case, speeds: tuple[float, ...], tissues: tuple[str, ...], out: Path, *,
             mesh: float = 30.0, end_time: float | None = None, model: Path | None = None,
             landmarks: dict | None = None, landmarks_path: Path | None = None,
             corridor: Corridor | None = None, dry_run: bool = False, quiet: bool = True,
             threads: int | str | None = None, engine: str = "hollowbody", np_: int = 1,
             engine_path: str | None = None, resume: bool = False,
             dump_minutes: float = DUMP_MINUTES,
             log: Callable[[str], None] = print) -> list[RunRecord]:
    """Every speed and tissue of ``case``, rated (hollow also against solid).

    A run stopped by the user raises :class:`ValidationInterrupted` carrying the
    records so far (the stopped run's included, rated)."""
    records: list[RunRecord] = []
    for speed in speeds:
        for tissue in (("user",) if model is not None else tissues):
            label = "user" if model is not None else tissue
            try:
                rec = run_one(case, speed, tissue, out, mesh=mesh,
                              end_time=end_time if end_time is not None
                              else end_time_of(case, speed),
                              model=model, landmarks=landmarks, landmarks_path=landmarks_path,
                              dry_run=dry_run, quiet=quiet, threads=threads, engine=engine,
                              np_=np_, engine_path=engine_path, resume=resume,
                              dump_minutes=dump_minutes, log=log)
            except KeyboardInterrupt:
                folder = out / case.name / f"{speed:g}ms" / label
                stopped = RunRecord(case.name, speed, label, folder)
                if (folder / "setup.json").is_file():
                    s = load_setup(folder)
                    stopped.setup = s.to_json()
                    _read_back(stopped, s)
                if stopped.status == "not run":
                    stopped.status, stopped.reason = "interrupted", "stopped by the user"
                records.append(stopped)
                rate_records(records, corridor)
                raise ValidationInterrupted(records) from None
            records.append(rec)
    rate_records(records, corridor)
    return records


def collect_records(out: Path, corridor: Corridor | None = None) -> list[RunRecord]:
    """The records of the runs already in ``out`` (every ``setup.json`` below it),
    read and rated again: a report of runs made earlier, or interrupted."""
    from hollowbody.validation.cases import CASES, ORDER

    records: list[RunRecord] = []
    for sj in sorted(Path(out).glob("*/*ms/*/setup.json")):
        d = json.loads(sj.read_text())
        s = Setup.from_json(d)
        if s.case not in CASES:
            continue
        folder = sj.parent
        for engine in ("lsdyna", "openradioss"):  # a run on an external engine
            if (folder / engine / "summary.json").is_file():
                folder = folder / engine
        rec = RunRecord(s.case, s.speed, s.tissue, folder, setup=d)
        _read_back(rec, s)
        records.append(rec)
    records.sort(key=lambda r: (ORDER.index(r.case), r.speed, r.tissue != "solid"))
    rate_records(records, corridor)
    return records
