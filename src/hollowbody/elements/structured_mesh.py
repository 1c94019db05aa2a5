"""Structured hexahedral block meshes (tests, benchmarks, quick studies).

LS-DYNA node order per element (N1..N4 bottom counter-clockwise, N5..N8 on
top). Node index of grid point (i, j, k) is ``(i * (ny + 1) + j) * (nz + 1) + k``.
Units: mm.
"""

from __future__ import annotations

import numpy as np


def block_mesh(nx: int, ny: int, nz: int, size: tuple[float, float, float] = (1.0, 1.0, 1.0),
               origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
               ) -> tuple[np.ndarray, np.ndarray]:
    """Block of nx * ny * nz hexahedra.

    Returns ``x`` (n, 3) float64 mm node coordinates and ``conn`` (e, 8) int32.
    """
    xs = origin[0] + np.linspace(0.0, size[0], nx + 1)
    ys = origin[1] + np.linspace(0.0, size[1], ny + 1)
    zs = origin[2] + np.linspace(0.0, size[2], nz + 1)
    x = np.stack(np.meshgrid(xs, ys, zs, indexing="ij"), axis=-1).reshape(-1, 3)
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()

    def idx(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
        return (a * (ny + 1) + b) * (nz + 1) + c

    conn = np.stack([idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
                     idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1),
                     idx(i, j + 1, k + 1)], axis=1).astype(np.int32)
    return x, conn


def boundary_nodes(x: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Boolean (n,) mask of nodes on the bounding box of x."""
    lo = x.min(axis=0)
    hi = x.max(axis=0)
    return np.any((np.abs(x - lo) < tol) | (np.abs(x - hi) < tol), axis=1)


def distort(x: np.ndarray, amount: float, seed: int = 0) -> np.ndarray:
    """Copy of x with interior nodes moved randomly by up to ``amount`` mm per axis."""
    rng = np.random.default_rng(seed)
    out = x.copy()
    inner = ~boundary_nodes(x)
    out[inner] += rng.uniform(-amount, amount, size=(int(inner.sum()), 3))
    return out
