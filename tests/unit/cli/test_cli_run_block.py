"""Command line: run and block report bad input in one line with exit code 2."""

from __future__ import annotations

import pytest

from hollowbody.cli.main import main


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "Traceback" not in err[0]
    return err[0]


def test_run_missing_deck(tmp_path, capsys):
    code = main(["run", str(tmp_path / "nope.k"), "--out", str(tmp_path / "o"), "--quiet"])
    assert code == 2
    assert "nope.k" in _one_line_error(capsys)


def test_run_bad_number_names_file_line_keyword(tmp_path, capsys):
    deck = tmp_path / "bad.k"
    deck.write_text("*KEYWORD\n*NODE\n       1     0.0abc     0.0     0.0\n*END\n")
    code = main(["run", str(deck), "--out", str(tmp_path / "o"), "--quiet"])
    assert code == 2
    line = _one_line_error(capsys)
    assert "bad.k:3" in line and "*NODE" in line


def test_run_deck_is_not_modified(tmp_path, capsys):
    deck = tmp_path / "bad.k"
    text = "*KEYWORD\n*NODE\n       1     0.0abc     0.0     0.0\n*END\n"
    deck.write_text(text)
    main(["run", str(deck), "--out", str(tmp_path), "--quiet"])
    assert deck.read_text() == text


@pytest.mark.parametrize("args, words", [
    (["--mesh", "7"], "does not divide"),
    (["--speed", "-3"], "positive"),
    (["--structure", "hollow", "--cell", "35"], "does not divide"),
    (["--solid-hourglass", "8"], "--solid-hourglass must be 1-7"),
    (["--solid-hourglass", "6", "--solid-hourglass-qm", "-0.1"], "must be >= 0"),
])
def test_block_bad_options(tmp_path, capsys, args, words):
    code = main(["block", "--out", str(tmp_path / "b"), "--quiet", *args])
    assert code == 2
    assert words in _one_line_error(capsys)
