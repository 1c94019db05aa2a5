"""The landmark file of a user's own body model (``--model DECK --landmarks FILE``).

A JSON object with one entry per case name; each entry holds what that
case's set-up needs of the model (node ids, part ids, points in mm,
directions). The keys of each kind of case are documented in
``docs/validation.md`` and in :mod:`hollowbody.validation.impact` /
:mod:`hollowbody.validation.bending`. Example::

    {"thorax": {"point": [0, 160, 1275], "direction": [-0.5, -0.866, 0],
                "contact_parts": [101, 102], "reference_node": 880001}}

Errors name the file and, for JSON syntax errors, the line.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from hollowbody.errors import UserInputError


def load_landmarks(path: str | Path) -> dict[str, dict[str, Any]]:
    """The landmark entries by case name; UserInputError naming the file (and line)."""
    p = Path(path)
    try:
        text = p.read_text()
    except OSError as e:
        raise UserInputError(f"{p}: cannot read the landmark file ({e.strerror})") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise UserInputError(f"{p}:{e.lineno}: not valid JSON ({e.msg})") from None
    if not isinstance(data, dict) or not all(isinstance(v, dict) for v in data.values()):
        raise UserInputError(f"{p}: the landmark file must be a JSON object of objects, "
                             "one per case name")
    return data


def entry(landmarks: dict[str, dict[str, Any]], case: str, path: str | Path
          ) -> dict[str, Any]:
    """The entry of ``case``; UserInputError naming the file when it is missing."""
    if case not in landmarks:
        raise UserInputError(f"{path}: no entry for case {case!r} (entries: "
                             f"{', '.join(sorted(landmarks)) or 'none'})")
    return landmarks[case]


def field_of(e: dict[str, Any], key: str, case: str, path: str | Path, kind: str) -> Any:
    """``e[key]`` checked to be ``kind``: ``point`` (3 numbers), ``ids`` (list of
    positive integers), ``id`` (a positive integer) or ``number``; UserInputError
    naming the file, case and key otherwise."""
    where = f"{path}: {case}.{key}"
    if key not in e:
        raise UserInputError(f"{where} is missing")
    v = e[key]

    def num(a: Any) -> bool:
        return isinstance(a, (int, float)) and not isinstance(a, bool)

    if kind == "point":
        if not (isinstance(v, list) and len(v) == 3 and all(num(a) for a in v)):
            raise UserInputError(f"{where} must be three numbers [x, y, z] (got {v!r})")
        return [float(a) for a in v]
    if kind == "ids":
        if not (isinstance(v, list) and v and all(isinstance(a, int) and a > 0 for a in v)):
            raise UserInputError(f"{where} must be a list of positive integer ids "
                                 f"(got {v!r})")
        return [int(a) for a in v]
    if kind == "id":
        if not (isinstance(v, int) and not isinstance(v, bool) and v > 0):
            raise UserInputError(f"{where} must be a positive integer id (got {v!r})")
        return int(v)
    if kind == "number":
        if not num(v):
            raise UserInputError(f"{where} must be a number (got {v!r})")
        return float(v)
    raise ValueError(f"unknown landmark kind {kind!r}")
