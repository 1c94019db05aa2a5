"""Axial crushing of thin-walled tubes: the deck, the run and its measures.

:func:`crush_deck` writes the classical crush test as an LS-DYNA deck (only
keywords hollowbody reads, valid LS-DYNA input):

- the tube (part 1): Belytschko-Tsay shells (*SECTION_SHELL ELFORM 2, NIP 5)
  of :mod:`hollowbody.mesh.tube`, *MAT_PIECEWISE_LINEAR_PLASTICITY (MAT_024)
  with SIGY and ETAN (rate-insensitive: no C, P, LCSR), aluminium-like or
  mild-steel-like (:data:`MATERIALS`);
- the base: the bottom ring clamped (*BOUNDARY_SPC_SET, all six dofs);
- the plate (part 2): a rigid square of shells (*MAT_RIGID, x, y and the
  rotations held) 0.1 mm above the tube's top edge (contact surfaces), moved
  down by *BOUNDARY_PRESCRIBED_MOTION_RIGID at ``speed`` mm/ms, reached over
  a ramp of 0.5 mm of travel (a sudden 10 m/s start sends a wave of
  rho c v = 0.41 GPa into steel, above its yield stress);
- contacts: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE id 1 tube (slave) - plate
  (master), whose master force is the crush force (rcforc), and
  *CONTACT_AUTOMATIC_SINGLE_SURFACE id 2 on the tube (its folds), friction
  ``friction`` in both;
- histories: GLSTAT, RCFORC, NODOUT (a plate node: its displacement), MATSUM.

:func:`run_crush` runs it and returns a :class:`CrushResult`: the mean crush
force over the stable folding range and the half-fold length from the force
oscillation (:mod:`hollowbody.scenarios.crush_analysis`), the analytical
range (:mod:`hollowbody.scenarios.crush_theory`), the energy shares, and the
plate's work against the energies it went into. Units: mm, ms, kg, kN, GPa, J.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hollowbody.io.keyword import (
    BoundarySpcSet,
    Contact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseHistoryNode,
    Deck,
    DefineCurve,
    Hourglass,
    MatPiecewiseLinearPlasticity,
    MatRigid,
    Part,
    PrescribedMotionRigid,
    SectionShell,
    SetNodeList,
    write_deck,
)
from hollowbody.mesh import circular_tube, square_tube
from hollowbody.scenarios import crush_analysis as ca
from hollowbody.scenarios.crush_theory import (
    CrushReference,
    circular_reference,
    flow_stress,
    square_reference,
)

#: Wall materials (E, sigma_y, ETAN GPa; rho kg/mm^3): rate-insensitive MAT_024.
MATERIALS: dict[str, dict[str, float]] = {
    "aluminium": {"e": 70.0, "ro": 2.7e-6, "pr": 0.3, "sigy": 0.25, "etan": 0.0},
    "steel": {"e": 210.0, "ro": 7.85e-6, "pr": 0.3, "sigy": 0.25, "etan": 0.0},
}
PID_TUBE, PID_PLATE = 1, 2
CID_PLATE, CID_SELF = 1, 2
#: First node / element id of the plate.
PLATE_ID0 = 1_000_001
PLATE_T = 2.0  # mm, rigid plate shells
CLEARANCE = 0.1  # mm between the plate's and the tube's contact surfaces at t = 0
RAMP = 0.5  # mm of plate travel over which the speed is reached


@dataclass(frozen=True)
class CrushCase:
    """One crush test.

    shape "square" (``size`` = side C) or "circular" (``size`` = diameter D),
    mid-surface mm; ``t`` wall mm; ``length`` mm; ``per_half_fold`` elements
    per closed-form half-fold length H (sets the element size H / n);
    ``trigger`` amplitude as a fraction of t (0: none) on the ring about H/2
    below the loaded end; ``speed`` mm/ms; ``crush`` the final plate travel
    as a fraction of the length; ``hourglass`` (IHQ, QH) for a *HOURGLASS
    card on the tube (None: the defaults, IHQ 1, QH 0.1).
    """

    shape: str = "square"
    size: float = 40.0
    t: float = 2.0
    length: float = 100.0
    per_half_fold: float = 3.0
    material: str = "aluminium"
    trigger: float = 0.3
    speed: float = 10.0
    crush: float = 0.72
    friction: float = 0.2
    hourglass: tuple[int, float] | None = None

    @property
    def slenderness(self) -> float:
        """C / t or D / t."""
        return self.size / self.t

    @property
    def name(self) -> str:
        trig = f"trig{self.trigger:g}" if self.trigger else "notrig"
        return (f"{self.shape}-{self.material}-{self.size:g}x{self.t:g}x{self.length:g}"
                f"-n{self.per_half_fold:g}-{trig}-v{self.speed:g}")

    def sigma0(self) -> float:
        """Flow stress (GPa) of the yardstick: energy-equivalent (crush_theory.flow_stress)."""
        m = MATERIALS[self.material]
        return flow_stress(m["sigy"], m["etan"])

    def reference(self) -> CrushReference:
        """The analytical yardstick of this tube."""
        if self.shape == "square":
            return square_reference(self.size, self.t, self.sigma0())
        return circular_reference(self.size, self.t, self.sigma0())


@dataclass
class CrushSetup:
    """What the deck writer chose: mesh counts, element size mm, the plate node id
    whose history is the plate's travel, the end time ms."""

    per_side: int
    around: int
    nz: int
    elem: float
    plate_node: int
    end_time: float
    n_shells: int


def _tube_mesh(case: CrushCase) -> tuple[np.ndarray, np.ndarray, int, int, int, float]:
    ref = case.reference()
    h = ref.half_fold / case.per_half_fold
    nz = max(4, int(round(case.length / h)))
    level = max(1, int(round(0.5 * ref.half_fold / (case.length / nz))))
    if case.shape == "square":
        per_side = max(2, int(round(case.size / h)))
        x, q = square_tube(case.size, case.t, case.length, per_side, nz,
                           trigger=case.trigger, trigger_level=level)
        return x, q, per_side, 4 * per_side, nz, case.size / per_side
    if case.shape != "circular":
        raise ValueError(f"tube shape {case.shape!r}: 'square' or 'circular'")
    around = max(8, 4 * int(round(math.pi * case.size / h / 4)))
    x, q = circular_tube(case.size, case.t, case.length, around, nz,
                         trigger=case.trigger, trigger_level=level)
    return x, q, 0, around, nz, math.pi * case.size / around


def _plate(half: float, n: int, z: float) -> tuple[np.ndarray, np.ndarray]:
    g = np.linspace(-half, half, n + 1)
    yy, xx = np.meshgrid(g, g, indexing="ij")
    x = np.column_stack([xx.ravel(), yy.ravel(), np.full(xx.size, z)])
    j, i = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    p = (j * (n + 1) + i).ravel()
    return x, np.column_stack([p, p + 1, p + n + 2, p + n + 1])


def crush_deck(case: CrushCase, output_step: float = 0.2) -> tuple[Deck, CrushSetup]:
    """The crush deck of ``case`` (module doc) and its set-up; histories every
    ``output_step`` mm of plate travel."""
    if case.material not in MATERIALS:
        raise ValueError(f"material {case.material!r}: one of {sorted(MATERIALS)}")
    if case.speed <= 0.0 or not 0.0 < case.crush < 1.0:
        raise ValueError("speed must be > 0 and crush in (0, 1)")
    xt, qt, per_side, around, nz, elem = _tube_mesh(case)
    mat = MATERIALS[case.material]
    tid = np.arange(1, xt.shape[0] + 1)
    # plate: 1.5 x the section, elements about the tube's, surfaces 0.1 mm apart
    half = 0.75 * case.size + 2.0 * elem
    n_plate = max(2, int(round(2.0 * half / elem)))
    zp = case.length + 0.5 * (case.t + PLATE_T) + CLEARANCE
    xp, qp = _plate(half, n_plate, zp)
    pid_nodes = PLATE_ID0 + np.arange(xp.shape[0])
    deck = Deck()
    deck.title = (f"axial crush of a {case.shape} tube {case.size:g} x {case.t:g} x "
                  f"{case.length:g} mm, {case.material}, {case.speed:g} m/s")
    deck.add_nodes(tid, xt)
    deck.add_nodes(pid_nodes, xp)
    deck.add_shells(np.arange(1, qt.shape[0] + 1), PID_TUBE, tid[qt])
    deck.add_shells(PLATE_ID0 + np.arange(qp.shape[0]), PID_PLATE, pid_nodes[qp])
    hgid = 1 if case.hourglass is not None else 0
    deck.add(Part(pid=PID_TUBE, secid=1, mid=1, hgid=hgid, title="tube"))
    deck.add(Part(pid=PID_PLATE, secid=2, mid=2, title="plate (rigid)"))
    deck.add(SectionShell(secid=1, elform=2, shrf=0.833333, t1=case.t, nip=5))
    deck.add(SectionShell(secid=2, elform=2, t1=PLATE_T, nip=2))
    if case.hourglass is not None:
        deck.add(Hourglass(hgid=1, ihq=int(case.hourglass[0]), qm=float(case.hourglass[1])))
    deck.add(MatPiecewiseLinearPlasticity(mid=1, ro=mat["ro"], e=mat["e"], pr=mat["pr"],
                                          sigy=mat["sigy"], etan=mat["etan"],
                                          title=case.material))
    # the motion is prescribed: the mass only sets the plate's kinetic energy, kept small
    # (0.1 kg: 5 J at 10 m/s against 1-5 kJ of crush) so that the energy ratio is the tube's
    plate_mass = 0.1
    deck.add(MatRigid(mid=2, ro=plate_mass / ((2.0 * half) ** 2 * PLATE_T), e=210.0, pr=0.3,
                      cmo=1, con1=4, con2=7, title="plate"))
    t_ramp = 2.0 * RAMP / case.speed
    travel = case.crush * case.length + CLEARANCE
    end = t_ramp + (travel - RAMP) / case.speed
    deck.add(DefineCurve(lcid=1, points=[[0.0, 0.0], [t_ramp, 1.0], [10.0 * end, 1.0]],
                         title="plate speed (ramp, then constant)"))
    deck.add(PrescribedMotionRigid(pid=PID_PLATE, dof=3, vad=0, lcid=1, sf=-case.speed))
    bottom = tid[np.abs(xt[:, 2]) < 1e-9]
    deck.add(SetNodeList(sid=1, nodes=bottom.tolist(), title="tube bottom (clamped)"))
    deck.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1, dofrx=1, dofry=1, dofrz=1))
    fr = case.friction
    deck.add(Contact(type="AUTOMATIC_SURFACE_TO_SURFACE", cid=CID_PLATE, heading="tube-plate",
                     ssid=PID_TUBE, sstyp=3, msid=PID_PLATE, mstyp=3, fs=fr, fd=fr, soft=1))
    deck.add(Contact(type="AUTOMATIC_SINGLE_SURFACE", cid=CID_SELF, heading="tube folds",
                     ssid=PID_TUBE, sstyp=3, fs=fr, fd=fr, soft=1))
    deck.add(ControlTermination(endtim=end))
    deck.add(ControlTimestep(tssfac=0.9))
    for name in ("GLSTAT", "RCFORC", "NODOUT", "MATSUM"):
        deck.add(DatabaseAscii(name=name, dt=output_step / case.speed))
    mid = int(pid_nodes[(n_plate // 2) * (n_plate + 1) + n_plate // 2])
    deck.add(DatabaseHistoryNode(ids=[mid]))
    return deck, CrushSetup(per_side=per_side, around=around, nz=nz, elem=elem,
                            plate_node=mid, end_time=end, n_shells=int(qt.shape[0]))


@dataclass
class CrushResult:
    """One crush run and its measures (forces kN, lengths mm, energies J).

    ``d``, ``f``: plate travel past the contact clearance and crush force;
    ``mean_force`` over the window (d0, d1); ``half_fold`` from the major force
    peaks between H / 2 (past the initial buckling peak) and d1;
    ``plate_work`` = int f dd (the work done on the tube);
    ``energy_sum`` = tube internal + hourglass + kinetic + contact energy at
    the end; ``hourglass_share`` = hourglass / internal; ``contact_share`` =
    contact / (internal + hourglass + contact).
    """

    case: CrushCase
    setup: CrushSetup
    status: str
    reference: CrushReference
    wall_seconds: float = float("nan")
    cycles: int = 0
    dt0: float = float("nan")
    dt_min: float = float("nan")
    energy_ratio: float = float("nan")
    window: tuple[float, float] = (float("nan"), float("nan"))
    mean_force: float = float("nan")
    half_fold: float = float("nan")
    peaks: np.ndarray = field(default_factory=lambda: np.zeros(0))
    plate_work: float = float("nan")
    energy_sum: float = float("nan")
    internal: float = float("nan")
    hourglass: float = float("nan")
    contact: float = float("nan")
    d: np.ndarray = field(default_factory=lambda: np.zeros(0))
    f: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def ratio(self) -> float:
        """Mean force / the upper end of the analytical range."""
        return self.mean_force / self.reference.high

    @property
    def hourglass_share(self) -> float:
        return self.hourglass / self.internal if self.internal > 0 else float("nan")

    @property
    def contact_share(self) -> float:
        tot = self.internal + self.hourglass + self.contact
        return self.contact / tot if tot > 0 else float("nan")


def _csv(path: Path) -> np.ndarray:
    return np.atleast_1d(np.genfromtxt(path, delimiter=",", names=True))


def read_crush(out_dir: str | Path, case: CrushCase, setup: CrushSetup) -> CrushResult:
    """The measures of a finished crush run in ``out_dir`` (its CSV histories)."""
    out = Path(out_dir)
    summary = json.loads((out / "summary.json").read_text())
    ref = case.reference()
    res = CrushResult(case=case, setup=setup, status=summary["status"], reference=ref,
                      wall_seconds=float(summary["wall_seconds"]),
                      cycles=int(summary["cycles"]),
                      dt0=float(summary["dt_initial_ms"] or float("nan")),
                      dt_min=float(summary["dt_min_ms"] or float("nan")),
                      energy_ratio=float(summary["energy_ratio"] or float("nan")))
    rc = _csv(out / "rcforc.csv")
    rc = rc[rc["contact"] == CID_PLATE]
    nod = _csv(out / "nodout.csv")
    nod = nod[nod["node"] == setup.plate_node]
    travel = np.interp(rc["time_ms"], nod["time_ms"], -nod["uz_mm"])
    res.d = np.maximum(travel - CLEARANCE, 0.0)
    res.f = np.asarray(rc["master_fz_kN"], dtype=float)
    res.plate_work = ca.work(travel, res.f)
    gl = _csv(out / "glstat.csv")
    ms = _csv(out / "matsum.csv")
    tube = ms[ms["part"] == PID_TUBE]
    res.internal = float(gl["internal_J"][-1])
    res.hourglass = float(gl["hourglass_J"][-1])
    res.contact = float(gl["contact_J"][-1])
    res.energy_sum = res.internal + res.hourglass + res.contact + float(tube["kinetic_J"][-1])
    try:
        res.window = ca.crush_window(case.length, ref.half_fold, ref.effective)
        res.mean_force = ca.mean_force(res.d, res.f, *res.window)
        res.peaks = ca.fold_peaks(res.d, res.f, 0.5 * ref.half_fold, res.window[1],
                                  ref.half_fold, res.mean_force)
        res.half_fold = ca.half_fold_from_peaks(res.peaks, ref.effective)
    except ValueError as exc:
        res.status += f" ({exc})"
    return res


def run_crush(case: CrushCase, out_dir: str | Path, threads: int | None = 1,
              overwrite: bool = True, tangent_drilling: bool = False,
              drilling: float | None = None) -> CrushResult:
    """Write the deck of ``case`` into ``out_dir``, run it there (no VTK states) and
    return its measures. ``tangent_drilling`` switches the shells' opt-in tangent
    drilling spring on (``Model.controls.shell_tangent_drilling``) and ``drilling`` sets
    the drilling stiffness factor (``Model.controls.shell_drilling``); neither is a deck
    card."""
    from hollowbody.api import load_model, run_deck, run_model

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    deck, setup = crush_deck(case)
    path = out / "crush.k"
    write_deck(deck, path)
    t0 = time.perf_counter()
    if tangent_drilling or drilling is not None:
        model = load_model(path)
        model.controls.shell_tangent_drilling = bool(tangent_drilling)
        model.controls.shell_drilling = drilling
        run_model(model, out, vtk=False, label=path.name, overwrite=overwrite, inputs=(path,),
                  threads=threads)
    else:
        run_deck(path, out, vtk=False, overwrite=overwrite, threads=threads)
    res = read_crush(out, case, setup)
    res.wall_seconds = time.perf_counter() - t0
    return res
