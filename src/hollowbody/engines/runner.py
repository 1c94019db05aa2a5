"""Run a deck on OpenRadioss or LS-DYNA and write hollowbody's output files from its results.

:func:`plan_run` prepares everything a run needs (the deck the engine reads,
the command lines, the OpenRadioss engine file) and :func:`execute` runs it:
each command in the output folder with its environment, its output in a log
file of that folder; then the engine's files are read back (``glstat.csv``,
``rcforc.csv``, ``nodout.csv``, ``summary.json``; VTK states from OpenRadioss's
animation files). ``hollowbody run --engine ... --dry-run`` prints the plan
(:meth:`Prepared.describe`) without running anything; without ``--dry-run`` a
missing engine is an EngineNotFound (exit code 2).
"""

from __future__ import annotations

import glob
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.engines.commands import (
    RunPlan,
    lsdyna_memory,
    lsdyna_plan,
    openradioss_plan,
    radioss_root,
    run_env,
)
from hollowbody.engines.discovery import (
    EngineNotFound,
    LsDynaInstall,
    OpenRadiossInstall,
    find_lsdyna,
    find_openradioss,
    platform_arch,
)
from hollowbody.errors import UserInputError


@dataclass
class Prepared:
    """A run ready to go: its plan, the engine file (OpenRadioss), what was changed in
    the deck, and the requested end time (ms)."""

    plan: RunPlan
    engine_file: tuple[str, str] | None = None  # (name, text)
    notes: list[str] = field(default_factory=list)
    end_time_ms: float | None = None
    found: bool = True

    def describe(self) -> str:
        text = self.plan.describe()
        extra = [f"note: {n}" for n in self.notes]
        if self.engine_file is not None:
            name, body = self.engine_file
            extra.append(f"[engine file] {self.plan.workdir / name} (merged after the starter "
                         "with the one it writes; these options replace the starter's):")
            extra += ["  " + line for line in body.splitlines()]
        return "\n".join([text, *extra])


def _placeholder_radioss(path: str | Path | None) -> OpenRadiossInstall:
    """An installation where none was found, for --dry-run: executables by name under
    ``$OPENRADIOSS_PATH/exec``."""
    arch = platform_arch()
    root = Path(path) if path is not None else Path("$OPENRADIOSS_PATH")
    ex = root / "exec"
    return OpenRadiossInstall(root=root, arch=arch, starter=ex / f"starter_{arch}",
                              engine=ex / f"engine_{arch}", engine_mpi=ex / f"engine_{arch}_ompi",
                              th_to_csv=ex / f"th_to_csv_{arch}",
                              anim_to_vtk=ex / f"anim_to_vtk_{arch}", mpirun="mpirun",
                              env={"OPENRADIOSS_PATH": str(root),
                                   "RAD_CFG_PATH": str(root / "hm_cfg_files"),
                                   "OMP_STACKSIZE": "400m"})


def model_size(deck: Path) -> tuple[int, int, object]:
    """(nodes, elements, Model) of a deck (DeckError on bad input)."""
    import warnings

    from hollowbody.build import build_model
    from hollowbody.io.keyword import UnsupportedKeywordWarning, read_deck

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnsupportedKeywordWarning)
        model = build_model(read_deck(deck))
    elements = 0
    for groups in (model.solid_groups, model.shell_groups, model.beam_groups,
                   model.discrete_groups):
        for g in groups:
            conn = getattr(g, "conn", None)
            elements += int(conn.shape[0]) if conn is not None else 0
    return model.n_nodes, elements, model


def initial_step(model) -> float:  # noqa: ANN001 - Model
    """hollowbody's initial time step (ms) of ``model``: what LS-DYNA's DTMIN is a
    fraction of, for the OpenRadioss engine file's absolute minimum step."""
    from hollowbody.solver.setup import assemble
    from hollowbody.solver.state import init_state
    from hollowbody.solver.step import start

    plan = assemble(model)
    state = init_state(model, plan)
    start(model, plan, state)
    return float(state.dt0)


def plan_run(engine: str, deck: Path, out: Path, np_: int = 1, threads: int = 1,
             engine_path: str | Path | None = None, dry_run: bool = False,
             memory: tuple[int, int] | None = None, write: bool = True,
             end_time: float | None = None) -> Prepared:
    """Prepare the run of ``deck`` on ``engine`` (``openradioss`` or ``lsdyna``) in
    folder ``out``: find the engine (EngineNotFound unless ``dry_run``), write the deck
    it reads into ``out`` (``write``), build the command lines. end_time (ms):
    instead of the deck's ENDTIM."""
    from hollowbody.engines import radioss_deck
    from hollowbody.io.keyword import read_deck

    deck = Path(deck)
    out = Path(out)
    if not deck.is_file():
        raise UserInputError(f"{deck}: no such deck")
    found = True
    notes: list[str] = []
    engine_deck = out / (deck.stem + ".k")
    if engine_deck.resolve() == deck.resolve():
        raise UserInputError(f"{out}: the deck would be overwritten by the copy the engine "
                             "reads; choose another output folder")
    if engine == "openradioss":
        try:
            install = find_openradioss(engine_path)
        except EngineNotFound as exc:
            if not dry_run:
                raise
            install, found = _placeholder_radioss(engine_path), False
            notes.append(f"not found here: {exc}")
        parsed = read_deck(deck)
        contact_notes = radioss_deck.check_for_openradioss(parsed)
        _, _, model = model_size(deck)
        dt0 = initial_step(model) if model.controls.dtmin > 0.0 else None
        settings = radioss_deck.engine_settings(parsed, dt0)
        if end_time is not None:
            settings = radioss_deck.EngineSettings(**{**settings.__dict__,
                                                      "end_time": float(end_time)})
        starter_in = radioss_deck.starter_input(engine_deck, out)
        if write:
            out.mkdir(parents=True, exist_ok=True)
            starter_in, changes = radioss_deck.rewrite_for_openradioss(deck, engine_deck)
            notes += changes
        else:
            notes += contact_notes
        root = radioss_root(starter_in)
        name = f"{root}_0001.rad"
        plan = openradioss_plan(install, starter_in, out, np_, threads, engine_file=name)
        text = radioss_deck.engine_file_text(root, settings, deck.name)
        if settings.dtmin_abs > 0.0:
            notes.append(f"DTMIN {model.controls.dtmin:g} x initial step {dt0:.6g} ms "
                         f"(hollowbody's estimate) = {settings.dtmin_abs:.6g} ms: "
                         "/DT/BRICK/STOP and /DT/SHELL/STOP")
        return Prepared(plan, (name, text), notes, settings.end_time, found)
    if engine == "lsdyna":
        try:
            ls = find_lsdyna(engine_path, mpp=True if np_ > 1 else None)
        except EngineNotFound as exc:
            if not dry_run:
                raise
            ls, found = LsDynaInstall(Path("$LSDYNA"), mpp=np_ > 1, mpirun="mpirun"), False
            notes.append(f"not found here: {exc}")
        nodes, elements, model = model_size(deck)
        if memory is None:
            memory = lsdyna_memory(nodes, elements, np_)
            notes.append(f"memory from the model size: {nodes} nodes, {elements} elements "
                         "(docs/engines.md)")
        end = model.controls.end_time if end_time is None else float(end_time)
        if write:
            from hollowbody.io.keyword import ControlTermination, write_deck

            out.mkdir(parents=True, exist_ok=True)
            parsed = read_deck(deck)
            if end_time is not None:
                for item in parsed.of_type(ControlTermination) or \
                        [parsed.add(ControlTermination())]:
                    item.endtim = end
            write_deck(parsed, engine_deck, flatten=True)
        if end_time is not None:
            notes.append(f"*CONTROL_TERMINATION ENDTIM set to {end:g} ms (--end-time)")
        plan = lsdyna_plan(ls, engine_deck, out, np_, threads, memory)
        return Prepared(plan, None, notes, end, found)
    raise UserInputError(f"unknown engine {engine!r}: choose hollowbody, openradioss or lsdyna")


@dataclass(frozen=True)
class ExternalEngine:
    """An installed engine that runs a scenario's deck instead of hollowbody's own.

    name: ``openradioss`` or ``lsdyna``; np: MPI ranks; threads: threads per rank;
    path: the engine's executable or folder (None: found on the PATH or through
    OPENRADIOSS_PATH / LSDYNA). Plain data, so calibration workers can receive it.
    """

    name: str
    np: int = 1
    threads: int = 1
    path: str | None = None

    def __post_init__(self) -> None:
        if self.name not in ("openradioss", "lsdyna"):
            raise UserInputError(f"unknown engine {self.name!r}: choose openradioss or lsdyna "
                                 "(hollowbody's own engine needs no ExternalEngine)")
        if self.np < 1 or self.threads < 1:
            raise UserInputError(f"--np and --threads must be at least 1 (got {self.np}, "
                                 f"{self.threads})")

    def plan(self, deck: Path, out: Path, end_time: float | None = None,
             dry_run: bool = False) -> Prepared:
        """:func:`plan_run` of ``deck`` in ``out`` (nothing written when ``dry_run``)."""
        return plan_run(self.name, deck, out, np_=self.np, threads=self.threads,
                        engine_path=self.path, dry_run=dry_run, write=not dry_run,
                        end_time=end_time)

    def run(self, deck: Path, out: Path, end_time: float | None = None,
            quiet: bool = True) -> dict:
        """Run ``deck`` in ``out`` (EngineNotFound when it is not installed); the run's
        ``summary.json`` dict, with ``glstat/rcforc/nodout.csv`` written next to it."""
        return execute(self.plan(deck, out, end_time), quiet=quiet)


def _run(cmd, env_base=None, quiet: bool = True, listing: Path | None = None) -> int:  # noqa: ANN001
    """Run one command (once, or once per file matching ``cmd.each``); returns the
    last non-zero exit code (0 when all succeeded)."""
    items = [None]
    if cmd.each:
        items = sorted(Path(p).name for p in glob.glob(str(cmd.cwd / cmd.each))
                       if not p.endswith((".csv", ".vtk")))
    code = 0
    for item in items:
        stdout = None
        if cmd.stdout:
            name = cmd.stdout.replace("{}", item) if item is not None else cmd.stdout
            stdout = open(cmd.cwd / name, "w")
        try:
            proc = subprocess.Popen(cmd.argv(item), cwd=cmd.cwd, env=run_env(cmd, env_base),
                                    stdout=stdout or subprocess.DEVNULL,
                                    stderr=subprocess.STDOUT)
            shown = ""
            while proc.poll() is None:
                time.sleep(1.0)
                if not quiet and listing is not None:
                    shown = _progress(listing, shown)
            code = proc.returncode or code
        finally:
            if stdout is not None:
                stdout.close()
    return code


def _progress(listing: Path, shown: str) -> str:
    """Print the listing's newest cycle row when it changed."""
    from hollowbody.engines.radioss_listing import read_listing

    lst = read_listing(listing)
    if lst.cycles is None:
        return shown
    line = f"cycle {lst.cycles}, t = {lst.end_time_ms:.6g} ms"
    if line != shown:
        print(line, file=sys.stderr)
    return line


def execute(prep: Prepared, quiet: bool = True) -> dict:
    """Run a prepared plan and write hollowbody's files from the engine's; returns the
    summary."""
    plan = prep.plan
    out = plan.workdir
    t0 = time.perf_counter()
    codes: dict[str, int] = {}
    for cmd in plan.commands:
        if cmd.step == "engine" and prep.engine_file is not None:
            from hollowbody.engines.radioss_deck import merge_engine_files

            name, text = prep.engine_file
            generated = _starter_engine_file(out, name)
            if generated is not None:  # the starter's translation of the deck's controls
                text = merge_engine_files(generated.read_text(errors="replace"), text)
            (out / name).write_text(text)
        listing = out / f"{radioss_root(plan.deck)}_0001.out" if cmd.step == "engine" else None
        codes[cmd.step] = _run(cmd, quiet=quiet, listing=listing)
        if cmd.step == "starter" and codes[cmd.step] != 0:
            break  # no engine run without the starter's restart files
    wall = time.perf_counter() - t0
    commands = [c.argv() for c in plan.commands]
    if plan.engine == "openradioss":
        return _collect_radioss(prep, wall, codes, commands)
    return _collect_lsdyna(prep, wall, codes, commands)


def _with_th_energies(g: np.ndarray, extra: dict[str, np.ndarray]) -> list[list[float]]:
    """glstat rows (n, len(GLSTAT_ORDER)) of the listing with the time history's
    hourglass and contact energies: the total is then hollowbody's (kinetic + internal
    + hourglass + contact; OpenRadioss's listing counts neither in its internal
    energy) and the ratio total / (initial total + external work) is recomputed.
    Rows where either energy is unknown (NaN) keep the listing's total and ratio."""
    from hollowbody.engines.lsdyna_ascii import GLSTAT_ORDER

    col = GLSTAT_ORDER.index
    for name, v in extra.items():
        g[:, col(name)] = v
    hg, ce = g[:, col("hourglass [J]")], g[:, col("contact [J]")]
    ok = np.isfinite(hg) & np.isfinite(ce)
    if ok.any():
        total = g[:, col("kinetic [J]")] + g[:, col("internal [J]")] + hg + ce
        e0 = total[np.argmax(ok)]
        denom = e0 + g[:, col("external_work [J]")]
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(denom != 0.0, total / denom, np.nan)
        g[ok, col("total [J]")] = total[ok]
        g[ok, col("energy_ratio")] = ratio[ok]
    return g.tolist()


def _starter_engine_file(out: Path, name: str) -> Path | None:
    """The engine file the starter wrote: ``name``, or (a keyword deck included in a
    native starter file) the other ``*_0001.rad`` of the folder; None when none."""
    if (out / name).is_file():
        return out / name
    others = sorted(p for p in out.glob("*_0001.rad") if p.name != name)
    return others[0] if others else None


def _collect_radioss(prep: Prepared, wall: float, codes: dict, commands: list) -> dict:
    from hollowbody.engines.lsdyna_status import ERROR, NORMAL, UNKNOWN
    from hollowbody.engines.radioss_listing import read_listing
    from hollowbody.engines.results import write_histories, write_summary

    out = prep.plan.workdir
    root = radioss_root(prep.plan.deck)
    lst = read_listing(out / f"{root}_0001.out", out / f"{root}_engine.log")
    status, reason = lst.status, lst.reason
    if codes.get("starter", 0) != 0:
        from hollowbody.engines.radioss_listing import starter_errors

        errs = starter_errors(out / f"{root}_0000.out")
        status, reason = ERROR, (f"the starter stopped (exit code {codes['starter']}); see "
                                 f"{root}_0000.out" + (": " + " | ".join(errs) if errs else ""))
    elif status == UNKNOWN and codes.get("engine", 0) != 0:
        status, reason = ERROR, f"the engine stopped (exit code {codes['engine']})"
    notes = list(prep.notes)
    rows: dict[str, list[list[float]]] = {"glstat": lst.rows}
    th = out / f"{root}T01.csv"
    if th.is_file():
        from hollowbody.engines.radioss_th import energies_at, histories

        rows.update(histories(th))
        if lst.rows:  # the listing's table lacks the hourglass and contact energies
            rows["glstat"] = _with_th_energies(np.array(lst.rows, dtype=float),
                                               energies_at(th, np.array(lst.rows)[:, 0]))
        notes.append(f"rcforc.csv and nodout.csv from the time history {th.name}")
    else:
        notes.append(f"no time history {th.name} (th_to_csv missing or the run stopped "
                     "early): no rcforc.csv nor nodout.csv")
    write_histories(out, rows)
    vtk = sorted(glob.glob(str(out / f"{root}A*.vtk")))
    if vtk:
        _write_pvd(out, [Path(v).name for v in vtk], prep)
    end = lst.end_time_ms
    if status == NORMAL and prep.end_time_ms is not None:
        end = prep.end_time_ms  # the listing's table stops at its last /PRINT cycle
    return write_summary(out, engine="openradioss", version=lst.version, status=status,
                         reason=reason, where=lst.where, end_time_ms=end,
                         requested_end_time_ms=prep.end_time_ms, cycles=lst.cycles,
                         wall_seconds=wall, glstat=rows["glstat"], commands=commands,
                         notes=notes)


def _write_pvd(out: Path, files: list[str], prep: Prepared) -> None:
    """states.pvd over the animation states converted to VTK (state k at k x the
    animation interval)."""
    from hollowbody.engines.radioss_deck import DEFAULT_STATE_COUNT

    end = prep.end_time_ms or 0.0
    dt = end / DEFAULT_STATE_COUNT if end else 1.0
    if prep.engine_file is not None:
        for line_a, line_b in zip(prep.engine_file[1].splitlines(),
                                  prep.engine_file[1].splitlines()[1:]):
            if line_a.strip() == "/ANIM/DT":
                dt = float(line_b.split()[1])
    rows = "\n".join(f'    <DataSet timestep="{k * dt:.9g}" file="{f}"/>'
                     for k, f in enumerate(files))
    (out / "states.pvd").write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        f"{rows}\n  </Collection>\n</VTKFile>\n")


def _collect_lsdyna(prep: Prepared, wall: float, codes: dict, commands: list) -> dict:
    from hollowbody.engines import lsdyna_binout
    from hollowbody.engines.lsdyna_ascii import read_ascii
    from hollowbody.engines.lsdyna_status import ERROR, UNKNOWN, read_termination
    from hollowbody.engines.results import write_histories, write_summary

    out = prep.plan.workdir
    term = read_termination(out)
    status, reason = term.status, term.reason
    if status == UNKNOWN and codes.get("lsdyna", 0) != 0:
        status, reason = ERROR, f"LS-DYNA stopped (exit code {codes['lsdyna']})"
    notes = list(prep.notes)
    rows = read_ascii(out)
    if glob.glob(str(out / "binout*")):
        if lsdyna_binout.available():
            rows = {**rows, **lsdyna_binout.read_binout(out)}
            notes.append("histories from binout")
        else:
            notes.append("binout not read: lasso-python is not installed "
                         "(pip install 'hollowbody[d3plot]')")
    write_histories(out, rows)
    glstat = rows.get("glstat", [])
    end = term.end_time_ms if term.end_time_ms is not None else (glstat[-1][0] if glstat
                                                                 else None)
    return write_summary(out, engine="lsdyna", version=term.version, status=status,
                         reason=reason, where=term.where, end_time_ms=end,
                         requested_end_time_ms=prep.end_time_ms, cycles=term.cycles,
                         wall_seconds=wall, glstat=glstat, commands=commands, notes=notes)
