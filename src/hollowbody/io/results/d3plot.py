"""d3plot states for LS-PrePost (through the optional extra lasso-python).

Files: ``d3plot`` (geometry) and ``d3plot01`` (the states), the file family
LS-PrePost opens from ``d3plot``.

:class:`D3plotSeries` keeps the states of a run in memory (single precision,
as LS-DYNA writes them) and writes the whole d3plot file with lasso-python's
writer when asked (:meth:`D3plotSeries.write`; a run writes it when it ends,
normally, by an error or by Ctrl-C). A resumed run reads the states already
written back first (:meth:`D3plotSeries.resume`), so one file holds the whole
run.

What a state holds: node coordinates and velocities; per solid element its
stress (one layer, global Voigt ``xx yy zz xy yz zx``, GPa), effective
plastic strain and alive flag; per shell element its stress at three layers
(inner, middle, outer surface, global, GPa), effective plastic strain per
layer, thickness (mm) and alive flag; the global kinetic, internal and total
energy (J) and the mean velocity. Geometry: node ids, element ids, part ids and
titles (the part's index in sorted part-id order). Units are those of the deck
(mm, ms, kg, kN, GPa): LS-PrePost shows what it reads.
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass
from pathlib import Path

import numpy as np

EXTRA = "pip install 'hollowbody[d3plot]'"


def available() -> bool:
    """True when lasso-python (the d3plot writer) is installed."""
    return importlib.util.find_spec("lasso") is not None


@dataclass
class StateFields:
    """One state: t ms; x, v (n, 3) mm, mm/ms; solid_stress (s, 6) GPa, solid_eps (s,),
    solid_alive (s,) bool; shell_stress (h, 3, 6) GPa, shell_eps (h, 3), shell_thickness
    (h,) mm, shell_alive (h,) bool; kinetic, internal, total J; beam_resultants (b, 6):
    axial force, shear forces s and t (kN), torsion, bending moments s and t (kN*mm),
    beam_alive (b,) bool (None: no beams)."""

    t: float
    x: np.ndarray
    v: np.ndarray
    solid_stress: np.ndarray
    solid_eps: np.ndarray
    solid_alive: np.ndarray
    shell_stress: np.ndarray
    shell_eps: np.ndarray
    shell_thickness: np.ndarray
    shell_alive: np.ndarray
    kinetic: float
    internal: float
    total: float
    beam_resultants: np.ndarray | None = None
    beam_alive: np.ndarray | None = None


@dataclass
class Geometry:
    """Mesh of the d3plot: node_ids (n,), x0 (n, 3) mm; solid_conn (s, 8) node indices,
    solid_part (s,) part index, solid_ids (s,); shell_conn (h, 4), shell_part, shell_ids;
    part_ids (p,) sorted, part_titles (p,) str; beam_conn (b, 3) N1 N2 N3 (the
    orientation node; N2 where there is none), beam_part, beam_ids (None: no beams)."""

    node_ids: np.ndarray
    x0: np.ndarray
    solid_conn: np.ndarray
    solid_part: np.ndarray
    solid_ids: np.ndarray
    shell_conn: np.ndarray
    shell_part: np.ndarray
    shell_ids: np.ndarray
    part_ids: np.ndarray
    part_titles: list[str]
    beam_conn: np.ndarray | None = None  # (b, 3) N1 N2 N3 node indices
    beam_part: np.ndarray | None = None  # (b,)
    beam_ids: np.ndarray | None = None  # (b,)


class D3plotSeries:
    """The states of one run, written as ``path`` (a single d3plot file)."""

    def __init__(self, path: Path, geometry: Geometry) -> None:
        if not available():
            raise ImportError(f"d3plot output needs lasso-python: {EXTRA}")
        self.path = Path(path)
        self.geometry = geometry
        self.states: list[StateFields] = []

    def add(self, state: StateFields) -> None:
        """Keep one state (single precision copies)."""
        f32 = np.float32
        self.states.append(StateFields(
            t=float(state.t), x=state.x.astype(f32), v=state.v.astype(f32),
            solid_stress=state.solid_stress.astype(f32), solid_eps=state.solid_eps.astype(f32),
            solid_alive=state.solid_alive.astype(bool),
            shell_stress=state.shell_stress.astype(f32), shell_eps=state.shell_eps.astype(f32),
            shell_thickness=state.shell_thickness.astype(f32),
            shell_alive=state.shell_alive.astype(bool), kinetic=float(state.kinetic),
            internal=float(state.internal), total=float(state.total),
            beam_resultants=(None if state.beam_resultants is None
                             else state.beam_resultants.astype(f32)),
            beam_alive=None if state.beam_alive is None else state.beam_alive.astype(bool)))

    def resume(self, count: int) -> None:
        """Read the first ``count`` states of the existing file back (a resumed run)."""
        if count <= 0 or not self.path.is_file():
            return
        from lasso.dyna import ArrayType as A
        from lasso.dyna import D3plot

        d = D3plot(str(self.path))
        arr = d.arrays
        g = self.geometry
        n_s, n_h = g.solid_ids.size, g.shell_ids.size
        n_b = 0 if g.beam_ids is None else g.beam_ids.size
        for k in range(min(count, arr[A.global_timesteps].size)):
            beams = None
            if n_b:
                beams = np.column_stack([
                    arr[A.element_beam_axial_force][k], arr[A.element_beam_shear_force][k],
                    arr[A.element_beam_torsion_moment][k],
                    arr[A.element_beam_bending_moment][k]])
            self.add(StateFields(
                t=arr[A.global_timesteps][k], x=arr[A.node_displacement][k],
                v=arr[A.node_velocity][k],
                solid_stress=arr[A.element_solid_stress][k, :, 0] if n_s else np.zeros((0, 6)),
                solid_eps=(arr[A.element_solid_effective_plastic_strain][k, :, 0] if n_s
                           else np.zeros(0)),
                solid_alive=(arr[A.element_solid_is_alive][k] if n_s else np.zeros(0)) > 0.5,
                shell_stress=arr[A.element_shell_stress][k] if n_h else np.zeros((0, 3, 6)),
                shell_eps=(arr[A.element_shell_effective_plastic_strain][k] if n_h
                           else np.zeros((0, 3))),
                shell_thickness=arr[A.element_shell_thickness][k] if n_h else np.zeros(0),
                shell_alive=(arr[A.element_shell_is_alive][k] if n_h else np.zeros(0)) > 0.5,
                kinetic=arr[A.global_kinetic_energy][k],
                internal=arr[A.global_internal_energy][k],
                total=arr[A.global_total_energy][k], beam_resultants=beams,
                beam_alive=(arr[A.element_beam_is_alive][k] > 0.5) if n_b else None))

    def write(self) -> None:
        """Write every state kept so far into ``path`` (replaces the file)."""
        if not self.states:
            return
        from lasso.dyna import ArrayType as A
        from lasso.dyna import D3plot

        g, st = self.geometry, self.states
        d = D3plot()
        a = d.arrays
        a[A.node_coordinates] = g.x0.astype(np.float32)
        a[A.node_ids] = g.node_ids.astype(np.int32)
        a[A.part_ids] = g.part_ids.astype(np.int32)
        a[A.part_titles_ids] = g.part_ids.astype(np.int32)
        a[A.part_titles] = np.array([t.encode("ascii", "replace")[:70] for t in g.part_titles])
        a[A.global_timesteps] = np.array([s.t for s in st], dtype=np.float32)
        a[A.node_displacement] = np.stack([s.x for s in st])
        a[A.node_velocity] = np.stack([s.v for s in st])
        a[A.global_kinetic_energy] = np.array([s.kinetic for s in st], dtype=np.float32)
        a[A.global_internal_energy] = np.array([s.internal for s in st], dtype=np.float32)
        a[A.global_total_energy] = np.array([s.total for s in st], dtype=np.float32)
        a[A.global_velocity] = np.stack([s.v.mean(axis=0) if s.v.size else np.zeros(3)
                                         for s in st]).astype(np.float32)
        if g.solid_ids.size:
            a[A.element_solid_node_indexes] = g.solid_conn.astype(np.int32)
            a[A.element_solid_part_indexes] = g.solid_part.astype(np.int32)
            a[A.element_solid_ids] = g.solid_ids.astype(np.int32)
            a[A.element_solid_stress] = np.stack([s.solid_stress for s in st])[:, :, None, :]
            a[A.element_solid_effective_plastic_strain] = \
                np.stack([s.solid_eps for s in st])[:, :, None]
            a[A.element_solid_is_alive] = np.stack([s.solid_alive for s in st]).astype(
                np.float32)
        if g.shell_ids.size:
            a[A.element_shell_node_indexes] = g.shell_conn.astype(np.int32)
            a[A.element_shell_part_indexes] = g.shell_part.astype(np.int32)
            a[A.element_shell_ids] = g.shell_ids.astype(np.int32)
            a[A.element_shell_stress] = np.stack([s.shell_stress for s in st])
            a[A.element_shell_effective_plastic_strain] = np.stack([s.shell_eps for s in st])
            a[A.element_shell_thickness] = np.stack([s.shell_thickness for s in st])
            a[A.element_shell_is_alive] = np.stack([s.shell_alive for s in st]).astype(
                np.float32)
        if g.beam_ids is not None and g.beam_ids.size:
            c = g.beam_conn.astype(np.int32)
            a[A.element_beam_node_indexes] = np.column_stack(
                [c, np.zeros((c.shape[0], 2), np.int32)])
            a[A.element_beam_part_indexes] = g.beam_part.astype(np.int32)
            a[A.element_beam_ids] = g.beam_ids.astype(np.int32)
            r = np.stack([s.beam_resultants for s in st])
            a[A.element_beam_axial_force] = r[:, :, 0]
            a[A.element_beam_shear_force] = r[:, :, 1:3]
            a[A.element_beam_torsion_moment] = r[:, :, 3]
            a[A.element_beam_bending_moment] = r[:, :, 4:6]
            a[A.element_beam_is_alive] = np.stack([s.beam_alive for s in st]).astype(
                np.float32)
        # LS-DYNA's family of files: the geometry in ``d3plot``, the states in
        # ``d3plot01`` (lasso removes the earlier family first)
        d.write_d3plot(str(self.path))
