"""Beam models for tests, the example and the benchmark (docs/beams.md).

- :func:`cantilever_deck`: keyword text of a straight beam along x, node 1
  clamped (all six degrees of freedom), ``n`` elements, ELFORM 1 or 2,
  *MAT_ELASTIC or *MAT_PLASTIC_KINEMATIC;
- :class:`EndLoad`: a force term (``solver.terms`` interface) that puts a
  ramped force and moment on one node and, optionally, mass-proportional
  damping on every node (dynamic relaxation to a static solution); its work
  is the run's external work (damping is reported separately).

Units mm, ms, kg, kN, GPa.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def _f(v: float) -> str:
    s = f"{v:.6g}"
    return s.rjust(10) if len(s) <= 10 else f"{v:10.3e}"


def cantilever_deck(n: int = 10, length: float = 100.0, elform: int = 2, *,
                    width: float = 5.0, height: float = 5.0, tube: tuple[float, float] | None
                    = None, qr: int = 2, shrf: float = 5.0 / 6.0, e_mod: float = 200.0,
                    nu: float = 0.3, rho: float = 7.85e-6, sigy: float = 0.0,
                    etan: float = 0.0, end_time: float = 1.0, tssfac: float = 0.9,
                    orientation: bool = True, shear_area: float | None = None,
                    gauss_rule: tuple[int, int] | None = None, clamped: bool = True,
                    src: float = 0.0, srp: float = 0.0, fail: float = 0.0) -> str:
    """Keyword text of a clamped beam along +x (nodes 1..n+1, elements 1..n).

    Section: rectangle ``width`` (s, along global y) x ``height`` (t, along z),
    or ``tube`` = (outer, inner diameter) for ELFORM 1. ELFORM 2 gets the
    rectangle's A, ISS, ITT, J (St Venant torsion constant of the rectangle)
    and SA = shrf A (or ``shear_area``). sigy > 0: *MAT_PLASTIC_KINEMATIC with
    ETAN (BETA 1, isotropic), else *MAT_ELASTIC. orientation: N3 node above
    the root (node n+2 at y = 10), else no N3. gauss_rule (n_s, n_t): ELFORM 1
    with an *INTEGRATION_BEAM rule (IRID 1) of n_s x n_t Gauss points.
    clamped: node 1 fixed (else the beam is free). src, srp: Cowper-Symonds
    constants of the *MAT_PLASTIC_KINEMATIC (1/ms; 0 = none). fail > 0: a
    *MAT_PIECEWISE_LINEAR_PLASTICITY (SIGY, ETAN) with that FAIL instead.
    """
    lines = ["*KEYWORD", "*TITLE", "beam cantilever", "*CONTROL_TERMINATION",
             _f(end_time), "*CONTROL_TIMESTEP", _f(0.0) + _f(tssfac), "*NODE"]
    for k in range(n + 1):
        lines.append(f"{k + 1:8d}{length * k / n:16.8g}{0.0:16.8g}{0.0:16.8g}")
    lines.append(f"{n + 2:8d}{0.0:16.8g}{10.0:16.8g}{0.0:16.8g}")
    lines.append("*ELEMENT_BEAM")
    n3 = n + 2 if orientation else 0
    for k in range(n):
        lines.append(f"{k + 1:8d}{1:8d}{k + 1:8d}{k + 2:8d}{n3:8d}")
    lines += ["*PART", "beam", f"{1:10d}{1:10d}{1:10d}", "*SECTION_BEAM"]
    if elform == 2:
        b, h = width, height
        area = b * h
        iss, itt = b * h ** 3 / 12.0, h * b ** 3 / 12.0
        a, c = max(b, h), min(b, h)
        tors = a * c ** 3 * (1.0 / 3.0 - 0.21 * c / a * (1.0 - c ** 4 / (12.0 * a ** 4)))
        sa = shrf * area if shear_area is None else shear_area
        lines.append(f"{1:10d}{2:10d}{_f(1.0)}{2:10d}{0:10d}")
        lines.append("".join(_f(v) for v in (area, iss, itt, tors, sa)))
    else:
        cst = 1 if tube else 0
        rule = -1 if gauss_rule else qr
        lines.append(f"{1:10d}{1:10d}{_f(shrf)}{rule:10d}{cst:10d}")
        dims = (tube[0], tube[0], tube[1], tube[1]) if tube else (width, width, height, height)
        lines.append("".join(_f(v) for v in dims))
        if gauss_rule:
            xs, ws = np.polynomial.legendre.leggauss(gauss_rule[0])
            xt, wt = np.polynomial.legendre.leggauss(gauss_rule[1])
            lines += ["*INTEGRATION_BEAM", f"{1:10d}{xs.size * xt.size:10d}{_f(1.0)}"]
            for a, wa in zip(xs, ws):
                for b, wb in zip(xt, wt):
                    lines.append(f"{a:10.7f}{b:10.7f}{0.25 * wa * wb:10.7f}")
    if sigy > 0.0 and fail > 0.0:
        lines += ["*MAT_PIECEWISE_LINEAR_PLASTICITY", "".join(
            [f"{1:10d}", _f(rho), _f(e_mod), _f(nu), _f(sigy), _f(etan), _f(fail)])]
    elif sigy > 0.0:
        lines += ["*MAT_PLASTIC_KINEMATIC", "".join(
            [f"{1:10d}", _f(rho), _f(e_mod), _f(nu), _f(sigy), _f(etan), _f(1.0)]),
            _f(src) + _f(srp)]
    else:
        lines += ["*MAT_ELASTIC", f"{1:10d}{_f(rho)}{_f(e_mod)}{_f(nu)}"]
    if clamped:
        lines += ["*BOUNDARY_SPC_NODE", f"{1:10d}{0:10d}" + f"{1:10d}" * 6]
    if orientation:
        lines += ["*BOUNDARY_SPC_NODE", f"{n + 2:10d}{0:10d}" + f"{1:10d}" * 6]
    lines.append("*END")
    return "\n".join(lines) + "\n"


class EndLoad:
    """Force term: ``force(t)`` (3,) kN and ``moment(t)`` (3,) kN mm on node ``node``
    (a 0-based index), and damping ``-damping m v`` (1/ms) on every node; or
    ``spin(t)`` (3,) rad/ms / ``velocity(t)`` (3,) mm/ms: the node's rotational /
    translational velocity imposed.

    ``external_work`` (J): the load's work (trapezoid of force times the
    displacement increments); ``damping_work`` (J): energy taken by damping.
    """

    STATE_FIELDS = ("external_work", "damping_work", "_last_f", "_last_m")

    def __init__(self, node: int, force: Callable[[float], np.ndarray] | None = None,
                 moment: Callable[[float], np.ndarray] | None = None,
                 damping: float = 0.0, spin: Callable[[float], np.ndarray] | None = None,
                 velocity: Callable[[float], np.ndarray] | None = None) -> None:
        self.node = int(node)
        self.spin = spin
        self.velocity = velocity
        self.force = force
        self.moment = moment
        self.damping = float(damping)
        self.external_work = 0.0
        self.damping_work = 0.0
        self._last_f = np.zeros(3)
        self._last_m = np.zeros(3)

    def constrain(self, state, dt: float) -> None:  # noqa: ANN001
        """With ``spin``: the node's rotational velocity (rad/ms) imposed at t + dt / 2."""
        if self.spin is not None:
            state.w[self.node] = np.asarray(self.spin(state.t + 0.5 * dt), float)
        if self.velocity is not None:
            state.v[self.node] = np.asarray(self.velocity(state.t + 0.5 * dt), float)

    def add_forces(self, state, dt: float) -> tuple[float, int, int]:  # noqa: ANN001
        """Add the load (and damping) at t^{n+1}; its work over the last step."""
        i = self.node
        fv = np.zeros(3) if self.force is None else np.asarray(self.force(state.t), float)
        mv = np.zeros(3) if self.moment is None else np.asarray(self.moment(state.t), float)
        # work over the step just taken: mean load times the displacement / rotation
        self.external_work += dt * float(0.5 * (fv + self._last_f) @ state.v[i])
        self.external_work += dt * float(0.5 * (mv + self._last_m) @ state.w[i])
        self._last_f[:] = fv
        self._last_m[:] = mv
        state.f[i] += fv
        state.mom[i] += mv
        if self.damping > 0.0:
            fd = self.damping * state.node_mass[:, None] * state.v
            self.damping_work += dt * float((fd * state.v).sum())
            state.f -= fd
            md = self.damping * state.node_rot_inertia[:, None] * state.w
            self.damping_work += dt * float((md * state.w).sum())
            state.mom -= md
        return np.inf, -1, -1
