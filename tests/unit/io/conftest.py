"""Fixtures of the keyword I/O tests: write deck text to a temporary folder."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest


@pytest.fixture
def deck_file(tmp_path: Path):
    """``deck_file(text, name="deck.k")`` writes dedented ``text`` and returns its path."""

    def make(text: str, name: str = "deck.k") -> Path:
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text).lstrip("\n"))
        return path

    return make
