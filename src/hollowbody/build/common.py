"""Helpers shared by the modules of the build layer: errors at a card, LS-DYNA defaults."""

from __future__ import annotations

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.io.keyword import KeywordItem
from hollowbody.model.model import Model


def item_error(item: KeywordItem, message: str, line: int | None = None) -> DeckError:
    """DeckError at ``item``'s card (or ``line`` of its file), naming its keyword."""
    return DeckError(message, item.source.file, item.source.line if line is None else line,
                     item.keyword_line().lstrip("*"))


def or_default(value: float, default: float) -> float:
    """LS-DYNA's 'zero (or blank) means default'."""
    return default if not value else value


def node_set(model: Model, sid: int, item: KeywordItem) -> np.ndarray:
    """(k,) node indices of node set ``sid``; DeckError at ``item`` when it is not defined."""
    if sid not in model.node_sets:
        raise item_error(item, f"node set {sid} is not defined")
    return model.node_sets[sid]


def no_cid(item: KeywordItem, cid: int, name: str = "CID") -> None:
    """DeckError at ``item`` for a local coordinate system (``name`` = ``cid`` != 0)."""
    if cid:
        raise item_error(item, f"{name}={cid}: local coordinate systems are not supported")
