"""Where a definition came from: the deck file and line that defined it.

Both the keyword reader (which records it) and the static model (which keeps
it for messages that name file and line) use :class:`Source`; it lives here,
below both, so neither has to import the other.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Source:
    """Where a definition came from: file path (as given) and 1-based line."""

    file: str = "<api>"
    line: int = 0

    def __str__(self) -> str:
        return f"{self.file}:{self.line}"
