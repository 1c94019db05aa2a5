"""Mass of a hollowized part: wall density and nodal masses that keep mass, centre and inertia.

The removed solids' mass properties (exact, continuous body: mass ``M``,
centre ``c``, inertia ``J`` about ``c``) are the target. The walls are seen
as the solver and LS-DYNA see them: each shell's mass ``rho A t`` shared
equally by its distinct nodes (lumped). With a fraction ``phi`` of ``M`` in
the walls' density (``rho = phi M / sum(A t)``), the rest is put on the
wall nodes as point masses (*ELEMENT_MASS) ``e >= 0`` chosen so that all ten
moments match exactly: mass, first moments (centre) and second moments
(inertia tensor). Among all such ``e`` the one closest to spreading the rest
like the walls' own mass is taken (weighted least change; nodes whose mass
would be negative are fixed at zero and the system re-solved). The inertia
target is first moved from the solid's toward the uniform walls' by as
much as keeps the principal moments within 80 % of the 5 % tolerance
(:func:`relaxed_target`), which keeps the point masses small.

- ``density`` mode: ``phi = 1`` (one density, no point masses) when that
  already meets the tolerances, else the largest ``phi`` for which the
  correction exists (a ladder of values, refined by bisection);
- ``nodal`` mode: the walls keep the tissue's density (``phi = rho_tissue
  sum(A t) / M``) and the rest is point masses.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.model.mass import (
    MassProperties,
    point_mass_properties,
    quad_areas,
    spread_element_mass,
)

#: Tolerances of the conversion: relative mass, centre distance (mm), relative principal moments.
TOL_MASS, TOL_CENTRE, TOL_INERTIA = 1e-3, 1.0, 0.05
#: Fractions of the mass tried in the walls' density (density mode), largest first.
PHI_LADDER = (1.0, 0.97, 0.94, 0.9, 0.85, 0.8, 0.75, 0.7, 0.6, 0.5, 0.4, 0.3, 0.2, 0.1, 0.0)


@dataclass
class MassPlan:
    """Mass of the walls: ``density`` kg/mm^3 of their material, ``nodal`` (n,) kg point
    masses on ``nodes`` (n,) (combined node indices; zeros where none), ``phi``: share of
    the mass in the density; ``exact``: all moments matched; ``note``: why not."""

    density: float
    nodes: np.ndarray
    nodal: np.ndarray
    phi: float
    exact: bool
    note: str = ""


def lumped_volumes(conn: np.ndarray, x: np.ndarray, thickness: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Shell volume ``A t`` lumped to the nodes: (nodes (n,), volume (n,) mm^3).

    conn (w, 4) node indices into x (N, 3) mm (triangles N4 == N3).
    """
    vol = quad_areas(conn, x) * thickness
    acc = np.zeros(x.shape[0])
    spread_element_mass(acc, conn, vol)
    nodes = np.unique(conn)
    return nodes, acc[nodes]


def compare(before: MassProperties, after: MassProperties) -> dict:
    """Errors of ``after`` against ``before``: relative mass, centre distance (mm),
    relative principal moments (3,) (sorted), and whether each is within tolerance."""
    mass_rel = (after.mass - before.mass) / before.mass if before.mass else 0.0
    dist = float(np.linalg.norm(after.centre - before.centre))
    pb = np.sort(np.linalg.eigvalsh(before.inertia))
    pa = np.sort(np.linalg.eigvalsh(after.inertia))
    rel = (pa - pb) / np.maximum(np.abs(pb), 1e-300)
    return {"mass_rel": float(mass_rel), "centre_mm": dist, "inertia_rel": rel.tolist(),
            "ok_mass": abs(mass_rel) <= TOL_MASS, "ok_centre": dist <= TOL_CENTRE,
            "ok_inertia": bool(np.all(np.abs(rel) <= TOL_INERTIA))}


def _moment_rows(x: np.ndarray, centre: np.ndarray, scale: float) -> np.ndarray:
    """(10, n) rows: 1, r, and the six second-moment products of r = (x - centre) / scale."""
    r = (x - centre) / scale
    return np.vstack([np.ones(x.shape[0]), r.T, r[:, 0] ** 2, r[:, 1] ** 2, r[:, 2] ** 2,
                      r[:, 0] * r[:, 1], r[:, 1] * r[:, 2], r[:, 2] * r[:, 0]])


def _targets(target: MassProperties, scale: float) -> np.ndarray:
    s = np.eye(3) * 0.5 * np.trace(target.inertia) - target.inertia  # sum m r r^T
    s = s / scale**2
    return np.array([target.mass, 0.0, 0.0, 0.0, s[0, 0], s[1, 1], s[2, 2], s[0, 1], s[1, 2],
                     s[2, 0]])


def _correction(a: np.ndarray, rhs: np.ndarray, prior: np.ndarray) -> np.ndarray | None:
    """e >= 0 with a e = rhs, closest to ``prior`` (weights = prior); None if none found."""
    free = prior > 0.0
    e = prior.copy()
    norm = max(float(np.abs(rhs).max()), 1e-300)
    for _ in range(60):
        if not free.any():
            return None
        af = a[:, free]
        p = prior[free]
        m = (af * p) @ af.T
        lam = np.linalg.lstsq(m, rhs - af @ p, rcond=1e-13)[0]
        e = np.zeros_like(prior)
        e[free] = p + p * (af.T @ lam)
        neg = e < 0.0
        if not neg.any():
            return e if np.abs(a @ e - rhs).max() <= 1e-8 * norm else None
        free &= ~neg
    return None


def relaxed_target(x: np.ndarray, volume: np.ndarray, target: MassProperties,
                   aim: float = 0.8 * TOL_INERTIA) -> MassProperties:
    """The target with its inertia moved toward that of uniform walls, so that the principal
    moments stay within ``aim`` (relative) of the target's: the correction then needs less
    point mass. Mass and centre are the target's."""
    walls = point_mass_properties(x, target.mass * volume / volume.sum())
    err = max(abs(v) for v in compare(target, walls)["inertia_rel"])
    beta = min(1.0, aim / err) if err > 0.0 else 0.0
    inertia = target.inertia + beta * (walls.inertia - target.inertia)
    return MassProperties(target.mass, target.centre, inertia)


def match_mass(x: np.ndarray, volume: np.ndarray, target: MassProperties, mode: str = "density",
               tissue_density: float = 0.0) -> MassPlan:
    """Wall density and point masses for nodes at x (n, 3) mm with lumped wall volume
    ``volume`` (n,) mm^3 so that the walls' mass properties equal ``target``.

    mode: ``density`` or ``nodal`` (see the module docstring); tissue_density
    kg/mm^3 (nodal mode). The returned plan's ``nodes`` are positions 0..n-1.
    """
    if mode not in ("density", "nodal"):
        raise ValueError(f"mass mode must be 'density' or 'nodal', not {mode!r}")
    total_v = float(volume.sum())
    n = x.shape[0]
    idx = np.arange(n)
    if target.mass <= 0.0 or total_v <= 0.0:
        return MassPlan(0.0, idx, np.zeros(n), 1.0, False, "no mass or no wall volume")
    scale = float(np.sqrt(max(np.trace(target.inertia) / (2.0 * target.mass), 1e-300)))
    a = _moment_rows(x, target.centre, scale)
    b = _targets(relaxed_target(x, volume, target), scale)
    share = volume / total_v
    if mode == "density":
        ladder = PHI_LADDER
    else:
        phi0 = min(1.0, tissue_density * total_v / target.mass)
        ladder = (phi0,) + tuple(p for p in PHI_LADDER if p < phi0)

    def attempt(phi: float) -> MassPlan | None:
        rho = phi * target.mass / total_v
        base = rho * volume
        if phi >= 1.0:
            err = compare(target, point_mass_properties(x, base))
            worst = max(abs(v) for v in err["inertia_rel"])
            if err["centre_mm"] <= 0.5 * TOL_CENTRE and worst <= 0.8 * TOL_INERTIA:
                return MassPlan(rho, idx, np.zeros(n), 1.0, False,
                                "uniform density meets the tolerances")
            return None
        e = _correction(a, b - a @ base, (1.0 - phi) * target.mass * share)
        return None if e is None else MassPlan(rho, idx, e, phi, True)

    failed = None
    for phi in ladder:
        plan = attempt(phi)
        if plan is None:
            failed = phi
            continue
        if failed is not None:
            lo, hi = phi, failed  # refine: largest feasible share in the walls' density
            for _ in range(6):
                mid = 0.5 * (lo + hi)
                better = attempt(mid) if mid < 1.0 else None
                if better is None:
                    hi = mid
                else:
                    lo, plan = mid, better
        return plan
    rho = target.mass / total_v
    return MassPlan(rho, idx, np.zeros(n), 1.0, False,
                    "no non-negative nodal-mass correction found; uniform density used")
