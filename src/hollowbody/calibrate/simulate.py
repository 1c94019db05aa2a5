"""What the calibration runs: a simulator of the solid and the hollow block.

A *simulator* is any picklable object with

- ``solid(speed_kmh, run_dir) -> RunOutcome``: the solid reference block,
- ``hollow(params, speed_kmh, run_dir) -> RunOutcome``: the hollow block with
  wall parameters ``params`` ({name: value} in the units of
  :mod:`hollowbody.calibrate.space`),
- ``describe() -> dict``: a JSON description of everything that changes the
  result (the cache and the resume check compare it).

:class:`BlockSimulator` runs the real block test
(:func:`hollowbody.scenarios.block.block_impact`); the analytic
:class:`~hollowbody.calibrate.surrogate.SurrogateSimulator` stands in for it in
tests and benchmarks. Simulators are shipped to worker processes, so they
hold plain data only.
"""

from __future__ import annotations

import time
from contextlib import redirect_stderr, redirect_stdout
from dataclasses import asdict, dataclass, field, fields
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from hollowbody.calibrate.space import PARAMETERS
from hollowbody.curves.force_displacement import ForceDisplacement
from hollowbody.solver.run_lock import check_free

if TYPE_CHECKING:
    from hollowbody.engines.runner import ExternalEngine

NORMAL = "normal termination"
ERROR = "error termination"
INTERRUPT = "user interrupt"
#: Status of an evaluation that raised a Python exception (not cached).
EXCEPTION = "exception"
#: Status of an evaluation whose worker was lost for good (not cached).
LOST = "lost"
#: Status of an evaluation with a run that ended normally but whose verdict is
#: ``suspect`` (:mod:`hollowbody.solver.verdict`): failed, penalised, never the best.
SUSPECT = "suspect run"

#: File in a run folder that receives the run's console output (warnings).
CONSOLE_LOG = "console.log"

#: Cell size (mm) of the hollow grid, as in the paper.
CELL_MM = 30.0


def package_version() -> str:
    """hollowbody's version (part of every simulator description)."""
    try:
        return version("hollowbody")
    except PackageNotFoundError:  # pragma: no cover - source tree without install
        return "0+unknown"


@dataclass
class RunOutcome:
    """One run: its curve (time ms, displacement mm, force kN), status and cost.

    status: 'normal termination' / 'error termination' / 'user interrupt';
    summary: the run's summary.json dict (may be partial for surrogates).
    """

    curve: ForceDisplacement
    status: str
    reason: str
    wall_seconds: float
    cycles: int = 0
    run_dir: str | None = None
    summary: dict = field(default_factory=dict)


class Simulator(Protocol):
    """The solid and hollow block at a speed (see the module docstring)."""

    def solid(self, speed_kmh: float, run_dir: Path) -> RunOutcome: ...

    def hollow(self, params: dict[str, float], speed_kmh: float,
               run_dir: Path) -> RunOutcome: ...

    def describe(self) -> dict: ...


def elements_per_edge(mesh: float, cell: float = CELL_MM) -> int:
    """Shell elements along a hollow cell's edge for a mesh size (mm): round(cell/mesh) >= 1."""
    return max(1, int(round(cell / mesh)))


@dataclass(frozen=True)
class BlockSimulator:
    """The block test of :mod:`hollowbody.scenarios.block`.

    tissue: 'muscle' or 'fat'; mesh: solid element edge (mm), also the hollow
    walls' element size (``elements_per_edge = round(cell / mesh)``, the cell 30 mm
    unless ``options`` give one); end_time:
    simulated time (ms; None: the block's default); fixed: values of hollow
    parameters that are not calibrated ({name: value}, e.g. {'thickness': 1.2});
    options: further :class:`~hollowbody.scenarios.block.BlockConfig` fields
    (e.g. {'friction': 0.1}); vtk: write ParaView states; dtmin: stop a run in
    error termination when its time step falls below ``dtmin`` x the initial one
    (*CONTROL_TERMINATION DTMIN), applied to the solid runs when the block
    test supports it (a ``dtmin`` field of BlockConfig); hollow runs use the
    block's default (DTMIN erosion of crushed wall elements). The solver's
    console output (warnings) goes to ``console.log`` in each run folder.
    engine: an installed OpenRadioss or LS-DYNA that runs every evaluation
    (:class:`~hollowbody.engines.runner.ExternalEngine`; None: hollowbody's own).
    """

    tissue: str = "muscle"
    mesh: float = 7.5
    end_time: float | None = None
    fixed: tuple[tuple[str, float], ...] = ()
    options: tuple[tuple[str, Any], ...] = ()
    vtk: bool = False
    dtmin: float | None = 0.01
    engine: ExternalEngine | None = None

    @classmethod
    def make(cls, tissue: str = "muscle", mesh: float = 7.5, end_time: float | None = None,
             fixed: dict[str, float] | None = None, options: dict[str, Any] | None = None,
             vtk: bool = False, dtmin: float | None = 0.01,
             engine: ExternalEngine | None = None) -> BlockSimulator:
        """Build from dicts (kept as sorted tuples so the simulator is hashable)."""
        return cls(tissue, float(mesh), end_time, tuple(sorted((fixed or {}).items())),
                   tuple(sorted((options or {}).items())), vtk, dtmin, engine)

    def config(self, structure: str, speed_kmh: float, params: dict[str, float] | None = None):
        """The :class:`~hollowbody.scenarios.block.BlockConfig` of one run (ValueError if bad)."""
        from hollowbody.scenarios.block import BlockConfig

        kw: dict[str, Any] = dict(self.options)
        if (self.dtmin and structure == "solid"
                and "dtmin" in {f.name for f in fields(BlockConfig)}):
            kw.setdefault("dtmin", self.dtmin)  # hollow: the block's own DTMIN erosion
        if structure == "hollow":
            values = {**dict(self.fixed), **(params or {})}
            for name, value in values.items():
                kw[PARAMETERS[name][3]] = float(value)
            kw.setdefault("elements_per_edge", elements_per_edge(self.mesh,
                                                                 kw.get("cell", CELL_MM)))
        return BlockConfig(tissue=self.tissue, structure=structure, speed_kmh=float(speed_kmh),
                           mesh=self.mesh, end_time=self.end_time, **kw)

    def _run(self, structure: str, speed_kmh: float, run_dir: Path,
             params: dict[str, float] | None = None) -> RunOutcome:
        from hollowbody.scenarios.block import block_impact

        cfg = self.config(structure, speed_kmh, params)
        t0 = time.perf_counter()
        run_dir = Path(run_dir)
        run_dir.mkdir(parents=True, exist_ok=True)
        check_free(run_dir)  # another process's run there: its console log kept
        # the solver's console warnings go to the run folder, not the calibration's terminal
        with open(run_dir / CONSOLE_LOG, "w") as fh, redirect_stderr(fh), redirect_stdout(fh):
            res = block_impact(cfg, run_dir, vtk=self.vtk, quiet=True, engine=self.engine)
        s = res.summary
        return RunOutcome(curve=res.curve, status=s.get("status", ERROR),
                          reason=s.get("reason", ""),
                          wall_seconds=float(s.get("wall_seconds", time.perf_counter() - t0)),
                          cycles=int(s.get("cycles", 0)), run_dir=str(run_dir), summary=s)

    def solid(self, speed_kmh: float, run_dir: Path) -> RunOutcome:
        return self._run("solid", speed_kmh, run_dir)

    def hollow(self, params: dict[str, float], speed_kmh: float, run_dir: Path) -> RunOutcome:
        return self._run("hollow", speed_kmh, run_dir, params)

    def warm_up(self, params: dict[str, float] | None = None) -> None:
        """Compile the solver's kernels in this process (a 0.05 ms solid and hollow run in a
        scratch folder), so that measured wall times are those of the runs alone."""
        import tempfile
        from dataclasses import replace

        if self.engine is not None:  # nothing of this process's to compile
            return
        short = replace(self, end_time=0.05, vtk=False)
        with tempfile.TemporaryDirectory(prefix="hollowbody_warm_up_") as tmp:
            for structure in ("solid", "hollow"):
                try:
                    short._run(structure, 40.0, Path(tmp) / structure, params)
                except Exception:  # the measured run will report it
                    pass

    def describe(self) -> dict:
        d = asdict(self)
        d["fixed"] = dict(self.fixed)
        d["options"] = dict(self.options)
        d.pop("vtk")
        if self.engine is None:  # descriptions (and caches) of earlier versions stay valid
            d.pop("engine")
        from hollowbody.scenarios.block import BlockConfig

        if "dtmin" not in {f.name for f in fields(BlockConfig)}:
            d["dtmin"] = None  # not supported by the block test: not applied
        d["elements_per_edge"] = elements_per_edge(self.mesh,
                                                   dict(self.options).get("cell", CELL_MM))
        from hollowbody.scenarios.block import DTMIN_HOLLOW

        d["dtmin_hollow"] = dict(self.options).get("dtmin", DTMIN_HOLLOW)
        # the solid reference's hourglass control, given or the block's default, recorded once
        # (not also as options); left out when it is the one of calibrations made before it
        # was recorded (IHQ 4, QM 0.05), so those resume and keep their caches
        from hollowbody.calibrate.wall import LEGACY_SOLID_HOURGLASS, SOLID_CONTROL_FIELDS

        d["options"] = {k: v for k, v in d["options"].items() if k not in SOLID_CONTROL_FIELDS}
        solid = self.config("solid", 40.0)
        control = (int(solid.hourglass_ihq), float(solid.hourglass_qh))
        if control != LEGACY_SOLID_HOURGLASS:
            d["solid_hourglass"] = list(control)
        return {"kind": "block", "hollowbody": package_version(), **d}
