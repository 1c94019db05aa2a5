"""Verification: a short aluminium square tube crushed axially by a rigid plate.

C = 40 mm, t = 2 mm (C/t = 20), L = 100 mm (6.9 closed-form half folds),
3 elements per half fold (8 per side, 5 mm), trigger 0.3 t near the loaded
end, MAT_024 sigma_y 0.25 GPa perfectly plastic, plate at 15 m/s to 72 % of
L (:mod:`hollowbody.scenarios.crush`). One run (about 20 s on one core) serves
every test.

What holds today, with its band:

- energy balance: the ratio stays in 0.98-1.02 at every output once the
  plate has done 1 % of its final work, and ends within 1 % of 1 (measured
  0.999-1.006, end 1.000). Central differences with penalty contact conserve
  energy to O(dt^2); the solver's verification tests hold 2 %, 1 % at the
  end is what this case keeps with margin. The first outputs are left out:
  there the energies are below 2 J and the plate's start from rest (its
  prescribed-motion work counted per cycle against its full-step kinetic
  energy) is off by a few 0.01 J, i.e. a ratio of 0.94 at 0.013 ms.
- the plate's work int F dd (rcforc of the tube-plate contact times the
  plate's travel, trapezoidal on samples every 0.2 mm) equals the tube's
  internal + hourglass + kinetic energy + the contact energy (both contacts,
  friction included) within 1 % (measured 0.03 %): the trapezoid rule's error
  on a force sampled 25 times per fold is < 0.5 %, the plate is rigid and
  only the two contacts do work on the tube.
- the mean crush force over the stable folding range (2 H to 0.7 L) is
  within a factor 2 of the analytical range [Wierzbicki-Abramowicz 1983,
  Abramowicz-Jones 1984] (a guard band), and inside the range itself
  (measured 29.8 kN against 25.9-35.4 kN, 0.84 x the upper end; with the
  former elastic drilling spring of 0.1 G t A it was 1.30 x);
- a half-fold length within 25 % of the closed form 0.99 t^(1/3) C^(2/3) =
  14.6 mm (measured 11.0 mm from the force peaks, 0.76 x, near the band's
  edge; 12.4 mm before the fresh-contact rule, 19.9 mm with the drilling
  spring). 25 %: the peaks of a 3-element-per-half-fold mesh place a fold to
  about one element (5 mm of a 29 mm fold, 17 %);
- hourglass energy below 5 % of the internal energy (measured 2.3 %; 6.1 %
  before the fresh-contact rule, 32 % with the drilling spring; OpenRadioss'
  QEPH shells keep ~0).
"""

from __future__ import annotations

import pytest
from crush_checks import assert_balanced_run

from hollowbody.scenarios.crush import CrushCase, run_crush

CASE = CrushCase(shape="square", size=40.0, t=2.0, length=100.0, per_half_fold=3.0,
                 material="aluminium", trigger=0.3, speed=15.0)


@pytest.fixture(scope="module")
def crushed(tmp_path_factory):
    out = tmp_path_factory.mktemp("crush")
    return run_crush(CASE, out / "run", threads=1), out / "run"


def test_crush_runs_to_the_end_with_energy_balance(crushed):
    r, out = crushed
    assert_balanced_run(r, out)


def test_plate_work_equals_the_energies_it_went_into(crushed):
    r, _ = crushed
    assert r.plate_work > 0.5 * r.mean_force * CASE.crush * CASE.length  # the tube was crushed
    assert abs(r.energy_sum / r.plate_work - 1.0) < 0.01


def test_mean_force_within_a_factor_two_of_the_analytical_range(crushed):
    r, _ = crushed
    ref = r.reference
    assert ref.low / 2.0 < r.mean_force < 2.0 * ref.high


def test_mean_force_inside_the_analytical_range(crushed):
    r, _ = crushed
    assert r.reference.low <= r.mean_force <= r.reference.high


def test_hourglass_energy_is_small(crushed):
    r, _ = crushed
    assert r.hourglass_share < 0.05


def test_half_fold_length_near_the_closed_form(crushed):
    r, _ = crushed
    assert abs(r.half_fold / r.reference.half_fold - 1.0) < 0.25
