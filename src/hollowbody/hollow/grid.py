"""Hollow structures: shell walls on every face of a cubic grid of cells.

The paper's hollow block is a 6 x 6 x 3 grid of 30 mm cells whose every face
(outer faces included) is a 1.5 mm shell wall. Walls are meshed with
``elements_per_edge`` quadrilaterals along each cell edge; nodes are shared
wherever walls meet (conforming), because every node is a point of one global
lattice of spacing ``cell / elements_per_edge``.

Walls are grouped by orientation (normal along x, y or z), so each
orientation can be its own part.
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
               elements_per_edge: int = 4, origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
               ) -> HollowGrid:
    """Walls of a box of ``size`` (mm) divided into cubic cells of edge ``cell``.

    ``cell`` must divide every side; walls on every cell face including the
    outer ones. ``origin`` is the box's minimum corner. ValueError for sizes
    the cell does not divide or fewer than one element per edge.
    """
    if elements_per_edge < 1:
        raise ValueError("elements_per_edge must be at least 1")
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
