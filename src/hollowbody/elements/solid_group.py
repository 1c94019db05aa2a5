"""Runtime state and kernels of one solid element group (one part).

:class:`SolidGroupRuntime` is what the solver calls every cycle: it owns the
time-varying arrays of the group (stress, volume, hourglass and material
history, energies) and the work arrays of its kernels (allocated once).
Formulation: 8-node one-point hexahedron (ELFORM 1) with Flanagan-Belytschko
hourglass control (viscous IHQ 1-3, stiffness IHQ 4-5), the Belytschko-Bindeman
assumed-strain stiffness (IHQ 6 incremental, IHQ 7 total; IHQ 8 and above run as
IHQ 6 with a warning)
and LS-DYNA bulk viscosity; degenerate wedges and
tetrahedra run through the same kernel (see docs/elements.md); or the fully
integrated, selectively reduced hexahedron (ELFORM 2,
:mod:`hollowbody.elements.hex8_full_kernels`: no hourglass modes, no hourglass
control).
Materials: the laws of :data:`hollowbody.materials.solid_laws.SOLID_LAWS`
(*MAT_ELASTIC ``"elastic"``, *MAT_SIMPLIFIED_RUBBER ``"rubber181"``); one
element kernel per law (:func:`~hollowbody.elements.hex8_solid_kernels.make_hex8_kernel`).

Energies (J, cumulative): ``internal_energy + hourglass_energy`` is the work
of the group's nodal forces, accounted exactly as the central-difference
scheme does it (``-dt v^{n+1/2} . (f^n + f^{n+1}) / 2``), so the solver's energy
balance closes. ``hourglass_energy`` is the hourglass forces' share
(dissipated in the viscous form, stored + dissipated in the stiffness form);
``internal_energy`` the rest: stress work *including* the bulk-viscosity work
and MAT_181's damping work.
"""

from __future__ import annotations

import warnings

import numba
import numpy as np

from hollowbody.elements.assembly import NodeGather, scatter_add
from hollowbody.elements.hex8_full_kernels import gauss_gradients, make_hex8_full_kernel
from hollowbody.elements.hex8_kinematics import (
    SHAPE_TET,
    canonical_connectivity,
    hex8_gradients,
)
from hollowbody.elements.hex8_solid_kernels import (
    H_G,
    H_IHQ,
    H_K,
    H_Q1,
    H_Q2,
    H_QH,
    N_HG,
    make_hex8_kernel,
)
from hollowbody.elements.time_step import element_time_steps
from hollowbody.errors import DeckError
from hollowbody.materials.solid_laws import HISTORY_FIELDS, SOLID_LAWS
from hollowbody.model.model import FULL_ELFORMS, Curve, HourglassDef, MaterialDef, SolidGroup

#: Elements per chunk of the parallel element loop.
CHUNK = 256
#: Groups at least this large use the parallel node gather (when > 1 thread).
GATHER_MIN_ELEMENTS = 2048


def reference_half_lengths(conn: np.ndarray, x0: np.ndarray) -> np.ndarray:
    """(e, 3) mm norms of the centre Jacobian's columns (1/8) sum_a xi_k,a x_a."""
    xi = np.array([[-1, 1, 1, -1, -1, 1, 1, -1], [-1, -1, 1, 1, -1, -1, 1, 1],
                   [-1, -1, -1, -1, 1, 1, 1, 1]], dtype=np.float64)
    if conn.shape[0] == 0:
        return np.ones((0, 3))
    j = np.einsum("ka,eai->eki", xi, x0[conn]) / 8.0
    return np.ascontiguousarray(np.maximum(np.linalg.norm(j, axis=2), 1e-300))


def _chunk_bounds(n: int, chunk: int = CHUNK) -> np.ndarray:
    nchunk = max(1, -(-n // chunk))
    return np.linspace(0, n, nchunk + 1).round().astype(np.int64)


class SolidGroupRuntime:
    """Runtime state + kernels of one SolidGroup (one part: one material, one hourglass def).

    Attributes (e = number of elements):
    pid; elem_ids (e,) int64; conn (e, 8) int32 as in the deck; n_elem;
    shape (e,) int8 (hex8_kinematics.SHAPE_*); alive (e,) bool (False = eroded);
    stress (e, 6) float64 GPa Cauchy, Voigt xx yy zz xy yz zx (without the
    bulk-viscosity pressure; ELFORM 2: the volume mean of the points' stresses
    ``stress_gp`` (8e, 6), else an empty array); elform 1 or 2;
    volume0, volume (e,) mm^3 initial / current;
    mass (e,) kg = density * volume0; dt_elem (e,) ms critical step of the last
    call (unscaled, inf for dead elements); internal_energy, hourglass_energy
    J cumulative (see module docstring). The law's history arrays are
    attributes named as in its ``HISTORY_FIELDS`` (those of the other laws
    are empty arrays).
    """

    #: Attributes that change in time (saved and restored by a restart):
    #: arrays are restored in place, floats by assignment. ``_fwork`` holds the
    #: element forces f^n, read by the next call (energy of the step).
    STATE_FIELDS: tuple[str, ...] = (
        "alive", "stress", "volume", "dt_elem", "_c", "_hgstate", "_hgdisp", "_hgmod",
        "_fwork", "internal_energy", "hourglass_energy", "stress_gp") + HISTORY_FIELDS

    def __init__(self, group: SolidGroup, material: MaterialDef, hourglass: HourglassDef,
                 curves: dict[int, Curve], node_x0: np.ndarray, elform: int = 1) -> None:
        self.pid = int(group.pid)
        self.elem_ids = np.asarray(group.elem_ids, dtype=np.int64)
        self.conn = np.ascontiguousarray(group.conn, dtype=np.int32)
        self.n_elem = int(self.conn.shape[0])
        e = self.n_elem
        self._conn_k, self.shape = canonical_connectivity(self.conn)
        x0 = np.ascontiguousarray(node_x0, dtype=np.float64)
        self._b0, self.volume0 = hex8_gradients(self._conn_k, x0)
        if e and np.any(self.volume0 <= 0.0):
            i = int(np.nonzero(self.volume0 <= 0.0)[0][0])
            raise DeckError(f"solid element {int(self.elem_ids[i])} of part {self.pid} has "
                            f"zero or negative initial volume ({self.volume0[i]:.4g} mm^3); "
                            "check its node order", material.source.file, None, "ELEMENT_SOLID")
        self.volume = self.volume0.copy()
        self.density = float(material.density)
        self.mass = self.density * self.volume0
        self.kind = material.kind
        self.alive = np.ones(e, dtype=bool)
        self.stress = np.zeros((e, 6))
        self.internal_energy = 0.0
        self.hourglass_energy = 0.0
        self._lfac = np.where(self.shape == SHAPE_TET, 3.0, 1.0)

        law = SOLID_LAWS.get(self.kind)
        if law is None:
            raise DeckError(f"material {material.mid} ({material.keyword or material.kind}) "
                            "is not available for solid elements", material.source.file,
                            material.source.line, material.keyword or None)
        self._law = law
        self._params = law.solid_params(material, curves)
        c0 = law.solid_wave_speed0(self._params)
        self.elform = 2 if int(elform) in FULL_ELFORMS else 1
        if int(elform) in (-1, -2):
            warnings.warn(f"part {self.pid}: solid ELFORM {int(elform)} runs as ELFORM 2 "
                          "(fully integrated, selectively reduced)", UserWarning, stacklevel=2)
        elif int(elform) not in (0, 1, 2, 10):  # 10: the one-point tetrahedron
            warnings.warn(f"part {self.pid}: solid ELFORM {int(elform)} is not available; it "
                          "runs as ELFORM 1 (one-point)", UserWarning, stacklevel=2)
        full = self.elform == 2
        # per-point arrays of the fully integrated element: rows 8e .. 8e + 7
        history = law.solid_history(self._params, 8 * e if full else e)
        for name in HISTORY_FIELDS:
            setattr(self, name, history.get(name, np.zeros(0)))
        self.stress_gp = np.zeros((8 * e if full else 0, 6))
        self._b0g = np.zeros((0, 8, 3))
        if full:
            self._b0g, jac0 = gauss_gradients(self._conn_k, x0)
            if e and np.any(jac0 <= 0.0):
                i = int(np.nonzero((jac0 <= 0.0).any(axis=1))[0][0])
                raise DeckError(f"solid element {int(self.elem_ids[i])} of part {self.pid} "
                                "(ELFORM 2) has a Gauss point with zero or negative Jacobian "
                                "in its initial shape (a corner inverted or collapsed); "
                                "check its node order and shape, or use ELFORM 1",
                                material.source.file, None, "ELEMENT_SOLID")
        self._kernel = make_hex8_full_kernel(law) if full else make_hex8_kernel(law)

        ihq = int(hourglass.ihq) if hourglass.ihq else 1
        if ihq > 7:
            warnings.warn(f"part {self.pid}: hourglass type IHQ={ihq} is not available for "
                          "solids; the assumed-strain stiffness form (IHQ=6, incremental) "
                          f"is used with QM={hourglass.qm}", UserWarning, stacklevel=2)
            ihq = 6
        self.ihq = ihq
        g_hg, k_hg = law.solid_hourglass_moduli(self._params)
        self._hg = np.zeros(N_HG)
        self._hg[[H_IHQ, H_QH, H_Q1, H_Q2, H_G, H_K]] = (
            float(ihq), float(hourglass.qm), float(hourglass.q1), float(hourglass.q2),
            g_hg, k_hg)
        self._hgstate = np.zeros((e, 4, 3))  # generalised hourglass forces (kN)
        self._axes0 = reference_half_lengths(self._conn_k, x0)
        self._hgdisp = np.zeros((e if ihq == 7 else 1, 4, 3))  # hourglass displacements (mm)
        # shear modulus (GPa) of the assumed-strain stiffness at the last call (passive rule)
        self._hgmod = np.full(e if ihq >= 6 else 1, g_hg)

        self._fwork = np.zeros((e, 8, 3))
        self.dt_elem = element_time_steps(self._conn_k, x0, c0, self.shape) if e else \
            np.zeros(0)
        self._c = np.full(e, c0)
        self._bounds = _chunk_bounds(e)
        self._out = np.zeros((self._bounds.size - 1, 5))
        self._gather = NodeGather(self._conn_k) if e >= GATHER_MIN_ELEMENTS else None

    # ------------------------------------------------------------------
    def add_forces(self, x: np.ndarray, v: np.ndarray, dt: float,
                   f: np.ndarray) -> tuple[float, int, int]:
        """Advance the group's stress to t^{n+1} and add its nodal forces to f.

        x: (n, 3) float64 mm positions at t^{n+1}; v: (n, 3) float64 mm/ms
        velocities at t^{n+1/2}; dt: ms, the step just taken (0 at start: no
        stress increment, no energy); f: (n, 3) float64 kN, receives
        -(internal + hourglass + bulk viscosity) forces. Arrays must be
        C-contiguous float64. Returns (dt_crit_min ms unscaled, 0-based index
        of the element setting it, index of the first element with volume <= 0
        or -1); (inf, -1, -1) when no element is alive.
        """
        if self.n_elem == 0:
            return np.inf, -1, -1
        out = self._out
        # dynamic scheduling of the chunks: the cost per element varies in space
        # (contact zone, eigen-solver sweeps), a static split leaves threads idle
        old_chunk = numba.set_parallel_chunksize(1)
        # argument groups built per call, so a rebound attribute is always the one used
        if self.elform == 2:
            geom = (self._conn_k, self._lfac, self.volume0, self._b0g, self._bounds)
            state = (self.alive, self.stress, self.stress_gp, self.volume, self._fwork,
                     self.dt_elem, self._c)
        else:
            geom = (self._conn_k, self._lfac, self.volume0, self._b0, self._bounds,
                    self._axes0)
            state = (self.alive, self.stress, self.volume, self._hgstate, self._hgdisp,
                     self._hgmod, self._fwork, self.dt_elem, self._c)
        history = tuple(getattr(self, name) for name in self._law.HISTORY_FIELDS)
        self._kernel(x, v, float(dt), geom, state, self._params, history, self._hg, out)
        numba.set_parallel_chunksize(old_chunk)
        if self._gather is not None and numba.get_num_threads() > 1:
            self._gather.add(self._fwork, f)
        else:
            scatter_add(self._conn_k, self._fwork, f)
        self.internal_energy += float(out[:, 0].sum())
        self.hourglass_energy += float(out[:, 1].sum())
        k = int(np.argmin(out[:, 2]))
        dtmin = float(out[k, 2])
        imin = int(out[k, 3]) if np.isfinite(dtmin) else -1
        negs = out[:, 4]
        neg = int(negs[negs >= 0].min()) if np.any(negs >= 0) else -1
        return dtmin, imin, neg

    def erode(self, idx: np.ndarray) -> None:
        """Mark elements idx (0-based in the group) dead and zero their stress and history."""
        idx = np.asarray(idx, dtype=np.int64)
        self.alive[idx] = False
        self.stress[idx] = 0.0
        self._hgstate[idx] = 0.0
        if self._hgdisp.shape[0] == self.n_elem:
            self._hgdisp[idx] = 0.0
        rows = idx
        if self.elform == 2:  # the history rows are the eroded elements' points
            rows = (8 * idx[:, None] + np.arange(8)).ravel()
            self.stress_gp[rows] = 0.0
        self._law.solid_erode(tuple(getattr(self, n) for n in self._law.HISTORY_FIELDS), rows)
        self.dt_elem[idx] = np.inf

    def wave_speed(self) -> np.ndarray:
        """Current dilatational wave speed (e,) mm/ms (initial value before the first call)."""
        return self._c.copy()

    def pressure(self) -> np.ndarray:
        """Pressure (e,) GPa, -tr(stress)/3 (compression positive, no bulk viscosity)."""
        return -self.stress[:, :3].sum(axis=1) / 3.0

    def connectivity_used(self) -> np.ndarray:
        """(e, 8) int32 connectivity of the kernels (tetrahedra rewritten, see hex8_kinematics)."""
        return self._conn_k
