"""Definitions made by unsupported keywords, so that a reference to one can name it.

A part may refer to a material that the deck defines with a keyword the
reader keeps as text (``*MAT_HONEYCOMB``); the builder then says so instead of
"not defined": ``part 3 refers to material 9, defined by *MAT_HONEYCOMB at
deck.k:120, which is not supported``. Only the id of such a keyword is read
(its first field; the second card for ``*PART``), never its values.
"""

from __future__ import annotations

from hollowbody.io.keyword import Deck, RawKeyword

#: Keyword prefix -> what it defines.
FAMILIES = (("MAT_", "material"), ("SECTION_", "section"), ("PART", "part"),
            ("HOURGLASS", "hourglass"))


def _first_int(text: str) -> int | None:
    field = text.split(",")[0] if "," in text else text[:10]
    try:
        return int(field.strip())
    except ValueError:
        return None


def _defined_id(raw: RawKeyword, family: str) -> int | None:
    name = raw.keyword.split()[0].upper() if raw.keyword.split() else ""
    cards = [t for t in raw.lines if not t.startswith("$")]
    skip = 1 if family == "part" or name.endswith("_TITLE") else 0
    return _first_int(cards[skip]) if len(cards) > skip else None


def unsupported_definitions(deck: Deck) -> dict[tuple[str, int], RawKeyword]:
    """(what, id) -> the unsupported keyword defining it, e.g. ("material", 9)."""
    out: dict[tuple[str, int], RawKeyword] = {}
    for raw in deck.of_type(RawKeyword):
        if not raw.unsupported:
            continue
        name = raw.keyword.split()[0].upper() if raw.keyword.split() else ""
        for prefix, family in FAMILIES:
            if name.startswith(prefix):
                ident = _defined_id(raw, family)
                if ident is not None:
                    out.setdefault((family, ident), raw)
                break
    return out


def not_defined(defs: dict[tuple[str, int], RawKeyword], what: str, ident: int) -> str:
    """End of a reference message (after the id): `` which is not defined``, or
    ``, defined by *KEYWORD at file:line, which is not supported``."""
    raw = defs.get((what, ident))
    if raw is None:
        return " which is not defined"
    name = raw.keyword.split()[0].upper()
    return f", defined by *{name} at {raw.source.file}:{raw.source.line}, which is not supported"
