"""Parameter space: names, bounds, rounding, parsing errors."""

from __future__ import annotations

import pytest

from hollowbody.calibrate.space import (
    make_space,
    parse_bounds,
    parse_names,
    parse_speeds,
    round_significant,
)
from hollowbody.errors import UserInputError


def test_default_bounds():
    s = make_space(["E", "yield", "etan", "thickness"])
    assert s.lower.tolist() == [10.0, 0.5, 0.0, 0.5]
    assert s.upper.tolist() == [400.0, 40.0, 50.0, 3.0]
    assert [p.unit for p in s.parameters] == ["MPa", "MPa", "MPa", "mm"]


def test_rounded_and_key():
    s = make_space(["E", "yield"])
    p = s.rounded([123.456789, 4.0000001])
    assert p == {"E": 123.5, "yield": 4.0}
    assert s.key(p) == "E=123.5,yield=4.0"
    assert s.rounded([1e6, -3.0]) == {"E": 400.0, "yield": 0.5}  # clipped to bounds
    assert round_significant(0.0) == 0.0


def test_bounds_override():
    s = make_space(["E"], parse_bounds(["E=20:300"]))
    assert (s.lower[0], s.upper[0]) == (20.0, 300.0)


@pytest.mark.parametrize("call, words", [
    (lambda: make_space(["G"]), "unknown parameter"),
    (lambda: make_space(["E", "E"]), "twice"),
    (lambda: make_space(["E"], {"yield": (1.0, 2.0)}), "not calibrated"),
    (lambda: make_space(["E"], {"E": (0.0, 2.0)}), "positive"),
    (lambda: parse_bounds(["E=1-3"]), "NAME=LO:HI"),
    (lambda: parse_bounds(["E=a:3"]), "numbers"),
    (lambda: parse_bounds(["E=30:3"]), "LO < HI"),
    (lambda: parse_bounds(["E=3:3"]), "LO < HI"),
    (lambda: parse_bounds(["nu=0.1:0.3"]), "unknown parameter"),
    (lambda: parse_names(" , "), "--params"),
    (lambda: parse_speeds("40,x"), "--speeds"),
    (lambda: parse_speeds("-40"), "positive"),
    (lambda: parse_speeds("40,40"), "twice"),
])
def test_bad_inputs_are_user_errors(call, words):
    with pytest.raises(UserInputError, match=words):
        call()
