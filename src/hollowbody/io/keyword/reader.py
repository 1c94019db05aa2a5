"""Read an LS-DYNA keyword deck into a :class:`~hollowbody.io.keyword.deck.Deck`.

A file is split into keyword blocks (a line starting with ``*`` begins one;
``$`` lines are comments); each block goes to the keyword class registered
for its name (case-insensitive, ``_TITLE`` / ``_ID`` / ... options checked
by the class). ``*INCLUDE`` files are read relative to the including file's
folder (then the ``*INCLUDE_PATH`` folders), ``*END`` stops reading a file.
Unknown keywords are kept as text, warned about once per keyword name
(:class:`UnsupportedKeywordWarning`) and listed in ``Deck.unsupported``;
with ``strict=True`` the first one raises :class:`DeckError`.

Only the syntax of each keyword is checked here (numbers, cards, increasing
curve abscissae, include files); references between keywords are checked by
:func:`hollowbody.build.build_model`. :func:`read_deck_partial` stops at the
first error instead of raising it and returns what was read before it.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path
from typing import NamedTuple

from hollowbody.errors import DeckError
from hollowbody.io.keyword.base import Block, RawKeyword, resolve
from hollowbody.io.keyword.deck import Deck, Include
from hollowbody.source import Source

#: Keywords that are kept as text but are not "unsupported" (no warning).
IGNORED = ("COMMENT", "INCLUDE_PATH", "INCLUDE_PATH_RELATIVE")


class UnsupportedKeywordWarning(UserWarning):
    """A keyword the reader does not understand (kept as text, ignored)."""


def read_deck(path: str | os.PathLike[str], strict: bool = False) -> Deck:
    """Read a keyword file and its includes.

    ``path`` is used as given in messages (``deck.k:12: *PART: ...``).
    Raises :class:`~hollowbody.errors.DeckError` for malformed input.
    """
    return _Reader(strict).read_file(str(path), str(path), None)


class PartialRead(NamedTuple):
    """What :func:`read_deck_partial` read: ``deck`` (the items read before the
    error, included files in place), ``keywords`` (keyword blocks found per
    keyword name, through the includes, up to and including the one holding
    the error) and ``error`` (None when the whole deck reads)."""

    deck: Deck
    keywords: dict[str, int]
    error: DeckError | None


def read_deck_partial(path: str | os.PathLike[str], strict: bool = False) -> PartialRead:
    """Read as :func:`read_deck` does, but stop at the first error instead of raising
    it; see :class:`PartialRead`. A keyword block that holds an error adds no items."""
    deck = Deck(str(path))
    reader = _Reader(strict)
    try:
        reader.read_file(str(path), str(path), None, deck)
    except DeckError as exc:
        return PartialRead(deck, reader.keywords, exc)
    return PartialRead(deck, reader.keywords, None)


def read_deck_text(text: str, name: str = "<text>", strict: bool = False) -> Deck:
    """Read a deck from a string (includes relative to the current folder)."""
    return _Reader(strict).read_bytes(text.encode("latin-1"), name, os.path.join(".", name))


def is_binary(data: bytes, probe: int = 8192) -> bool:
    """Whether ``data`` looks like a binary file: a NUL byte, or more than 1 % control
    characters (other than tab, CR, LF, FF) in its first ``probe`` bytes."""
    head = data[:probe]
    if b"\x00" in head:
        return True
    ctrl = sum(head.count(bytes([c])) for c in range(32) if c not in (9, 10, 12, 13))
    return ctrl > 0.01 * max(len(head), 1)


def _split_keyword_line(raw: bytes) -> tuple[str, str, str | None]:
    """(NAME, arguments, format flag) of a keyword line; flag ``+``/``-``/``%`` or None."""
    text = raw.decode("latin-1").strip()[1:]
    tokens = text.split()
    if not tokens:
        return "", "", None
    name = tokens[0].upper()
    flag = None
    while name and name[-1] in "+-%":
        flag, name = name[-1], name[:-1]
    rest = []
    for tok in tokens[1:]:
        if tok in ("+", "-", "%"):
            flag = tok
        else:
            rest.append(tok)
    return name, " ".join(rest), flag


class _Reader:
    def __init__(self, strict: bool) -> None:
        self.strict = strict
        self.fmt = "standard"
        self.warned: set[str] = set()
        self.stack: list[str] = []
        self.paths: list[tuple[str, str]] = []  # (display, real) include search folders
        self.keywords: dict[str, int] = {}  # keyword blocks found per name

    # -- files -------------------------------------------------------------

    def read_file(self, display: str, real: str, origin: tuple[str, int] | None,
                  deck: Deck | None = None) -> Deck:
        """The file's items, added to ``deck`` (default: a new Deck) as they are read."""
        try:
            data = Path(real).read_bytes()
        except OSError as exc:
            file, line = origin if origin else (None, None)
            what = "include file" if origin else "deck"
            reason = "does not exist" if not os.path.exists(real) else exc.strerror
            raise DeckError(f"{what} '{display}' {reason}", file, line,
                            "INCLUDE" if origin else None) from None
        return self.read_bytes(data, display, real, deck)

    def read_bytes(self, data: bytes, display: str, real: str, deck: Deck | None = None) -> Deck:
        key = os.path.realpath(real)
        if key in self.stack:
            raise DeckError(f"include cycle: '{display}' includes itself", display, 1)
        self.stack.append(key)
        try:
            return self._parse(data, display, real, Deck(display) if deck is None else deck)
        finally:
            self.stack.pop()

    def _parse(self, data: bytes, display: str, real: str, deck: Deck) -> Deck:
        if data.startswith(b"\xef\xbb\xbf"):
            data = data[3:]
        if is_binary(data):
            raise DeckError("not a keyword deck: the file is binary (a keyword deck is text)",
                            display)
        starts = []
        if data.startswith(b"*"):
            pos = 0
        else:
            nxt = data.find(b"\n*")
            pos = nxt + 1 if nxt >= 0 else -1
        while pos >= 0:
            starts.append(pos)
            nxt = data.find(b"\n*", pos)
            pos = nxt + 1 if nxt >= 0 else -1
        if not starts and len(self.stack) == 1:
            what = "the file is empty" if not data.strip() else "no line starts with '*'"
            raise DeckError(f"not a keyword deck: {what} (a deck is keyword lines such as "
                            "*KEYWORD, *NODE, ... each followed by its cards)", display)
        line = 1 + data.count(b"\n", 0, starts[0]) if starts else 1
        for k, start in enumerate(starts):
            end = starts[k + 1] if k + 1 < len(starts) else len(data)
            eol = data.find(b"\n", start, end)
            eol = end if eol < 0 else eol
            if k:
                line += data.count(b"\n", starts[k - 1], start)
            name, args, flag = _split_keyword_line(data[start:eol])
            if name == "END":
                break
            self.keywords[name] = self.keywords.get(name, 0) + 1
            fmt = {"+": "long", "%": "i10", "-": "standard"}.get(flag or "", self.fmt)
            block = Block(name, name, (), fmt, display, line, data, min(eol + 1, end), end,
                          line + 1)
            self._block(deck, args, data[start:eol], block, real)
        return deck

    # -- blocks ------------------------------------------------------------

    def _block(self, deck: Deck, args: str, head: bytes, block: Block, real: str) -> None:
        name = block.name
        if name == "KEYWORD":
            self._keyword_args(deck, args)
            return
        if name == "INCLUDE":
            self._include(deck, block, real)
            return
        resolved = resolve(name)
        if name in IGNORED or resolved is None:
            lines = block.body.decode("latin-1").split("\n")
            if lines and not lines[-1]:
                lines.pop()
            raw = RawKeyword(keyword=head.decode("latin-1").rstrip("\r\n")[1:],
                             lines=[t.rstrip("\r") for t in lines],
                             unsupported=name not in IGNORED, source=Source(block.file, block.line))
            if name.startswith("INCLUDE_PATH"):
                self._include_path(raw, block.file, real)
            elif raw.unsupported:
                self._unsupported(name, block.file, block.line)
            deck.add(raw)
            return
        block.base, block.options = resolved[1], resolved[2]
        for item in resolved[0].read(block):
            deck.add(item)

    def _keyword_args(self, deck: Deck, args: str) -> None:
        deck.keyword_args = deck.keyword_args or args
        for tok in args.lower().split():
            key, _, value = tok.partition("=")
            if key == "long":
                self.fmt = "long" if value.startswith("y") else "standard"
            elif key == "i10" and value.startswith("y") and self.fmt == "standard":
                self.fmt = "i10"

    def _unsupported(self, name: str, file: str, line: int) -> None:
        if self.strict:
            raise DeckError("keyword not supported (strict mode)", file, line, name)
        if name not in self.warned:
            self.warned.add(name)
            warnings.warn(f"{file}:{line}: *{name}: keyword not supported; kept as text and "
                          "ignored", UnsupportedKeywordWarning, stacklevel=4)

    def _include(self, deck: Deck, block: Block, real: str) -> None:
        pending = ""
        for line, text in block.lines():
            name = text.strip()
            if not name:
                continue
            if name.endswith(" +") or (pending and name.endswith("+") and len(text) >= 78):
                pending += name[:-1].rstrip()
                continue
            name, pending = pending + name, ""
            display_path, real_path = self._locate(name, block.file, real)
            child = deck.add(Include(filename=name, deck=Deck(display_path),
                                     source=Source(block.file, line))).deck
            self.read_file(display_path, real_path, (block.file, line), child)

    def _locate(self, name: str, display: str, real: str) -> tuple[str, str]:
        if os.path.isabs(name):
            return name, name
        candidates = [(os.path.join(os.path.dirname(display), name),
                       os.path.join(os.path.dirname(real), name))]
        candidates += [(os.path.join(d, name), os.path.join(r, name)) for d, r in self.paths]
        for disp, path in candidates:
            if os.path.exists(path):
                return os.path.normpath(disp), path
        return os.path.normpath(candidates[0][0]), candidates[0][1]

    def _include_path(self, raw: RawKeyword, display: str, real: str) -> None:
        for text in raw.lines:
            folder = text.strip()
            if not folder or folder.startswith("$"):
                continue
            if os.path.isabs(folder):
                self.paths.append((folder, folder))
            else:
                self.paths.append((os.path.join(os.path.dirname(display), folder),
                                   os.path.join(os.path.dirname(real), folder)))

