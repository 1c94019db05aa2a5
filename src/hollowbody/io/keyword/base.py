"""Keyword items: the parsed content of one keyword block, and the registry.

Every supported keyword is a dataclass derived from :class:`KeywordItem`
(keyword-only constructor, field names are the LS-DYNA field names in lower
case). Reading turns a :class:`Block` (keyword line + its data lines) into a
list of items; writing turns one item back into keyword text. Most keywords
are :class:`SimpleKeyword`: a declarative list of cards whose fields are
the dataclass attributes, so parsing, defaults and writing come for free.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.io.keyword.cards import (
    Field,
    bad_number,
    field_width,
    format_card,
    parse_card,
    parse_int,
)
from hollowbody.source import Source

# ---------------------------------------------------------------------------
# Blocks and card cursors (reader side)


@dataclass
class Block:
    """One keyword block of a file as the reader found it.

    name: keyword as written, upper case, without ``*`` and format suffix
    (e.g. ``MAT_ELASTIC_TITLE``); base: the registered keyword it matched
    (``MAT_ELASTIC``); options: the remaining ``_`` suffixes (``("TITLE",)``);
    fmt: ``standard``/``i10``/``long``; line: 1-based line of the keyword;
    data[begin:end]: the data lines that follow it (``data`` is the whole
    file, so bulk parsers need not copy); body_line: line of the first.
    """

    name: str
    base: str
    options: tuple[str, ...]
    fmt: str
    file: str
    line: int
    data: bytes
    begin: int
    end: int
    body_line: int

    @property
    def body(self) -> bytes:
        return self.data[self.begin:self.end]

    def has(self, option: str) -> bool:
        return option in self.options

    def lines(self, trailing: bool = False) -> list[tuple[int, str]]:
        """(line number, text) of every line except ``$`` comments.

        Blank lines after the last non-blank one are dropped unless ``trailing``
        (a blank line can be a card of default values). The empty remainder
        after the block's final newline is never a line.
        """
        out = []
        raws = self.body.split(b"\n")
        if not raws[-1]:
            raws.pop()
        for k, raw in enumerate(raws):
            if raw[:1] == b"$":
                continue
            out.append((self.body_line + k, raw.decode("latin-1").rstrip("\r\n")))
        if not trailing:
            while out and not out[-1][1].strip():
                out.pop()
        return out

    def cursor(self, trailing: bool = False) -> Cursor:
        return Cursor(self, self.lines(trailing))

    def error(self, message: str, line: int | None = None) -> DeckError:
        return DeckError(message, self.file, self.line if line is None else line, self.name)

    def source(self, line: int) -> Source:
        return Source(self.file, line)


class Cursor:
    """Sequential access to the cards of a block."""

    def __init__(self, block: Block, lines: list[tuple[int, str]]) -> None:
        self.block = block
        self._lines = lines
        self._pos = 0

    def done(self) -> bool:
        return self._pos >= len(self._lines)

    def peek(self) -> tuple[int, str] | None:
        return None if self.done() else self._lines[self._pos]

    def take(self, what: str) -> tuple[int, str]:
        """The next card; DeckError naming ``what`` when the block has no more."""
        if self.done():
            last = self._lines[-1][0] if self._lines else self.block.line
            raise DeckError(f"{what} is missing", self.block.file, last, self.block.name)
        item = self._lines[self._pos]
        self._pos += 1
        return item

    def rest(self) -> list[tuple[int, str]]:
        out = self._lines[self._pos:]
        self._pos = len(self._lines)
        return out

    def only_blank(self) -> bool:
        """Whether every remaining line is blank (also when none remains)."""
        return all(not t.strip() for _, t in self._lines[self._pos:])

    def skip_blank(self) -> None:
        """Move past blank lines."""
        while not self.done() and not self._lines[self._pos][1].strip():
            self._pos += 1

    def parse(self, card: tuple[Field, ...], what: str) -> tuple[int, dict[str, object]]:
        line, text = self.take(what)
        b = self.block
        return line, parse_card(text, card, b.fmt, b.file, line, b.name)


# ---------------------------------------------------------------------------
# Items


@dataclass(kw_only=True)
class KeywordItem:
    """Base of all keyword items. ``source``: where it was read (not compared)."""

    source: Source = field(default_factory=Source, compare=False, repr=False)

    #: Canonical keyword name (without ``*`` and options) and accepted aliases.
    KEYWORD: ClassVar[str] = ""
    ALIASES: ClassVar[tuple[str, ...]] = ()
    #: Option suffixes the keyword accepts (``_TITLE``, ``_ID``, ...).
    OPTIONS: ClassVar[frozenset[str]] = frozenset()

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:  # pragma: no cover - abstract
        raise NotImplementedError

    def keyword_line(self) -> str:
        return "*" + self.KEYWORD

    def to_lines(self, fmt: str = "standard") -> list[str]:  # pragma: no cover - abstract
        raise NotImplementedError


def _kind_of(type_text: str) -> str:
    t = str(type_text)
    if "float" in t:
        return "f"
    if "int" in t:
        return "i"
    return "s"


def _parse_spec(spec: str, kinds: dict[str, str]) -> tuple[Field, ...]:
    out = []
    for token in spec.split():
        name, _, width = token.partition(":")
        w = int(width) if width else 10
        out.append(Field(name, w, "s" if name == "-" else kinds[name]))
    return tuple(out)


def _read_id_card(cur: Cursor, block: Block, attrs: tuple[str, str]) -> dict[str, object]:
    """The ``_ID`` card: ID (10 columns, 20 in long format) and a heading."""
    line, text = cur.take("ID card")
    # free format only when what precedes the first comma is an id (a heading
    # written in fixed format may itself contain commas)
    head = text.partition(",")[0].strip()
    if "," in text and (not head or head.lstrip("+-").isdigit()):
        ident, _, heading = text.partition(",")
    else:
        w = field_width(10, block.fmt)
        ident, heading = text[:w], text[w:w + 70]
    value = 0
    if ident.strip():
        try:
            value = parse_int(ident)
        except ValueError:
            raise bad_number(ident, attrs[0], "i", block.file, line, block.name) from None
    return {attrs[0]: value, attrs[1]: heading.strip()}


@dataclass(kw_only=True)
class SimpleKeyword(KeywordItem):
    """A keyword described by a list of cards (``CARDS``: one spec string per card).

    Spec strings name the fields in order, ``name:width`` for non-10 widths,
    ``-`` for an unused field. The first ``N_REQUIRED`` cards must be present;
    later cards are optional (defaults when absent). ``REPEAT``: the card set
    repeats until the next keyword (one item per repetition). Lines after the
    known cards of a non-repeating keyword are kept in ``extra_cards`` and
    written back unchanged.

    A blank line is a card of default values, as in LS-DYNA: a blank required
    card is read (also when it is the block's last line) and so is a blank
    optional card followed by more cards; blank lines at the end of the block
    are not optional cards. In a repeating keyword, blank lines between
    repetitions are skipped.
    """

    extra_cards: list[str] = field(default_factory=list)

    CARDS: ClassVar[tuple[str, ...]] = ()
    N_REQUIRED: ClassVar[int] = 1
    REPEAT: ClassVar[bool] = False
    #: Card whose line is the item's source line (the one holding its ids).
    MAIN_CARD: ClassVar[int] = 0
    #: Attribute holding the ``_TITLE`` title card (None: no title option).
    TITLE_ATTR: ClassVar[str | None] = None
    #: Attributes (id, heading) of the ``_ID`` card (None: no ID option).
    ID_ATTRS: ClassVar[tuple[str, str] | None] = None

    @classmethod
    def layout(cls) -> tuple[tuple[Field, ...], ...]:
        cached = cls.__dict__.get("_layout_cache")
        if cached is None:
            kinds = {f.name: _kind_of(f.type) for f in dataclasses.fields(cls)}
            cached = tuple(_parse_spec(s, kinds) for s in cls.CARDS)
            cls._layout_cache = cached  # type: ignore[attr-defined]
        return cached

    @classmethod
    def options(cls) -> frozenset[str]:
        opts = set(cls.OPTIONS)
        if cls.TITLE_ATTR:
            opts.add("TITLE")
        if cls.ID_ATTRS:
            opts.update(("ID", "TITLE"))
        return frozenset(opts)

    @classmethod
    def want_card(cls, index: int, values: dict[str, object]) -> bool:
        """Whether card ``index`` is present given the fields read so far."""
        return True

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        cur = block.cursor(trailing=True)
        items: list[KeywordItem] = []
        while not cur.done():
            if cls.REPEAT and (cur.only_blank() or cls._bulk_like(block)):
                cur.skip_blank()
                if cur.done():
                    break
            values: dict[str, object] = {}
            first = cur.peek()[0]  # type: ignore[index]
            if cls.TITLE_ATTR and block.has("TITLE") and not cls.ID_ATTRS:
                values[cls.TITLE_ATTR] = cur.take("title card")[1].strip()
            if cls.ID_ATTRS and (block.has("ID") or block.has("TITLE")):
                values.update(_read_id_card(cur, block, cls.ID_ATTRS))
            values.update(cls.read_prefix(cur, block))
            card_lines: dict[int, int] = {}
            for k, card in enumerate(cls.layout()):
                if not cls.want_card(k, values):
                    continue
                if k >= cls.N_REQUIRED and (cur.only_blank() or cls.REPEAT):
                    break
                names = ", ".join(f.name.upper() for f in card if f.name != "-")
                line, vals = cur.parse(card, f"card {k + 1} ({names})")
                card_lines[k] = line
                values.update(vals)
            values.update(cls.read_tail(cur, block, values))
            if not cls.REPEAT:
                extra = [t for _, t in cur.rest()]
                while extra and not extra[-1].strip():
                    extra.pop()
                values["extra_cards"] = extra
            main_line = card_lines.get(cls.MAIN_CARD, min(card_lines.values(), default=first))
            values["source"] = block.source(main_line)
            items.append(cls.build(values, block))
            if not cls.REPEAT:
                break
        if not items and cls.N_REQUIRED == 0:
            items.append(cls.build({"source": block.source(block.line)}, block))
        elif not items:
            first_card = cls.layout()[0] if cls.layout() else ()
            names = ", ".join(f.name.upper() for f in first_card if f.name != "-")
            raise block.error(f"card 1 ({names}) is missing")
        return items

    @classmethod
    def _bulk_like(cls, block: Block) -> bool:
        """A repeating single card (a list of rows): blank lines in it are skipped."""
        titled = (cls.TITLE_ATTR and block.has("TITLE")) or \
            (cls.ID_ATTRS and (block.has("ID") or block.has("TITLE")))
        return len(cls.layout()) == 1 and not titled

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        """Hook: cards between the ID/title card and card 1 (e.g. contact MPP cards)."""
        return {}

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        """Hook: variable cards after the declared ones (e.g. shell ply angles)."""
        return {}

    def tail_lines(self, fmt: str) -> list[str]:
        return []

    @classmethod
    def build(cls, values: dict[str, object], block: Block) -> KeywordItem:
        """Hook: construct the item from the parsed values (validation goes here)."""
        return cls(**values)

    def prefix_lines(self, fmt: str) -> list[str]:
        return []

    def to_lines(self, fmt: str = "standard") -> list[str]:
        lines = [self.keyword_line()]
        if self.TITLE_ATTR and not self.ID_ATTRS and getattr(self, self.TITLE_ATTR):
            lines[0] += "_TITLE"
            lines.append(str(getattr(self, self.TITLE_ATTR))[:80])
        if self.ID_ATTRS and getattr(self, self.ID_ATTRS[0]) is not None:
            lines[0] += "_ID"
            ident, heading = (getattr(self, a) for a in self.ID_ATTRS)
            w = field_width(10, fmt)
            lines.append(f"{int(ident):>{w}d}{str(heading or '')[:70]}".rstrip())
        lines.extend(self.prefix_lines(fmt))
        layout = self.layout()
        present = [k for k in range(len(layout)) if self.want_card(k, vars(self))]
        last = max((k for k in present if k < self.N_REQUIRED), default=-1)
        defaults = {f.name: f.default for f in dataclasses.fields(self)
                    if f.default is not dataclasses.MISSING}
        for k in present:
            if any(getattr(self, f.name) != defaults.get(f.name, object())
                   for f in layout[k] if f.name != "-"):
                last = max(last, k)
        tail = self.tail_lines(fmt)
        if tail or self.extra_cards:  # they follow the last declared card
            last = present[-1] if present else -1
        for k in present:
            if k > last:
                break
            lines.append(format_card(self, layout[k], fmt))
        lines.extend(tail)
        lines.extend(self.extra_cards)
        return lines


class ArrayEq:
    """Mixin: dataclass equality that compares numpy arrays by value."""

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            if not f.compare:
                continue
            a, b = getattr(self, f.name), getattr(other, f.name)
            if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
                if a is None or b is None or not np.array_equal(np.asarray(a), np.asarray(b)):
                    return False
            elif a != b:
                return False
        return True


def read_rows(cur: Cursor, names: list[str], kind: str,
              width: int = 10) -> tuple[list[list[float | int]], list[int]]:
    """All remaining non-blank cards as rows of fields ``names`` (blank = 0).

    Returns the rows and their line numbers. Used for id lists and tables.
    """
    card = tuple(Field(n, width, kind) for n in names)
    rows, lines = [], []
    b = cur.block
    for line, text in cur.rest():
        if not text.strip():
            continue
        vals = parse_card(text, card, b.fmt, b.file, line, b.name)
        rows.append([vals.get(f.name, 0) for f in card])
        lines.append(line)
    return rows, lines  # type: ignore[return-value]


# ---------------------------------------------------------------------------
# Raw keywords and the title


@dataclass(kw_only=True)
class RawKeyword(KeywordItem):
    """A keyword kept as text: ``keyword`` is the keyword line without ``*``,
    ``lines`` every following line (comments included) up to the next keyword.
    ``unsupported``: it was not understood (listed in ``Model.unsupported``).
    """

    keyword: str
    lines: list[str] = field(default_factory=list)
    unsupported: bool = True

    def keyword_line(self) -> str:
        return "*" + self.keyword

    def to_lines(self, fmt: str = "standard") -> list[str]:
        return [self.keyword_line(), *self.lines]


@dataclass(kw_only=True)
class Title(KeywordItem):
    """*TITLE: the model's title (one card)."""

    text: str = ""
    KEYWORD: ClassVar[str] = "TITLE"

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        lines = block.lines()
        text = lines[0][1].strip() if lines else ""
        return [cls(text=text, source=block.source(lines[0][0] if lines else block.line))]

    def to_lines(self, fmt: str = "standard") -> list[str]:
        return ["*TITLE", self.text[:80]]


# ---------------------------------------------------------------------------
# Registry

REGISTRY: dict[str, type[KeywordItem]] = {}


def register(cls: type[KeywordItem]) -> type[KeywordItem]:
    """Class decorator: make ``cls`` the reader of its KEYWORD and ALIASES."""
    for name in (cls.KEYWORD, *cls.ALIASES):
        REGISTRY[name] = cls
    return cls


register(Title)


def item_options(cls: type[KeywordItem]) -> frozenset[str]:
    opts = getattr(cls, "options", None)
    return opts() if callable(opts) else cls.OPTIONS


def resolve(name: str) -> tuple[type[KeywordItem], str, tuple[str, ...]] | None:
    """Match a keyword name (upper case, no ``*``) to (class, base name, options).

    The longest registered name that is a ``_``-prefix of ``name`` wins; the
    rest must be options the class accepts. None when nothing matches.
    """
    parts = name.split("_")
    for n in range(len(parts), 0, -1):
        base = "_".join(parts[:n])
        cls = REGISTRY.get(base)
        if cls is None:
            continue
        options = tuple(p for p in parts[n:] if p)
        if set(options) <= item_options(cls):
            return cls, base, options
        return None
    return None
