"""CFC filter of force histories (hollowbody.report.force_displacement)."""

import numpy as np
import pytest

from hollowbody.report.force_displacement import ForceDisplacement, cfc_filter


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
