"""Everything a run writes into its output folder.

- ``glstat.csv``  global energies and time step;
- ``rcforc.csv``  contact resultant forces per contact and side;
- ``nodout.csv``  displacement/velocity of *DATABASE_HISTORY_NODE nodes;
- ``rbdout.csv``  rigid-body displacement, velocity and resultant force;
- ``spcforc.csv`` total SPC reaction force;
- ``rwforc.csv``  rigid-wall forces (normal, tangential, components) per wall;
- ``matsum.csv``  kinetic, internal and hourglass energy per part;
- ``deforc.csv``  force, elongation and energy of each discrete element (PF = 0);
- ``jntforc.csv`` joint forces and moments, joint stiffness angles and moments;
- ``states.pvd`` + ``states_NNNN.vtu``  ParaView states (d3plot interval);
- ``d3plot`` (+ ``d3plot01``) the same states for LS-PrePost (optional extra lasso-python; when
  the deck has *DATABASE_BINARY_D3PLOT or the run asks for it), written at the end;
- ``messages.log`` the run log; ``summary.json`` how the run ended.

Histories are written at the deck's *DATABASE_<name> intervals, or at
``end_time / 500`` when the deck requests none; states at the
*DATABASE_BINARY_D3PLOT interval, or ``end_time / 20``. Every file is flushed
as it goes. :func:`prepare_out_dir` checks (and with ``overwrite`` clears) the
folder before a run writes into it, :func:`prepare_runs_dir` the folder of a
command that makes several runs.
"""

from __future__ import annotations

import json
import logging
import sys
from pathlib import Path

import numpy as np

from hollowbody.errors import UserInputError
from hollowbody.io.results.d3plot import EXTRA as D3PLOT_EXTRA
from hollowbody.io.results.d3plot import available as d3plot_available
from hollowbody.io.results.history import HistoryWriter
from hollowbody.io.results.vtk import VtkSeries, von_mises
from hollowbody.solver.d3plot_output import make_series, state_fields
from hollowbody.solver.energies import energies, node_velocity_full_step
from hollowbody.solver.energy_kernels import share_energy
from hollowbody.solver.joints import JointTerm
from hollowbody.solver.run_lock import check_free
from hollowbody.solver.step_control import StepControl
from hollowbody.solver.verdict import OK, Thresholds, assess, before_error, headline

DEFAULT_HISTORY_COUNT = 500
DEFAULT_STATE_COUNT = 20


class _Clock:
    """Fires when simulated time passes the next multiple of ``interval``."""

    def __init__(self, interval: float) -> None:
        self.interval = interval
        self.next = 0.0

    def due(self, t: float) -> bool:
        if self.interval <= 0.0 or t < self.next * (1.0 - 1e-9):
            return False
        self.next = (np.floor(t / self.interval + 1e-9) + 1.0) * self.interval
        return True


#: Files a run writes into its output folder (what ``overwrite`` deletes).
RUN_OUTPUTS = ("*.csv", "states*.vtu", "states*.pvd", "messages.log", "summary.json",
               "d3dump*", "force_displacement.*", "d3plot", "d3plot[0-9][0-9]")
#: Files that show a folder holds an earlier run.
EARLIER_RUN = ("summary.json", "messages.log", "glstat.csv", "states.pvd", "d3dump*")


def _earlier_run(out: Path) -> list[str]:
    """Names of the files that show ``out`` holds an earlier run (:data:`EARLIER_RUN`)."""
    return sorted({f.name for pat in EARLIER_RUN for f in out.glob(pat)})


def _existing_folder(out: Path, inputs: tuple[Path, ...]) -> set[Path] | None:
    """The resolved input paths when ``out`` is an existing folder, None when it does not
    exist yet; a file in its place is a UserInputError."""
    if out.exists() and not out.is_dir():
        raise UserInputError(f"{out} is a file, not an output folder")
    if not out.is_dir():
        return None
    return {Path(p).resolve() for p in inputs}


def prepare_out_dir(out: Path, overwrite: bool, inputs: tuple[Path, ...] = ()) -> None:
    """Check (and with ``overwrite`` clear) the output folder before a run writes to it.

    A folder holding an earlier run (:data:`EARLIER_RUN`) is refused with a
    UserInputError unless ``overwrite``, which deletes the earlier run's files
    (:data:`RUN_OUTPUTS`) first. An input file (``inputs``) is never deleted: one
    whose name is that of a run output is refused. A folder that a live run holds
    (:mod:`hollowbody.solver.run_lock`) is refused whatever ``overwrite`` says.
    """
    out = Path(out)
    keep = _existing_folder(out, inputs)
    if keep is None:
        return
    check_free(out)  # a run still going on there (solver.run_lock): touch nothing
    outputs = sorted({f for pat in RUN_OUTPUTS for f in out.glob(pat) if f.is_file()})
    clash = [f.name for f in outputs if f.resolve() in keep]
    if clash:
        raise UserInputError(f"{out}: the input file {clash[0]} has the name of a run output; "
                             "choose another output folder")
    earlier = _earlier_run(out)
    if earlier and not overwrite:
        raise UserInputError(f"{out} holds the outputs of an earlier run ({', '.join(earlier)}):"
                             " use --overwrite to replace them, --restart to resume that run, "
                             "or another output folder")
    if earlier:
        for f in outputs:
            f.unlink()


def prepare_runs_dir(out: Path, overwrite: bool, files: tuple[str, ...],
                     run_dirs: tuple[str, ...], run_files: tuple[str, ...] = (),
                     inputs: tuple[Path, ...] = ()) -> None:
    """Check (and with ``overwrite`` clear) the folder of a command that makes several
    runs (``hollowbody study``, ``hollowbody bending``) before it writes to it.

    files: glob patterns of the command's own files in ``out`` (tables, plots);
    run_dirs: glob patterns of its run folders under ``out``; run_files: glob
    patterns of the files the command writes into a run folder besides the
    run's outputs (its deck). The folder holds an earlier run when one of
    ``files`` exists or a run folder holds an earlier run (:data:`EARLIER_RUN`);
    it is refused with a UserInputError unless ``overwrite``, which deletes
    those files, the run folders' outputs (:data:`RUN_OUTPUTS`) and their
    ``run_files`` first. Other files are kept; an input file (``inputs``) is
    never deleted: one that would be is refused.
    """
    out = Path(out)
    keep = _existing_folder(out, inputs)
    if keep is None:
        return
    for d in sorted({d for pat in run_dirs for d in out.glob(pat) if d.is_dir()}):
        check_free(d)  # a run still going on in one of them: touch nothing
    own = sorted({f for pat in files for f in out.glob(pat) if f.is_file()})
    runs = sorted({d for pat in run_dirs for d in out.glob(pat)
                   if d.is_dir() and _earlier_run(d)})
    extra = sorted({f for d in runs for pat in run_files for f in d.glob(pat) if f.is_file()})
    for f in own + extra:
        if f.resolve() in keep:
            raise UserInputError(f"{out}: the input file {f.name} has the name of an output; "
                                 "choose another output folder")
    earlier = [f.name for f in own] + [f"{d.relative_to(out)}/" for d in runs]
    if earlier and not overwrite:
        shown = ", ".join(earlier[:6]) + (", ..." if len(earlier) > 6 else "")
        raise UserInputError(f"{out} holds the outputs of an earlier run ({shown}): use "
                             "--overwrite to replace them, or another output folder")
    for d in runs:
        prepare_out_dir(d, True, inputs)
    for f in own + extra:
        f.unlink()


#: Columns (with units) of glstat.csv, rcforc.csv and nodout.csv (also what the results
#: of an external engine are converted to: hollowbody.engines.results).
GLSTAT_COLUMNS = ("time [ms]", "cycle", "dt [ms]", "kinetic [J]", "internal [J]",
                  "hourglass [J]", "contact [J]", "external_work [J]", "total [J]",
                  "energy_ratio", "added_mass [kg]")
RCFORC_COLUMNS = ("time [ms]", "contact", "slave_fx [kN]", "slave_fy [kN]", "slave_fz [kN]",
                  "master_fx [kN]", "master_fy [kN]", "master_fz [kN]")
NODOUT_COLUMNS = ("time [ms]", "node", "ux [mm]", "uy [mm]", "uz [mm]", "vx [mm/ms]",
                  "vy [mm/ms]", "vz [mm/ms]")

HISTORIES = ("glstat", "rcforc", "nodout", "rbdout", "spcforc", "matsum", "rwforc",
             "deforc", "jntforc")


class RunOutputs:
    """Writers of one run (see the module docstring).

    Observers of the run: :meth:`record` receives the State after each cycle.
    resume: :meth:`position` saved in a restart file; the files are then cut
    at that point and written on (a resumed run) instead of started anew.
    """

    def __init__(self, out: Path, model, asm, end_time: float, vtk: bool = True,
                 resume: dict | None = None, thresholds: Thresholds | None = None,
                 d3plot: bool | None = None) -> None:
        self.out = Path(out)
        self.thresholds = thresholds or Thresholds()
        self.model = model
        self.asm = asm
        self.end_time = end_time
        self.logger = _make_logger(self.out / "messages.log", append=resume is not None)
        pos = (resume or {}).get("files", {})
        req = model.output.intervals
        default = end_time / DEFAULT_HISTORY_COUNT if end_time > 0 else 0.0
        self.clocks = {name: _Clock(req.get(name) or default)
                       for name in ("glstat", "rcforc", "nodout", "spcforc", "matsum", "rbdout",
                                    "rwforc", "deforc", "jntforc")}
        self.state_clock = _Clock(model.output.d3plot_dt or
                                  (end_time / DEFAULT_STATE_COUNT if end_time > 0 else 0.0))
        self.vtk = VtkSeries(self.out, "states") if vtk else None
        self.d3plot = None
        self.d3plot_note = ""
        if d3plot or (d3plot is None and model.output.d3plot_dt > 0.0):
            if d3plot_available():
                self.d3plot = make_series(self.out, model, asm)
                if resume is not None:
                    self.d3plot.resume(int(resume.get("d3plot_states", 0)))
            elif d3plot:
                raise UserInputError(f"d3plot output needs lasso-python: {D3PLOT_EXTRA}")
            else:
                self.d3plot_note = ("*DATABASE_BINARY_D3PLOT: no d3plot written (lasso-python "
                                    f"is not installed: {D3PLOT_EXTRA}); ParaView states only")
        self.glstat = HistoryWriter(self.out / "glstat.csv", list(GLSTAT_COLUMNS),
                                    pos.get("glstat"))
        self.rcforc = HistoryWriter(self.out / "rcforc.csv", list(RCFORC_COLUMNS),
                                    pos.get("rcforc"))
        self.nodout = HistoryWriter(self.out / "nodout.csv", list(NODOUT_COLUMNS),
                                    pos.get("nodout"))
        self.rbdout = HistoryWriter(self.out / "rbdout.csv", [
            "time [ms]", "part", "ux [mm]", "uy [mm]", "uz [mm]", "vx [mm/ms]", "vy [mm/ms]",
            "vz [mm/ms]", "fx [kN]", "fy [kN]", "fz [kN]"], pos.get("rbdout"))
        self.spcforc = HistoryWriter(self.out / "spcforc.csv", [
            "time [ms]", "fx [kN]", "fy [kN]", "fz [kN]"], pos.get("spcforc"))
        self.matsum = HistoryWriter(self.out / "matsum.csv", [
            "time [ms]", "part", "kinetic [J]", "internal [J]", "hourglass [J]"],
            pos.get("matsum"))
        self.rwforc = HistoryWriter(self.out / "rwforc.csv", [
            "time [ms]", "wall", "normal [kN]", "tangential [kN]", "fx [kN]", "fy [kN]",
            "fz [kN]"], pos.get("rwforc"))
        self.deforc = HistoryWriter(self.out / "deforc.csv", [
            "time [ms]", "element", "force [kN|kN*mm]", "elongation [mm|rad]", "energy [J]"],
            pos.get("deforc"))
        self.joint_term = next((t for t in asm.terms if isinstance(t, JointTerm)), None)
        self.jntforc = HistoryWriter(self.out / "jntforc.csv", list(JointTerm.JNTFORC_COLUMNS),
                                     pos.get("jntforc"))
        self.last_energies: dict[str, float] = {}
        #: the glstat record before the last one, with its time (an error termination's
        #: last record can be the collapse itself; the summary then keeps this one too)
        self.prev_energies: dict[str, float] = {}
        self._energy_time: float | None = 0.0  # time of last_energies (ms)
        self._last_forced: tuple[int, float] | None = None
        #: (cycle, time) of each output's last row: a forced write at the end of a run
        #: does not write a row again that its interval wrote at the same state
        self._rows_at: dict[str, tuple[int, float]] = {}
        if resume is not None:
            for name, nxt in resume["clocks"].items():
                self.clocks[name].next = nxt
            self.state_clock.next = resume["state_clock"]
            if self.vtk is not None:
                self.vtk.entries = [tuple(e) for e in resume["vtk_entries"]]
            self.last_energies = dict(resume["last_energies"])
            self.prev_energies = dict(resume.get("prev_energies", {}))
            # a dump written before the time was kept: no earlier record until two new ones
            self._energy_time = resume.get("energy_time")
            forced = resume["last_forced"]
            self._last_forced = tuple(forced) if forced is not None else None
            self._rows_at = {k: tuple(v) for k, v in resume.get("rows_at", {}).items()}

    def position(self) -> dict:
        """Where every output stands (file offsets, clocks, states written): saved in
        restart files so a resumed run continues the same files."""
        return {"files": {name: getattr(self, name).position() for name in HISTORIES},
                "clocks": {name: c.next for name, c in self.clocks.items()},
                "state_clock": self.state_clock.next,
                "vtk_entries": list(self.vtk.entries) if self.vtk is not None else [],
                "d3plot_states": len(self.d3plot.states) if self.d3plot is not None else 0,
                "last_energies": dict(self.last_energies),
                "prev_energies": dict(self.prev_energies),
                "energy_time": self._energy_time,
                "last_forced": self._last_forced,
                "rows_at": dict(self._rows_at)}

    # -- logging ---------------------------------------------------------------
    def log(self, message: str, level: int = logging.INFO) -> None:
        self.logger.log(level, message)

    # -- per cycle ----------------------------------------------------------------
    def record(self, state, force: bool = False) -> None:  # noqa: ANN001 - State
        """Write what is due at the State's time (everything when ``force``)."""
        if force and self._last_forced == (state.cycle, state.t):
            return  # already written at this very state (end of run after a forced row)
        if force:
            self._last_forced = (state.cycle, state.t)
        self._contact_events(state)
        t = state.t
        key = (state.cycle, t)
        if self._due("glstat", key, force):
            e = energies(self.asm, state, self._full_step_v(state))
            self.prev_energies = ({} if self._energy_time is None else
                                  {**self.last_energies, "time_ms": self._energy_time})
            self.last_energies, self._energy_time = e, t
            self.glstat.write([t, state.cycle, state.dt_next, e["kinetic"], e["internal"],
                               e["hourglass"], e["contact"], e["external_work"], e["total"],
                               e["energy_ratio"], e["added_mass"]])
            if state.monitors is not None and state.cycle > 0:
                part_e, part_hg = self._part_energies(state)
                elem, pid = state.dt_crit_elem
                for w in state.monitors.check(t, e["energy_ratio"], e["internal"],
                                              e["hourglass"], part_e, part_hg, state.dt_next,
                                              elem, pid, total=e["total"]):
                    self.log(w["message"], logging.WARNING)
        if self._due("rcforc", key, force):
            for c in self.asm.contacts:
                self.rcforc.write([t, c.cid, *c.slave_force, *c.master_force])
        if self._due("nodout", key, force):
            hist = self.model.output.history_nodes
            if hist.size:
                u = state.x[hist] - self.asm.node_x0[hist]
                for k, i in enumerate(hist):
                    self.nodout.write([t, int(self.model.node_ids[i]), *u[k], *state.v[i]])
        if self._due("rbdout", key, force):
            for b in self.asm.bodies:
                if getattr(b, "iprt", 0) == 2:  # a nodal rigid body's IPRT = 2: not written
                    continue
                self.rbdout.write([t, b.pid, *(b.xc - b.xc0), *b.vel, *b.force])
        if self._due("spcforc", key, force):
            self.spcforc.write([t, *self.asm.constraints.reactions(state.f)])
        if self._due("rwforc", key, force):
            for w in (tm for tm in getattr(self.asm, "terms", ()) if hasattr(tm, "rwid")):
                self.rwforc.write([t, w.rwid, w.normal_force(), w.tangential_force(), *w.force])
        if self._due("matsum", key, force):
            self._write_matsum(state)
        if self._due("deforc", key, force):
            for rt in self.asm.elements:
                if getattr(rt, "family", "") == "discrete":
                    for i in np.nonzero(rt.print_flag == 0)[0]:
                        self.deforc.write([t, int(rt.elem_ids[i]), rt.force[i], rt.defl[i],
                                           rt.energy[i]])
        if self._due("jntforc", key, force) and self.joint_term is not None:
            for row in self.joint_term.jntforc_rows(t, state.x):
                self.jntforc.write(row)
        if (self.vtk is not None or self.d3plot is not None) and \
                self._due("states", key, force):
            self.write_state(state)

    def _due(self, name: str, key: tuple[int, float], force: bool) -> bool:
        """Output ``name`` (a history or ``states``) writes a row at ``key`` = (cycle,
        time): its interval is due, or ``force`` and it has no row there yet."""
        clock = self.state_clock if name == "states" else self.clocks[name]
        if clock.due(key[1]) or (force and self._rows_at.get(name) != key):
            self._rows_at[name] = key
            return True
        return False

    def _contact_events(self, state) -> None:  # noqa: ANN001
        """Log the contacts' new warnings (nodes pushed through a surface)."""
        for c in self.asm.contacts:
            for w in (c.pop_events() if hasattr(c, "pop_events") else ()):
                self.log(w["message"], logging.WARNING)
                if state.monitors is not None:
                    state.monitors.warnings.append(w)

    def _part_energies(self, state) -> tuple[dict[int, float], dict[int, tuple[float, int]]]:
        energy = self._part_kinetic(state)
        hg: dict[int, tuple[float, int]] = {}
        for rt in self.asm.elements:
            energy[rt.pid] = energy.get(rt.pid, 0.0) + rt.internal_energy + rt.hourglass_energy
            eid = -1
            per_elem = getattr(rt, "elem_hourglass_energy", None)
            if per_elem is not None and per_elem.size:
                eid = int(rt.elem_ids[int(np.argmax(per_elem))])
            hg[rt.pid] = (rt.hourglass_energy, eid)
        return energy, hg

    def _full_step_v(self, state) -> np.ndarray:  # noqa: ANN001
        """The full-step velocities (n, 3) mm/ms at the State's cycle and time
        (computed once for all the outputs due then)."""
        key = (state.cycle, state.t)
        if getattr(self, "_at_key", None) != key:
            self._at_key, self._at = key, {}
        if "v" not in self._at:
            buf = getattr(self, "_vbuf", None)
            if buf is None or buf.shape != state.v.shape:
                buf = self._vbuf = np.empty_like(state.v)
            self._at["v"] = node_velocity_full_step(self.asm, state, buf)
        return self._at["v"]

    def _part_kinetic(self, state) -> dict[int, float]:  # noqa: ANN001
        """Kinetic energy (J) per part: rigid bodies exactly, other parts from their
        share of the lumped nodal masses at full-step velocities (once per state)."""
        v = self._full_step_v(state)
        if "part_ke" in self._at:
            return dict(self._at["part_ke"])
        # a body's kinetic energy goes to its lead part (parts merged into it: 0)
        bodies = {p: b for b in self.asm.bodies for p in (b.pids or [b.pid])}
        ke = {pid: (bodies[pid].kinetic_energy() if bodies[pid].pid == pid else 0.0)
              if pid in bodies else share_energy(v, share.nodes, share.mass)
              for pid, share in self.asm.part_share.items()}
        self._at["part_ke"] = ke
        return dict(ke)

    def _write_matsum(self, state) -> None:  # noqa: ANN001
        by_pid = {rt.pid: rt for rt in self.asm.elements}
        kinetic = self._part_kinetic(state)
        for pid in sorted(self.asm.part_share):
            ke = kinetic[pid]
            rt = by_pid.get(pid)
            ie = rt.internal_energy if rt is not None else 0.0
            hg = rt.hourglass_energy if rt is not None else 0.0
            self.matsum.write([state.t, pid, ke, ie, hg])

    def write_state(self, state) -> None:  # noqa: ANN001
        if self.d3plot is not None:
            self.d3plot.add(state_fields(self.model, self.asm, state))
        if self.vtk is None:
            return
        cells, data = [], {"part": [], "element": [], "alive": [], "stress [GPa]": [],
                           "von_mises [GPa]": [], "plastic_strain": []}
        runtimes = {rt.pid: rt for rt in self.asm.elements}
        for g in self.model.solid_groups:
            self._add_block(cells, data, "hexahedron", g, runtimes.get(g.pid))
        for g in self.model.shell_groups:
            self._add_block(cells, data, "quad", g, runtimes.get(g.pid))
        for rt in self.asm.elements:  # springs, dampers and beams as lines (N1, N2)
            if getattr(rt, "family", "") in ("discrete", "beams"):
                self._add_block(cells, data, "line", rt, rt)
        if not cells:
            return
        u = state.x - self.asm.node_x0
        self.vtk.write(state.t, state.x, {"displacement [mm]": u, "velocity [mm/ms]": state.v},
                       cells, data)

    @staticmethod
    def _add_block(cells, data, kind, group, rt) -> None:
        e = group.conn.shape[0]
        cells.append((kind, group.conn))
        data["part"].append(np.full(e, group.pid, dtype=np.int32))
        data["element"].append(group.elem_ids.astype(np.int64))
        stress = getattr(rt, "stress", None)
        if stress is None or stress.shape != (e, 6):
            stress = np.zeros((e, 6))
        alive = getattr(rt, "alive", None)
        data["alive"].append((np.ones(e) if alive is None else alive).astype(np.int8))
        data["stress [GPa]"].append(np.asarray(stress, dtype=np.float64))
        data["von_mises [GPa]"].append(von_mises(stress))
        # effective plastic strain (shells: largest over the integration points)
        eps = getattr(rt, "plastic_strain", None)
        if eps is None or np.shape(eps) != (e,):
            eps = np.zeros(e)
        data["plastic_strain"].append(np.asarray(eps, dtype=np.float64))

    # -- end -------------------------------------------------------------------
    def finish(self, state, status: str, reason: str, where: dict, wall: float,  # noqa: ANN001
               extra: dict | None = None) -> dict:
        """Write the last state and summary.json; close every file. ``extra``: more
        summary entries (restart files written, where the run resumed from)."""
        try:
            if state.cycle > 0 or state.monitors is not None:
                self.record(state, force=True)
        except Exception as exc:  # never lose the summary because a last write failed
            self.log(f"could not write the final state: {exc}", logging.ERROR)
        if self.d3plot is not None:
            try:
                self.d3plot.write()
                self.log(f"d3plot: {len(self.d3plot.states)} states in {self.d3plot.path}")
            except Exception as exc:  # the other outputs and the summary still come
                self.log(f"could not write the d3plot: {exc}", logging.ERROR)
        last = self.last_energies
        summary = {
            "status": status,
            "reason": reason,
            **{f"error_{k}": v for k, v in where.items()},
            "end_time_ms": state.t,
            "requested_end_time_ms": self.end_time,
            "cycles": state.cycle,
            "dt_initial_ms": state.dt0 if state.dt0 > 0.0 else None,
            "dt_min_ms": None if not np.isfinite(state.dt_min) else state.dt_min,
            # how far the step control held the step below the stable step
            "step_control": StepControl(*state.dt_control).summary(),
            "element_counts": self.asm.element_counts(),
            "nodes": int(self.model.n_nodes),
            "eroded_elements": state.n_eroded,
            "wall_seconds": wall,
            "timing_seconds": dict(state.timing),
            "energy_ratio": last.get("energy_ratio"),
            "energies_J": last,
            **before_error(status, last, self.prev_energies, self.thresholds),
            "warnings": state.monitors.warnings if state.monitors is not None else [],
            "mass_scaling": state.mass_scaling.summary(),
            "contact_pass_through": {
                str(c.cid): {"events": c.n_pass_through, "nodes": len(c.pass_through_nodes)}
                for c in self.asm.contacts if hasattr(c, "n_pass_through")},
            # how often each contact rebuilt its candidate lists (search cost)
            "contact_search": {
                str(c.cid): {"sorts": c.n_sorts, "near_filters": c.n_filters}
                for c in self.asm.contacts if hasattr(c, "n_filters")},
            # cycles in which a contact's kinematic limit set the step, and its smallest
            "contact_step": {
                str(c.cid): {"cycles": c.n_step_limited,
                             "dt_min_ms": (c.dt_kin_min if np.isfinite(c.dt_kin_min)
                                           else None)}
                for c in self.asm.contacts if hasattr(c, "n_step_limited")},
            **(extra or {}),
        }
        quality, reasons = assess(summary, self.thresholds)
        summary["quality"] = quality
        summary["quality_reasons"] = reasons
        summary["quality_thresholds"] = self.thresholds.to_dict()
        (self.out / "summary.json").write_text(json.dumps(summary, indent=2, default=_json))
        level = logging.INFO if status == "normal termination" else logging.ERROR
        self.log(f"{status}: {reason}; {state.cycle} cycles, wall {wall:.2f} s", level)
        self.log(f"{status} - {headline(quality, reasons)}",
                 logging.INFO if quality == OK else logging.WARNING)
        for name in HISTORIES:
            getattr(self, name).close()
        for h in list(self.logger.handlers):
            h.close()
            self.logger.removeHandler(h)
        return summary


def _json(o: object) -> object:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)


def _make_logger(path: Path, append: bool = False) -> logging.Logger:
    logger = logging.getLogger(f"hollowbody.run.{path.resolve()}")
    logger.setLevel(logging.INFO)
    logger.propagate = False
    for h in list(logger.handlers):
        logger.removeHandler(h)
    fh = logging.FileHandler(path, mode="a" if append else "w")
    fh.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
    logger.addHandler(fh)
    sh = logging.StreamHandler(sys.stderr)
    sh.setLevel(logging.WARNING)
    sh.setFormatter(logging.Formatter("hollowbody: %(levelname)s: %(message)s"))
    logger.addHandler(sh)
    return logger
