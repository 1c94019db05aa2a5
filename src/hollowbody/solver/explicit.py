"""The run loop: set-up, ``step`` until termination, observers, restart dumps.

``run(model, options)`` builds the static plan (:func:`~hollowbody.solver.setup.assemble`),
the State (:func:`~hollowbody.solver.state.init_state`), then repeats
:func:`~hollowbody.solver.step.step` (one central-difference cycle) and hands
the State to the observers (histories, states, monitors, progress) after each
cycle. Termination: end time (normal), negative volume (error, unless ERODE),
DTMIN, non-finite numbers (error), Ctrl-C or SIGTERM (user interrupt, at the
end of the current cycle). Every output is written and flushed as the run
goes, so whatever ends the run, what was computed is kept; with
``*DATABASE_BINARY_D3DUMP`` (and at a user interrupt or an error
termination) restart files are written and ``options.restart`` resumes from
one (:mod:`hollowbody.solver.restart`).
"""

from __future__ import annotations

import logging
import signal
import threading
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.errors import UserInputError
from hollowbody.io.results.d3plot import EXTRA as D3PLOT_EXTRA
from hollowbody.io.results.d3plot import available as d3plot_available
from hollowbody.model.summary import unsupported_entries, unsupported_lines
from hollowbody.solver import restart as rs
from hollowbody.solver import threads as th
from hollowbody.solver.contention import ContentionGuard
from hollowbody.solver.dump_policy import DumpPolicy
from hollowbody.solver.energies import kinetic_energy
from hollowbody.solver.monitors import Monitors
from hollowbody.solver.outputs import RunOutputs, prepare_out_dir
from hollowbody.solver.progress import COMPILE_NOTICE, LINE_INTERVAL, CompileWatch, Progress
from hollowbody.solver.run_lock import RunLock, check_free
from hollowbody.solver.setup import assemble
from hollowbody.solver.state import State, init_state, restore, snapshot
from hollowbody.solver.step import ERROR, INTERRUPT, NORMAL, Termination, start, step
from hollowbody.solver.verdict import Thresholds

__all__ = ["ERROR", "INTERRUPT", "NORMAL", "RunOptions", "RunResult", "run"]

#: Restart option value meaning "the newest dump of the output folder".
NEWEST = "newest"


@dataclass
class RunOptions:
    """How to run: output folder, overrides and display.

    end_time: overrides *CONTROL_TERMINATION ENDTIM (ms) when given.
    erode: overrides *CONTROL_TIMESTEP ERODE when given.
    vtk: write ParaView states; quiet: no progress display.
    d3plot: write a d3plot for LS-PrePost (True; needs lasso-python), never (False),
    or when the deck has *DATABASE_BINARY_D3PLOT and lasso-python is installed (None).
    restart: resume from this restart file, or from the newest ``d3dumpNN``
    of ``out_dir`` with :data:`NEWEST`; None starts at t = 0.
    dump_cycles: overrides *DATABASE_BINARY_D3DUMP CYCL when given (0 = none).
    dump_minutes: a restart file every M minutes of wall time as well (0 = none);
    keep_dumps: keep only the newest K restart files of the folder (0 = all);
    dump_at_end: a run that ends normally writes a restart file too (so that it
    can be continued to a later end time); see :mod:`hollowbody.solver.dump_policy`.
    overwrite: an ``out_dir`` holding an earlier run is cleared first (else refused);
    inputs: files the run reads (the deck and its includes), never deleted.
    quality: limits of the run's verdict (:mod:`hollowbody.solver.verdict`);
    None: the defaults.
    threads: numba threads, an integer (at most), ``"auto"`` or None (the
    process default, :func:`hollowbody.solver.threads.set_default`; unset: numba's
    current count); see :mod:`hollowbody.solver.threads`.
    progress_interval: seconds of wall time between progress lines (stdout when
    it is not a terminal, and messages.log).
    """

    out_dir: Path
    end_time: float | None = None
    erode: bool | None = None
    vtk: bool = True
    d3plot: bool | None = None
    quiet: bool = False
    label: str = "run"
    restart: Path | str | None = None
    dump_cycles: int | None = None
    dump_minutes: float = 0.0
    keep_dumps: int = 0
    dump_at_end: bool = False
    overwrite: bool = False
    inputs: tuple[Path, ...] = ()
    quality: Thresholds | None = None
    threads: int | str | None = None
    progress_interval: float = LINE_INTERVAL


@dataclass
class RunResult:
    """Summary of a finished run (also written to summary.json)."""

    status: str
    reason: str
    end_time_ms: float
    cycles: int
    summary: dict = field(default_factory=dict)
    out_dir: Path | None = None
    #: a stop (Ctrl-C, SIGTERM) asked for after the last cycle had begun: the run
    #: ended as it would have, but its caller should stop too
    stop_requested: str | None = None


class _Stop:
    """SIGINT / SIGTERM set a flag the loop reads between cycles (main thread only;
    elsewhere Ctrl-C arrives as KeyboardInterrupt)."""

    def __init__(self) -> None:
        self.requested: str | None = None
        self._old: dict[int, object] = {}

    def __enter__(self) -> _Stop:
        if threading.current_thread() is threading.main_thread():
            for sig, name in ((signal.SIGINT, "Ctrl-C"), (signal.SIGTERM, "SIGTERM")):
                self._old[sig] = signal.signal(sig, lambda *_, n=name: self._set(n))
        return self

    def _set(self, name: str) -> None:
        if self.requested is not None and name == "Ctrl-C":
            raise KeyboardInterrupt  # a second Ctrl-C stops at once
        self.requested = name

    def __exit__(self, *exc: object) -> None:
        for sig, old in self._old.items():
            signal.signal(sig, old)


def run(model, options: RunOptions) -> RunResult:  # noqa: ANN001 - Model
    """Run ``model`` (a :class:`hollowbody.model.model.Model`) to termination."""
    out = Path(options.out_dir)
    check_free(out)  # a live run there: refused before its files are read
    resume = None
    if options.restart is not None:  # checked before anything in the folder is touched
        given = None if str(options.restart) == NEWEST else Path(options.restart)
        path = rs.find_dump(out, given)
        header, payload = rs.read_dump(path, model)
        resume = (path, header, payload)
    wall0 = time.perf_counter()
    # the set-up's own kernels; its warnings (material checks) go to the run log as one
    # line each instead of Python warnings with source paths
    with CompileWatch() as setup_compile, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        plan = assemble(model)  # set-up errors (DeckError) before anything is written
    try:
        setting = options.threads if options.threads is not None else th.default()
        n_threads, threads_why = th.resolve(setting, th.model_work(plan))
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    policy = th.wait_policy()
    for c in plan.contacts:  # threaded per-cycle contact kernels: as cheap as a wake-up
        if hasattr(c, "parallel_min_rows"):
            c.parallel_min_rows = th.per_cycle_min_rows(policy)
    try:
        dumps = DumpPolicy(cycles=options.dump_cycles if options.dump_cycles is not None
                           else model.output.d3dump_cycles, minutes=options.dump_minutes,
                           keep=options.keep_dumps, at_end=options.dump_at_end)
    except ValueError as exc:
        raise UserInputError(str(exc)) from None
    if options.d3plot and not d3plot_available():  # before the folder is touched
        raise UserInputError(f"d3plot output needs lasso-python: {D3PLOT_EXTRA}")
    # one run at a time in a folder: taken before anything in it is written, given
    # back after the summary (solver.run_lock)
    with RunLock(out) as lock:
        if resume is None:  # a restart continues the folder's run
            prepare_out_dir(out, options.overwrite, options.inputs)
        end_time = options.end_time if options.end_time is not None else model.controls.end_time
        if options.erode is not None:
            plan.erode = bool(options.erode)
        state = init_state(model, plan)
        outputs = RunOutputs(out, model, plan, end_time, vtk=options.vtk,
                             resume=resume[2]["outputs"] if resume else None,
                             thresholds=options.quality, d3plot=options.d3plot)
        extra: dict = {"restart_files": [], "unsupported_keywords": unsupported_entries(model),
                       "threads": n_threads, "_wall0": wall0, "_wall_before": 0.0}
        if resume is None:
            outputs.log(f"hollowbody explicit run: {model.n_nodes} nodes, "
                        f"{plan.element_counts()} ; end time {end_time:g} ms; erosion "
                        f"{'on' if plan.erode else 'off'}")
            for line in unsupported_lines(model):
                outputs.log(line, logging.WARNING)
            if outputs.d3plot_note:
                outputs.log(outputs.d3plot_note)
            for w in caught:
                outputs.log(str(w.message), logging.WARNING)
            for rt in plan.elements:
                for w in getattr(rt, "warnings", []) or []:
                    outputs.log(f"part {rt.pid}: {w}", logging.WARNING)
            if plan.ties is not None:  # [tied] set-up messages (hollowbody.contact.tied)
                plan.ties.log(lambda lvl, msg: outputs.log(msg, getattr(logging, lvl.upper())))
        if lock.stale:
            outputs.log(lock.stale, logging.WARNING)
        outputs.log(f"numba threads: {n_threads} ({threads_why})")
        status, reason, where = NORMAL, f"end time {end_time:g} ms reached", {}
        complete = True  # the State is that of a whole cycle (a dump of it can be resumed)
        progress = Progress(end_time, quiet=options.quiet, label=options.label,
                            interval=options.progress_interval, log=outputs.log)
        watch = CompileWatch(on_first=lambda: progress.note(f"{COMPILE_NOTICE} ..."),
                             seconds=setup_compile.seconds, count=setup_compile.count)
        # the final restart file and the summary are written with the stop handler still on:
        # a Ctrl-C while they are written is kept as a request (RunResult.stop_requested)
        with _Stop() as stop:
            with th.using(n_threads), watch:
                try:
                    with progress:
                        progress.attach(outputs.logger)
                        if resume is None:
                            _start(model, plan, state, outputs)
                        else:
                            _resume(model, plan, state, outputs, resume, end_time, extra)
                        if watch.compiled:
                            progress.note(f"{COMPILE_NOTICE}: {watch.seconds:.1f} s")
                        progress.begin(state.t)
                        if policy != "passive" and n_threads > 1:  # spinning: watched
                            extra["_guard"] = ContentionGuard(n_threads)
                        _loop(model, plan, state, outputs, progress, stop, end_time, dumps,
                              extra)
                except Termination as term:
                    status, reason, where = term.status, term.reason, term.where
                except KeyboardInterrupt:
                    complete = False
                    status, reason = INTERRUPT, f"interrupted by the user at t={state.t:.6g} ms"
            extra["compile_seconds"] = round(watch.seconds, 3)
            if (status != NORMAL or dumps.at_end) and state.cycle > 0:
                _final_dump(model, state, outputs, extra, complete, dumps)
            wall = time.perf_counter() - wall0
            extra["wall_seconds_total"] = round(_wall_total(extra), 3)
            summary = outputs.finish(state, status, reason, where, wall,
                                     {k: v for k, v in extra.items() if not k.startswith("_")})
            requested = stop.requested
        return RunResult(status, reason, state.t, state.cycle, summary, out, requested)


def _step_setter(state: State) -> str:
    """What set ``state.dt_next``: a contact's kinematic limit or an element."""
    if state.dt_contact:
        return f"contact {state.dt_contact} (a node closing on it fast: its kinematic limit)"
    elem, pid = state.dt_crit_elem
    return f"element {elem} (part {pid})"


def _start(model, plan, state: State, outputs: RunOutputs) -> None:  # noqa: ANN001
    start(model, plan, state)
    state.monitors = Monitors(dt_initial=state.dt0)
    state.e0 = kinetic_energy(plan, state)
    outputs.log(f"initial time step {state.dt0:.4e} ms (set by {_step_setter(state)}); "
                f"initial kinetic energy {state.e0:.6g} J")
    ms = state.mass_scaling
    if model.controls.dt2ms > 0.0:
        outputs.log("DT2MS > 0 (mass scaling of every element to one step) runs as "
                    "DT2MS < 0: only elements below the target get mass", logging.WARNING)
    if ms.target > 0.0:
        outputs.log(f"mass scaling (DT2MS): elements keep a step >= {ms.target:.4e} ms "
                    f"(run step >= {plan.tssfac * ms.target:.4e} ms); "
                    f"{ms.total_added:.4g} kg added at t=0")
    outputs.record(state, force=True)


def _resume(model, plan, state: State, outputs: RunOutputs, resume: tuple,  # noqa: ANN001
            end_time: float, extra: dict) -> None:
    path, header, payload = resume
    restore(state, payload["state"])
    if header.get("format", 0) < 3:
        # contact lists of an older format: cut for the Euclidean re-sort bound
        for obj in state.parts.values():
            if hasattr(obj, "expire_lists"):  # the contacts
                obj.expire_lists()
    prior = payload.get("restart_files", [])  # those still in the folder
    extra["restart_files"] = [f for f in prior if (outputs.out / f["file"]).is_file()]
    extra["resumed_from"] = {"file": path.name, "time_ms": header["time_ms"],
                             "cycle": header["cycle"]}
    extra["resumed"] = list(payload.get("resumed", [])) + [extra["resumed_from"]]
    extra["_wall_before"] = float(payload.get("wall_seconds", 0.0))
    outputs.log(f"resumed from restart file {path.name} at t={state.t:.6g} ms, cycle "
                f"{state.cycle}; end time {end_time:g} ms; erosion "
                f"{'on' if plan.erode else 'off'}")


def _loop(model, plan, state: State, outputs: RunOutputs, progress: Progress,  # noqa: ANN001
          stop: _Stop, end_time: float, dumps: DumpPolicy, extra: dict) -> None:
    dtmin = model.controls.dtmin
    while state.t < end_time * (1.0 - 1e-12):
        chosen = state.dt_next  # the stable step; the last one may be cut to end_time
        dt = min(chosen, end_time - state.t) if end_time > state.t else 0.0
        smallest = min(state.dt_min, chosen)  # a cut step is not a stability step
        try:
            step(model, plan, state, dt)
        finally:
            state.dt_min = smallest
            _drain(state, outputs)
        running = state.t < end_time * (1.0 - 1e-12)
        if running and not np.isfinite(state.dt_next):
            raise Termination(ERROR, f"no deformable element left at t={state.t:.6g} ms "
                              f"({state.n_eroded} eroded)")
        if running and not state.dt_next > 0.0:
            elem, pid = state.dt_crit_elem
            raise Termination(ERROR, f"time step collapsed to zero at t={state.t:.6g} ms "
                              f"(element {elem}, part {pid})", element=elem, part=pid)
        if dtmin > 0.0 and not plan.erode and state.dt_stable < dtmin * state.dt0:
            elem, pid = state.dt_crit_elem
            raise Termination(ERROR, f"time step {state.dt_stable:.4e} ms below DTMIN "
                              f"({dtmin:g} x initial) set by {_step_setter(state)} "
                              f"at t={state.t:.6g} ms", element=elem, part=pid)
        outputs.record(state)
        progress.update(state.t, state.cycle, dt)
        if "_guard" in extra:
            _watch_threads(extra, state, progress)
        if running and dumps.active and dumps.due(state.cycle):
            _dump(model, state, outputs, extra, dumps)
        if stop.requested is not None and running:
            raise Termination(INTERRUPT, f"interrupted by the user ({stop.requested}) at "
                              f"t={state.t:.6g} ms")


def _watch_threads(extra: dict, state: State, progress: Progress) -> None:
    """One thread while the run's threads keep waiting for cores, all of them again
    when cores are free (:class:`~hollowbody.solver.contention.ContentionGuard`): each
    kept change said in the log and listed in ``summary.json`` (``thread_changes``)."""
    guard = extra["_guard"]
    change = guard.check()
    if change is None:
        return
    n, share = change
    extra.setdefault("thread_changes", []).append(
        {"time_ms": round(state.t, 6), "cycle": state.cycle, "threads": n,
         "waiting_share": round(share, 3)})
    if n == 1:
        progress.note(f"threads: {guard.threads} -> 1 at t={state.t:.6g} ms (cycle "
                      f"{state.cycle}): the run's threads waited {100.0 * share:.0f} % of "
                      "their time for a core held by other processes")
    else:
        progress.note(f"threads: 1 -> {n} at t={state.t:.6g} ms (cycle {state.cycle}): "
                      f"cores free again (the threads waited {100.0 * share:.0f} % of "
                      "their time)")


def _wall_total(extra: dict) -> float:
    """Wall seconds of the run so far: this process's share plus, for a resumed run,
    the earlier processes' up to the restart file it resumed from (the time they spent
    after it was computed again)."""
    return extra["_wall_before"] + time.perf_counter() - extra["_wall0"]


def _drain(state: State, outputs: RunOutputs) -> None:
    for level, message in state.events:
        outputs.log(message, getattr(logging, level.upper()))
    state.events.clear()


def _dump(model, state: State, outputs: RunOutputs, extra: dict,  # noqa: ANN001
          dumps: DumpPolicy) -> None:
    """Write the next restart file of the run folder (then delete the older ones
    that ``dumps`` does not keep)."""
    path = rs.next_dump_path(outputs.out)
    try:
        snap = snapshot(state)
    except TypeError as exc:  # a runtime that cannot save its state
        outputs.log(f"no restart file written: {exc}", logging.WARNING)
        return
    kept = dumps.kept_after(outputs.out, path.name)
    files = [f for f in [*extra["restart_files"], {"file": path.name, "time_ms": state.t,
                                                   "cycle": state.cycle}]
             if kept is None or f["file"] in kept]
    payload = {"state": snap, "outputs": outputs.position(), "restart_files": files,
               "resumed": list(extra.get("resumed", [])),
               "wall_seconds": _wall_total(extra)}
    rs.write_dump(path, model, payload, state.t, state.cycle)
    dumps.written()
    gone = set(dumps.prune(outputs.out))
    extra["restart_files"] = files
    outputs.log(f"restart file {path.name} written at t={state.t:.6g} ms, cycle {state.cycle}"
                + (f" ({', '.join(sorted(gone))} deleted)" if gone else ""))


def _final_dump(model, state: State, outputs: RunOutputs, extra: dict,  # noqa: ANN001
                complete: bool, dumps: DumpPolicy) -> None:
    """The restart file of an interrupted or failed run, or of one that ended normally
    with ``dumps.at_end`` (when its State can be resumed)."""
    if not complete:
        outputs.log("no restart file written: the run was stopped inside a cycle",
                    logging.WARNING)
        return
    if not (np.all(np.isfinite(state.x)) and np.all(np.isfinite(state.v))):
        outputs.log("no restart file written: the state holds non-finite numbers",
                    logging.WARNING)
        return
    try:  # before the final row is written: a resumed run continues without it
        _dump(model, state, outputs, extra, dumps)
    except OSError as exc:
        outputs.log(f"could not write the restart file: {exc}", logging.ERROR)
