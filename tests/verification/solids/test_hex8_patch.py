"""Constant-strain patch tests of the one-point solid (hexahedra, wedges, tetrahedra).

A linear velocity (or displacement) field on a distorted patch must give every
element the same, exact stress, and the interior nodes zero net force (the
element contributions cancel) -- to round-off.
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.elements.solid_group import SolidGroupRuntime
from hollowbody.mesh import block_mesh, boundary_nodes, distort
from hollowbody.model.model import Curve, HourglassDef, MaterialDef, SolidGroup

E_MOD, NU = 0.2, 0.3
LAM = E_MOD * NU / ((1 + NU) * (1 - 2 * NU))
MU = E_MOD / (2 * (1 + NU))
A = np.array([[0.8, 0.3, -0.2], [0.1, -0.5, 0.4], [-0.3, 0.2, 0.6]])  # 1/ms

MUSCLE_STRAIN = np.array([-0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0,
                          0.1, 0.2, 0.3, 0.5, 0.75, 1.0])
MUSCLE_MPA = np.array([-11.8, -4.15, -1.90, -0.987, -0.543, -0.299, -0.153, -0.061, 0.0,
                       0.0419, 0.0716, 0.093, 0.120, 0.139, 0.148])


def split_wedges(conn: np.ndarray) -> np.ndarray:
    """Each hexahedron -> 2 wedges (LS-DYNA pattern N1 N2 N3 N4 N5 N5 N6 N6)."""
    out = []
    for c in conn:
        out.append([c[1], c[0], c[4], c[5], c[2], c[2], c[6], c[6]])
        out.append([c[3], c[2], c[6], c[7], c[0], c[0], c[4], c[4]])
    return np.array(out, dtype=np.int32)


def split_tets(conn: np.ndarray) -> np.ndarray:
    """Each hexahedron -> 6 tetrahedra (LS-DYNA pattern N1 N2 N3 N4 N4 N4 N4 N4)."""
    tets = [[0, 1, 2, 6], [0, 2, 3, 6], [0, 3, 7, 6], [0, 7, 4, 6], [0, 4, 5, 6], [0, 5, 1, 6]]
    out = [[c[a], c[b], c[d_], c[e], c[e], c[e], c[e], c[e]]
           for c in conn for a, b, d_, e in tets]
    return np.array(out, dtype=np.int32)


def patch(kind: str):
    x0, conn = block_mesh((3, 3, 3), (3.0, 3.0, 3.0))
    x0 = distort(x0, 0.25, seed=11)
    if kind == "wedge":
        conn = split_wedges(conn)
    elif kind == "tet":
        conn = split_tets(conn)
    return x0, conn


def make(x0, conn, mat, curves=None, ihq=1):
    g = SolidGroup(1, np.arange(len(conn)), conn)
    hg = HourglassDef(0, ihq=ihq, qm=0.1, q1=0.0, q2=0.0)
    return SolidGroupRuntime(g, mat, hg, curves or {}, x0)


def voigt(m):
    return np.array([m[0, 0], m[1, 1], m[2, 2], m[0, 1], m[1, 2], m[2, 0]])


@pytest.mark.parametrize("kind", ["hex", "wedge", "tet"])
def test_volume_of_patch(kind):
    x0, conn = patch(kind)
    rt = make(x0, conn, MaterialDef(1, "elastic", 1e-6, {"E": E_MOD, "PR": NU}))
    assert np.all(rt.volume0 > 0.0)
    assert rt.volume0.sum() == pytest.approx(27.0, rel=1e-13)


@pytest.mark.parametrize("ihq", [1, 4, 6])
@pytest.mark.parametrize("kind", ["hex", "wedge", "tet"])
def test_elastic_patch_linear_velocity(kind, ihq):
    x0, conn = patch(kind)
    rt = make(x0, conn, MaterialDef(1, "elastic", 1e-6, {"E": E_MOD, "PR": NU}), ihq=ihq)
    dt = 2e-3
    x = x0.copy()
    f = np.zeros_like(x)
    rt.add_forces(x, np.zeros_like(x), 0.0, f)
    sig = np.zeros((3, 3))
    for _ in range(4):
        v = x @ A.T  # affine velocity field
        x = x + dt * v
        f[:] = 0.0
        rt.add_forces(x, v, dt, f)
        # expected: same kinematics as the kernel, for an affine increment
        l_end = A @ np.linalg.inv(np.eye(3) + dt * A)
        l_mid = np.linalg.solve(np.eye(3) - 0.5 * dt * l_end, l_end)
        d = 0.5 * (l_mid + l_mid.T)
        w = 0.5 * (l_mid - l_mid.T)
        q = np.linalg.solve(np.eye(3) - 0.5 * dt * w, np.eye(3) + 0.5 * dt * w)
        de = dt * d
        sig = q @ sig @ q.T + LAM * np.trace(de) * np.eye(3) + 2 * MU * de
    scale = np.abs(sig).max()
    np.testing.assert_allclose(rt.stress, np.broadcast_to(voigt(sig), rt.stress.shape),
                               rtol=0, atol=1e-12 * scale)
    inner = ~boundary_nodes(x0)
    fmax = np.abs(f).max()
    assert fmax > 0.0
    assert np.abs(f[inner]).max() < 1e-12 * fmax
    assert abs(rt.hourglass_energy) < 1e-12 * rt.internal_energy


@pytest.mark.parametrize("kind", ["hex", "wedge", "tet"])
def test_rubber_patch_affine_deformation(kind):
    x0, conn = patch(kind)
    mat = MaterialDef(2, "rubber181", 1e-6, {"KM": 0.01, "MU": 0.1, "SGL": 1.0, "SW": 1.0,
                                             "ST": 1.0, "LCID": 3})
    curves = {3: Curve(3, MUSCLE_STRAIN, MUSCLE_MPA * 1e-3)}
    rt = make(x0, conn, mat, curves)
    fgrad = np.array([[1.2, 0.1, 0.0], [-0.05, 0.9, 0.15], [0.02, 0.0, 0.85]])
    x = x0 @ fgrad.T
    f = np.zeros_like(x)
    rt.add_forces(x, np.zeros_like(x), 0.0, f)
    s = rt.stress
    scale = np.abs(s).max()
    np.testing.assert_allclose(s, np.broadcast_to(s[0], s.shape), rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(rt.volume / rt.volume0, np.linalg.det(fgrad), rtol=1e-12)
    inner = ~boundary_nodes(x0)
    assert np.abs(f[inner]).max() < 1e-12 * np.abs(f).max()
