"""ShellGroupRuntime interface and element-level properties (Belytschko-Lin-Tsay shell)."""

import math

import numpy as np
import pytest

from hollowbody.elements.shell_bt_kinematics import bt_bmatrix, bt_geometry, bt_strain_rates
from hollowbody.elements.shell_group import ShellGroupRuntime
from hollowbody.errors import DeckError
from hollowbody.model.model import HourglassDef, MaterialDef, SectionDef, ShellGroup

E, NU, RHO = 210.0, 0.3, 7.85e-6
QUAD = np.array([[0, 0, 0], [10, 1, 0.5], [11, 9, -0.3], [-1, 8, 0.2]], dtype=float)


def runtime(x, conn, kind="elastic", params=None, nip=5, t=1.0, hg=None, elform=2, **kw):
    conn = np.asarray(conn, dtype=np.int32)
    e = conn.shape[0]
    g = ShellGroup(pid=7, elem_ids=np.arange(1, e + 1, dtype=np.int64), conn=conn,
                   thickness=np.full((e, 4), t))
    p = {"E": E, "PR": NU}
    p.update(params or {})
    mat = MaterialDef(mid=1, kind=kind, density=RHO, params=p)
    sec = SectionDef(secid=1, kind="shell", elform=elform, params={"NIP": nip})
    return ShellGroupRuntime(g, mat, sec, hg or HourglassDef(hgid=0), {}, x, **kw)


def call(rt, x, v=None, w=None, dt=0.0):
    n = x.shape[0]
    f = np.zeros((n, 3))
    m = np.zeros((n, 3))
    v = np.zeros((n, 3)) if v is None else v
    w = np.zeros((n, 3)) if w is None else w
    out = rt.add_forces(x, v, dt, f, w, m)
    return out, f, m


def test_interface_shapes_and_initial_query():
    rt = runtime(QUAD, [[0, 1, 2, 3]])
    assert rt.rotational is True
    assert rt.n_elem == 1 and rt.conn.dtype == np.int32 and rt.elem_ids.dtype == np.int64
    assert rt.stress.shape == (1, 6) and rt.plastic_strain.shape == (1,)
    assert rt.alive.all() and rt.thickness == pytest.approx([1.0])
    (d, i, neg), f, m = call(rt, QUAD)
    assert np.all(f == 0.0) and np.all(m == 0.0)
    assert i == 0 and neg == -1 and d > 0.0
    assert rt.internal_energy == 0.0 and rt.hourglass_energy == 0.0


def test_time_step_is_area_over_longest_side():
    c = math.sqrt(E / (RHO * (1 - NU ** 2)))
    sq = np.array([[0, 0, 0], [10, 0, 0], [10, 5, 0], [0, 5, 0]], dtype=float)
    (d, _, _), _, _ = call(runtime(sq, [[0, 1, 2, 3]]), sq)
    assert d == pytest.approx(50.0 / 10.0 / c, rel=1e-12)
    tri = np.array([[0, 0, 0], [10, 0, 0], [0, 5, 0]], dtype=float)
    (d, _, _), _, _ = call(runtime(tri, [[0, 1, 2, 2]]), tri)
    # triangle: 2 A / longest side = the smallest altitude
    assert d == pytest.approx(2 * 25.0 / math.hypot(10, 5) / c, rel=1e-12)


def test_mass_and_rotational_inertia():
    rt = runtime(QUAD, [[0, 1, 2, 3]], t=2.0)
    area = 0.5 * np.linalg.norm(np.cross(QUAD[2] - QUAD[0], QUAD[3] - QUAD[1]))
    assert rt.mass[0] == pytest.approx(RHO * area * 2.0)
    inertia = rt.lumped_rotational_inertia(4)
    assert inertia.sum() == pytest.approx(rt.mass[0] * max(4.0 / 12.0, area / 4.0))
    tri = runtime(QUAD, [[0, 1, 2, 2]])
    it = tri.lumped_rotational_inertia(4)
    assert it[3] == 0.0 and it[0] == pytest.approx(it[2])


def test_forces_are_the_transpose_of_the_strain_rates():
    """Nodal power of the forces equals the stress power A (N.d + M.k + Q.g)."""
    rng = np.random.default_rng(3)
    rt = runtime(QUAD, [[0, 1, 2, 3]], hg=HourglassDef(hgid=1, qm=0.0), drilling=0.0)
    rt.sig[:] = rng.normal(size=rt.sig.shape)
    rt.tau[:] = rng.normal(size=rt.tau.shape)
    v = rng.normal(size=(4, 3))
    w = rng.normal(size=(4, 3))
    _, f, m = call(rt, QUAD, v, w)
    e1, e2, e3, xl, yl, _, area = bt_geometry(*[tuple(r) for r in QUAD])
    b1, b2 = bt_bmatrix(xl, yl, area)
    rot = np.array([e1, e2, e3])
    vl, wl = v @ rot.T, w @ rot.T
    rates = bt_strain_rates(b1, b2, *[tuple(a) for a in (vl[:, 0], vl[:, 1], vl[:, 2],
                                                          wl[:, 0], wl[:, 1])])
    z = rt.zeta * 0.5
    wk = rt.weights * 0.5
    n = (wk[:, None] * rt.sig[0]).sum(axis=0)
    mom = (wk[:, None] * z[:, None] * rt.sig[0]).sum(axis=0)
    q = rt.shrf * rt.tau[0]
    power = area * (n @ rates[0:3] + mom @ rates[3:6] + q @ rates[6:8])
    assert -(f * v).sum() - (m * w).sum() == pytest.approx(power, rel=1e-12)


def test_rigid_translation_and_rotation_give_no_forces():
    rng = np.random.default_rng(0)
    rt = runtime(QUAD, [[0, 1, 2, 3]], kind="pwl024", params={"SIGY": 0.3, "ETAN": 1.0})
    omega = rng.normal(size=3)
    vel = rng.normal(size=3)
    x = QUAD.copy()
    dt = 1e-3
    for _ in range(50):
        # exact rigid motion: chord velocity of a finite rotation about the centroid
        c = x.mean(axis=0)
        th = omega * dt
        ang = np.linalg.norm(th)
        k = th / ang
        kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        r = np.eye(3) + math.sin(ang) * kx + (1 - math.cos(ang)) * kx @ kx
        xn = c + (x - c) @ r.T + vel * dt
        v = (xn - x) / dt
        w = np.tile(omega, (4, 1))
        (_, _, _), f, m = call(rt, xn, v, w, dt)
        x = xn
    assert np.abs(rt.sig).max() < 1e-12 * E
    assert np.abs(rt.tau).max() < 1e-6 * E * 1e-3 * np.linalg.norm(omega)
    # forces of a strain of 1e-6 would be ~2e-3 kN here
    assert np.abs(f).max() < 1e-6 and np.abs(m).max() < 1e-6


def test_uniform_stretch_of_a_triangle_and_a_quad():
    for conn, x in (([[0, 1, 2, 2]], np.array([[0, 0, 0], [8, 1, 0], [2, 7, 0]], float)),
                    ([[0, 1, 2, 3]], QUAD * [1, 1, 0])):
        rt = runtime(x, conn)
        grad = np.array([[1e-3, 2e-4, 0.0], [-1e-4, -5e-4, 0.0], [0.0, 0.0, 0.0]])
        v = x @ grad.T
        dt = 0.01
        call(rt, x + dt * v, v, None, dt)
        d = 0.5 * (grad + grad.T) * dt
        c = E / (1 - NU ** 2)
        sxx = c * (d[0, 0] + NU * d[1, 1])
        syy = c * (d[1, 1] + NU * d[0, 0])
        sxy = E / (2 * (1 + NU)) * 2 * d[0, 1]
        assert rt.stress[0, [0, 1, 3]] == pytest.approx([sxx, syy, sxy], rel=2e-3)
        assert abs(rt.stress[0, 2]) < 1e-12


def test_without_rotations_and_erosion():
    x = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]],
                 dtype=float)
    rt = runtime(x, [[0, 1, 2, 3], [1, 4, 5, 2]])
    v = np.zeros((6, 3))
    v[4:, 0] = 1.0
    f = np.zeros((6, 3))
    d, i, neg = rt.add_forces(x + 1e-3 * v, v, 1e-3, f)  # no w, no moment
    assert np.abs(f[4:, 0]).max() > 0.0 and neg == -1
    rt.erode(np.array([1]))
    f[:] = 0.0
    d2, i2, _ = rt.add_forces(x + 1e-3 * v, v, 0.0, f)
    assert not rt.alive[1] and i2 == 0
    assert np.all(f[4:] == 0.0) and np.all(rt.stress[1] == 0.0)


def test_material_failure_deletes_the_element():
    x = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], dtype=float)
    rt = runtime(x, [[0, 1, 2, 3]], kind="pwl024",
                 params={"SIGY": 0.3, "ETAN": 1.0, "FAIL": 0.01})
    v = np.zeros((4, 3))
    v[1:3, 0] = 1.0
    xx = x.copy()
    for _ in range(400):
        xx += 1e-3 * v
        call(rt, xx, v, None, 1e-3)
    assert not rt.alive[0] and rt.failed == [0]
    (d, i, _), f, _ = call(rt, xx, v, None, 1e-3)
    assert i == -1 and d == np.inf and np.all(f == 0.0)


def test_unsupported_input():
    with pytest.raises(DeckError, match="not available for shell"):
        runtime(QUAD, [[0, 1, 2, 3]], kind="rubber181")
    with pytest.raises(DeckError, match="NIP"):
        runtime(QUAD, [[0, 1, 2, 3]], nip=12)
    with pytest.raises(DeckError, match="SIGY"):
        runtime(QUAD, [[0, 1, 2, 3]], kind="plastic003", params={"SIGY": 0.0})
    rt = runtime(QUAD, [[0, 1, 2, 3]], elform=16, hg=HourglassDef(hgid=1, ihq=6))
    assert len(rt.warnings) == 2


def test_thickness_follows_membrane_strain_when_updated():
    x = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], dtype=float)
    for update in (False, True):
        rt = runtime(x, [[0, 1, 2, 3]], thickness_update=update)
        v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)  # biaxial
        call(rt, x + 1e-4 * v, v, None, 1e-4)
        ezz = -2 * NU / (1 - NU) * 1e-5
        assert rt.thickness_strain[0] == pytest.approx(ezz, rel=2e-5)  # midpoint B
        expected = math.exp(rt.thickness_strain[0]) if update else 1.0
        assert rt.thickness[0] == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize("nip, qr", [(1, 0.0), (3, -1.0), (4, 1.0), (10, 0.0)])
def test_integration_rules_give_the_same_membrane_state(nip, qr):
    x = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], dtype=float)
    conn = np.array([[0, 1, 2, 3]], dtype=np.int32)
    g = ShellGroup(pid=1, elem_ids=np.array([1]), conn=conn, thickness=np.full((1, 4), 1.0))
    mat = MaterialDef(mid=1, kind="elastic", density=RHO, params={"E": E, "PR": NU})
    sec = SectionDef(secid=1, kind="shell", elform=2, params={"NIP": nip, "QR": qr})
    rt = ShellGroupRuntime(g, mat, sec, HourglassDef(hgid=0), {}, x)
    assert rt.nip == nip and rt.weights.sum() == pytest.approx(2.0)
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 0, 0], [0, 0, 0]], dtype=float)
    call(rt, x + 1e-4 * v, v, None, 1e-4)
    assert rt.stress[0, 0] == pytest.approx(E / (1 - NU ** 2) * 1e-5, rel=1e-4)


def test_thickened_shell_has_a_shorter_step():
    """With thickness update the membrane stiffness grows with t while the mass
    (rho A0 t0) stays: the step is L_s / c * sqrt(t0 / t) (4x thicker: half)."""
    c = math.sqrt(E / (RHO * (1 - NU ** 2)))
    sq = np.array([[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]], dtype=float)
    for update, factor in ((False, 1.0), (True, 0.5)):
        rt = runtime(sq, [[0, 1, 2, 3]], thickness_update=update)
        rt.thickness_strain[:] = math.log(4.0)
        (d, _, _), _, _ = call(rt, sq)
        assert d == pytest.approx(10.0 / c * factor, rel=1e-12)
