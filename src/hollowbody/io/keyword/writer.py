"""Write a :class:`~hollowbody.io.keyword.deck.Deck` as LS-DYNA keyword text.

Output is fixed-width standard format (``*KEYWORD`` ... ``*END``) that
LS-DYNA and OpenRadioss read; bulk blocks whose ids do not fit 8 columns
switch to long format (``+`` suffix) on their own. Includes are either
flattened into one file (default) or kept: each included deck is written to
its ``filename`` relative to the written file's folder.
"""

from __future__ import annotations

import os
from pathlib import Path

from hollowbody.io.keyword.deck import Deck, Include

HEADER = "$ written by hollowbody (units: mm, ms, kg, kN, GPa)"


def deck_lines(deck: Deck, flatten: bool = True, fmt: str = "standard") -> list[str]:
    """Lines of the file for ``deck`` (without trailing newlines).

    flatten: expand includes in place; otherwise write ``*INCLUDE`` cards.
    fmt: ``standard`` or ``long`` (20-column fields, ``*KEYWORD long=y``).
    """
    lines = ["*KEYWORD" + (" long=y" if fmt == "long" else ""), HEADER]
    items = deck.iter_items() if flatten else deck.items
    for item in items:
        lines.extend(item.to_lines(fmt))
    lines.append("*END")
    return lines


def write_deck(deck: Deck, path: str | os.PathLike[str], flatten: bool = True,
               fmt: str = "standard") -> list[Path]:
    """Write ``deck`` to ``path``; returns the files written.

    With ``flatten=False`` every included deck is written too, at its
    ``filename`` relative to ``path``'s folder (folders are created);
    absolute include names are refused (they would overwrite the source).
    An ``external`` include (someone else's file) is referred to, never written.
    """
    if fmt not in ("standard", "long"):
        raise ValueError(f"fmt must be 'standard' or 'long', not {fmt!r}")
    path = Path(path)
    written = [path]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(deck_lines(deck, flatten, fmt)) + "\n", encoding="latin-1")
    if not flatten:
        for item in deck.items:
            if isinstance(item, Include) and not item.external:
                if os.path.isabs(item.filename):
                    raise ValueError(f"include '{item.filename}' has an absolute path; "
                                     "write with flatten=True or give a relative name")
                written += write_deck(item.deck, path.parent / item.filename, False, fmt)
    return written
