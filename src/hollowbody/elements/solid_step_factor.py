"""Factor on the L_e / c step of one-point hexahedra for the volumetric modes of free surfaces.

LS-DYNA's solid rule ``dt = L_e / c`` (``c^2 = (K + 4G/3) / rho``, ``L_e = V / A_max``)
is the exact limit of the highest mode of a regular mesh's interior, but an element
with free faces has a stiffer volumetric ("breathing") mode: a lone cube of side
h has ``w^2 = 12 K / (rho h^2)``, so its exact limit is ``h / sqrt(3 K / rho)``,
``1 / sqrt(3)`` of the rule for K >> G. A neighbour on a face restrains the
mode along that face's axis. Measured (largest eigenvalue of M^-1 K of free
regular meshes, lumped mass, FB hourglass stiffness QM 0.05; see
tests/verification/solids/test_solid_step_limits.py), the exact limit as a fraction
of L_e / c, by the smallest number ``k`` of element axes (xi, eta, zeta) along
which an element of the mesh has at least one face neighbour:

===  =========================  ===========  ===========
k    mesh                       K >> G       nu = 0.3
===  =========================  ===========  ===========
0    1 x 1 x 1                  0.577        0.734
1    2 x 1 x 1, 1 x 1 x 4       0.633-0.652  0.792-0.804
2    2 x 2 x 1, 4 x 4 x 1       0.707-0.742  0.874-0.891
3    2 x 2 x 2 ... 4 x 4 x 4    0.815-0.844  0.937-0.970
===  =========================  ===========  ===========

The engine uses the restrained-axes factor ``gamma = 3 - k / 3`` for k <= 2 (3,
2.67, 2.33) and 1.5 for k = 3, with k the group's ``min_axes`` (the smallest
count over its elements, faces shared with any solid group counting): its
omega_max dt / 2 stays <= 0.96 on the meshes above at TSSFAC 0.9, and long runs
with random and alternating velocities and small-strain impacts stay stable
with the default bulk viscosity (gamma = 2 at k = 2 diverged on a 2 x 2 x 1
rubber plate). It gives LS-DYNA's step to an elastic nu 0.3 block and 0.816 of
it to a rubber block. The lone-element bound ``sqrt(M / max(M, 3K))`` (k = 0:
1 at nu = 0, 0.734 at nu = 0.3, 0.577 for rubber) is a bound for any mesh.
LS-DYNA's rule (factor 1) is not stable for rubber: free rubber meshes
diverge within 4-30 cycles at TSSFAC 0.9, with or without the bulk viscosity.

The larger step needs two things elsewhere (docs/elements.md, "Time step"): the
step's bulk-viscosity term continuous in tr D
(:func:`hollowbody.elements.time_step.critical_time_step`; LS-DYNA's
compression-only term made the step alternate and pumped the highest mode of a
block dropped on a wall), and the contacts' kinematic limit
(:mod:`hollowbody.contact.kinematic_step`; a plate closing at 20-30 mm/ms on a
soft block met the contact after a large step, the step fell at once and nodes
went through).
Degenerate elements (wedges, tetrahedra) always have min_axes 0.
"""

from __future__ import annotations

import numpy as np

#: Local node numbers of the six faces of a hexahedron (LS-DYNA order).
HEX_FACES = np.array([[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5],
                      [2, 3, 7, 6], [3, 0, 4, 7]])
#: Pairs of opposite faces (indices into HEX_FACES): zeta, eta, xi.
AXIS_PAIRS = np.array([[0, 1], [2, 4], [3, 5]])


def restrained_axes(conns: list[np.ndarray]) -> list[np.ndarray]:
    """Number of element axes (0..3) along which an element has a face neighbour.

    conns: list of (e_g, 8) int node-index connectivities (the solid groups of
    one model; a face shared by elements of different groups counts for both).
    Faces are compared by their sorted node numbers; the axes are the pairs of
    opposite faces (N1-N4 / N5-N8, N1-N2-N6-N5 / N3-N4-N8-N7, N2-N3-N7-N6 /
    N4-N1-N5-N8). Returns one (e_g,) int64 array per group.
    """
    sizes = [int(c.shape[0]) for c in conns]
    if sum(sizes) == 0:
        return [np.zeros(0, dtype=np.int64) for _ in conns]
    conn = np.concatenate([np.asarray(c, dtype=np.int64).reshape(-1, 8) for c in conns])
    faces = np.sort(conn[:, HEX_FACES], axis=2).reshape(-1, 4)
    _, inverse, counts = np.unique(faces, axis=0, return_inverse=True, return_counts=True)
    shared = (counts[inverse.ravel()] > 1).reshape(-1, 6)
    n = (shared[:, AXIS_PAIRS[:, 0]] | shared[:, AXIS_PAIRS[:, 1]]).sum(axis=1).astype(np.int64)
    out, start = [], 0
    for s in sizes:
        out.append(n[start:start + s])
        start += s
    return out


def volumetric_step_factor(kind: str, params: dict[str, float], curves: dict,
                           min_axes: int = 0) -> float:
    """Factor (<= 1) on the L_e / c step of a group of one-point hexahedra.

    kind, params: the material (``"elastic"`` E, PR GPa; ``"rubber181"`` KM GPa and
    its curve LCID in ``curves``, initial shear modulus E0 / 3 from the curve's
    slope at zero strain); min_axes: the smallest number of restrained axes of
    an element of the group (:func:`group_min_axes`; 0 for a lone element).
    Returns ``sqrt(M / max(M, gamma K))``, ``M = K + 4G/3``, ``gamma = 3 - k / 3``
    for k <= 2 and 1.5 for k = 3 (module docstring); 1.0 for other laws.
    """
    if kind == "elastic":
        e, nu = params.get("E", 0.0), params.get("PR", 0.0)
        if e <= 0.0 or nu >= 0.5:
            return 1.0
        k, g = e / (3.0 * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))
    elif kind == "rubber181":
        k = params.get("KM", 0.0)
        curve = curves.get(int(params.get("LCID", 0)))
        g = 0.0
        if curve is not None and curve.x.size >= 2:
            sgl = params.get("SGL", 1.0) or 1.0
            area = (params.get("SW", 1.0) or 1.0) * (params.get("ST", 1.0) or 1.0)
            strain, stress = curve.x / sgl, curve.y / area
            slope = np.gradient(stress, strain)
            g = max(float(np.interp(0.0, strain, slope)), 0.0) / 3.0
    else:
        return 1.0
    m = k + 4.0 * g / 3.0
    if m <= 0.0 or k <= 0.0:
        return 1.0
    axes = min(max(int(min_axes), 0), 3)
    gamma = 1.5 if axes == 3 else 3.0 - axes / 3.0
    return float(np.sqrt(m / max(m, gamma * k)))


def group_min_axes(conn: np.ndarray, axes: np.ndarray) -> int:
    """Smallest restrained-axes count of a group; 0 when it has degenerate elements.

    conn: (e, 8) int connectivity as in the deck; axes: (e,) from
    :func:`restrained_axes`. Returns 0 for an empty group.
    """
    if conn.shape[0] == 0:
        return 0
    s = np.sort(np.asarray(conn), axis=1)
    if np.any(np.count_nonzero(np.diff(s, axis=1), axis=1) != 7):
        return 0
    return int(axes.min())
