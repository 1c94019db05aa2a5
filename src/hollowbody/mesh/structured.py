"""Structured hexahedral blocks and quadrilateral plates.

Element node order is LS-DYNA's: N1..N4 counter-clockwise on the bottom
(z-low) face, N5..N8 above them. Two numberings of the grid
points (i, j, k) of an (nx, ny, nz) block are offered:

- ``x_fastest=False`` (default): node ``(i * (ny + 1) + j) * (nz + 1) + k``,
  elements in the same order (k fastest);
- ``x_fastest=True``: node ``(k * (ny + 1) + j) * (nx + 1) + i``, elements with
  i fastest (layer by layer from the bottom, as the block-test decks number
  them).

Units: mm. Grid coordinates along each axis are ``numpy.linspace(o, o + s,
n + 1)`` for origin ``o`` and side ``s``.
"""

from __future__ import annotations

import numpy as np


def block_counts(size: tuple[float, float, float], h: float) -> tuple[int, int, int]:
    """Elements per side of a box of sides ``size`` (mm) meshed with edge ``h`` (mm).

    ``h`` must divide every side (to 1e-9 relative), else ValueError.
    """
    counts = []
    for s in size:
        k = s / h
        if abs(k - round(k)) > 1e-9 * max(k, 1.0) or round(k) < 1:
            raise ValueError(f"mesh size {h:g} mm does not divide the block side {s:g} mm")
        counts.append(int(round(k)))
    return counts[0], counts[1], counts[2]


def block_mesh(counts: tuple[int, int, int], size: tuple[float, float, float] = (1.0, 1.0, 1.0),
               origin: tuple[float, float, float] = (0.0, 0.0, 0.0), *,
               x_fastest: bool = False, dtype: type = np.int32
               ) -> tuple[np.ndarray, np.ndarray]:
    """Block of ``nx * ny * nz`` hexahedra spanning ``origin .. origin + size`` (mm).

    Returns ``x`` (n, 3) float64 mm node coordinates and ``conn`` (e, 8) of
    ``dtype`` (0-based node indices, LS-DYNA order); numbering per the module
    doc.
    """
    nx, ny, nz = (int(c) for c in counts)
    xs, ys, zs = (np.linspace(origin[d], origin[d] + size[d], n + 1)
                  for d, n in enumerate((nx, ny, nz)))
    if x_fastest:
        zz, yy, xx = np.meshgrid(zs, ys, xs, indexing="ij")
        k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")

        def idx(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
            return (c * (ny + 1) + b) * (nx + 1) + a
    else:
        xx, yy, zz = np.meshgrid(xs, ys, zs, indexing="ij")
        i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")

        def idx(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
            return (a * (ny + 1) + b) * (nz + 1) + c
    x = np.column_stack([xx.ravel(), yy.ravel(), zz.ravel()])
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    conn = np.column_stack([idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k),
                            idx(i, j + 1, k), idx(i, j, k + 1), idx(i + 1, j, k + 1),
                            idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)])
    return x, conn.astype(dtype)


def standing_block(size: tuple[float, float, float], h: float) -> tuple[np.ndarray, np.ndarray]:
    """Hexahedra of edge ``h`` (mm) filling a box of sides ``size`` (mm) centred in x and y
    on the origin and standing on z = 0 (x in [-sx/2, sx/2], z in [0, sz]).

    x-fastest numbering (module doc). Returns (nodes (n, 3) mm, conn (e, 8) int64).
    ``h`` must divide every side, else ValueError.
    """
    return block_mesh(block_counts(size, h), size, (-size[0] / 2, -size[1] / 2, 0.0),
                      x_fastest=True, dtype=np.int64)


def plate_mesh(n: tuple[int, int] = (10, 10), size: tuple[float, float] = (10, 10),
               origin: tuple[float, float, float] = (0, 0, 0)) -> tuple[np.ndarray, np.ndarray]:
    """Structured quad plate in the plane z = origin[2], normal +z.

    Node ``i * (ny + 1) + j`` at grid point (i, j). Returns x (m, 3) float64 mm and
    conn (e, 4) int32.
    """
    nx, ny = n
    gx, gy = np.meshgrid(np.linspace(origin[0], origin[0] + size[0], nx + 1),
                         np.linspace(origin[1], origin[1] + size[1], ny + 1), indexing="ij")
    x = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, float(origin[2]))])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    i, j = i.ravel(), j.ravel()

    def idx(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return a * (ny + 1) + b

    conn = np.column_stack([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)])
    return x, conn.astype(np.int32)


def boundary_nodes(x: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Boolean (n,) mask of the nodes of ``x`` (n, 3) on its bounding box."""
    lo = x.min(axis=0)
    hi = x.max(axis=0)
    return np.any((np.abs(x - lo) < tol) | (np.abs(x - hi) < tol), axis=1)


def distort(x: np.ndarray, amount: float, seed: int = 0) -> np.ndarray:
    """Copy of ``x`` (n, 3) with interior nodes moved randomly by up to ``amount`` mm per axis."""
    rng = np.random.default_rng(seed)
    out = x.copy()
    inner = ~boundary_nodes(x)
    out[inner] += rng.uniform(-amount, amount, size=(int(inner.sum()), 3))
    return out
