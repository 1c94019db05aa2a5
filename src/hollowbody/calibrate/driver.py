"""The calibration loop: references, GA generations, cache, checkpoint, outputs.

:func:`calibrate` fits the hollow block's wall parameters to the solid block's
force-displacement response (paper section 2.1)::

    from hollowbody.calibrate import CalibrationSettings, calibrate, make_space
    from hollowbody.calibrate.simulate import BlockSimulator
    settings = CalibrationSettings("muscle", (40.0,), make_space(["E", "yield"]))
    result = calibrate(settings, "cal_muscle", BlockSimulator.make("muscle", mesh=15))

Files in the output folder ``DIR``:

- ``reference/<speed>kmh/`` — the solid reference runs (reused when complete),
- ``runs/<context>/<candidate>/<speed>kmh/`` — every hollow run,
- ``evaluations.jsonl`` — the evaluation cache (one record a line),
- ``checkpoint.json`` — settings and every completed generation's decision
  vectors and fitness (``--resume`` replays them; see :mod:`.ga`),
- ``calibration.json`` — settings, best parameters and fitness, per-generation
  statistics, every evaluation, ``elapsed_seconds`` (wall time of this call,
  references included) and ``runs_here`` (evaluations run by this call, not
  from the cache); rewritten after each generation,
- the report (``convergence.png``, ``overlay.png``, ``best_hollow/deck.k``,
  ``table1.md``, ``table1.csv``; :mod:`hollowbody.report.calibration`).

Ctrl-C stops after writing ``calibration.json`` with status ``interrupted``;
the checkpoint of the last completed generation and every finished evaluation
are kept, so ``resume=True`` continues without running anything twice.
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from hollowbody.calibrate.cache import EvaluationCache, cacheable
from hollowbody.calibrate.evaluation import CandidateTask, context_hash, evaluate_candidate
from hollowbody.calibrate.fitness import FitnessSettings
from hollowbody.calibrate.ga import GASettings, GeneticSearch, ReplayError
from hollowbody.calibrate.progress import CalibrationProgress
from hollowbody.calibrate.reference import ensure_references
from hollowbody.calibrate.runner import SerialRunner
from hollowbody.calibrate.simulate import EXCEPTION, INTERRUPT, LOST, NORMAL, SUSPECT
from hollowbody.calibrate.space import ParameterSpace
from hollowbody.curves.force_displacement import ForceDisplacement
from hollowbody.errors import UserInputError

CHECKPOINT = "checkpoint.json"
CACHE = "evaluations.jsonl"
RESULT = "calibration.json"
CHECKPOINT_FORMAT = 1


class CalibrationError(RuntimeError):
    """The calibration cannot go on (every evaluation of a generation raised, ...)."""


@dataclass(frozen=True)
class CalibrationSettings:
    """What is calibrated and how: tissue, speeds (km/h), parameter space, GA, fitness."""

    tissue: str
    speeds: tuple[float, ...]
    space: ParameterSpace
    ga: GASettings = field(default_factory=GASettings)
    fitness: FitnessSettings = field(default_factory=FitnessSettings)

    def to_dict(self, simulator: Any) -> dict:
        return {"tissue": self.tissue, "speeds_kmh": [float(s) for s in self.speeds],
                "parameters": self.space.to_dict(), "ga": self.ga.to_dict(),
                "fitness": self.fitness.to_dict(), "simulator": simulator.describe()}


@dataclass
class CalibrationResult:
    """Outcome of :func:`calibrate`.

    best_params: {name: value} (units of :mod:`.space`) or None if nothing
    ended normally; evaluations: every record of this calibration in order of
    first appearance (with its ``generation``); history: per-generation
    statistics; references: {speed: solid curve}; runs_here: evaluations run
    in this call (not taken from the cache).
    """

    out_dir: Path
    status: str
    best_params: dict[str, float] | None
    best_fitness: float | None
    best_record: dict | None
    evaluations: list[dict]
    history: list[dict]
    references: dict[float, ForceDisplacement]
    runs_here: int
    data: dict = field(default_factory=dict)


def _write_json(path: Path, data: dict) -> None:
    """Atomic JSON write (a kill never leaves a torn file)."""
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=1, default=str))
    os.replace(tmp, path)


def _comparable(d: dict) -> dict:
    d = json.loads(json.dumps(d, default=str))
    d["ga"].pop("generations", None)
    return d


def load_checkpoint(out_dir: Path, settings_dict: dict) -> dict:
    """The checkpoint in ``out_dir`` if it matches the settings (UserInputError otherwise)."""
    path = out_dir / CHECKPOINT
    if not path.exists():
        raise UserInputError(f"--resume: no checkpoint in {out_dir} (nothing to resume)")
    try:
        ck = json.loads(path.read_text())
    except json.JSONDecodeError:
        raise UserInputError(f"--resume: {path} is not a readable checkpoint") from None
    if ck.get("format") != CHECKPOINT_FORMAT:
        raise UserInputError(f"--resume: {path} has an unknown format")
    old, new = _comparable(ck["settings"]), _comparable(settings_dict)
    diff = []
    for k in sorted(set(old) | set(new)):
        a, b = old.get(k), new.get(k)
        if a == b:
            continue
        if isinstance(a, dict) and isinstance(b, dict):
            diff += [f"{k}.{j}" for j in sorted(set(a) | set(b)) if a.get(j) != b.get(j)]
        else:
            diff.append(k)
    if diff:
        raise UserInputError(f"--resume: settings differ from the checkpoint in {out_dir} "
                             f"({', '.join(diff)}); use the same options (only "
                             "--generations may change) or another --out")
    return ck


def _lost_record(task: CandidateTask, err: BaseException) -> dict:
    return {"key": task.key, "context": task.context, "params": dict(task.params),
            "fitness": task.fitness.penalty * len(task.speeds), "status": LOST,
            "reason": f"worker lost: {type(err).__name__}: {err}".splitlines()[0],
            "wall_seconds": None, "runs": []}


def _gen_stats(generation: int, records: list[dict], best_so_far: float | None) -> dict:
    ok = [r["fitness"] for r in records if r["status"] == NORMAL]
    return {"generation": generation, "evaluations": len(records),
            "best": best_so_far, "generation_best": min(ok) if ok else None,
            "mean": float(np.mean(ok)) if ok else None,
            "failed": sum(r["status"] != NORMAL for r in records),
            "suspect": sum(r["status"] == SUSPECT for r in records)}


def _run_dir_name(params: dict[str, float]) -> str:
    return "_".join(f"{k}{v:g}" for k, v in params.items())


class _Session:
    """State of one :func:`calibrate` call (kept small; the loop is in calibrate)."""

    def __init__(self, settings: CalibrationSettings, out: Path, simulator: Any,
                 evaluate: Callable[[CandidateTask], dict]) -> None:
        self.settings = settings
        self.out = out
        self.simulator = simulator
        self.evaluate = evaluate
        self.settings_dict = settings.to_dict(simulator)
        self.context = context_hash(simulator.describe(), settings.speeds, settings.fitness)
        self.cache = EvaluationCache(out / CACHE)
        self.generations: list[dict] = []
        self.by_key: dict[str, dict] = {}
        self.first_gen: dict[str, int] = {}
        self.history: list[dict] = []
        self.best: dict | None = None
        self.runs_here = 0
        self.references: dict[float, ForceDisplacement] = {}
        self.runner_description = ""
        self.t0 = time.perf_counter()

    def remember(self, record: dict, generation: int) -> None:
        key = record["key"]
        self.by_key[key] = record
        self.first_gen.setdefault(key, generation)
        if record["status"] == NORMAL and (self.best is None
                                           or record["fitness"] < self.best["fitness"]):
            self.best = record

    def evaluations(self) -> list[dict]:
        return [{**self.by_key[k], "generation": g} for k, g in self.first_gen.items()]

    def result_data(self, status: str) -> dict:
        b = self.best
        return {**self.settings_dict, "status": status, "context": self.context,
                "runner": self.runner_description,
                "elapsed_seconds": time.perf_counter() - self.t0, "runs_here": self.runs_here,
                "best_parameters": None if b is None else b["params"],
                "best_fitness": None if b is None else b["fitness"],
                "best_run_dirs": None if b is None else [r["run_dir"] for r in b["runs"]],
                "generations": self.history, "evaluations": self.evaluations(),
                "reference": {f"{s:g}": {"peak_force_kN": c.peak_force,
                                         "max_displacement_mm": c.max_displacement,
                                         "run_dir": str(self.out / "reference" / f"{s:g}kmh")}
                              for s, c in self.references.items()}}

    def write_result(self, status: str) -> dict:
        data = self.result_data(status)
        _write_json(self.out / RESULT, data)
        return data

    def write_checkpoint(self) -> None:
        _write_json(self.out / CHECKPOINT, {"format": CHECKPOINT_FORMAT,
                                            "settings": self.settings_dict,
                                            "generations": self.generations})

    def restore(self, ck: dict, search: GeneticSearch) -> None:
        """Replay the checkpoint's generations; records come from the cache or the checkpoint."""
        try:
            search.replay(ck["generations"])
        except ReplayError as exc:
            raise CalibrationError(str(exc)) from None
        for g, gen in enumerate(ck["generations"], start=1):
            recs = []
            for key, f in zip(gen["keys"], gen["F"]):
                rec = self.cache.get(self.context, key) or gen.get("uncached", {}).get(key)
                if rec is None:  # cache file lost: keep what the checkpoint knows
                    rec = {"key": key, "context": self.context, "params": {}, "fitness": f,
                           "status": NORMAL, "reason": "from checkpoint", "runs": []}
                self.remember(rec, g)
                recs.append(rec)
            self.generations.append(gen)
            self.history.append(_gen_stats(g, recs, None if self.best is None
                                           else self.best["fitness"]))


def calibrate(settings: CalibrationSettings, out_dir: str | Path, simulator: Any,
              runner: Any = None, resume: bool = False,
              progress: CalibrationProgress | None = None,
              evaluate: Callable[[CandidateTask], dict] = evaluate_candidate
              ) -> CalibrationResult:
    """Run (or resume) a calibration; see the module docstring.

    simulator: see :mod:`hollowbody.calibrate.simulate`; runner: a
    :mod:`hollowbody.calibrate.runner` runner (default: serial in this
    process; the caller closes it); evaluate: the per-candidate function
    (picklable for dask). Raises UserInputError (bad resume),
    :class:`~hollowbody.calibrate.reference.ReferenceRunError` (solid
    reference failed), :class:`CalibrationError`, KeyboardInterrupt (after
    saving).
    """
    out = Path(out_dir).resolve()  # workers may run elsewhere: absolute run folders
    out.mkdir(parents=True, exist_ok=True)
    runner = runner or SerialRunner()
    progress = progress or CalibrationProgress()
    s = _Session(settings, out, simulator, evaluate)
    s.runner_description = getattr(runner, "description", type(runner).__name__)
    ga = settings.ga
    search = GeneticSearch(settings.space, ga)
    if resume:
        s.restore(load_checkpoint(out, s.settings_dict), search)
    progress.start(ga.population * ga.generations, ga.generations)
    progress.done = sum(len(g["keys"]) for g in s.generations)
    progress.best = None if s.best is None else s.best["fitness"]
    try:
        s.references = ensure_references(simulator, settings.speeds, out / "reference", runner)
        while search.generation < ga.generations:
            _one_generation(s, search, runner, progress)
    except KeyboardInterrupt:
        s.write_result("interrupted")
        progress.message(f"interrupted: checkpoint and {len(s.cache)} finished evaluations "
                         f"kept in {out}; continue with --resume")
        progress.close()
        raise
    except BaseException:
        progress.close()
        raise
    progress.close()
    data = s.write_result("complete")
    b = s.best
    return CalibrationResult(out, "complete", None if b is None else dict(b["params"]),
                             None if b is None else b["fitness"], b, s.evaluations(),
                             s.history, s.references, s.runs_here, data)


def _one_generation(s: _Session, search: GeneticSearch, runner: Any,
                    progress: CalibrationProgress) -> None:
    g = search.generation + 1
    x = search.ask()
    params = [s.settings.space.rounded(v) for v in x]
    keys = [s.settings.space.key(p) for p in params]
    progress.start_generation(g, len(keys))
    records: dict[str, dict] = {}
    tasks: list[CandidateTask] = []
    for p, k in zip(params, keys):
        if k in records or any(t.key == k for t in tasks):
            continue
        rec = s.cache.get(s.context, k)
        if rec is not None:
            records[k] = rec
            progress.evaluated(rec, cached=True)
            continue
        tasks.append(CandidateTask(s.simulator, p, k, s.context, s.settings.speeds,
                                   s.references, str(s.out / "runs" / s.context /
                                                     _run_dir_name(p)), s.settings.fitness))
    broken = []
    for i, rec, err in runner.run(s.evaluate, tasks):
        if err is not None:
            rec = _lost_record(tasks[i], err)
        if rec["status"] == INTERRUPT:
            raise KeyboardInterrupt
        s.cache.put(rec)
        s.runs_here += 1
        records[rec["key"]] = rec
        if rec["status"] in (EXCEPTION, LOST):
            broken.append(rec)
        progress.evaluated(rec, cached=False)
    if tasks and len(broken) == len(records):
        raise CalibrationError(f"every evaluation of generation {g} failed before running "
                               f"(first: {broken[0]['reason']})")
    f = np.array([records[k]["fitness"] for k in keys], dtype=float)
    search.tell(f)
    for k in keys:
        s.remember(records[k], g)
    uncached = {k: records[k] for k in keys if not cacheable(records[k])}
    s.generations.append({"X": x.tolist(), "F": f.tolist(), "keys": keys,
                          "uncached": uncached})
    s.write_checkpoint()
    stats = _gen_stats(g, [records[k] for k in dict.fromkeys(keys)],
                       None if s.best is None else s.best["fitness"])
    s.history.append(stats)
    s.write_result("running")
    progress.end_generation(stats)
