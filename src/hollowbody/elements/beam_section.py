"""Beam cross-sections: integration rules, section constants, nodal inertia, step.

Local axes (r, s, t) of :mod:`hollowbody.model.beams`; a stress point sits at
``(s, t)`` mm with a weight (mm^2, its share of the area).

* Rectangular section (ELFORM 1, CST 0): widths TS (along s) and TT (along t),
  the mean of the two nodes' values; QR n x n Gauss points (QR 1: 1, 2: 2x2,
  3: 3x3, 5: 4x4) or 3x3 Lobatto (QR 4).
* Tubular section (CST 1): outer diameter TS, inner diameter TT; ``nc``
  equally spaced points around the circumference times ``nr`` Gauss points
  through the wall in the radius (weight ``r dr dtheta``): QR 1: 8 x 1,
  QR 2: 8 x 2, QR >= 3: 16 x 3.

**Nodal rotational inertia.** Each node of a beam gets, per axis, ``J = m_node
* max(L^2 / 4, (ISS + ITT) / A)`` (m_node = half the beam's mass with NSM).
``(ISS + ITT) / A`` is the physical polar inertia of the section per unit
mass; ``L^2 / 4`` scales it up (this project's rule; explicit codes scale beam
rotary inertia for the same reason) so that the rotational modes of the
element are never faster than its axial wave: with it, the element's exact
highest frequency (lumped masses, the element's elastic stiffness) gives a
critical step of at least ``L / c`` for every aspect ratio when the beam has
shear flexibility (ELFORM 1; ELFORM 2 with SA > 0), and for L >= 2 h for the
Euler-Bernoulli resultant beam (SA = 0), whose stubby elements are stiffer in
bending (12 EI / L^3) than axially (checked by
``tests/unit/elements/test_beam_section.py``). The step of each element is
computed exactly at set-up (:func:`element_step`) and scaled with the current
length in the cycle.
"""

from __future__ import annotations

import math

import numpy as np

from hollowbody.model.beams import section_constants

_GAUSS = {1: ([0.0], [2.0]),
          2: ([-1.0 / math.sqrt(3.0), 1.0 / math.sqrt(3.0)], [1.0, 1.0]),
          3: ([-math.sqrt(0.6), 0.0, math.sqrt(0.6)], [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0]),
          4: ([-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
               0.8611363115940526],
              [0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
               0.3478548451374538])}
_LOBATTO3 = ([-1.0, 0.0, 1.0], [1.0 / 3.0, 4.0 / 3.0, 1.0 / 3.0])


def _rule_1d(qr: int) -> tuple[np.ndarray, np.ndarray]:
    """Points in [-1, 1] and weights (sum 2) of QR along one side of a rectangle."""
    pts, wts = {1: _GAUSS[1], 2: _GAUSS[2], 3: _GAUSS[3], 4: _LOBATTO3, 5: _GAUSS[4]}[qr]
    return np.asarray(pts), np.asarray(wts)


def rectangle_points(ts: float, tt: float, qr: int) -> np.ndarray:
    """(p, 3) rows (s mm, t mm, weight mm^2) of a TS x TT rectangle with rule QR."""
    xi, wi = _rule_1d(qr)
    s, t = np.meshgrid(0.5 * ts * xi, 0.5 * tt * xi, indexing="ij")
    w = np.outer(wi, wi) * 0.25 * ts * tt
    return np.column_stack([s.ravel(), t.ravel(), w.ravel()])


def tube_points(d_out: float, d_in: float, qr: int) -> np.ndarray:
    """(p, 3) rows (s, t, weight) of a tube of outer / inner diameter (mm) with rule QR."""
    nc, nr = (8, 1) if qr <= 1 else (8, 2) if qr == 2 else (16, 3)
    ro, ri = 0.5 * d_out, 0.5 * d_in
    g, gw = _GAUSS[nr]
    rows = []
    for k in range(nc):
        th = 2.0 * math.pi * (k + 0.5) / nc
        for x, w in zip(g, gw):
            r = 0.5 * (ro + ri) + 0.5 * (ro - ri) * x
            rows.append((r * math.cos(th), r * math.sin(th),
                         w * 0.5 * (ro - ri) * r * 2.0 * math.pi / nc))
    return np.asarray(rows)


def section_points(params: dict[str, float]) -> np.ndarray:
    """Stress points (p, 3) of an ELFORM 1 section from its params (TS1.., CST, QR)."""
    ts = 0.5 * (params["TS1"] + params["TS2"])
    tt = 0.5 * (params["TT1"] + params["TT2"])
    qr = int(params.get("QR", 2) or 2)
    if int(params.get("CST", 0)) == 1:
        return tube_points(ts, tt, qr)
    return rectangle_points(ts, tt, qr)


def exact_constants(params: dict[str, float]) -> tuple[float, float, float, float]:
    """(A mm^2, ISS, ITT, J mm^4) of an ELFORM 1 section
    (:func:`hollowbody.model.beams.section_constants`)."""
    return section_constants(1, params)


def rotational_r2(length: np.ndarray, area: float, iss: float, itt: float) -> np.ndarray:
    """(e,) mm^2: J_node / m_node of the beams (see the module docstring)."""
    return np.maximum(0.25 * length * length, (iss + itt) / area)


def _bending_matrices(ei: float, kga: float, length: np.ndarray, cubic: bool) -> np.ndarray:
    """(e, 4, 4) bending stiffness in one plane, dofs (w1, th1, w2, th2).

    cubic: the Timoshenko beam's exact stiffness (kga = inf: Euler-Bernoulli);
    else the one-point linear element (curvature and shear at the middle).
    """
    e = length.shape[0]
    k = np.zeros((e, 4, 4))
    L = length
    if cubic:
        phi = 12.0 * ei / (kga * L * L) if np.isfinite(kga) else np.zeros_like(L)
        c = ei / (L ** 3 * (1.0 + phi))
        rows = [[12, 6 * L, -12, 6 * L], [6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L],
                [-12, -6 * L, 12, -6 * L], [6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L]]
        for a in range(4):
            for b in range(4):
                k[:, a, b] = c * np.broadcast_to(np.asarray(rows[a][b], dtype=float), L.shape)
        return k
    bk = np.stack([np.zeros_like(L), -1.0 / L, np.zeros_like(L), 1.0 / L], axis=1)
    bg = np.stack([-1.0 / L, -0.5 * np.ones_like(L), 1.0 / L, -0.5 * np.ones_like(L)], axis=1)
    return L[:, None, None] * (ei * bk[:, :, None] * bk[:, None, :]
                               + kga * bg[:, :, None] * bg[:, None, :])


def element_step(length: np.ndarray, m_node: np.ndarray, j_node: np.ndarray, e_mod: float,
                 g_mod: float, area: float, iss: float, itt: float, torsion: float,
                 kga: float, cubic: bool) -> np.ndarray:
    """(e,) ms: exact critical step 2 / omega_max of each free beam element.

    Lumped masses m_node (kg) and rotational inertias j_node (kg mm^2) at both
    nodes; axial (EA / L), torsional (G J / L) and the two bending planes
    (:func:`_bending_matrices`); kga: shear stiffness k G A (kN; inf: none).
    """
    w2 = 2.0 * e_mod * area / (length * m_node)
    w2 = np.maximum(w2, 2.0 * g_mod * torsion / (length * j_node))
    sq = np.stack([np.sqrt(m_node), np.sqrt(j_node), np.sqrt(m_node), np.sqrt(j_node)], axis=1)
    for ei in (e_mod * iss, e_mod * itt):
        k = _bending_matrices(ei, kga, length, cubic)
        k = k / (sq[:, :, None] * sq[:, None, :])
        w2 = np.maximum(w2, np.linalg.eigvalsh(k)[:, -1])
    return 2.0 / np.sqrt(w2)
