"""Field parsing and formatting of keyword cards."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from hollowbody.errors import DeckError
from hollowbody.io.keyword.cards import (
    Field,
    field_width,
    format_card,
    format_float,
    parse_card,
    parse_float,
    parse_int,
    split_card,
)

CARD = (Field("mid", 10, "i"), Field("ro", 10, "f"), Field("e", 10, "f"), Field("name", 10, "s"))


@pytest.mark.parametrize("text, value", [
    ("1.5", 1.5), ("  -2.5e-3 ", -2.5e-3), ("1.0D+02", 100.0), ("1.5d-3", 1.5e-3),
    ("1.5-3", 1.5e-3), ("-2.+4", -2e4), (".5", 0.5), ("7", 7.0), ("1.E6", 1e6),
])
def test_parse_float_fortran_forms(text, value):
    assert parse_float(text) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize("text", ["abc", "1.2.3", "--1", "1e", "nan"])
def test_parse_float_rejects(text):
    with pytest.raises(ValueError):
        parse_float(text)


def test_parse_int_accepts_integral_reals():
    assert parse_int(" 12 ") == 12
    assert parse_int("3.") == 3
    assert parse_int("-4.0") == -4
    with pytest.raises(ValueError):
        parse_int("3.5")


def test_fixed_and_free_format_give_the_same_values():
    fixed = f"{1:>10}{'1.0e-6':>10}{'210.0':>10}{'steel':>10}"
    free = "1, 1.0e-6, 210.0, steel"
    assert parse_card(fixed, CARD, "standard") == parse_card(free, CARD, "standard") == {
        "mid": 1, "ro": 1.0e-6, "e": 210.0, "name": "steel"}


def test_blank_fields_are_left_out():
    assert parse_card(f"{1:>10}{'':10}{3.0:>10}", CARD, "standard") == {"mid": 1, "e": 3.0}
    assert parse_card("1,,3.0,", CARD, "standard") == {"mid": 1, "e": 3.0}
    assert split_card("1", [10, 10]) == ["1", ""]


def test_long_and_i10_widths():
    assert field_width(8, "long") == 20 and field_width(16, "long") == 20
    assert field_width(8, "i10") == 10 and field_width(16, "i10") == 16
    line = f"{1:>20d}{2.5:>20}"
    assert parse_card(line, CARD[:2], "long") == {"mid": 1, "ro": 2.5}


def test_bad_number_names_the_field():
    with pytest.raises(DeckError) as err:
        parse_card("         1       abc", CARD, "standard", "d.k", 7, "MAT_ELASTIC")
    assert str(err.value) == "d.k:7: *MAT_ELASTIC: field RO: 'abc' is not a number"


def test_text_card_keeps_commas():
    card = (Field("title", 80, "s"),)
    assert parse_card("muscle, left leg", card, "standard") == {"title": "muscle, left leg"}


def test_format_card_right_justifies_and_blanks_none():
    values = {"mid": 1, "ro": 1e-6, "e": None, "name": "x"}
    assert format_card(values, CARD) == "         1      1e-6          x"


@pytest.mark.parametrize("width", [10, 16, 20])
@given(st.floats(min_value=-1e30, max_value=1e30).filter(lambda v: v == 0 or abs(v) > 1e-30))
def test_format_float_fits_and_is_close(width, value):
    text = format_float(value, width)
    assert len(text) == width
    back = parse_float(text)
    # 10 columns keep at least 4 significant digits (sign and 2-digit exponent)
    assert math.isclose(back, value, rel_tol=1e-3 if width == 10 else 1e-9, abs_tol=1e-300)


@given(st.from_regex(r"-?[0-9]{1,4}\.[0-9]{1,4}", fullmatch=True))
def test_short_decimals_round_trip_exactly(text):
    value = float(text)
    assert parse_float(format_float(value, 10)) == value
