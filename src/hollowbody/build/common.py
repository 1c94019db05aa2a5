"""Helpers shared by the modules of the build layer: errors at a card, LS-DYNA defaults."""

from __future__ import annotations

from hollowbody.errors import DeckError
from hollowbody.io.keyword import KeywordItem


def item_error(item: KeywordItem, message: str, line: int | None = None) -> DeckError:
    """DeckError at ``item``'s card (or ``line`` of its file), naming its keyword."""
    return DeckError(message, item.source.file, item.source.line if line is None else line,
                     item.keyword_line().lstrip("*"))


def or_default(value: float, default: float) -> float:
    """LS-DYNA's 'zero (or blank) means default'."""
    return default if not value else value
