"""Write a converted deck: the main file at ``--out``, rewritten includes next to it with a
suffix, unchanged includes referenced where they are.

A file is rewritten when the conversion changed it or any file it includes
(its ``*INCLUDE`` names change); rewritten includes go into the output's
folder as ``<name><suffix><ext>`` (numbered when names clash). Unchanged
includes are referenced by their path relative to the file that includes
them, so the input files are never touched (relative ``*INCLUDE_PATH``
folders are re-expressed from the new location). No written file may be an
input file.
"""

from __future__ import annotations

import os
from pathlib import Path

from hollowbody.errors import UserInputError
from hollowbody.hollow import deck_edit as de
from hollowbody.io.keyword import Deck, Include, RawKeyword
from hollowbody.io.keyword.writer import deck_lines


def input_files(deck: Deck) -> list[Path]:
    """Resolved paths of the deck's files (those read from disk)."""
    return [Path(d.path).resolve() for d in de.file_decks(deck) if d.path]


def write_converted(deck: Deck, out: str | os.PathLike[str], changed: list[Deck],
                    inputs: list[Path] | None = None, suffix: str = "_hollow") -> list[Path]:
    """Write ``deck`` (a converted copy) to ``out``; returns the files written.

    changed: the file decks the conversion edited; inputs: paths that must
    not be overwritten (default: the decks' own paths).
    """
    out = Path(out)
    protected = {p.resolve() for p in (inputs if inputs is not None else input_files(deck))}
    if out.resolve() in protected:
        raise UserInputError(f"--out {out} is an input file; choose another name")
    edited = {id(d) for d in changed}
    parents = de.parents(deck)
    rewrite: set[int] = {id(deck)}
    for d in de.file_decks(deck):
        if id(d) in edited or not d.path or not Path(d.path).exists():
            node = d
            while True:
                rewrite.add(id(node))
                if id(node) not in parents:
                    break
                node = parents[id(node)]
    folder = out.parent
    folder.mkdir(parents=True, exist_ok=True)
    taken = {out.resolve()}
    written: list[Path] = []

    def name_for(include: Include) -> Path:
        base = Path(include.filename)
        stem, ext = base.stem, base.suffix or ".k"
        k = 0
        while True:
            cand = folder / f"{stem}{suffix}{'' if k == 0 else f'_{k}'}{ext}"
            if cand.resolve() not in taken and cand.resolve() not in protected:
                taken.add(cand.resolve())
                return cand
            k += 1

    def emit(d: Deck, path: Path) -> None:
        copy = Deck(d.path)
        copy.keyword_args = d.keyword_args
        for item in d.items:
            if isinstance(item, RawKeyword) and item.keyword.upper().startswith("INCLUDE_PATH"):
                copy.items.append(_moved_include_path(item, d.path, path))
                continue
            if not isinstance(item, Include):
                copy.items.append(item)
                continue
            if id(item.deck) in rewrite:
                child = name_for(item)
                emit(item.deck, child)
                name = os.path.relpath(child, path.parent)
            else:
                name = os.path.relpath(Path(item.deck.path).resolve(), path.parent.resolve())
            copy.items.append(Include(filename=name.replace(os.sep, "/"), deck=item.deck,
                                      source=item.source))
        fmt = "long" if "long=y" in d.keyword_args.lower().replace(" ", "") else "standard"
        path.write_text("\n".join(deck_lines(copy, flatten=False, fmt=fmt)) + "\n",
                        encoding="latin-1")
        written.append(path)

    emit(deck, out)
    return written


def _moved_include_path(raw: RawKeyword, source: str | None, target: Path) -> RawKeyword:
    """*INCLUDE_PATH(_RELATIVE) with its relative folders re-expressed from ``target``'s
    folder (they were relative to the file ``source`` that held them)."""
    if not source:
        return raw
    lines = []
    for text in raw.lines:
        folder = text.strip()
        if not folder or folder.startswith("$") or os.path.isabs(folder):
            lines.append(text)
            continue
        real = (Path(source).parent / folder).resolve()
        lines.append(os.path.relpath(real, target.parent.resolve()).replace(os.sep, "/"))
    return RawKeyword(keyword=raw.keyword, lines=lines, unsupported=raw.unsupported,
                      source=raw.source)
