"""de Leva (1996) segment parameters: consistency of the table and of the scaling."""

from __future__ import annotations

import pytest

from hollowbody.body.anthropometry import (
    DE_LEVA_MALE,
    DE_LEVA_MASS,
    DE_LEVA_STATURE,
    DE_LEVA_TRUNK,
    segments,
    total_mass_fraction,
)


def test_mass_fractions_sum_to_one() -> None:
    # published to 4 decimals for 16 segments: the sum is 1 within 1e-4
    assert total_mass_fraction() == pytest.approx(1.0, abs=1e-4)


def test_trunk_thirds_make_the_trunk() -> None:
    """Upper, middle and lower trunk (Table 4) add up to the whole trunk's length (Table
    1, 0.1 mm rounding) and mass fraction, and their centres of mass to its centre
    (within 1 % of its length: each third's CM fraction is rounded to 1e-4)."""
    thirds = [p for p in DE_LEVA_MALE if p.name.endswith("_trunk")]
    assert sum(p.length for p in thirds) == pytest.approx(DE_LEVA_TRUNK.length, abs=0.15)
    assert sum(p.mass for p in thirds) == pytest.approx(DE_LEVA_TRUNK.mass, abs=1e-4)
    z, start = 0.0, 0.0
    for p in thirds:
        z += p.mass * (start + p.com * p.length)
        start += p.length
    com = z / sum(p.mass for p in thirds)
    assert com == pytest.approx(DE_LEVA_TRUNK.com * DE_LEVA_TRUNK.length,
                                abs=0.01 * DE_LEVA_TRUNK.length)


def test_scaling() -> None:
    ref = segments(DE_LEVA_STATURE, DE_LEVA_MASS)
    assert ref["thigh"].length == pytest.approx(422.2)
    assert ref["thigh"].mass == pytest.approx(0.1416 * 73.0)
    big = segments(2 * DE_LEVA_STATURE, 3 * DE_LEVA_MASS)
    for name, s in ref.items():
        b = big[name]
        assert b.length == pytest.approx(2 * s.length)
        assert b.com == pytest.approx(2 * s.com)
        assert b.mass == pytest.approx(3 * s.mass)
        for i0, i1 in zip(s.inertia, b.inertia):
            assert i1 == pytest.approx(12 * i0)  # m L^2


def test_default_pedestrian_values() -> None:
    """1,753 mm, 76.75 kg: thigh 0.1416 x 76.75 = 10.87 kg, its CM 0.4095 x 425.1 mm
    from the hip; head 0.0694 x 76.75 = 5.33 kg; total 76.75 kg within 0.01 %."""
    s = segments()
    assert s["thigh"].mass == pytest.approx(10.868, abs=1e-3)
    assert s["thigh"].com == pytest.approx(0.4095 * 422.2 * 1753 / 1741, rel=1e-12)
    assert s["head"].mass == pytest.approx(5.326, abs=1e-3)
    total = sum(seg.mass * seg.count for seg in s.values())
    assert total == pytest.approx(76.75, rel=1e-4)
    r = 0.329 * s["thigh"].length
    assert s["thigh"].inertia[0] == pytest.approx(s["thigh"].mass * r * r)


def test_bad_size() -> None:
    with pytest.raises(ValueError, match="positive"):
        segments(0.0, 70.0)
