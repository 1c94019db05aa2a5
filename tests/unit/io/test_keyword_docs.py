"""The deck-building example of docs/keyword.md runs and gives a deck that can run."""

from __future__ import annotations

import re
from pathlib import Path

from hollowbody.build import build_model
from hollowbody.io.keyword import read_deck
from hollowbody.model.summary import summarize

DOC = Path(__file__).resolve().parents[3] / "docs" / "keyword.md"


def test_docs_example_builds_writes_and_checks(tmp_path, monkeypatch):
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)
    example = next(b for b in blocks if "Deck()" in b)
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(example, str(DOC), "exec"), namespace)
    back = read_deck(tmp_path / "block.k")
    assert back == namespace["deck"]
    summary = summarize(build_model(back))
    assert summary["can_run"] and summary["elements"]["hexahedra"] == 1
