"""One shell in uniaxial stress: MAT_003 (bilinear, isotropic and kinematic) and MAT_024
(tabulated) hardening curves, plane stress and plastic incompressibility."""

import numpy as np
import pytest
from shell_driver import ShellDriver, plate_mesh, section

from hollowbody.model.model import Curve, MaterialDef

E, NU = 210.0, 0.3
RHO = 7.85e-4  # mass-scaled x100: a quasi-static pull in few steps (rate-independent laws)
LCSS = Curve(lcid=7, x=np.array([0.0, 0.02, 0.05, 0.1, 0.3]),
             y=np.array([0.30, 0.36, 0.40, 0.43, 0.48]))


def pull(mat, strain_path, curves=None, speed=0.02):
    """Stretch a 10 x 10 x 1 mm shell along x through the engineering strains given.

    Nodes at x = 0 slide on the plane x = 0 (node 0 also fixed in y); nodes at x = 10
    move with the prescribed speed (mm/ms). Returns per cycle: stress (6,), max
    plastic strain, thickness log strain, width log strain and x log strain.
    """
    x, conn = plate_mesh(10.0, 10.0, 1, 1)
    d = ShellDriver(x, conn, mat, section(5), thickness=1.0, curves=curves or {})
    left = np.isclose(x[:, 0], 0.0)
    right = ~left
    d.fix_v[left, 0] = True
    d.fix_v[0, :] = True
    d.fix_v[:, 2] = True
    d.fix_w[:] = True
    rows = []
    ramp = 2.0  # ms, ~5 periods of the lateral mode: no start-up wave
    for a, b in zip(strain_path[:-1], strain_path[1:]):
        sign = 1.0 if b > a else -1.0
        mask = np.zeros((4, 3), dtype=bool)
        mask[right, 0] = True
        t0 = d.t

        def vel(t_now, s=sign, t0=t0):
            r = min((t_now - t0) / ramp, 1.0)
            return np.tile([s * speed * r * r * (3.0 - 2.0 * r), 0.0, 0.0], (4, 1))

        d.prescribed = (mask, vel)
        while sign * (d.x[1, 0] - 10.0 - 10.0 * b) < 0.0:
            d.step()
            width = d.x[3, 1] - d.x[0, 1]
            rows.append((d.rt.stress[0].copy(), d.rt.plastic_strain[0],
                         d.rt.thickness_strain[0], np.log(width / 10.0),
                         np.log((d.x[1, 0] - d.x[0, 0]) / 10.0)))
    return rows


def check_against(rows, yield_stress):
    n_plastic = 0
    for s, ep, ezz, eyy, _ in rows:
        assert abs(s[2]) < 1e-12  # sigma_zz = 0 (plane stress)
        assert abs(s[1]) < 5e-3 * max(abs(s[0]), 0.05)  # uniaxial (dynamic remainder)
        if ep > 2e-3:
            n_plastic += 1
            assert s[0] == pytest.approx(yield_stress(ep), rel=0.01)
            # total thickness strain = elastic (-nu s/E) + plastic (-eps_p/2)
            assert ezz == pytest.approx(-NU * s[0] / E - 0.5 * ep, rel=0.01)
            # plastic incompressibility: width and thickness contract alike
            assert eyy == pytest.approx(ezz, rel=0.01)
    assert n_plastic > 20


def test_mat024_tabulated_curve():
    mat = MaterialDef(mid=1, kind="pwl024", density=RHO, params={"E": E, "PR": NU, "LCSS": 7})
    rows = pull(mat, [0.0, 0.25], curves={7: LCSS})
    yield_stress = lambda ep: np.interp(ep, LCSS.x, LCSS.y)  # noqa: E731
    check_against(rows, yield_stress)
    assert rows[-1][1] > 0.15


def test_mat003_bilinear_isotropic():
    etan = 1.0
    h = E * etan / (E - etan)
    mat = MaterialDef(mid=1, kind="plastic003", density=RHO,
                      params={"E": E, "PR": NU, "SIGY": 0.25, "ETAN": etan, "BETA": 1.0})
    rows = pull(mat, [0.0, 0.1])
    check_against(rows, lambda ep: 0.25 + h * ep)


def test_mat003_kinematic_reversal_shows_the_bauschinger_effect():
    etan = 1.0
    h = E * etan / (E - etan)
    sigy = 0.25
    params = {"E": E, "PR": NU, "SIGY": sigy, "ETAN": etan}
    kin = MaterialDef(mid=1, kind="plastic003", density=RHO, params={**params, "BETA": 0.0})
    iso = MaterialDef(mid=1, kind="plastic003", density=RHO, params={**params, "BETA": 1.0})
    path = [0.0, 0.05, 0.03]
    rk, ri = pull(kin, path), pull(iso, path)
    turn_k = int(np.argmax([r[0][0] for r in rk]))
    turn_i = int(np.argmax([r[0][0] for r in ri]))
    assert rk[turn_k][0][0] == pytest.approx(ri[turn_i][0][0], rel=1e-3)  # same loading
    ep_k, ep_i = rk[turn_k][1], ri[turn_i][1]
    rev_k = [r for r in rk[turn_k:] if r[1] > ep_k + 2e-3]
    rev_i = [r for r in ri[turn_i:] if r[1] > ep_i + 2e-3]
    assert len(rev_k) > 10 and len(rev_i) > 10
    # kinematic (Bauschinger): the yield surface moved with the back stress h eps_p
    for s, ep, *_ in rev_k:
        assert s[0] == pytest.approx(h * (2 * ep_k - ep) - sigy, rel=0.01)
    # isotropic: the surface grew, reverse yield at -(sigma_y + h eps_p)
    for s, ep, *_ in rev_i:
        assert s[0] == pytest.approx(-(sigy + h * ep), rel=0.01)
