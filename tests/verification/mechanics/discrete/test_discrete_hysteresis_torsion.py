"""S06 loading / unloading / hysteresis energy, and a torsional spring on a rigid body."""

from __future__ import annotations

import numpy as np
import pytest
from discrete_decks import Driver, crossings, curve, f10, oscillator_deck
from discrete_decks import load as load_model

from hollowbody.solver.energies import energies
from hollowbody.solver.step import step

LOAD = [(0.0, 0.0), (2.0, 10.0), (10.0, 14.0), (20.0, 16.0)]  # kN vs mm
UNLOAD = [(-2.0, -30.0), (-1.0, -10.0), (0.0, 0.0), (0.5, 6.0), (1.0, 10.0)]


def _curve_value(pts, d):
    xs, ys = np.array(pts).T
    if d > xs[-1]:
        return ys[-1] + (ys[-1] - ys[-2]) / (xs[-1] - xs[-2]) * (d - xs[-1])
    if d < xs[0]:
        return ys[0] + (ys[1] - ys[0]) / (xs[1] - xs[0]) * (d - xs[0])
    return float(np.interp(d, xs, ys))


def _s06_runtime(beta: float = 1.0, tyi: float = 0.0, cyi: float = 0.0, load=LOAD):
    mat = ("*MAT_SPRING_GENERAL_NONLINEAR\n" + f10(1, 11, 12, beta, tyi, cyi) + "\n"
           + curve(11, load) + curve(12, UNLOAD))
    dr = Driver(load_model(oscillator_deck([mat], v0=0.0, end=1.0)))
    return dr.plan.elements[0], dr.state.x.copy()


def _force_at(rt, x, d):
    x = x.copy()
    x[1, 0] = 100.0 + d
    f = np.zeros_like(x)
    rt.add_forces(x, np.zeros_like(x), 1e-3, f)
    return -f[1, 0]


def _path(rt, x, a, b, n):
    return [(d, _force_at(rt, x, d)) for d in np.linspace(a, b, n + 1)[1:]]


def test_s06_loads_on_lcdl_unloads_on_shifted_lcdu_and_dissipates_the_loop_area():
    rt, x = _s06_runtime()
    for d, f in _path(rt, x, 0.0, 10.0, 2000):
        assert abs(f - _curve_value(LOAD, d)) < 1e-9
    # unloading from F = L(10) = 14: LCDU shifted along the deflection axis so that it
    # passes through (10, 14); U^-1(14) = 1.5 (end slope 8) -> shift 8.5 mm
    shift = 10.0 - 1.5
    for d, f in _path(rt, x, 10.0, shift, 600):
        assert abs(f - _curve_value(UNLOAD, d - shift)) < 1e-9
    assert abs(rt.force[0]) < 1e-9
    # dissipated = loop area = int_0^10 L - int_shift^10 U(d - shift) (trapezoid, fine)
    dd = np.linspace(0.0, 10.0, 100001)
    area_load = np.trapezoid([_curve_value(LOAD, d) for d in dd], dd)
    du = np.linspace(shift, 10.0, 100001)
    area_unload = np.trapezoid([_curve_value(UNLOAD, d - shift) for d in du], du)
    # tolerance 0.1 %: the element integrates the same curves with 0.005 mm steps
    assert abs(rt.energy[0] / (area_load - area_unload) - 1.0) < 1e-3
    # reloading: elastic on the shifted unloading curve up to the last force, then LCDL
    assert abs(_force_at(rt, x, 9.5) - _curve_value(UNLOAD, 1.0)) < 1e-9
    for d, f in _path(rt, x, 9.5, 12.0, 500):
        assert f <= _curve_value(LOAD, d) + 1e-9
    assert abs(f - _curve_value(LOAD, 12.0)) < 1e-9


def test_s06_isotropic_hardening_raises_the_compressive_yield():
    """BETA = 1: after tension to 14 kN the compressive yield force is -14 kN: unloading
    follows the shifted LCDU down to -14 kN (U^-1(-14) = -1.2, at d = 7.3) and then
    yields at -14 kN while the loading curve has no compression branch there."""
    rt, x = _s06_runtime(beta=1.0)
    _path(rt, x, 0.0, 10.0, 200)
    for d, f in _path(rt, x, 10.0, 6.0, 400):
        want = max(_curve_value(UNLOAD, d - 8.5), -14.0)
        assert abs(f - want) < 1e-9, (d, f, want)
    assert abs(f + 14.0) < 1e-9


def test_s06_beta_zero_softens_along_the_loading_curve():
    """BETA = 0: the force follows a loading curve that falls after its peak (softening),
    never below the initial yield force TYI; BETA = 1 holds the peak instead."""
    peak = [(0.0, 0.0), (2.0, 10.0), (4.0, 6.0), (10.0, 6.0)]
    soft, x = _s06_runtime(beta=0.0, tyi=1.0, load=peak)
    hard, _ = _s06_runtime(beta=1.0, tyi=1.0, load=peak)
    for (d, fs), (_, fh) in zip(_path(soft, x, 0.0, 6.0, 600), _path(hard, x, 0.0, 6.0, 600)):
        if d >= 0.1:  # elastic on LCDU up to TYI = 1 kN (d = 1/12 mm), then yielding
            assert abs(fs - max(_curve_value(peak, d), 1.0)) < 1e-9, (d, fs)
            assert abs(fh - max(_curve_value(peak, min(d, 2.0)), 1.0)) < 1e-9, (d, fh)


def test_s06_kinematic_hardening_moves_the_elastic_range():
    """BETA = 0.5 (kinematic), TYI = 4, CYI = -4: after tension to 14 kN the elastic range
    [6, 14] kN: unloading leaves LCDU at +6 kN (reverse yield)."""
    rt, x = _s06_runtime(beta=0.5, tyi=4.0, cyi=-4.0)
    _path(rt, x, 0.0, 10.0, 200)
    assert abs(rt.hist[0, 2] - 14.0) < 1e-9 and abs(rt.hist[0, 3] - 6.0) < 1e-9
    for d, f in _path(rt, x, 10.0, 5.0, 500):
        assert abs(f - max(_curve_value(UNLOAD, d - 8.5), 6.0)) < 1e-9, (d, f)


TORSION = """\
*KEYWORD
*CONTROL_TERMINATION
{end:>10}
*CONTROL_TIMESTEP
       0.0      0.05
*NODE
       1             0.0             0.0           -10.0
       2             0.0             0.0             0.0
       3            10.0             0.0             0.0
       4             0.0            10.0             0.0
       5           -10.0             0.0             0.0
       6             0.0           -10.0             0.0
*BOUNDARY_SPC_NODE
         1         0         1         1         1         1         1         1
*SECTION_SHELL
         1         2
       1.0       1.0       1.0       1.0
*MAT_RIGID
         1    7.8e-6     200.0       0.3
       1.0         7         4
*PART_INERTIA
plate
         1         1         1
       0.0       0.0       0.0       2.0
{izz:>10}       0.0       0.0{izz:>10}       0.0{izz:>10}
       0.0       0.0       0.0       0.0       0.0       1.0
*ELEMENT_SHELL
       1       1       2       3       4       4
       2       1       2       4       5       5
       3       1       2       5       6       6
       4       1       2       6       3       3
*SECTION_DISCRETE
         2         1

*PART
torsion spring
         2         2         2
*MAT_SPRING_ELASTIC
         2{kt:>10}
*ELEMENT_DISCRETE
       1       2       1       2       0             1.0       0             0.0
*END
"""


GROUNDED = ("       1       2       1       2       0",
            "       1       2       2       0       9")


@pytest.mark.parametrize("grounded", [False, True])
def test_torsional_spring_on_a_rigid_body_period(grounded):
    """Between a fixed node and the body's centre node (axis along their line), or
    grounded (N2 = 0) about a *DEFINE_SD_ORIENTATION vector along z."""
    izz, kt = 50.0, 200.0  # kg*mm^2, kN*mm/rad: omega = 2 rad/ms, period pi ms
    text = TORSION.format(end=15.0, izz=izz, kt=kt)
    if grounded:
        text = text.replace(*GROUNDED).replace(
            "*END", "*DEFINE_SD_ORIENTATION\n" + f10(9, 0, 0.0, 0.0, 1.0) + "\n*END")
    model = load_model(text)
    dr = Driver(model)
    body = dr.plan.bodies[0]
    rows = []
    s = dr.state
    while s.t < 15.0:
        step(model, dr.plan, s, s.dt_next)
        rows.append((s.t, body.omega[2], energies(dr.plan, s)["total"]))
    t, w, total = np.array(rows).T
    periods = np.diff(crossings(t, w))
    exact = 2.0 * np.pi * np.sqrt(izz / kt)
    assert periods.size >= 3
    # tolerance 1 %; (omega dt)^2/24 of the integrator is 0.2 % at TSSFAC 0.05
    assert np.all(np.abs(periods / exact - 1.0) < 0.01), (periods, exact)
    # amplitude of the twist: w0 / omega = 0.5 rad, stored energy at it 0.5 kt 0.25
    rt = dr.plan.elements[0]
    assert rt.torsional and rt.n_elem == 1
    assert abs(np.abs(w).max() - 1.0) < 0.01
    # balance: body kinetic + spring energy = 0.5 Izz w0^2 = 25 J (full-step estimates,
    # O((omega dt)^2) = 1 % swing at most)
    assert np.all(np.abs(total / (0.5 * izz) - 1.0) < 0.01), (total.min(), total.max())


def test_s06_unloading_curve_not_through_the_origin_gives_no_force_at_rest():
    """An LCDU whose zero force is at 0.5 mm is placed with it at zero deflection: no
    force at rest, and the first elastic response is U(d + 0.5)."""
    mat = ("*MAT_SPRING_GENERAL_NONLINEAR\n" + f10(1, 11, 12, 1.0, 5.0, -5.0) + "\n"
           + curve(11, LOAD) + curve(12, [(0.0, -10.0), (0.5, 0.0), (1.5, 20.0)]))
    dr = Driver(load_model(oscillator_deck([mat], v0=0.0, end=1.0)))
    rt, x = dr.plan.elements[0], dr.state.x.copy()
    assert rt.force[0] == 0.0
    assert abs(_force_at(rt, x, 0.1) - 2.0) < 1e-12  # 20 kN/mm x 0.1 mm, below TYI
