"""Hollow structures: shell walls on every face of a cubic grid of cells.

The paper's hollow block is a 6 x 6 x 3 grid of 30 mm cells whose every face
(outer faces included) is a 1.5 mm shell wall. Walls are meshed with
``elements_per_edge`` quadrilaterals along each cell edge; nodes are shared
wherever walls meet (conforming), because every node is a point of one global
lattice of spacing ``cell / elements_per_edge``.

Walls are grouped by orientation (normal along x, y or z), so each
orientation can be its own part.

Perfectly flat walls loaded in their own plane have no reason to buckle: the
discrete model crushes them in-plane (elements shorten to slivers, the time
step collapses) where a real wall, or the same model with the smallest
asymmetry, folds. ``imperfection`` gives every wall panel (one cell face) an
out-of-plane offset shaped like its first buckling mode,
``a sin(pi u / c) sin(pi v / c)`` (u, v in-panel coordinates, c the cell
size), with the sign alternating between neighbouring panels (checkerboard),
as the buckling modes of a stiffened wall grid alternate. The offset is zero
on every cell edge, so the walls still meet on straight, shared lines and the
grid stays conforming.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class HollowGrid:
    """Shell walls of a cell grid.

    nodes: (n, 3) float64 mm; quads: (q, 4) int64 node indices;
    orientation: (q,) int8 wall normal axis (0 x, 1 y, 2 z);
    cell: cell size mm; thickness: wall thickness mm.
    """

    nodes: np.ndarray
    quads: np.ndarray
    orientation: np.ndarray
    cell: float
    thickness: float

    @property
    def wall_area(self) -> float:
        """Total mid-surface wall area in mm^2."""
        x = self.nodes[self.quads]
        return float(0.5 * np.linalg.norm(np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 1]),
                                          axis=1).sum())

    def density_for_mass(self, mass: float) -> float:
        """Wall density (kg/mm^3) that makes the walls weigh ``mass`` kg."""
        return mass / (self.wall_area * self.thickness)


def hollow_box(size: tuple[float, float, float], cell: float = 30.0, thickness: float = 1.5,
               elements_per_edge: int = 4, origin: tuple[float, float, float] = (0.0, 0.0, 0.0),
               imperfection: float = 0.0) -> HollowGrid:
    """Walls of a box of ``size`` (mm) divided into cubic cells of edge ``cell``.

    ``cell`` must divide every side; walls on every cell face including the
    outer ones. ``origin`` is the box's minimum corner. ``imperfection`` is
    the amplitude (mm) of the out-of-plane panel offsets (module docstring;
    0 gives flat walls). ValueError for sizes the cell does not divide, fewer
    than one element per edge or an imperfection not smaller than the cell.
    """
    if elements_per_edge < 1:
        raise ValueError("elements_per_edge must be at least 1")
    if not 0.0 <= imperfection < 0.5 * cell:
        raise ValueError(f"imperfection must be in [0, cell/2) (got {imperfection:g} mm)")
    cells = []
    for s in size:
        k = s / cell
        if abs(k - round(k)) > 1e-9 * max(k, 1.0) or round(k) < 1:
            raise ValueError(f"cell size {cell:g} mm does not divide the side {s:g} mm")
        cells.append(int(round(k)))
    k = elements_per_edge
    dims = [c * k for c in cells]  # lattice intervals per axis
    h = cell / k
    on_wall = [np.arange(d + 1) % k == 0 for d in dims]

    index = -np.ones([d + 1 for d in dims], dtype=np.int64)
    ii, jj, ll = np.meshgrid(*[np.arange(d + 1) for d in dims], indexing="ij")
    used = on_wall[0][ii] | on_wall[1][jj] | on_wall[2][ll]
    # a lattice point is a node when at least one of its indices lies on a wall plane
    index[used] = np.arange(int(used.sum()))
    pts = np.column_stack([ii[used], jj[used], ll[used]]).astype(np.float64) * h
    nodes = pts + np.asarray(origin, dtype=np.float64)
    if imperfection > 0.0:
        lat = np.column_stack([ii[used], jj[used], ll[used]])
        nodes += panel_offsets(lat, k, imperfection)

    quads, orient = [], []
    for axis in range(3):
        a, b = [ax for ax in range(3) if ax != axis]
        planes = np.nonzero(on_wall[axis])[0]
        ua, ub = np.meshgrid(np.arange(dims[a]), np.arange(dims[b]), indexing="ij")
        ua, ub = ua.ravel(), ub.ravel()
        for p in planes:
            corners = []
            for da, db in ((0, 0), (1, 0), (1, 1), (0, 1)):
                idx = [None, None, None]
                idx[axis] = np.full(ua.size, p)
                idx[a] = ua + da
                idx[b] = ub + db
                corners.append(index[idx[0], idx[1], idx[2]])
            q = np.column_stack(corners)
            quads.append(q)
            orient.append(np.full(q.shape[0], axis, dtype=np.int8))
    return HollowGrid(nodes=nodes, quads=np.vstack(quads), orientation=np.concatenate(orient),
                      cell=cell, thickness=thickness)


def panel_offsets(lattice: np.ndarray, k: int, amplitude: float) -> np.ndarray:
    """Out-of-plane offsets (n, 3) mm of panel-interior lattice points.

    lattice (n, 3) int lattice indices (spacing cell / k); a point lies on
    the wall plane normal to ``axis`` when its index along ``axis`` is a
    multiple of k, and inside that panel when neither in-plane index is. Its
    offset along ``axis`` is ``amplitude sin(pi r_a / k) sin(pi r_b / k)``
    (r the in-cell remainders) times the checkerboard sign of the panel.
    """
    off = np.zeros(lattice.shape, dtype=np.float64)
    rem = lattice % k
    cellidx = lattice // k
    for axis in range(3):
        a, b = [ax for ax in range(3) if ax != axis]
        inside = (rem[:, axis] == 0) & (rem[:, a] != 0) & (rem[:, b] != 0)
        sign = np.where((cellidx[:, axis] + cellidx[:, a] + cellidx[:, b]) % 2 == 0, 1.0, -1.0)
        shape = np.sin(np.pi * rem[:, a] / k) * np.sin(np.pi * rem[:, b] / k)
        off[inside, axis] = (amplitude * sign * shape)[inside]
    return off
