"""Plain text for ``--help``: module docstrings without their reST markup.

The subcommand modules' docstrings double as their ``--help`` descriptions;
:func:`plain` turns the inline markup of a docstring into the plain words a
terminal shows (``hollowbody run`` -> hollowbody run, a role such as
:func:`~pkg.mod.name` -> name, a literal-block marker ``Example::`` ->
``Example:``).
"""

from __future__ import annotations

import re

_ROLE = re.compile(r":[a-z]+(?::[a-z]+)?:`~?([^`<]*?)(?:\s*<[^`>]*>)?`")
_LITERAL = re.compile(r"``(.+?)``", re.DOTALL)
_INTERPRETED = re.compile(r"(?<![\w`])`([^`]+)`(?!`)")


def plain(doc: str | None) -> str:
    """``doc`` with its reST inline markup removed (roles, literals, ``::``)."""
    if not doc:
        return ""
    text = _ROLE.sub(lambda m: m.group(1).rsplit(".", 1)[-1] if "~" in m.group(0)
                     else m.group(1), doc)
    text = _LITERAL.sub(r"\1", text)
    text = _INTERPRETED.sub(r"\1", text)
    text = re.sub(r"\s::$", "", text, flags=re.MULTILINE)
    text = re.sub(r"::$", ":", text, flags=re.MULTILINE)
    return text.strip() + "\n"
