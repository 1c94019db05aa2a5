"""Verification: a short aluminium circular tube crushed axially by a rigid plate.

D = 40 mm, t = 1.333 mm (D/t = 30), L = 70 mm (10.8 Alexander half folds),
2 elements per half fold, outward ring trigger 0.3 t near the loaded end,
MAT_024 sigma_y 0.25 GPa perfectly plastic, plate at 15 m/s to 72 % of L.
Bands as in test_crush_square_tube.py (same reasoning): energy ratio 0.98-1.02
once the plate has done 1 % of its work and within 1 % at the end; plate work =
the energies within 1 %; mean force within a factor 2 of the analytical range
[Alexander 1960, Abramowicz-Jones 1986 with the effective crush distance].
Measured: energy ratio 0.999-1.001, plate work / energies 1.005 (the contact
energy is -8 % of the total here: energy the contacts created, which the sum
includes), mean force 26.0 kN against 13.6-22.5 kN (1.15 x the upper end),
half fold from the force peaks 6.48 mm against Alexander's 6.47 mm,
hourglass 30 % of the internal energy. The target, the mean force inside the
range, is xfail(strict=True).
"""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.scenarios.crush import CrushCase, run_crush

CASE = CrushCase(shape="circular", size=40.0, t=40.0 / 30.0, length=70.0, per_half_fold=2.0,
                 material="aluminium", trigger=0.3, speed=15.0)


@pytest.fixture(scope="module")
def crushed(tmp_path_factory):
    out = tmp_path_factory.mktemp("crush_circular")
    return run_crush(CASE, out / "run", threads=1), out / "run"


def test_circular_crush_energy_balance_and_plate_work(crushed):
    r, out = crushed
    assert r.status == "normal termination"
    gl = np.genfromtxt(out / "glstat.csv", delimiter=",", names=True)
    ratio = gl["energy_ratio"][gl["external_work_J"] >= 0.01 * gl["external_work_J"][-1]]
    assert ratio.size > 100
    assert ratio.min() > 0.98 and ratio.max() < 1.02
    assert abs(ratio[-1] - 1.0) < 0.01
    assert abs(r.energy_sum / r.plate_work - 1.0) < 0.01


def test_circular_mean_force_within_a_factor_two_of_the_analytical_range(crushed):
    r, _ = crushed
    assert r.reference.low / 2.0 < r.mean_force < 2.0 * r.reference.high


@pytest.mark.xfail(strict=True, reason="the shell folds too stiffly on this mesh (2 "
                   "elements per half fold): mean force 1.15 x the upper end of the analytical "
                   "range, hourglass 30 % of IE")
def test_circular_mean_force_inside_the_analytical_range(crushed):
    r, _ = crushed
    assert r.reference.low <= r.mean_force <= r.reference.high
