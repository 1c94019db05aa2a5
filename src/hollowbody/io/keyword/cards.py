"""Card layouts: fixed-width and free-format fields of one keyword card.

A card is a sequence of :class:`Field` specs (attribute name, standard width,
kind ``"i"`` integer / ``"f"`` real / ``"s"`` text). Widths change with the
keyword's format: ``"standard"`` (as in the manual), ``"i10"`` (fields
narrower than 10 become 10 wide; ``%`` suffix or ``*KEYWORD i10=y``) and
``"long"`` (fields narrower than 20 become 20 wide; ``+`` suffix or
``*KEYWORD long=y``). A card line containing a comma is free format: fields
are separated by commas. Blank fields are left out of the parsed result so
that the caller keeps its LS-DYNA default.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from hollowbody.errors import DeckError

FORMATS = ("standard", "i10", "long")


@dataclass(frozen=True)
class Field:
    """One field of a card: attribute ``name`` ("-" = unused), ``width``, ``kind``."""

    name: str
    width: int
    kind: str  # "i", "f" or "s"


def field_width(width: int, fmt: str) -> int:
    """Width of a field of standard ``width`` in format ``fmt``."""
    if fmt == "long":
        return max(width, 20)
    if fmt == "i10":
        return max(width, 10)
    return width


def card_widths(card: tuple[Field, ...], fmt: str) -> list[int]:
    return [field_width(f.width, fmt) for f in card]


# ---------------------------------------------------------------------------
# Numbers

# Fortran forms LS-DYNA accepts besides Python's: D exponents and an exponent
# without its letter ("1.5-3" = 1.5e-3).
_IMPLICIT_EXP = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d+)$")


def parse_float(text: str) -> float:
    """Parse a real number as LS-DYNA does; raises ValueError (also for nan / inf)."""
    s = text.strip()
    try:
        value = float(s)
    except ValueError:
        t = s.replace("d", "e").replace("D", "E")
        try:
            value = float(t)
        except ValueError:
            m = _IMPLICIT_EXP.match(t)
            if not m:
                raise ValueError(text) from None
            value = float(f"{m.group(1)}e{m.group(2)}")
    if not math.isfinite(value):
        raise ValueError(text)
    return value


#: Integers must fit in a signed 64-bit integer (ids are stored as int64).
INT_LIMIT = 2 ** 63


def parse_int(text: str) -> int:
    """Parse an integer field; an integral real ("3." or "3.0") is accepted.

    Raises ValueError also for a value outside the signed 64-bit range.
    """
    s = text.strip()
    try:
        value = int(s)
    except ValueError:
        real = parse_float(s)  # raises ValueError
        if not math.isfinite(real) or real != int(real):
            raise ValueError(text) from None
        value = int(real)
    if not -INT_LIMIT <= value < INT_LIMIT:
        raise ValueError(text)
    return value


def bad_number(text: str, name: str, kind: str, file: str | None, line: int | None,
               keyword: str | None) -> DeckError:
    what = "an integer" if kind == "i" else "a number"
    if kind == "i" and re.fullmatch(r"[+-]?\d+", text.strip()):
        what = "an integer of at most 18 digits"
    return DeckError(f"field {name.upper()}: '{text.strip()}' is not {what}", file, line,
                     keyword)


# ---------------------------------------------------------------------------
# Reading one card


def split_card(text: str, widths: list[int]) -> list[str]:
    """Raw field strings of one card line (free format when it has a comma)."""
    if "," in text:
        parts = text.split(",")
        return [p.strip() for p in parts[: len(widths)]] + [""] * max(0, len(widths) - len(parts))
    out = []
    pos = 0
    for w in widths:
        out.append(text[pos:pos + w].strip())
        pos += w
    return out


def parse_card(text: str, card: tuple[Field, ...], fmt: str, file: str | None = None,
               line: int | None = None, keyword: str | None = None) -> dict[str, object]:
    """Values of the non-blank named fields of one card line.

    Raises :class:`DeckError` (naming the field) for a bad number.
    """
    if len(card) == 1 and card[0].kind == "s":  # a text card (title): commas are text
        return {card[0].name: text[: field_width(card[0].width, fmt)].strip()}
    raw = split_card(text, card_widths(card, fmt))
    values: dict[str, object] = {}
    for spec, s in zip(card, raw):
        if not s or spec.name == "-":
            continue
        try:
            if spec.kind == "i":
                values[spec.name] = parse_int(s)
            elif spec.kind == "f":
                values[spec.name] = parse_float(s)
            else:
                values[spec.name] = s
        except ValueError:
            raise bad_number(s, spec.name, spec.kind, file, line, keyword) from None
    return values


# ---------------------------------------------------------------------------
# Writing


def _compact_exponent(s: str) -> str:
    """'1.5e-06' -> '1.5e-6', '2e+20' -> '2e20'."""
    if "e" not in s:
        return s
    mant, exp = s.split("e")
    sign = "-" if exp.startswith("-") else ""
    digits = exp.lstrip("+-").lstrip("0") or "0"
    return f"{mant}e{sign}{digits}"


def format_float(value: float, width: int) -> str:
    """Shortest text of ``value`` that fits in ``width`` columns (right-justified).

    The shortest round-trip representation is used when it fits, so values
    read from a deck are written back exactly; otherwise the precision is
    reduced until the text fits.
    """
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{value!r} cannot be written to a keyword deck")
    if v == 0.0:
        return "0.0".rjust(width) if width >= 3 else "0".rjust(width)
    if v == int(v) and abs(v) < 1e15:
        s = f"{int(v)}.0"
        if len(s) <= width:
            return s.rjust(width)
        s = f"{int(v)}."
        if len(s) <= width:
            return s.rjust(width)
    s = _compact_exponent(repr(v))
    if len(s) <= width:
        return s.rjust(width)
    if s.startswith("0.") or s.startswith("-0."):
        t = s.replace("0.", ".", 1)
        if len(t) <= width:
            return t.rjust(width)
    for prec in range(16, 0, -1):
        for form in ("g", "e"):
            t = _compact_exponent(format(v, f".{prec}{form}"))
            if len(t) <= width:
                return t.rjust(width)
    raise ValueError(f"{value!r} does not fit in {width} columns")


def format_int(value: int, width: int) -> str:
    s = str(int(value))
    if len(s) > width:
        raise ValueError(f"{value} does not fit in {width} columns (use long format)")
    return s.rjust(width)


def format_value(value: object, spec: Field, width: int) -> str:
    if value is None:
        return " " * width
    if spec.kind == "i":
        return format_int(value, width)  # type: ignore[arg-type]
    if spec.kind == "f":
        return format_float(value, width)  # type: ignore[arg-type]
    return str(value)[:width].ljust(width)


def format_card(values: dict[str, object] | object, card: tuple[Field, ...],
                fmt: str = "standard") -> str:
    """One card line from a mapping or an object with the fields as attributes."""
    get = values.get if isinstance(values, dict) else (lambda n: getattr(values, n))
    out = []
    for spec, w in zip(card, card_widths(card, fmt)):
        out.append(" " * w if spec.name == "-" else format_value(get(spec.name), spec, w))
    return "".join(out).rstrip()


def comment_header(card: tuple[Field, ...], fmt: str = "standard") -> str:
    """A ``$#`` comment line naming the fields above their columns."""
    out = []
    for spec, w in zip(card, card_widths(card, fmt)):
        name = "" if spec.name == "-" else spec.name
        out.append(name[:w - 1].rjust(w))
    text = "".join(out)
    return "$#" + text[2:] if len(text) >= 2 else "$#"
