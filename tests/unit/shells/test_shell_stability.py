"""Element-level stability claims: the critical step, rotational inertia and hourglass control.

The element stiffness is taken from the runtime itself (finite strain-rate
increments of size ~1e-9 from a stress-free state), the masses from its
lumped masses and rotational inertias.
"""

import numpy as np
import pytest

from hollowbody.elements.shell_group import ShellGroupRuntime
from hollowbody.model.model import HourglassDef, MaterialDef, SectionDef, ShellGroup

RHO = 7.85e-6
SHAPES = {
    "square": [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]],
    "rectangle": [[0, 0, 0], [20, 0, 0], [20, 5, 0], [0, 5, 0]],
    "distorted": [[0, 0, 0], [10, 1, 0], [12, 9, 0], [-2, 7, 0]],
    "triangle": [[0, 0, 0], [10, 0, 0], [5, 8.66, 0], [5, 8.66, 0]],
}


def single(xs, nu, t, hg=None, drilling=0.1):
    x = np.asarray(xs, dtype=float)
    conn = np.array([[0, 1, 2, 3]], dtype=np.int32)
    g = ShellGroup(pid=1, elem_ids=np.array([1]), conn=conn, thickness=np.full((1, 4), t))
    mat = MaterialDef(mid=1, kind="elastic", density=RHO, params={"E": 210.0, "PR": nu})
    sec = SectionDef(secid=1, kind="shell", elform=2, params={"NIP": 5.0})
    return x, ShellGroupRuntime(g, mat, sec, hg or HourglassDef(hgid=1, qm=0.0), {}, x,
                                drilling=drilling)


def stiffness(x, rt):
    """Tangent stiffness (24, 24) of a stress-free element (translations, rotations)."""
    n = 4
    k = np.zeros((6 * n, 6 * n))
    dt = 1e-9
    for j in range(6 * n):
        rt.sig[:] = 0.0
        rt.tau[:] = 0.0
        rt.drill[:] = 0.0
        rt.hgq[:] = 0.0
        v = np.zeros((n, 3))
        w = np.zeros((n, 3))
        (v if j % 6 < 3 else w)[j // 6, j % 6 % 3] = 1.0
        f = np.zeros((n, 3))
        m = np.zeros((n, 3))
        rt.add_forces(x + 0.5 * dt * v, v, dt, f, w, m)
        k[:, j] = -np.concatenate([f, m], axis=1).ravel() / dt
    return k


@pytest.mark.parametrize("shape", SHAPES)
@pytest.mark.parametrize("nu", [0.0, 0.3])
@pytest.mark.parametrize("t", [0.5, 2.0])
def test_rotations_never_govern_the_time_step(shape, nu, t):
    x, rt = single(SHAPES[shape], nu, t)
    k = stiffness(x, rt)
    assert np.abs(k - k.T).max() < 1e-6 * np.abs(k).max()  # symmetric at zero stress
    (dtc, _, _) = rt.add_forces(x, np.zeros((4, 3)), 0.0, np.zeros((4, 3)))
    mt = rt.lumped_mass(4)
    mr = rt.lumped_rotational_inertia(4)
    if shape == "triangle":  # the 4th corner is the 3rd node
        t_map = np.zeros((24, 18))
        for a in range(4):
            t_map[6 * a:6 * a + 6, 6 * min(a, 2):6 * min(a, 2) + 6] = np.eye(6)
        k = t_map.T @ k @ t_map
    mass = np.concatenate([np.repeat(mt[:, None], 3, 1), np.repeat(mr[:, None], 3, 1)],
                          axis=1).ravel()[:k.shape[0]]
    a = 0.5 * (k + k.T) / np.sqrt(np.outer(mass, mass))
    ev, vec = np.linalg.eigh(a)
    rot_share = (vec.reshape(-1, 6, vec.shape[1])[:, 3:, :] ** 2).sum(axis=(0, 1))
    omega = np.sqrt(np.maximum(ev, 0.0))
    w_rot = omega[rot_share > 0.5].max()
    w_mem = omega[rot_share <= 0.5].max()
    # rotation-dominated modes (bending, transverse shear, drilling) stay stable at the
    # unscaled critical step with a margin, whatever TSSFAC <= 1
    assert w_rot * dtc < 1.9
    # the translational bound: an isolated element's breathing mode, 2 sqrt(1 + nu) / dt
    assert w_mem * dtc <= 2.0 * np.sqrt(1.0 + nu) * (1 + 1e-9)


@pytest.mark.parametrize("ihq", [1, 4])
def test_hourglass_control_resists_the_modes(ihq):
    x, rt = single(SHAPES["distorted"], 0.3, 1.0, HourglassDef(hgid=1, ihq=ihq, qm=0.1),
                   drilling=0.0)
    h = np.array([1.0, -1.0, 1.0, -1.0])
    for comp in range(5):  # membrane x, y; w; rotations about x, y
        rt.hgq[:] = 0.0
        rt.sig[:] = 0.0
        rt.tau[:] = 0.0
        v = np.zeros((4, 3))
        w = np.zeros((4, 3))
        if comp < 3:
            v[:, comp] = h
        else:
            w[:, comp - 3] = h
        e_hg0 = rt.hourglass_energy
        f = np.zeros((4, 3))
        m = np.zeros((4, 3))
        xx = x.copy()
        for _ in range(3):
            xx = xx + 1e-6 * v
            f[:] = 0.0
            m[:] = 0.0
            rt.add_forces(xx, v, 1e-6, f, w, m)
        power = (f * v).sum() + (m * w).sum()
        assert power < 0.0  # the hourglass forces oppose the mode
        assert rt.hourglass_energy > e_hg0
