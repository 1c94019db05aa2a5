"""Errors that reach the user as one clear line and exit code 2.

Any error caused by what the user gave (a deck, a CSV, a command-line value)
is raised as :class:`UserInputError` (or a subclass). The command-line entry
point prints ``str(error)`` on one line and exits with code 2; it never shows a
traceback for these.
"""

from __future__ import annotations


class UserInputError(Exception):
    """Bad input from the user: printed as one line, exit code 2."""

    exit_code = 2


class DeckError(UserInputError):
    """A problem in a keyword deck, located by file, line and keyword.

    ``str(err)`` is ``file:line: *KEYWORD: message`` (parts that are unknown
    are left out).
    """

    def __init__(self, message: str, file: str | None = None, line: int | None = None,
                 keyword: str | None = None) -> None:
        self.message = message
        self.file = file
        self.line = line
        self.keyword = keyword
        super().__init__(self.format())

    def format(self) -> str:
        parts = []
        if self.file is not None:
            parts.append(f"{self.file}:{self.line}" if self.line is not None else self.file)
        if self.keyword:
            kw = self.keyword if self.keyword.startswith("*") else "*" + self.keyword
            parts.append(kw)
        parts.append(self.message)
        return ": ".join(parts)
