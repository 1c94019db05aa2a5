"""The :class:`Deck`: an ordered list of keyword items, include structure kept.

A deck is one file's worth of keyword items in the order they appear;
``*INCLUDE`` becomes an :class:`Include` item holding the included file's
own :class:`Deck`, so a tool can rewrite one include and keep the others.
Items are dataclasses from :mod:`hollowbody.io.keyword` (``Nodes``,
``SolidElements``, ``Part``, ``MatElastic``, ...; unsupported keywords are
``RawKeyword`` text). Build one in code::

    deck = Deck()
    deck.add_nodes(ids, xyz)                       # (n,), (n, 3) mm
    deck.add_solids(eids, pid=1, conn=conn)        # (e, 8) node ids
    deck.add(Part(pid=1, secid=1, mid=1, title="block"))
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import ClassVar, TypeVar

import numpy as np

from hollowbody.io.keyword.base import KeywordItem, RawKeyword, Title
from hollowbody.io.keyword.kw_mesh import MassElements, Nodes, ShellElements, SolidElements

T = TypeVar("T", bound=KeywordItem)


@dataclass(kw_only=True, eq=False)
class Include(KeywordItem):
    """*INCLUDE: ``filename`` as written (relative to the including file's
    folder) and the included file's ``deck``.

    ``external``: the file is someone else's (a user's model): writing the deck
    with its includes writes only the *INCLUDE card, never the file, and the
    name may be absolute. Names longer than 78 characters are continued on the
    next line with a trailing `` +`` (LS-DYNA's long file names).
    """

    filename: str
    deck: Deck = field(default_factory=lambda: Deck())
    external: bool = False

    KEYWORD: ClassVar[str] = "INCLUDE"

    def to_lines(self, fmt: str = "standard") -> list[str]:
        name, lines = self.filename, ["*INCLUDE"]
        while len(name) > 78:
            cut = 78
            while cut > 1 and " " in name[cut - 1:cut + 1]:  # the reader strips blanks
                cut -= 1
            lines.append(name[:cut] + " +")
            name = name[cut:]
        return lines + [name]


class Deck:
    """Keyword items of one file (``path``: where it was read from, or None).

    ``keyword_args``: text after ``*KEYWORD`` in the file (e.g. ``long=y``),
    kept for information. Equality compares the flattened item lists.
    """

    def __init__(self, path: str | None = None) -> None:
        self.path = path
        self.items: list[KeywordItem] = []
        self.keyword_args = ""

    # -- building ------------------------------------------------------------

    def add(self, item: T) -> T:
        """Append a keyword item and return it."""
        if not isinstance(item, KeywordItem):
            raise TypeError(f"{item!r} is not a keyword item")
        self.items.append(item)
        return item

    def add_nodes(self, ids: np.ndarray, xyz: np.ndarray) -> Nodes:
        """*NODE: ids (n,) int, xyz (n, 3) mm."""
        return self.add(Nodes(ids=ids, xyz=xyz))

    def add_solids(self, eids: np.ndarray, pid: int | np.ndarray,
                   conn: np.ndarray) -> SolidElements:
        """*ELEMENT_SOLID: eids (e,), pid scalar or (e,), conn node ids (e, 8);
        (e, 6) pentahedra and (e, 4) tetrahedra are stored as degenerate hexahedra."""
        return self.add(SolidElements(ids=eids, pids=pid, conn=conn))

    def add_shells(self, eids: np.ndarray, pid: int | np.ndarray, conn: np.ndarray,
                   thickness: np.ndarray | float | None = None) -> ShellElements:
        """*ELEMENT_SHELL(_THICKNESS): conn node ids (e, 4) or (e, 3); thickness
        None (section), a scalar, (e,) or (e, 4) mm."""
        return self.add(ShellElements(ids=eids, pids=pid, conn=conn, thickness=thickness))

    def add_masses(self, eids: np.ndarray, nids: np.ndarray,
                   mass: np.ndarray | float) -> MassElements:
        """*ELEMENT_MASS: point masses (kg) on nodes."""
        return self.add(MassElements(ids=eids, nids=nids, mass=mass))

    def add_include(self, filename: str, deck: Deck | None = None) -> Include:
        """*INCLUDE of ``filename`` (relative to this file's folder) holding ``deck``."""
        return self.add(Include(filename=filename, deck=deck if deck is not None else Deck()))

    @property
    def title(self) -> str:
        titles = self.of_type(Title)
        return titles[0].text if titles else ""

    @title.setter
    def title(self, text: str) -> None:
        for item in self.items:
            if isinstance(item, Title):
                item.text = text
                return
        self.items.insert(0, Title(text=text))

    # -- queries ---------------------------------------------------------------

    def iter_items(self) -> Iterator[KeywordItem]:
        """All items in reading order, included files expanded in place."""
        for item in self.items:
            if isinstance(item, Include):
                yield from item.deck.iter_items()
            else:
                yield item

    def of_type(self, cls: type[T]) -> list[T]:
        """All items (through includes) that are instances of ``cls``."""
        return [item for item in self.iter_items() if isinstance(item, cls)]

    def includes(self) -> list[Include]:
        """Include items of this file and, recursively, of the included files."""
        out = []
        for item in self.items:
            if isinstance(item, Include):
                out.append(item)
                out.extend(item.deck.includes())
        return out

    @property
    def unsupported(self) -> list[tuple[str, str, int]]:
        """(keyword, file, line) of every keyword that was not understood."""
        return [(r.keyword.split()[0].upper() if r.keyword.split() else r.keyword,
                 r.source.file, r.source.line)
                for r in self.of_type(RawKeyword) if r.unsupported]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Deck):
            return NotImplemented
        return list(self.iter_items()) == list(other.iter_items())

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"Deck(path={self.path!r}, items={len(self.items)})"
