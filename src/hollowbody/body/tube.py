"""Structured layered tubes: the mesh of a limb segment or of the trunk.

A tube is a stack of cross-sections along a local axis z (stations z_k). Each
cross-section runs from an inner ellipse (the bone's or the spine's shell) to
an outer ellipse (the skin), both given by centre (cx, cy) and semi-axes
(a, b) per station; ring j of a section is the blend at radial fraction f_j
(f_0 = 0 inner, f_nr = 1 outer) of the two ellipses at the same angle theta_i.
Element (k, j, i) is the hexahedron between stations k, k+1, rings j, j+1 and
angles i, i+1; shells on ring j are the quadrilaterals (k, i). Node numbering
is (k, j, i) lexicographic, 0-based, so a part is a slice of rows.

Hexahedra are ordered so their volume is positive (checked), quads so their
normal points away from the tube's axis (outward on the skin). Units mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Ellipses:
    """Ellipses per station: cx, cy, a, b arrays of shape (nz + 1,) mm."""

    cx: np.ndarray
    cy: np.ndarray
    a: np.ndarray
    b: np.ndarray

    @classmethod
    def constant(cls, n: int, a: float, b: float, cx: float = 0.0, cy: float = 0.0
                 ) -> Ellipses:
        """The same ellipse at ``n`` stations."""
        return cls(np.full(n, cx), np.full(n, cy), np.full(n, a), np.full(n, b))

    def points(self, theta: np.ndarray) -> np.ndarray:
        """(nz + 1, nt, 2) points at angles theta (nt,) rad."""
        x = self.cx[:, None] + self.a[:, None] * np.cos(theta)[None, :]
        y = self.cy[:, None] + self.b[:, None] * np.sin(theta)[None, :]
        return np.stack([x, y], axis=-1)


@dataclass
class Tube:
    """A generated tube: xyz (nz+1, nr+1, nt, 3) local coordinates mm."""

    xyz: np.ndarray

    @property
    def shape(self) -> tuple[int, int, int]:
        """(nz, nr, nt): element rows, radial layers, elements around."""
        nz1, nr1, nt, _ = self.xyz.shape
        return nz1 - 1, nr1 - 1, nt

    def index(self, k, j, i):  # noqa: ANN001, ANN201 - numpy index arrays
        """0-based node index of station k, ring j, angle i (i wraps around)."""
        _, nr, nt = self.shape
        return (np.asarray(k) * (nr + 1) + np.asarray(j)) * nt + np.asarray(i) % nt

    def nodes(self) -> np.ndarray:
        """(n, 3) local coordinates in node-index order."""
        return self.xyz.reshape(-1, 3)

    def hexes(self, rows: np.ndarray, layers: np.ndarray) -> np.ndarray:
        """(e, 8) 0-based connectivity of the hexahedra of element rows x radial layers
        (every angle), positive volume."""
        _, _, nt = self.shape
        k, j, i = (a.ravel() for a in np.meshgrid(rows, layers, np.arange(nt), indexing="ij"))
        conn = np.column_stack([self.index(k, j, i), self.index(k, j + 1, i),
                                self.index(k, j + 1, i + 1), self.index(k, j, i + 1),
                                self.index(k + 1, j, i), self.index(k + 1, j + 1, i),
                                self.index(k + 1, j + 1, i + 1), self.index(k + 1, j, i + 1)])
        if conn.shape[0] and _signed_volume(self.nodes(), conn[:1])[0] < 0.0:
            conn = conn[:, [4, 5, 6, 7, 0, 1, 2, 3]]
        return conn

    def quads(self, ring: int, rows: np.ndarray) -> np.ndarray:
        """(q, 4) 0-based shells on ``ring`` over element rows, normal away from the axis."""
        _, _, nt = self.shape
        k, i = (a.ravel() for a in np.meshgrid(rows, np.arange(nt), indexing="ij"))
        conn = np.column_stack([self.index(k, ring, i), self.index(k, ring, i + 1),
                                self.index(k + 1, ring, i + 1), self.index(k + 1, ring, i)])
        if conn.shape[0]:
            x = self.nodes()
            q = x[conn[0]]
            n = np.cross(q[2] - q[0], q[3] - q[1])
            c = q.mean(axis=0)
            axis_pt = self.xyz[k[0], 0].mean(axis=0)  # centre of the inner ring
            if np.dot(n[:2], (c - axis_pt)[:2]) < 0.0:
                conn = conn[:, [0, 3, 2, 1]]
        return conn


def layered_tube(stations: np.ndarray, inner: Ellipses, outer: Ellipses,
                 fractions: np.ndarray, n_theta: int, theta0: float = 0.0) -> Tube:
    """The tube of ``stations`` (nz + 1,) local z mm between ``inner`` and ``outer``,
    rings at radial ``fractions`` (nr + 1,) from 0 to 1, ``n_theta`` elements around."""
    z = np.asarray(stations, float)
    f = np.asarray(fractions, float)
    if z.size < 2 or f.size < 2 or n_theta < 3:
        raise ValueError("a tube needs two stations, two rings and three angles")
    theta = theta0 + 2.0 * np.pi * np.arange(n_theta) / n_theta
    pin = inner.points(theta)
    pout = outer.points(theta)
    xy = (1.0 - f)[None, :, None, None] * pin[:, None] + f[None, :, None, None] * pout[:, None]
    zz = np.broadcast_to(z[:, None, None, None], xy.shape[:-1] + (1,))
    return Tube(np.concatenate([xy, zz], axis=-1))


def stations(breaks: list[float], size: float) -> tuple[np.ndarray, np.ndarray]:
    """Stations through the increasing ``breaks`` (mm), each interval split into
    equal elements of at most ``size`` mm; returns (stations, interval index of each row)."""
    zs = [breaks[0]]
    owner = []
    for n, (lo, hi) in enumerate(zip(breaks[:-1], breaks[1:])):
        m = max(1, int(np.ceil((hi - lo) / size - 1e-9)))
        zs.extend(np.linspace(lo, hi, m + 1)[1:])
        owner.extend([n] * m)
    return np.array(zs), np.array(owner, dtype=np.int64)


def _signed_volume(x: np.ndarray, conn: np.ndarray) -> np.ndarray:
    """Hexahedron volumes (mm^3, exact for parallelepipeds) from the Jacobian at the
    centre; negative for an inverted ordering."""
    p = x[conn]
    a = (p[:, 1] + p[:, 2] + p[:, 5] + p[:, 6] - p[:, 0] - p[:, 3] - p[:, 4] - p[:, 7]) / 4.0
    b = (p[:, 2] + p[:, 3] + p[:, 6] + p[:, 7] - p[:, 0] - p[:, 1] - p[:, 4] - p[:, 5]) / 4.0
    c = (p[:, 4] + p[:, 5] + p[:, 6] + p[:, 7] - p[:, 0] - p[:, 1] - p[:, 2] - p[:, 3]) / 4.0
    return np.einsum("ij,ij->i", a, np.cross(b, c))
