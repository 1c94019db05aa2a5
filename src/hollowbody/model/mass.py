"""Lumped nodal masses and rigid-body mass properties.

Solids: each element's mass ``rho * V0`` is shared equally by its distinct
nodes (8 for a hexahedron, 6 for a wedge, 4 for a tetrahedron). Shells:
``rho * A * t`` (mean nodal thickness) shared equally by the 4 (3) distinct
nodes. *ELEMENT_MASS adds to its node. All vectorised numpy; used once at
set-up, not in the time loop.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.model.beams import beam_masses
from hollowbody.model.model import Model

# Hexahedron split into 6 tetrahedra around the diagonal 0-6 (exact for
# planar-faced hexes, consistent for degenerate ones: collapsed tets add 0).
_HEX_TETS = np.array([[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6],
                      [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]])


def hex_volumes(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Volumes of (possibly degenerate) hexahedra.

    conn: (e, 8) int node indices; x: (n, 3) mm. Returns (e,) mm^3. Uses the
    exact trilinear volume (sum of the 12 triple products of the
    Flanagan-Belytschko volume formula reduces to this for planar faces;
    here the 6-tetrahedron split, exact when faces are planar).
    """
    xe = x[conn]  # (e, 8, 3)
    vol = np.zeros(conn.shape[0])
    for a, b, c, d in _HEX_TETS:
        p0 = xe[:, a]
        vol += np.einsum("ij,ij->i", np.cross(xe[:, b] - p0, xe[:, c] - p0), xe[:, d] - p0)
    return vol / 6.0


def quad_areas(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Areas of quadrilaterals (triangles when N4 == N3). conn (e, 4); returns (e,) mm^2."""
    xe = x[conn]
    d1 = xe[:, 2] - xe[:, 0]
    d2 = xe[:, 3] - xe[:, 1]
    return 0.5 * np.linalg.norm(np.cross(d1, d2), axis=1)


def _distinct_counts(conn: np.ndarray) -> np.ndarray:
    s = np.sort(conn, axis=1)
    return 1 + np.count_nonzero(np.diff(s, axis=1), axis=1)


def spread_element_mass(node_mass: np.ndarray, conn: np.ndarray, elem_mass: np.ndarray) -> None:
    """Add elem_mass (e,) equally to the distinct nodes of each element."""
    s = np.sort(conn, axis=1)
    first = np.ones_like(s, dtype=bool)
    first[:, 1:] = s[:, 1:] != s[:, :-1]
    share = elem_mass / _distinct_counts(conn)
    np.add.at(node_mass, s[first], np.broadcast_to(share[:, None], s.shape)[first])


def lumped_node_mass(model: Model, x0: np.ndarray | None = None
                     ) -> tuple[np.ndarray, dict[int, float]]:
    """Lumped nodal masses from the initial coordinates x0 (n, 3) mm (None:
    ``model.node_x0``; a run passes its tied contacts' coordinates).

    Returns ``node_mass`` (n,) kg and ``part_mass`` {pid: kg} (element masses
    only; *ELEMENT_MASS is in ``node_mass`` but in no part).
    """
    x0 = model.node_x0 if x0 is None else x0
    node_mass = model.node_extra_mass.astype(np.float64).copy()
    part_mass: dict[int, float] = {}
    for g in model.solid_groups:
        rho = model.material_of(g.pid).density
        m = rho * np.abs(hex_volumes(g.conn, x0))
        spread_element_mass(node_mass, g.conn, m)
        part_mass[g.pid] = part_mass.get(g.pid, 0.0) + float(m.sum())
    for g in model.shell_groups:
        rho = model.material_of(g.pid).density
        m = rho * quad_areas(g.conn, x0) * g.thickness.mean(axis=1)
        spread_element_mass(node_mass, g.conn, m)
        part_mass[g.pid] = part_mass.get(g.pid, 0.0) + float(m.sum())
    for g in model.beam_groups:  # [beams] rho A L + NSM L, half on each end node
        sec = model.sections[model.parts[g.pid].secid]
        m = beam_masses(g, model.material_of(g.pid).density, sec.elform, sec.params, x0)
        spread_element_mass(node_mass, g.conn[:, :2], m)
        part_mass[g.pid] = part_mass.get(g.pid, 0.0) + float(m.sum())
    return node_mass, part_mass


def part_nodes(model: Model, pid: int) -> np.ndarray:
    """Sorted unique node indices used by the elements of part ``pid`` (solids, shells,
    beams' N1 and N2, discrete elements)."""
    conns = [g.conn.ravel() for g in model.solid_groups if g.pid == pid]
    conns += [g.conn.ravel() for g in model.shell_groups if g.pid == pid]
    conns += [g.conn[:, :2].ravel() for g in model.beam_groups if g.pid == pid]
    conns += [np.concatenate([g.n1, g.n2]) for g in model.discrete_groups if g.pid == pid]
    conns = [c[c >= 0] for c in conns]  # a grounded spring's N2 is no node
    if not conns:
        return np.zeros(0, dtype=np.int64)
    return np.unique(np.concatenate(conns)).astype(np.int64)


@dataclass
class MassProperties:
    """Mass, centre of mass (3,) mm and inertia tensor (3, 3) kg*mm^2 about it."""

    mass: float
    centre: np.ndarray
    inertia: np.ndarray


def point_mass_properties(x: np.ndarray, m: np.ndarray) -> MassProperties:
    """Mass properties of point masses x (k, 3) mm, m (k,) kg."""
    total = float(m.sum())
    if total <= 0.0:
        return MassProperties(0.0, np.zeros(3), np.zeros((3, 3)))
    xc = (m[:, None] * x).sum(axis=0) / total
    r = x - xc
    r2 = np.einsum("ij,ij->i", r, r)
    inertia = np.eye(3) * float((m * r2).sum()) - np.einsum("i,ij,ik->jk", m, r, r)
    return MassProperties(total, xc, inertia)
