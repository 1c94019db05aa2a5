"""Runtimes of beam element groups (see :mod:`hollowbody.solver.setup`).

One :class:`BeamGroupRuntime` per *ELEMENT_BEAM part: the co-rotational
two-node beam of :mod:`hollowbody.elements.beam_kernels` with the resultant
elastic law (ELFORM 2) or cross-section integration (ELFORM 1). Masses,
nodal rotational inertia and the critical step: :mod:`hollowbody.elements.beam_section`.
"""

from __future__ import annotations

import numpy as np

from hollowbody.elements.beam_kernels import (
    LAW_INTEGRATED,
    LAW_RESULTANT,
    N_SEC,
    S_E,
    S_EA,
    S_EIS,
    S_EIT,
    S_GJ,
    S_GS,
    S_HK,
    S_PHIS,
    S_PHIT,
    S_PLASTIC,
    beam_forces,
)
from hollowbody.elements.beam_section import (
    element_step,
    exact_constants,
    rotational_r2,
    section_points,
)
from hollowbody.errors import DeckError
from hollowbody.materials.plane_stress_material import SHELL_MATERIAL_KINDS, shell_material
from hollowbody.model.beams import BeamGroup, beam_frames, section_constants
from hollowbody.model.model import Curve, MaterialDef, SectionDef


class BeamGroupRuntime:
    """Beams of one part.

    Attributes (e elements, p stress points): pid; elem_ids (e,) int64; conn
    (e, 2) int32 (N1, N2); n_elem; alive (e,) bool; elform 1 or 2; mass (e,) kg
    (rho A L + NSM L); r2 (e,) mm^2 (nodal rotational inertia per nodal mass);
    length0 (e,) mm; resultants (e, 6): N, Q_s, Q_t (kN), T, M_s, M_t (kN mm)
    in the local frame; stress (e, 6) GPa: the mean section stress in the local
    (r, s, t) frame, Voigt order (N/A, 0, 0, Q_s/A, 0, Q_t/A); plastic_strain
    (e,) largest effective plastic strain over the points; internal_energy,
    hourglass_energy (0) J; failed: indices of beams deleted by material
    failure (FAIL of the material: a stress point whose effective plastic
    strain reaches it carries no stress from then on, the beam goes when all
    its points have failed).
    """

    family = "beams"
    rotational = True
    #: attributes that change in time (restored in place or by assignment)
    STATE_FIELDS: tuple[str, ...] = ("alive", "triad", "nat", "force", "resultants", "stress",
                                     "sig", "back", "eps_p", "pfail", "plastic_strain",
                                     "_dte", "internal_energy", "hourglass_energy", "failed")

    def __init__(self, group: BeamGroup, material: MaterialDef, section: SectionDef,
                 curves: dict[int, Curve], node_x0: np.ndarray) -> None:
        self.pid = int(group.pid)
        self.elem_ids = np.asarray(group.elem_ids, dtype=np.int64)
        full = np.asarray(group.conn, dtype=np.int32)
        self.conn = np.ascontiguousarray(full[:, :2])
        self.n_elem = e = int(self.conn.shape[0])
        self.warnings: list[str] = []
        self.elform = int(section.elform)
        src = section.source
        if material.kind not in SHELL_MATERIAL_KINDS:
            raise DeckError(f"material {material.mid} ({material.keyword or material.kind}) of "
                            f"part {self.pid} is not available for beams (MAT_ELASTIC, "
                            "MAT_PLASTIC_KINEMATIC, MAT_PIECEWISE_LINEAR_PLASTICITY)",
                            material.source.file, material.source.line,
                            material.keyword or None)
        mat = shell_material(material, curves)
        if self.elform == 2 and mat.kind != 0:
            raise DeckError(f"part {self.pid}: the resultant beam (ELFORM 2) is elastic here; "
                            f"material {material.mid} is plastic (use ELFORM 1 with "
                            "cross-section integration)", src.file, src.line, "SECTION_BEAM")
        self.material = mat
        e_mod, nu, rho = mat.e_mod, mat.nu, mat.density
        g_mod = 0.5 * e_mod / (1.0 + nu)
        p = section.params
        shrf = float(p.get("SHRF", 1.0) or 1.0)
        frames, length, _bad = beam_frames(full, np.asarray(node_x0, dtype=np.float64))
        self.frame0 = np.ascontiguousarray(frames)
        self.length0 = np.ascontiguousarray(length)
        self.sec = np.zeros(N_SEC)
        # the mass is that of the section's shape (what model.mass lumps), the
        # stiffness that of its stress points
        mass_area = section_constants(self.elform, p)[0]
        if self.elform == 2:
            area, iss, itt, tors = p["A"], p["ISS"], p["ITT"], p["J"]
            sa = float(p.get("SA", 0.0))
            kga = g_mod * sa if sa > 0.0 else np.inf
            self.law = LAW_RESULTANT
            self.pts = np.zeros((1, 3))
            self.sec[S_EA], self.sec[S_GJ] = e_mod * area, g_mod * tors
            self.sec[S_EIS], self.sec[S_EIT] = e_mod * iss, e_mod * itt
            if sa > 0.0:  # Timoshenko: P = sec[S_PHI*] / L^2 in the kernel
                self.sec[S_PHIS] = 12.0 * e_mod * iss / kga
                self.sec[S_PHIT] = 12.0 * e_mod * itt / kga
        else:
            area, iss, itt, tors = exact_constants(p)
            self.law = LAW_INTEGRATED
            if group.rule is not None:  # *INTEGRATION_BEAM points
                ts, tt = 0.5 * (p["TS1"] + p["TS2"]), 0.5 * (p["TT1"] + p["TT2"])
                r = np.asarray(group.rule, dtype=np.float64)
                self.pts = np.ascontiguousarray(np.column_stack(
                    [0.5 * ts * r[:, 0], 0.5 * tt * r[:, 1], ts * tt * r[:, 2]]))
                w = self.pts[:, 2]
                area = float(w.sum())
                iss = float((w * self.pts[:, 1] ** 2).sum())
                itt = float((w * self.pts[:, 0] ** 2).sum())
                tors = iss + itt
            else:
                self.pts = np.ascontiguousarray(section_points(p))
            kga = shrf * g_mod * area
            self.sec[S_E], self.sec[S_GS], self.sec[S_HK] = e_mod, shrf * g_mod, mat.hk
            self.sec[S_PLASTIC] = float(mat.kind != 0)
        self.area, self.iss, self.itt, self.torsion = float(area), float(iss), float(itt), \
            float(tors)
        nsm = float(p.get("NSM", 0.0))
        self.mass = (rho * mass_area + nsm) * self.length0
        self.r2 = rotational_r2(self.length0, area, iss, itt)
        m_node = 0.5 * self.mass
        self.dt0 = np.ascontiguousarray(element_step(
            self.length0, m_node, m_node * self.r2, e_mod, g_mod, area, iss, itt, tors, kga,
            cubic=self.elform == 2))
        self.wave_speed = float(np.sqrt(e_mod / rho))
        self.hard_x = np.ascontiguousarray(mat.hard_x, dtype=np.float64)
        self.hard_y = np.ascontiguousarray(mat.hard_y, dtype=np.float64)
        self.params = mat.params()  # packed, for the strain-rate factor
        self.rate_x = np.ascontiguousarray(mat.rate_x, dtype=np.float64)
        self.rate_y = np.ascontiguousarray(mat.rate_y, dtype=np.float64)
        npt = self.pts.shape[0]
        # state
        self.alive = np.ones(e, dtype=bool)
        self.triad = np.zeros((e, 2, 3, 3))
        self.triad[:, :, 0, 0] = self.triad[:, :, 1, 1] = self.triad[:, :, 2, 2] = 1.0
        self.nat = np.zeros((e, 6))
        self.force = np.zeros((e, 6))
        self.resultants = np.zeros((e, 6))
        self.stress = np.zeros((e, 6))
        self.sig = np.zeros((e, npt, 3))
        self.back = np.zeros((e, npt, 3))
        self.eps_p = np.zeros((e, npt))
        self.pfail = np.zeros((e, npt), dtype=np.uint8)
        #: indices of the beams deleted by material failure, in order
        self.failed: list[int] = []
        self.plastic_strain = np.zeros(e)
        self.internal_energy = 0.0
        self.hourglass_energy = 0.0
        self._dte = np.full(e, np.inf)
        self._ework = np.zeros(e)
        self._rot = np.zeros((e, 6))

    # -- set-up helpers -----------------------------------------------------------
    def _spread(self, n_nodes: int, values: np.ndarray) -> np.ndarray:
        out = np.zeros(n_nodes)
        np.add.at(out, self.conn[:, 0], 0.5 * values)
        np.add.at(out, self.conn[:, 1], 0.5 * values)
        return out

    def lumped_mass(self, n_nodes: int) -> np.ndarray:
        """(n,) kg: half of each beam's mass (rho A L + NSM L) on each node."""
        return self._spread(n_nodes, self.mass)

    def lumped_rotational_inertia(self, n_nodes: int) -> np.ndarray:
        """(n,) kg mm^2: ``m_node * r2`` per node (beam_section module docstring)."""
        return self._spread(n_nodes, self.mass * self.r2)

    @property
    def dt_elem(self) -> np.ndarray:
        """(e,) ms critical step of each element at the last call (inf when deleted)."""
        return self._dte

    @property
    def inverted(self) -> np.ndarray:
        """(e,) bool: beams never turn inside out (all False; the solver's erosion
        asks volume-less groups for this)."""
        return np.zeros(self.n_elem, dtype=bool)

    # -- the cycle ---------------------------------------------------------------
    def add_forces(self, x: np.ndarray, v: np.ndarray, dt: float, f: np.ndarray,
                   w: np.ndarray | None = None, moment: np.ndarray | None = None
                   ) -> tuple[float, int, int]:
        """Update the beams and add their nodal forces (kN) into f (n, 3) and moments
        (kN mm) into moment (n, 3).

        x (n, 3) mm at t^{n+1}; v (n, 3) mm/ms and w (n, 3) rad/ms at t^{n+1/2}
        (w None: the nodes do not rotate); dt ms (0 allowed). Returns
        ``(dt_crit ms, index in group, -1)``: the smallest critical step over
        live beams and its beam (inf, -1 when none); beams do not invert.
        """
        if w is None:
            w = np.zeros_like(x)
        if moment is None:
            moment = np.zeros_like(x)
        d, i, de = beam_forces(x, w, float(dt), f, moment, self.conn, self.alive, self.frame0,
                               self.length0, self.triad, self.nat, self.force, self.resultants,
                               self.law, self.sec, self.pts, self.sig, self.back, self.eps_p,
                               self.pfail, self.hard_x, self.hard_y, self.params, self.rate_x,
                               self.rate_y, self.dt0, self._dte, self._ework,
                               self._rot)
        self.internal_energy += de
        self.stress[:, 0] = self.resultants[:, 0] / self.area
        self.stress[:, 3] = self.resultants[:, 1] / self.area
        self.stress[:, 5] = self.resultants[:, 2] / self.area
        if self.law == LAW_INTEGRATED and self.sec[S_PLASTIC] > 0.0:
            np.max(self.eps_p, axis=1, out=self.plastic_strain)
            if self.material.fail > 0.0 and len(self.failed) < self.n_elem:
                gone = np.nonzero(~self.alive & (self.pfail.min(axis=1) > 0))[0]
                known = set(self.failed)
                self.failed.extend(int(k) for k in gone if int(k) not in known)
        return float(d), int(i), -1

    def erode(self, idx: np.ndarray) -> None:
        """Delete beams ``idx`` (no force, no step from them)."""
        self.alive[idx] = False
        self.force[idx] = 0.0
        self.resultants[idx] = 0.0
        self.stress[idx] = 0.0
        self._dte[idx] = np.inf


def beam_runtimes(model, x0: np.ndarray) -> list:  # noqa: ANN001 - Model
    """One runtime per beam group of ``model`` (rigid parts get none); x0 (n, 3) mm."""
    out = []
    for g in model.beam_groups:
        mat = model.material_of(g.pid)
        if mat.kind == "rigid":
            part = model.parts[g.pid]
            raise DeckError(f"part {g.pid}: rigid beams (*MAT_RIGID) are not supported",
                            part.source.file, part.source.line, "PART")
        sec = model.sections[model.parts[g.pid].secid]
        out.append(BeamGroupRuntime(g, mat, sec, model.curves, x0))
    return out
