"""Command line: decks that are not keyword decks, unsupported keywords, the output
folder of an earlier run (--overwrite) and the inventory of ``check``."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import pytest

from hollowbody.cli.main import main

DECKS = Path(__file__).parents[2] / "regression" / "decks"
RUN = ["--quiet", "--no-vtk", "--end-time", "0.01"]


@pytest.mark.parametrize("data", [b"", b"just text\n", b"\x00\x01binary\xff" * 50])
def test_run_refuses_a_file_that_is_not_a_deck_before_creating_anything(tmp_path, capsys, data):
    deck = tmp_path / "deck.k"
    deck.write_bytes(data)
    out = tmp_path / "out"
    assert main(["run", str(deck), "--out", str(out), *RUN]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"hollowbody run: error: {deck}: not a keyword "
                                               "deck")
    assert not out.exists()


def test_check_refuses_a_binary_file(tmp_path, capsys):
    deck = tmp_path / "deck.k"
    deck.write_bytes(bytes(range(256)))
    assert main(["check", str(deck)]) == 2
    assert "the file is binary" in capsys.readouterr().err


def test_unsupported_keywords_go_to_messages_log_and_summary_not_to_python_warnings(
        tmp_path, capsys):
    out = tmp_path / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a Python warning would fail the run
        assert main(["run", str(DECKS / "unsupported_mix.k"), "--out", str(out), *RUN]) == 0
    deck = DECKS / "unsupported_mix.k"
    log = (out / "messages.log").read_text()
    assert f"{deck}:19: *SECTION_SPH: keyword not supported, ignored" in log
    assert f"{deck}:40: *EOS_LINEAR_POLYNOMIAL: keyword not supported, ignored" in log
    s = json.loads((out / "summary.json").read_text())
    assert {"keyword": "ELEMENT_TSHELL", "file": str(deck), "line": 25} in \
        s["unsupported_keywords"]
    assert len(s["unsupported_keywords"]) == 8
    captured = capsys.readouterr()
    assert "UnsupportedKeywordWarning" not in captured.err + captured.out
    assert ".py:" not in captured.err + captured.out


def test_a_part_whose_material_is_an_unsupported_keyword_names_it(tmp_path, capsys):
    text = (DECKS / "hand_check.k").read_text().replace(
        "*MAT_ELASTIC\n         3   7.85e-6     210.0       0.3",
        "*MAT_HONEYCOMB\n         3   7.85e-6", 1)
    deck = tmp_path / "deck.k"
    deck.write_text(text)
    line = text.splitlines().index("*MAT_HONEYCOMB") + 1
    assert main(["check", str(deck)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"hollowbody check: error: {deck}:20: *PART: part 3 refers to material 3, "
                   f"defined by *MAT_HONEYCOMB at {deck}:{line}, which is not supported")


def test_an_element_whose_part_is_an_unsupported_keyword_names_it(tmp_path, capsys):
    text = (DECKS / "hand_check.k").read_text().replace(
        "*PART\nsteel plate\n", "*PART_COMPOSITE\nsteel plate\n", 1)
    deck = tmp_path / "deck.k"
    deck.write_text(text)
    assert main(["check", str(deck)]) == 2
    err = capsys.readouterr().err
    assert "element 10 refers to part 3, defined by *PART_COMPOSITE at" in err
    assert "which is not supported" in err


def test_check_prints_the_inventory_of_a_deck_that_cannot_be_built(tmp_path, capsys):
    text = (DECKS / "hand_check.k").read_text().replace(
        "         3         2         3\n", "         3         2         9\n", 1)
    deck = tmp_path / "deck.k"
    deck.write_text(text.replace("*END", "*SECTION_SPH\n         5\n*END"))
    assert main(["check", str(deck), "--json"]) == 2
    captured = capsys.readouterr()
    s = json.loads(captured.out)
    assert s["can_run"] is False
    assert s["problems"] == [f"{deck}:20: *PART: part 3 refers to material 9 which is not "
                             "defined"]
    assert s["nodes"] == 20
    assert s["elements"]["hexahedra"] == 2 and s["elements"]["shells"] == 1
    assert s["elements"]["mass_elements"] == 1
    assert [p["pid"] for p in s["parts"]] == [1, 2, 3]
    assert s["parts"][2]["material"] == "9 (not defined)"
    assert s["materials"] == {"*MAT_ELASTIC": [1, 3], "*MAT_SIMPLIFIED_RUBBER": [2]}
    assert s["sections"] == {"*SECTION_SHELL": [2], "*SECTION_SOLID": [1]}
    assert [u["keyword"] for u in s["unsupported"]] == ["SECTION_SPH"]
    assert captured.err.strip().splitlines() == [f"hollowbody check: error: {s['problems'][0]}"]
    # the text form prints the same inventory
    assert main(["check", str(deck)]) == 2
    text_out = capsys.readouterr().out
    for words in ("nodes 20", "steel plate", "*MAT_ELASTIC 1, 3", "*SECTION_SOLID 1",
                  "*SECTION_SPH", "cannot run", "material 9"):
        assert words in text_out


def test_check_of_a_deck_that_can_run_lists_materials_and_sections(capsys):
    assert main(["check", str(DECKS / "hand_check.k"), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["can_run"] is True
    assert s["materials"] == {"*MAT_ELASTIC": [1, 3], "*MAT_SIMPLIFIED_RUBBER": [2]}
    assert s["sections"] == {"*SECTION_SHELL": [2], "*SECTION_SOLID": [1]}


def _deck_in(folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / "deck.k"
    deck.write_text((DECKS / "hand_check.k").read_text())
    return deck


def test_out_folder_of_an_earlier_run_is_refused_unless_overwrite(tmp_path, capsys):
    deck = _deck_in(tmp_path / "in")
    out = tmp_path / "out"
    assert main(["run", str(deck), "--out", str(out), *RUN]) == 0
    first = (out / "summary.json").read_text()
    (out / "d3dump07").write_bytes(b"stale restart file")
    (out / "notes.txt").write_text("mine")
    capsys.readouterr()
    assert main(["run", str(deck), "--out", str(out), *RUN]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "holds the outputs of an earlier run" in err[0]
    assert "--overwrite" in err[0]
    assert (out / "summary.json").read_text() == first  # nothing touched
    assert main(["run", str(deck), "--out", str(out), "--overwrite", *RUN]) == 0
    assert not (out / "d3dump07").exists()  # the earlier run's files were cleared
    assert (out / "notes.txt").read_text() == "mine"  # other files are kept
    assert json.loads((out / "summary.json").read_text())["status"] == "normal termination"


def test_overwrite_keeps_the_deck_inside_the_output_folder(tmp_path):
    deck = _deck_in(tmp_path)
    text = deck.read_text()
    assert main(["run", str(deck), "--out", str(tmp_path), *RUN]) == 0
    assert main(["run", str(deck), "--out", str(tmp_path), "--overwrite", *RUN]) == 0
    assert deck.read_text() == text
    assert (tmp_path / "summary.json").exists()


def test_an_input_named_like_a_run_output_is_never_overwritten(tmp_path, capsys):
    deck = _deck_in(tmp_path)
    csv_deck = tmp_path / "glstat.csv"
    csv_deck.write_text(deck.read_text())
    assert main(["run", str(csv_deck), "--out", str(tmp_path), "--overwrite", *RUN]) == 2
    assert "has the name of a run output" in capsys.readouterr().err
    assert csv_deck.read_text() == deck.read_text()


def test_an_output_folder_that_is_a_file_is_refused(tmp_path, capsys):
    deck = _deck_in(tmp_path / "in")
    out = tmp_path / "out"
    out.write_text("a file")
    assert main(["run", str(deck), "--out", str(out), *RUN]) == 2
    assert capsys.readouterr().err.strip() == (f"hollowbody run: error: {out} is a file, not "
                                               "an output folder")


def test_block_refuses_an_earlier_run_unless_overwrite(tmp_path, capsys):
    out = tmp_path / "b"
    out.mkdir()
    (out / "summary.json").write_text("{}")
    (out / "force_displacement.csv").write_text("old")
    args = ["block", "--out", str(out), "--mesh", "30", "--end-time", "0.001", "--quiet",
            "--no-vtk"]
    assert main(args) == 2
    assert "holds the outputs of an earlier run" in capsys.readouterr().err
    assert not (out / "deck.k").exists()
    assert main([*args, "--overwrite"]) == 0
    assert (out / "force_displacement.csv").read_text() != "old"
