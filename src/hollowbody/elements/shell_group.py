"""Runtime of one group of Belytschko-Lin-Tsay shells (one part, one material, one section).

The time loop calls :meth:`ShellGroupRuntime.add_forces` once per cycle with
the positions at t^{n+1}, the velocities and angular velocities at t^{n+1/2};
the runtime updates its stresses and adds nodal forces and moments. See
:mod:`hollowbody.elements.shell_bt_forces` for the element and
``docs/shells.md`` for the formulation, its options and its limits.

Section (``SectionDef.params``): NIP (0/missing = 2), QR (0 Gauss, -1 Lobatto,
1 trapezoidal), SHRF (0/missing = 5/6); the thickness comes from the
``ShellGroup`` (mean of the 4 nodal thicknesses). ELFORM 2 (and 0) is the
Belytschko-Tsay shell; any other ELFORM runs as Belytschko-Tsay too and is
reported in :attr:`ShellGroupRuntime.warnings`.

Rotational inertia (LS-DYNA style scaling so rotations never govern the time
step): every distinct node of an element gets ``m_e / n_nodes * max(t^2/12,
A/4)`` (m_e = rho A t). An element-level eigen-analysis (docs/shells.md) shows
that with A/4 the rotation-dominated modes (bending, transverse shear,
drilling) stay below the membrane modes that set dt = L_s / c for squares,
rectangles, distorted quadrilaterals and triangles; A/8 is not enough for
square elements with nu = 0. Thick elements (t^2 > 3 A) keep the physical
rotary inertia t^2 / 12.

Drilling: nodal rotations about the element normal have no stiffness in the
Belytschko-Tsay shell, and by default none is added (``drilling=0``, LS-DYNA's
element): an element neither resists nor produces a moment about its normal.
An optional elastic drilling stiffness ``drilling * G t A`` per node ties them
to the element's in-plane spin (its energy is reported with the hourglass
energy); it is needed only where an external moment acts about a shell's
normal at a node no other element turns (a fixed-axis end moment on a rolled-up
strip spins its free tip otherwise), and it holds the corner between two walls
like a stiff hinge (folding tubes crush 1.2-1.5x too stiffly with 0.1, see
docs/crush.md). ``drilling_tangent`` (default
False, opt-in; in a run ``Model.controls.shell_tangent_drilling``) loads the
springs with the section's tangent ratio times their stiffness and unloads
them elastically (a yielded wall no longer holds a corner between two walls
like a stiff hinge); ``hourglass_tangent`` (default False, experimental, not
an LS-DYNA form) relaxes the stiffness hourglass forces (IHQ 4, 5) with the
tangent ratio. See docs/shells.md.
"""

from __future__ import annotations

import numpy as np

from hollowbody.elements.shell_bt_forces import (
    HG_NONE,
    HG_STIFFNESS,
    HG_VISCOUS,
    K_DRILL,
    K_DRILL_TANGENT,
    K_HG_KIND,
    K_HG_TANGENT,
    K_QH,
    K_SHRF,
    K_THICK_UPDATE,
    N_CONTROLS,
    bt_shell_forces,
)
from hollowbody.elements.shell_gather import gather_node_forces, node_gather_map
from hollowbody.elements.shell_thickness_rules import through_thickness_rule
from hollowbody.errors import DeckError
from hollowbody.materials.plane_stress_material import PlaneStressMaterial, shell_material
from hollowbody.materials.shell_laws import SHELL_LAWS
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, SectionDef, ShellGroup

DEFAULT_SHRF = 5.0 / 6.0
#: Drilling stiffness factor: k = factor * G t A per node (see docs/shells.md); 0 is
#: LS-DYNA's Belytschko-Tsay shell, whose drilling rotations are free.
DEFAULT_DRILLING = 0.0
#: Factor of the opt-in tangent drilling spring when none is given.
TANGENT_DRILLING = 0.1


def drilling_factor(given: float | None, tangent: bool) -> float:
    """The drilling stiffness factor of a run: ``given`` if set, else
    :data:`TANGENT_DRILLING` with the tangent spring on, else :data:`DEFAULT_DRILLING`."""
    if given is not None:
        if given < 0.0:
            raise ValueError(f"shell drilling factor must be >= 0 (got {given:g})")
        return float(given)
    return TANGENT_DRILLING if tangent else DEFAULT_DRILLING
SUPPORTED_ELFORM = (0, 2)


def _quad_geometry(conn: np.ndarray, x: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Areas (e,) mm^2 (half the diagonal cross product), triangle flags (e,)
    bool and unit normals (e,3) (the Belytschko-Tsay e3 direction)."""
    xe = x[conn]
    n = np.cross(xe[:, 2] - xe[:, 0], xe[:, 3] - xe[:, 1])
    norm = np.linalg.norm(n, axis=1)
    unit = n / np.where(norm > 0.0, norm, 1.0)[:, None]
    return 0.5 * norm, conn[:, 2] == conn[:, 3], unit


class ShellGroupRuntime:
    """Belytschko-Lin-Tsay shells of one part.

    Attributes (e = number of elements): pid; elem_ids (e,) int64; conn (e,4)
    int32; n_elem; alive (e,) bool; thickness (e,) mm used by the element
    (constant unless ``thickness_update``); thickness_strain (e,) through-
    thickness log strain (tracked always); stress (e,6) GPa global Voigt
    membrane stress (mean over the thickness) with the transverse shears;
    plastic_strain (e,) max effective plastic strain over the points;
    internal_energy, hourglass_energy: J cumulative; mass (e,) kg;
    warnings: list of str about substitutions made; failed: list of element
    indices deleted by material failure (in order).
    """

    rotational = True
    #: Attributes that change in time (saved and restored by a restart): arrays
    #: are restored in place, the floats and the ``failed`` list by assignment.
    #: ``flip`` and ``_dte`` (``inverted``, ``dt_elem``) are the last call's
    #: results the solver reads between calls.
    STATE_FIELDS: tuple[str, ...] = (
        "alive", "thickness", "thickness_strain", "sig", "epsp", "back", "pfail", "tau",
        "hgq", "drill", "stress", "plastic_strain", "normal", "flip", "_dte",
        "internal_energy", "hourglass_energy", "failed")

    def __init__(self, group: ShellGroup, material: MaterialDef, section: SectionDef,
                 hourglass: HourglassDef, curves: dict[int, Curve], node_x0: np.ndarray,
                 *, thickness_update: bool = False, drilling: float = DEFAULT_DRILLING,
                 drilling_tangent: bool = False, hourglass_tangent: bool = False) -> None:
        self.pid = int(group.pid)
        self.elem_ids = np.asarray(group.elem_ids, dtype=np.int64)
        self.conn = np.ascontiguousarray(group.conn, dtype=np.int32)
        self.n_elem = int(self.conn.shape[0])
        self.warnings: list[str] = []
        self.failed: list[int] = []
        e = self.n_elem
        src = section.source
        self.material: PlaneStressMaterial = shell_material(material, curves)
        elform = int(section.elform)
        if elform not in SUPPORTED_ELFORM:
            self.warnings.append(f"part {self.pid}: shell ELFORM {elform} runs as "
                                 "Belytschko-Tsay (ELFORM 2)")
        p = section.params
        try:
            self.zeta, self.weights = through_thickness_rule(float(p.get("NIP", 0.0) or 0.0),
                                                             float(p.get("QR", 0.0) or 0.0))
        except ValueError as err:
            raise DeckError(f"section {section.secid}: {err}", src.file, src.line,
                            "SECTION_SHELL") from None
        self.nip = int(self.zeta.size)
        shrf = float(p.get("SHRF", 0.0) or 0.0)
        self.shrf = shrf if shrf > 0.0 else DEFAULT_SHRF
        t0 = np.asarray(group.thickness, dtype=np.float64).mean(axis=1)
        if e and not np.all(t0 > 0.0):
            bad = int(self.elem_ids[np.nonzero(~(t0 > 0.0))[0][0]])
            raise DeckError(f"part {self.pid}: shell element {bad} has thickness <= 0",
                            src.file, src.line, "SECTION_SHELL")
        self.t0 = np.ascontiguousarray(t0)
        self.thickness = self.t0.copy()
        self.thickness_strain = np.zeros(e)
        self.thickness_update = bool(thickness_update)
        x0 = np.asarray(node_x0, dtype=np.float64)
        area, self.triangle, normal = _quad_geometry(self.conn, x0)
        self.area0 = area
        rho = self.material.density
        self.mass = rho * area * self.t0
        self.mass_q = 0.25 * self.mass
        self.r2 = np.maximum(self.t0 ** 2 / 12.0, area / 4.0)
        ihq = int(hourglass.ihq)
        self.qh = float(hourglass.qm)
        if self.qh <= 0.0:
            self.hg_kind = HG_NONE
        elif ihq in (4, 5):
            self.hg_kind = HG_STIFFNESS
        else:
            self.hg_kind = HG_VISCOUS
            if ihq not in (0, 1, 2, 3):
                self.warnings.append(f"part {self.pid}: hourglass IHQ {ihq} runs as the "
                                     "Belytschko-Tsay viscous form for shells")
        self.params = self.material.params()
        self._law = SHELL_LAWS[self.material.kind]
        self.hard_x = np.ascontiguousarray(self.material.hard_x, dtype=np.float64)
        self.hard_y = np.ascontiguousarray(self.material.hard_y, dtype=np.float64)
        self.rate_x = np.ascontiguousarray(self.material.rate_x, dtype=np.float64)
        self.rate_y = np.ascontiguousarray(self.material.rate_y, dtype=np.float64)
        # state
        self.alive = np.ones(e, dtype=bool)
        self.sig = np.zeros((e, self.nip, 3))
        self.epsp = np.zeros((e, self.nip))
        self.back = np.zeros((e, self.nip, 3)) if self.material.hk > 0.0 else np.zeros((1, 1, 3))
        self.pfail = np.zeros((e, self.nip), dtype=np.uint8)
        self.tau = np.zeros((e, 2))
        self.hgq = np.zeros((e, 5))
        self.drill = np.zeros((e, 4))
        self.drilling = float(drilling)
        self.stress = np.zeros((e, 6))
        self.plastic_strain = np.zeros(e)
        self.normal = np.ascontiguousarray(normal)
        #: (e,) uint8: 1 for elements turned inside out in the last call (see
        #: :attr:`inverted`)
        self.flip = np.zeros(e, dtype=np.uint8)
        self.internal_energy = 0.0
        self.hourglass_energy = 0.0
        # work arrays, allocated once
        self._fe = np.zeros((e, 4, 6))
        self._dte = np.full(e, np.inf)
        self._die = np.zeros(e)
        self._dhe = np.zeros(e)
        self._nodes, self._ptr, self._ref = node_gather_map(self.conn)
        self._controls = np.zeros(N_CONTROLS)
        self._controls[K_SHRF] = self.shrf
        self._controls[K_HG_KIND] = self.hg_kind
        self._controls[K_QH] = self.qh
        self._controls[K_DRILL] = self.drilling
        self._controls[K_THICK_UPDATE] = 1.0 if self.thickness_update else 0.0
        self.drilling_tangent = bool(drilling_tangent)
        self.hourglass_tangent = bool(hourglass_tangent)
        self._controls[K_DRILL_TANGENT] = 1.0 if self.drilling_tangent else 0.0
        self._controls[K_HG_TANGENT] = 1.0 if self.hourglass_tangent else 0.0
        self._wzero = np.zeros((0, 3))
        self._mzero = np.zeros((1, 3))

    # -- set-up helpers -----------------------------------------------------------
    def lumped_rotational_inertia(self, n_nodes: int) -> np.ndarray:
        """(n,) kg*mm^2 nodal rotational inertia of this group.

        Each distinct node of an element gets ``m_e / k * max(t^2/12, A/4)``
        (k = 4 for quadrilaterals, 3 for triangles), so rotations never govern
        the time step (see the module docstring).
        """
        out = np.zeros(n_nodes)
        s = np.sort(self.conn, axis=1)
        first = np.ones_like(s, dtype=bool)
        first[:, 1:] = s[:, 1:] != s[:, :-1]
        share = self.mass * self.r2 / first.sum(axis=1)
        np.add.at(out, s[first], np.broadcast_to(share[:, None], s.shape)[first])
        return out

    def lumped_mass(self, n_nodes: int) -> np.ndarray:
        """(n,) kg nodal masses of this group (element mass shared by its distinct nodes)."""
        out = np.zeros(n_nodes)
        s = np.sort(self.conn, axis=1)
        first = np.ones_like(s, dtype=bool)
        first[:, 1:] = s[:, 1:] != s[:, :-1]
        share = self.mass / first.sum(axis=1)
        np.add.at(out, s[first], np.broadcast_to(share[:, None], s.shape)[first])
        return out

    # -- the cycle ---------------------------------------------------------------
    def add_forces(self, x: np.ndarray, v: np.ndarray, dt: float, f: np.ndarray,
                   w: np.ndarray | None = None, moment: np.ndarray | None = None
                   ) -> tuple[float, int, int]:
        """Update stresses and add nodal forces (and moments) of the group.

        x (n,3) mm at t^{n+1}; v (n,3) mm/ms and w (n,3) rad/ms at t^{n+1/2}
        (w None: no rotations); dt ms (0 allowed). Adds forces on the nodes
        (kN) into f (n,3) and moments (kN*mm) into moment (n,3) when given.
        Returns ``(dt_crit ms, index in group, inverted)``: the smallest
        unscaled critical step over live elements and its element (inf, -1 when
        none), and the index of the first element that collapsed in its plane
        this call (area below 1 % of the initial, or inside out: the shell
        counterpart of a solid's negative volume; -1 when none).
        """
        if w is None:
            if self._wzero.shape[0] != v.shape[0]:
                self._wzero = np.zeros_like(v)
            w = self._wzero
        with_moment = moment is not None
        mom = moment if with_moment else self._mzero
        n_alive_before = int(self.alive.sum()) if self.material.fail > 0.0 else 0
        geom = (self.conn, self.triangle, self.t0, self.mass_q, self.r2, self.area0,
                self.zeta, self.weights)
        state = (self.alive, self.thickness, self.thickness_strain, self.sig, self.tau,
                 self.hgq, self.drill, self.normal)
        params = (self.params, self.hard_x, self.hard_y, self.rate_x, self.rate_y)
        out = (self._fe, self._dte, self._die, self._dhe, self.stress, self.plastic_strain,
               self.flip)
        bt_shell_forces(self._law, x, v, w, float(dt), geom, state, params,
                        (self.epsp, self.back, self.pfail), self._controls, out)
        gather_node_forces(self._fe, self._nodes, self._ptr, self._ref, f, mom, with_moment)
        self.internal_energy += float(self._die.sum())
        self.hourglass_energy += float(self._dhe.sum())
        if n_alive_before and int(self.alive.sum()) < n_alive_before:
            self._record_failures()
        if self.n_elem == 0:
            return np.inf, -1, -1
        inv = int(np.argmax(self.flip)) if self.flip.any() else -1
        i = int(np.argmin(self._dte))
        d = float(self._dte[i])
        if not np.isfinite(d):
            return np.inf, -1, inv
        return d, i, inv

    @property
    def inverted(self) -> np.ndarray:
        """(e,) bool: live elements that collapsed in their plane in the last call."""
        return (self.flip > 0) & self.alive

    def _record_failures(self) -> None:
        known = set(self.failed)
        for i in np.nonzero(~self.alive & (self.pfail.min(axis=1) > 0))[0]:
            if int(i) not in known:
                self.failed.append(int(i))

    def erode(self, idx: np.ndarray) -> None:
        """Delete elements ``idx`` (indices in the group): no more forces, stress or step."""
        idx = np.asarray(idx, dtype=np.int64)
        self.alive[idx] = False
        self.stress[idx] = 0.0
        self._fe[idx] = 0.0
        self._dte[idx] = np.inf

    @property
    def dt_elem(self) -> np.ndarray:
        """(e,) ms unscaled critical step of each element at the last call (inf: deleted)."""
        return self._dte

    # -- output helpers ------------------------------------------------------------
    def point_stress(self) -> np.ndarray:
        """(e, nip, 3) GPa local in-plane stress (xx, yy, xy) at the integration points."""
        return self.sig.copy()

    @property
    def point_plastic_strain(self) -> np.ndarray:
        """(e, nip) effective plastic strain at the integration points."""
        return self.epsp
