"""The SAE J211 channel-frequency-class (CFC) filter: the one low pass of the project.

Definition (SAE J211-1, Rev. MAR95, Appendix C "Butterworth 4-pole phaseless
digital filter"; the same filter is ISO 6487's): a 2-pole Butterworth low pass

    Y[i] = a0 X[i] + a1 X[i-1] + a2 X[i-2] + b1 Y[i-1] + b2 Y[i-2]

with, for the sampling interval T (s) and the channel frequency class CFC (Hz),

    w_d = 2 pi CFC 2.0775,    w_a = sin(w_d T / 2) / cos(w_d T / 2),
    a0 = a2 = w_a^2 / (1 + sqrt(2) w_a + w_a^2),   a1 = 2 a0,
    b1 = -2 (w_a^2 - 1) / (1 + sqrt(2) w_a + w_a^2),
    b2 = (-1 + sqrt(2) w_a - w_a^2) / (1 + sqrt(2) w_a + w_a^2),

run once forward and once backward over the data, which doubles the order
(4 poles) and cancels the phase. Its gain is -3 dB at 1.6667 x CFC and about
-0.45 dB at CFC, inside the J211-1 corridor (+0.5/-1 dB up to CFC, +0.5/-4 dB
at 1.6667 x CFC, -9 to -24 dB per octave above); the tests check it against
that corridor. Public descriptions of the same algorithm: the SAE J211 notes of
the FlexPro "CFC Filter Calculation" page (weisang.com) and the J211-compliant
filter of the MATLAB File Exchange (no. 61852), which both state the forward
and backward 2-pole pass and the 2.0775 design factor.

Ends: a forward-backward filter needs data before the first and after the last
sample to settle. SAE J211-1 recommends recording pre- and post-event data for
this or, where a record has none (a simulation that starts at first contact),
padding the record; here it is extended by its inverted mirror image (odd
reflection about the first and the last sample, as long as the record itself)
before filtering and the extension is cut off again. The filtered series then
starts at the first sample and ends at the last one: a contact force that is
zero at first contact starts at zero even when a single-cycle contact spike
follows, instead of starting at the spike smeared back into the time before
contact. Away from the ends the result is the same as with any other padding
(the peak of a force pulse in the middle of the record moves by round-off).
"""

from __future__ import annotations

import numpy as np

#: Ratio of the J211 design frequency of one 2-pole pass to the class (w_d / 2 pi CFC).
DESIGN_RATIO = 2.0775
#: Fewer samples than this are returned unchanged (the filter needs a start-up).
MIN_SAMPLES = 16
#: A design frequency at or above this fraction of the sampling rate is not filtered
#: (the series is too coarse for the class; it is returned unchanged).
MAX_DESIGN_FRACTION = 0.45


def j211_coefficients(cfc: float, dt_s: float) -> tuple[np.ndarray, np.ndarray]:
    """(b (3,), a (3,)) of one 2-pole J211 pass for class ``cfc`` (Hz) and step ``dt_s`` (s).

    In the transfer-function form ``sum b_k z^-k / sum a_k z^-k`` (``a[0] = 1``), so
    ``a = (1, -b1, -b2)`` and ``b = (a0, a1, a2)`` of the J211 difference equation.
    """
    wd = 2.0 * np.pi * cfc * DESIGN_RATIO
    wa = np.tan(0.5 * wd * dt_s)
    den = 1.0 + np.sqrt(2.0) * wa + wa * wa
    a0 = wa * wa / den
    b1 = -2.0 * (wa * wa - 1.0) / den
    b2 = (-1.0 + np.sqrt(2.0) * wa - wa * wa) / den
    return np.array([a0, 2.0 * a0, a0]), np.array([1.0, -b1, -b2])


def cfc_gain(freq_hz: np.ndarray, cfc: float, dt_s: float) -> np.ndarray:
    """Gain (linear, (m,)) of the phaseless filter (both passes) at ``freq_hz`` (m,) Hz."""
    b, a = j211_coefficients(cfc, dt_s)
    z = np.exp(-1j * 2.0 * np.pi * np.asarray(freq_hz, dtype=float) * dt_s)
    h = (b[0] + b[1] * z + b[2] * z * z) / (a[0] + a[1] * z + a[2] * z * z)
    return np.abs(h) ** 2


def cfc_filter(t: np.ndarray, y: np.ndarray, cfc: float) -> np.ndarray:
    """``y`` (k,) filtered with SAE J211 class ``cfc`` (Hz); ``t`` (k,) uniform times in ms.

    The step is the mean step of ``t``. Series shorter than :data:`MIN_SAMPLES`,
    or sampled too coarsely for the class (design frequency 2.0775 x CFC at or
    above :data:`MAX_DESIGN_FRACTION` of the sampling rate), are returned
    unchanged (a copy). The ends are padded by odd reflection (module doc), so
    the result starts at ``y[0]`` and ends at ``y[-1]``. Returns a new (k,) array
    in the unit of ``y``.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if y.size < MIN_SAMPLES:
        return y.copy()
    dt_s = (t[-1] - t[0]) / (t.size - 1) * 1e-3
    if not dt_s > 0.0 or DESIGN_RATIO * cfc * dt_s >= MAX_DESIGN_FRACTION:
        return y.copy()
    b, a = j211_coefficients(cfc, dt_s)
    from scipy.signal import filtfilt  # imported here: scipy.signal takes ~1 s to load

    return filtfilt(b, a, y, padtype="odd", padlen=y.size - 1)
