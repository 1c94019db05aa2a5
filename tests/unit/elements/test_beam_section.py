"""Beam cross-section rules, section constants and the element's critical step."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hollowbody.elements.beam_section import (
    element_step,
    rectangle_points,
    rotational_r2,
    section_points,
    tube_points,
)
from hollowbody.model.beams import beam_frames, section_constants


@pytest.mark.parametrize("qr", [2, 3, 4, 5])
def test_rectangle_rules_integrate_area_and_inertia(qr):
    ts, tt = 6.0, 4.0
    p = rectangle_points(ts, tt, qr)
    w, s, t = p[:, 2], p[:, 0], p[:, 1]
    assert w.sum() == pytest.approx(ts * tt, rel=1e-14)
    assert (w * t * t).sum() == pytest.approx(ts * tt ** 3 / 12.0, rel=1e-14)  # ISS
    assert (w * s * s).sum() == pytest.approx(tt * ts ** 3 / 12.0, rel=1e-14)  # ITT
    assert abs((w * s).sum()) < 1e-12 and abs((w * t).sum()) < 1e-12


@pytest.mark.parametrize("qr, npts", [(1, 8), (2, 16), (3, 48)])
def test_tube_rule_integrates_area_and_inertia(qr, npts):
    d, di = 10.0, 8.0
    p = tube_points(d, di, qr)
    assert p.shape == (npts, 3)
    w = p[:, 2]
    area = math.pi * (d * d - di * di) / 4.0
    i = math.pi * (d ** 4 - di ** 4) / 64.0
    assert w.sum() == pytest.approx(area, rel=1e-12)
    if qr >= 2:  # r^3 dr: exact with 2 points through the wall
        assert (w * p[:, 1] ** 2).sum() == pytest.approx(i, rel=1e-12)
    params = {"TS1": d, "TS2": d, "TT1": di, "TT2": di, "CST": 1, "QR": qr}
    assert section_constants(1, params)[:3] == pytest.approx((area, i, i))
    assert np.array_equal(section_points(params), p)


@pytest.mark.parametrize("cubic", [True, False])
@pytest.mark.parametrize("aspect", [0.25, 0.5, 1.0, 2.0, 5.0, 20.0, 100.0])
def test_rotations_never_govern_the_step(cubic, aspect):
    """With J_node = m_node max(L^2/4, (ISS+ITT)/A) the exact step of a free
    element (lumped masses, elastic stiffness) is at least L / c (to 1e-9) for
    any aspect ratio L / h with shear flexibility (ELFORM 1; ELFORM 2 with SA),
    and for L >= 2 h for the Euler-Bernoulli resultant beam (SA = 0), whose
    stubby elements are stiffer in bending (12 EI / L^3) than axially: there
    the step is lower, computed exactly."""
    e_mod, nu, rho = 200.0, 0.3, 7.85e-6
    g = e_mod / (2 * (1 + nu))
    for b, h in ((5.0, 5.0), (10.0, 2.0)):
        area, iss, itt = b * h, b * h ** 3 / 12, h * b ** 3 / 12
        tors = iss + itt
        length = np.array([aspect * max(b, h)])
        m = rho * area * length / 2
        j = m * rotational_r2(length, area, iss, itt)
        dt_axial = length[0] / math.sqrt(e_mod / rho)
        dt = element_step(length, m, j, e_mod, g, area, iss, itt, tors, 5.0 / 6.0 * g * area,
                          cubic)
        assert dt[0] >= (1.0 - 1e-9) * dt_axial
        if cubic:
            dt = element_step(length, m, j, e_mod, g, area, iss, itt, tors, np.inf, cubic)
            if aspect >= 2.0:
                assert dt[0] >= (1.0 - 1e-9) * dt_axial
            else:
                assert dt[0] < dt_axial


def test_physical_inertia_is_kept_for_stubby_beams():
    length = np.array([1.0, 100.0])
    r2 = rotational_r2(length, 25.0, 52.0, 52.0)
    assert r2[0] == pytest.approx(104.0 / 25.0)  # (ISS + ITT) / A
    assert r2[1] == pytest.approx(100.0 ** 2 / 4.0)


def test_frames_with_and_without_orientation_node():
    x = np.array([[0.0, 0, 0], [10, 0, 0], [0, 5, 5], [0, 0, 10], [3, 0, 0]])
    conn = np.array([[0, 1, 2], [0, 1, -1], [0, 3, -1], [0, 1, 4]])
    f, length, bad = beam_frames(conn, x)
    assert np.allclose(f[0], [[1, 0, 0], [0, 1 / math.sqrt(2), 1 / math.sqrt(2)],
                              [0, -1 / math.sqrt(2), 1 / math.sqrt(2)]])
    assert np.allclose(f[1, 1], [0, 1, 0])  # along x: s = global y
    assert np.allclose(f[2, 1], [0, 1, 0])  # along z: s = global y
    assert bad.tolist() == [False, False, False, True]  # N3 on the axis
    assert length.tolist() == [10.0, 10.0, 10.0, 10.0]


def test_default_orientation_of_axis_aligned_beams():
    """Without N3: s = global Y for beams along X and Z, global X along Y."""
    x = np.array([[0.0, 0, 0], [5, 0, 0], [0, 5, 0], [0, 0, 5]])
    f, _, bad = beam_frames(np.array([[0, 1, -1], [0, 2, -1], [0, 3, -1]]), x)
    assert not bad.any()
    assert np.allclose(f[:, 1], [[0, 1, 0], [1, 0, 0], [0, 1, 0]])
    assert np.allclose(np.einsum("ij,ij->i", f[:, 0], f[:, 1]), 0.0)
