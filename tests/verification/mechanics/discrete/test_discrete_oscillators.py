"""Springs and dampers against closed-form oscillators (the solver's own cycle).

Units mm, ms, kg, kN: a 1 kg mass on a 1 kN/mm spring has omega = 1 rad/ms and
period 2 pi ms. The decks run with TSSFAC 0.05 (omega dt = 0.095): the central
difference shortens the period by (omega dt)^2 / 24 = 0.04 %, far inside the
1 % tolerances, which therefore test the element (a wrong stiffness, mass or
direction shows as several %), not the integrator.
"""

from __future__ import annotations

import numpy as np
from discrete_decks import Driver, crossings, curve, f10, load, oscillator_deck

SPRING = "*MAT_SPRING_ELASTIC\n" + f10(1, 1.0) + "\n"


def _peaks(t: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Positive maxima of u (parabola through the three samples around each)."""
    k = np.nonzero((u[1:-1] > u[:-2]) & (u[1:-1] >= u[2:]) & (u[1:-1] > 0.0))[0] + 1
    a, b, c = u[k - 1], u[k], u[k + 1]
    return b - 0.125 * (c - a) ** 2 / (a - 2.0 * b + c)


def test_spring_mass_period_and_energy_balance():
    dr = Driver(load(oscillator_deck([SPRING], end=40.0)))
    r = dr.run(40.0)
    t, u = r[:, 0], r[:, 1] - 100.0
    periods = np.diff(crossings(t, u))
    assert periods.size >= 5
    exact = 2.0 * np.pi * np.sqrt(1.0 / 1.0)
    # tolerance 1 % (brief); measured error 0.04 % = the integrator's (omega dt)^2/24
    assert np.all(np.abs(periods / exact - 1.0) < 0.01), periods
    # amplitude v0 / omega = 1 mm
    assert abs(np.max(np.abs(u)) - 1.0) < 0.01
    # energy: kinetic + spring energy stays the initial 0.5 m v0^2 = 0.5 J over 6 periods;
    # the full-step kinetic-energy estimate of the central difference oscillates by
    # O((omega dt)^2) = 1 %, so 1.5 % bounds it
    total = r[:, 9]
    assert np.all(np.abs(total / 0.5 - 1.0) < 0.015), (total.min(), total.max())
    # the spring's energy is its stored energy 0.5 k d^2 (trapezoidal work is exact)
    rt = dr.plan.elements[0]
    assert abs(rt.internal_energy - 0.5 * rt.defl[0] ** 2) < 1e-12


def test_damped_oscillator_frequency_decrement_and_dissipation():
    c = 0.1  # kN*ms/mm: damping ratio xi = c / (2 sqrt(k m)) = 0.05
    damper = "*MAT_DAMPER_VISCOUS\n" + f10(2, c) + "\n"
    dr = Driver(load(oscillator_deck([SPRING, damper], end=40.0)))
    r = dr.run(40.0)
    t, u, v = r[:, 0], r[:, 1] - 100.0, r[:, 4]
    xi = c / 2.0
    wd = np.sqrt(1.0 - xi ** 2)
    periods = np.diff(crossings(t, u))
    assert np.all(np.abs(periods / (2.0 * np.pi / wd) - 1.0) < 0.01), periods
    peaks = _peaks(t, u)
    assert peaks.size >= 5
    decrement = np.log(peaks[:-1] / peaks[1:])
    exact = 2.0 * np.pi * xi / np.sqrt(1.0 - xi ** 2)  # 0.31455
    assert np.all(np.abs(decrement / exact - 1.0) < 0.01), (decrement, exact)
    spring, dashpot = dr.plan.elements
    # the damper's energy is what it dissipated: int c v^2 dt (row k holds v^{k+1/2},
    # the velocity of the step that ends at t[k])
    dissipated = float(np.sum(c * v ** 2 * np.diff(np.concatenate([[0.0], t]))))
    assert abs(dashpot.internal_energy / dissipated - 1.0) < 0.01
    # balance: kinetic + stored + dissipated = initial 0.5 J
    e = r[:, 9]
    assert np.all(np.abs(e / 0.5 - 1.0) < 0.015), (e.min(), e.max())
    assert dashpot.internal_energy > 0.9 * 0.5 * (1.0 - np.exp(-2 * xi * 40.0))


def test_nonlinear_spring_static_force_follows_its_curve_and_energy_is_conserved():
    pts = [(-20.0, -40.0), (-10.0, -12.0), (0.0, 0.0), (10.0, 12.0), (20.0, 40.0)]
    mat = "*MAT_SPRING_NONLINEAR_ELASTIC\n" + f10(1, 7) + "\n" + curve(7, pts)
    model = load(oscillator_deck([mat], v0=5.0, end=30.0))
    dr = Driver(model)
    rt = dr.plan.elements[0]
    # static: node 2 placed at elongations d, the force on it is -F(d) along x
    s = dr.state
    x = s.x.copy()
    for d in (-25.0, -15.0, -3.0, 0.0, 4.0, 10.0, 17.5, 26.0):
        x[1, 0] = 100.0 + d
        f = np.zeros_like(x)
        saved = (rt.force.copy(), rt.defl.copy(), rt.energy.copy())
        rt.add_forces(x, np.zeros_like(x), 0.0, f)
        rt.force[:], rt.defl[:], rt.energy[:] = saved
        xs = np.array([p[0] for p in pts])
        ys = np.array([p[1] for p in pts])
        if d < xs[0]:
            want = ys[0] + (ys[1] - ys[0]) / (xs[1] - xs[0]) * (d - xs[0])
        elif d > xs[-1]:
            want = ys[-1] + (ys[-1] - ys[-2]) / (xs[-1] - xs[-2]) * (d - xs[-1])
        else:
            want = np.interp(d, xs, ys)
        assert abs(-f[1, 0] - want) < 1e-12 * max(1.0, abs(want))
        assert abs(f[0, 0] - want) < 1e-12 * max(1.0, abs(want))
    # dynamics: 1 kg at 5 m/s: 12.5 J; turning point where int_0^d F = 12.5 J
    r = dr.run(30.0)
    u = r[:, 1] - 100.0
    total = r[:, 9]
    assert np.all(np.abs(total / 12.5 - 1.0) < 0.015), (total.min(), total.max())
    dd = np.linspace(0.0, 20.0, 200001)
    work = np.concatenate([[0.0], np.cumsum(0.5 * np.diff(dd) * (
        np.interp(dd, *zip(*pts))[1:] + np.interp(dd, *zip(*pts))[:-1]))])
    d_max = float(np.interp(12.5, work, dd))
    assert abs(u.max() / d_max - 1.0) < 0.01, (u.max(), d_max)
    assert abs(-u.min() / d_max - 1.0) < 0.01  # symmetric curve


def test_reported_step_is_the_stability_limit_of_the_cycle():
    """Spring k = 1 and damper c = 0.6 in parallel on 1 kg (xi = 0.3): the damped limit
    (2/omega)(sqrt(1 + xi^2) - xi) = 1.488 ms is the step the element reports; the
    solver's own cycle is stable just below it (TSSFAC 0.97) and unstable just above it
    (1.05). The smaller of the two elements' own limits (2 ms spring, 3.33 ms damper)
    would not be: the step sums the springs and dampers at a node."""
    damper = "*MAT_DAMPER_VISCOUS\n" + f10(2, 0.6) + "\n"
    limit = 2.0 * (np.sqrt(1.09) - 0.3)
    for tssfac, stable in ((0.97, True), (1.05, False)):
        dr = Driver(load(oscillator_deck([SPRING, damper], end=200.0, tssfac=tssfac)))
        assert abs(dr.state.dt_next / tssfac - limit) < 1e-12
        r = dr.run(200.0)
        u = np.abs(r[:, 1] - 100.0)
        assert (u[-50:].max() < 1e-3) == stable, (tssfac, u[-50:].max())


def test_failure_deflection_releases_the_mass_with_the_energy_left():
    """FD = 0.6 mm on a spring whose free amplitude is 1 mm: the element is deleted when
    |d| > FD and the mass flies on with 0.5 m v^2 = 0.5 m v0^2 - 0.5 k FD^2, v = 0.8;
    the spring's energy stays in the balance."""
    text = oscillator_deck([SPRING], end=3.0).replace(f10(1, 0) + "\n",
                                                       f10(1, 0, 0.0, 0.0, 0.0, 0.6) + "\n")
    dr = Driver(load(text))
    r = dr.run(3.0)
    rt = dr.plan.elements[0]
    assert not rt.alive[0] and rt.force[0] == 0.0 and 0.6 < rt.defl[0] < 0.7
    v_end = r[-1, 4]
    want = np.sqrt(1.0 - 0.6 ** 2)  # m = k = 1, v0 = 1
    # 1 %: the spring fails within one step's motion (0.08 mm) beyond FD
    assert abs(v_end / want - 1.0) < 0.01, v_end
    assert np.all(np.diff(r[-5:, 1]) > 0.0) and abs(r[-1, 9] / 0.5 - 1.0) < 0.01


def test_mass_scaling_adds_no_mass_for_springs_and_keeps_their_step():
    """DT2MS = -5 ms above the spring's 2 ms step: mass scaling adds no mass for a
    (massless) discrete element, and the run keeps the spring's own step instead of
    reporting the target it could not reach."""
    text = oscillator_deck([SPRING], end=1.0, tssfac=0.5).replace(
        "*CONTROL_TIMESTEP\n" + f10(0.0, 0.5), "*CONTROL_TIMESTEP\n" + f10(0.0, 0.5, 0, 0.0,
                                                                          -5.0))
    dr = Driver(load(text))
    assert dr.state.mass_scaling.target == 5.0
    dr.run(1.0)
    assert dr.state.mass_scaling.total_added == 0.0
    assert abs(dr.state.dt_next - 0.5 * 2.0) < 1e-12  # TSSFAC x 2 sqrt(m / k)
