"""Repository files: the licence, the citation metadata, documentation that names only
files of the repository and speaks of the project (no work-tracking references)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = sorted((ROOT / "docs").glob("*.md"))
PROSE = [ROOT / "README.md", ROOT / "CHANGELOG.md", *DOCS]


def _version() -> str:
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    return re.search(r'^version\s*=\s*"([^"]+)"', text, re.MULTILINE).group(1)


def test_license_is_the_apache_2_0_text():
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert "Apache License" in text and "Version 2.0, January 2004" in text
    assert "TERMS AND CONDITIONS FOR USE, REPRODUCTION, AND DISTRIBUTION" in text
    assert "END OF TERMS AND CONDITIONS" in text
    for section in range(1, 10):
        assert re.search(rf"^\s+{section}\. \w", text, re.MULTILINE), section
    assert 'license = {text = "Apache-2.0"}' in (ROOT / "pyproject.toml").read_text()


def test_citation_metadata_matches_the_package():
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    assert re.search(r"^cff-version: 1\.2\.0$", text, re.MULTILINE)
    assert re.search(rf"^version: {re.escape(_version())}$", text, re.MULTILINE)
    assert re.search(r"^license: Apache-2\.0$", text, re.MULTILINE)
    for key in ("message", "title", "authors", "type"):
        assert re.search(rf"^{key}:", text, re.MULTILINE), key
    assert "A novel modeling approach for finite element human body" in text


def test_readme_cites_the_paper_and_the_data_sources():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "## Citing" in text and "CITATION.cff" in text
    flat = " ".join(" ".join(line.lstrip("> ") for line in text.splitlines()).split())
    assert ("A novel modeling approach for finite element human body models with high "
            "computational efficiency and stability: application in pedestrian safety "
            "analysis") in flat
    assert "Viano" in text and "SAFER HBM" in text and "Apache License 2.0" in text


@pytest.mark.parametrize("path", PROSE, ids=lambda p: p.name)
def test_prose_has_no_work_tracking_words(path):
    text = path.read_text(encoding="utf-8")
    assert not re.search(r"\(#\d+|#\d+\)", text), "work-tracking number"
    assert not re.search(r"\bsessions?\b", text, re.IGNORECASE)
    assert "DESIGN.md" not in text and "design document" not in text


@pytest.mark.parametrize("path", [ROOT / "README.md", *DOCS], ids=lambda p: p.name)
def test_docs_name_only_repository_paths(path):
    """Every `docs/...`, `tests/...`, `src/...` or `benchmarks/...` path in backticks or
    prose exists."""
    text = path.read_text(encoding="utf-8")
    for ref in re.findall(r"\b((?:docs|tests|src|benchmarks)/[\w./-]*\w)", text):
        assert (ROOT / ref).exists(), ref
