"""SAE J211 CFC filter: the J211-1 frequency-response corridor, no phase shift, the design.

Corridor (SAE J211-1, channel frequency classes): gain within +0.5 / -1 dB from
0.1 Hz up to F_H = CFC, within +0.5 / -4 dB at F_N = 1.6667 x CFC, and above
F_N between an upper bound falling 9 dB per octave from +0.5 dB and a lower
bound falling 24 dB per octave from -4 dB (checked while the upper bound is
above -30 dB).
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.curves.cfc import DESIGN_RATIO, cfc_filter, cfc_gain, j211_coefficients

F_N_RATIO = 1.0 / 0.6  # F_N / CFC = 1.6667


def corridor_db(f: np.ndarray, cfc: float) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper) J211-1 corridor (dB) at frequencies ``f`` (Hz) for class ``cfc``."""
    f = np.asarray(f, dtype=float)
    f_n = F_N_RATIO * cfc
    octaves = np.log2(np.maximum(f / f_n, 1.0))
    upper = 0.5 - 9.0 * octaves
    lower = np.where(f <= cfc, -1.0, -4.0 - 24.0 * octaves)
    return lower, upper


def _sine_response(cfc: float, f: float, dt_ms: float, periods: float = 60.0
                   ) -> tuple[float, float]:
    """(gain, phase rad) of the filter on a sine of ``f`` Hz, fitted away from the ends."""
    n = int(round(periods / (f * dt_ms * 1e-3)))
    n = max(n, 4000)
    t = np.arange(n) * dt_ms
    w = 2.0 * np.pi * f * t * 1e-3
    y = cfc_filter(t, np.sin(w), cfc)
    core = slice(n // 4, 3 * n // 4)
    basis = np.column_stack([np.sin(w[core]), np.cos(w[core])])
    (s, c), *_ = np.linalg.lstsq(basis, y[core], rcond=None)
    return float(np.hypot(s, c)), float(np.arctan2(c, s))


@pytest.mark.parametrize("cfc", [60.0, 180.0, 600.0, 1000.0])
def test_gain_inside_the_j211_corridor(cfc):
    dt_s = 1.0e-5  # 100 kHz sampling
    f = np.concatenate([np.geomspace(0.1, cfc, 40),
                        np.geomspace(F_N_RATIO * cfc, 10.0 * F_N_RATIO * cfc, 40)])
    db = 20.0 * np.log10(cfc_gain(f, cfc, dt_s))
    lower, upper = corridor_db(f, cfc)
    keep = upper >= -30.0
    assert np.all(db[keep] <= upper[keep] + 1e-9)
    assert np.all(db[keep] >= lower[keep] - 1e-9)
    # the phaseless 4-pole filter is -3 dB at F_N and about -0.45 dB at CFC
    f_n_db = 20.0 * np.log10(cfc_gain(np.array([F_N_RATIO * cfc]), cfc, dt_s))[0]
    assert f_n_db == pytest.approx(-3.0, abs=0.1)
    assert -4.0 < f_n_db < 0.5
    cfc_db = 20.0 * np.log10(cfc_gain(np.array([cfc]), cfc, dt_s))[0]
    assert cfc_db == pytest.approx(-0.45, abs=0.05)
    # well below the class the gain is 1
    assert cfc_gain(np.array([0.01 * cfc]), cfc, dt_s)[0] == pytest.approx(1.0, abs=1e-6)


def test_design_frequency_is_2_0775_cfc():
    """One 2-pole pass is -3 dB (half power) exactly at the pre-warped design frequency
    2.0775 x CFC, so both passes give a gain of 1/2 there; the DC gain is 1."""
    for cfc, dt_s in ((180.0, 1e-4), (600.0, 1e-5), (1000.0, 2e-5)):
        f_d = DESIGN_RATIO * cfc
        assert cfc_gain(np.array([f_d]), cfc, dt_s)[0] == pytest.approx(0.5, rel=1e-12)
        b, a = j211_coefficients(cfc, dt_s)
        assert b.sum() / a.sum() == pytest.approx(1.0, rel=1e-12)
        assert b[1] == 2.0 * b[0] and b[2] == b[0]


@pytest.mark.parametrize("cfc,f", [(600.0, 50.0), (600.0, 600.0), (600.0, 1000.0),
                                   (600.0, 3000.0), (180.0, 180.0), (180.0, 300.0)])
def test_filtered_sines_have_the_corridor_gain_and_no_phase_shift(cfc, f):
    dt_ms = 0.01
    gain, phase = _sine_response(cfc, f, dt_ms)
    expected = cfc_gain(np.array([f]), cfc, dt_ms * 1e-3)[0]
    assert gain == pytest.approx(expected, rel=1e-3, abs=1e-6)
    lower, upper = corridor_db(np.array([f]), cfc)
    assert lower[0] - 0.01 <= 20.0 * np.log10(gain) <= upper[0] + 0.01
    assert abs(phase) < 1e-3


def test_symmetric_pulse_stays_symmetric_and_in_place():
    t = np.linspace(0.0, 40.0, 4001)  # ms, 100 kHz; sample 2000 at 20 ms
    pulse = np.exp(-0.5 * ((t - 20.0) / 0.4) ** 2)  # 0.4 ms wide, centred at 20 ms
    pulse = 0.5 * (pulse + pulse[::-1])  # exactly symmetric samples
    y = cfc_filter(t, pulse, 180.0)
    assert int(np.argmax(y)) == 2000
    assert np.max(np.abs(y - y[::-1])) < 1e-9 * y.max()
    # a causal (one-pass) filter would delay the peak; this one keeps the centroid
    centroid = float(np.sum(t * y) / np.sum(y))
    assert centroid == pytest.approx(20.0, abs=1e-6)


def test_short_or_coarse_series_are_returned_unchanged():
    t = np.arange(10) * 0.01
    y = np.arange(10.0)
    out = cfc_filter(t, y, 600.0)
    assert np.array_equal(out, y) and out is not y
    t = np.arange(100) * 1.0  # 1 kHz sampling: far too coarse for CFC 600
    y = np.sin(t)
    assert np.array_equal(cfc_filter(t, y, 600.0), y)


def test_filtered_contact_force_starts_at_the_first_sample():
    """A force that is zero at first contact and spikes in the next cycles (a
    first-contact spike, then a slow pulse) keeps its zero start when filtered:
    the ends are padded by odd reflection, not smeared back into the time before
    contact. The slow pulse's peak is that of the unpadded filter to round-off."""
    t = np.arange(0.0, 20.0, 0.02)  # ms, 50 kHz
    slow = 14.0 * np.sin(np.pi * t / t[-1]) ** 2  # kN, peak 14 kN at 10 ms
    spike = np.zeros_like(t)
    spike[1:4] = (41.0, 48.0, 31.0)  # single-cycle contact spike right after contact
    force = slow + spike
    for cfc in (180.0, 600.0):
        y = cfc_filter(t, force, cfc)
        assert abs(y[0]) < 1e-9 and abs(y[-1]) < 1e-9
        assert np.max(np.abs(y[:10])) < 0.5 * 48.0  # the spike is smoothed, not kept
        core = slice(200, 800)
        assert np.max(y[core]) == pytest.approx(np.max(slow[core]), rel=2e-3)
    # the first value is the first sample also when it is not zero
    y = cfc_filter(t, force + 2.5, 180.0)
    assert y[0] == pytest.approx(2.5, abs=1e-9)
