"""Force-displacement curves: CFC filtering of force histories, peak force, smoothing."""

import numpy as np
import pytest

from hollowbody.curves.cfc import cfc_filter
from hollowbody.curves.force_displacement import ForceDisplacement, smoothed


def test_cfc600_passes_slow_signals_and_removes_fast_ones():
    t = np.arange(0.0, 40.0, 0.01)  # ms, 100 kHz
    slow = np.sin(2 * np.pi * 0.05 * t)  # 50 Hz: far below the 990 Hz corner
    fast = 0.5 * np.sin(2 * np.pi * 10.0 * t)  # 10 kHz: 10x above the corner
    out = cfc_filter(t, slow + fast, 600.0)
    core = slice(200, -200)
    # 4-pole Butterworth: gain at 50 Hz > 0.9999, at 10 kHz ~ (0.099)^4 ~ 1e-4
    assert np.max(np.abs(out[core] - slow[core])) < 2e-3


def test_peak_force_uses_filtered_curve():
    t = np.arange(0.0, 20.0, 0.02)
    f = np.sin(np.pi * t / 20.0) * 10.0
    f_spike = f.copy()
    f_spike[5] = 50.0  # one-sample first-contact spike
    c = ForceDisplacement(t, t, f_spike)
    assert c.peak_force_raw == 50.0
    assert c.peak_force == pytest.approx(10.0, rel=0.05)


def test_cfc_filter_keeps_slow_and_removes_fast_signals():
    t = np.linspace(0.0, 20.0, 1001)  # ms, 50 kHz
    slow = np.sin(2 * np.pi * 0.05 * t)  # 50 Hz
    fast = 0.5 * np.sin(2 * np.pi * 5.0 * t)  # 5 kHz
    out = cfc_filter(t, slow + fast, 180.0)
    core = slice(100, -100)
    assert np.max(np.abs(out[core] - slow[core])) < 0.03


def test_smoothed_drops_repeated_times():
    c = ForceDisplacement(np.array([0.0, 0.1, 0.1, 0.2, 0.3]), np.arange(5.0),
                          np.ones(5))
    s = smoothed(c, None)
    assert np.all(np.diff(s.time) > 0)
