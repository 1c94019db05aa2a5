"""``hollowbody check``: the inventory of a deck that does not read (a bad card, a missing
include file) and the numba threads a run of the deck would use."""

from __future__ import annotations

import json
from pathlib import Path

import numba
import pytest

from hollowbody.cli.main import main
from hollowbody.solver import threads as th

DECKS = Path(__file__).parents[2] / "regression" / "decks"
BAD_SHELL = ("         2         2       1.0         5\n",
             "         2       two       1.0         5\n")


def _bad_card_deck(tmp_path: Path) -> tuple[Path, int]:
    """hand_check.k with a non-numeric ELFORM in *SECTION_SHELL; (deck, line of the card)."""
    text = (DECKS / "hand_check.k").read_text()
    assert BAD_SHELL[0] in text
    text = text.replace(*BAD_SHELL, 1)
    deck = tmp_path / "bad.k"
    deck.write_text(text)
    return deck, text.splitlines().index(BAD_SHELL[1].rstrip("\n")) + 1


def test_a_bad_card_gives_the_inventory_read_before_it_and_the_error(tmp_path, capsys):
    deck, line = _bad_card_deck(tmp_path)
    error = f"{deck}:{line}: *SECTION_SHELL: field ELFORM: 'two' is not an integer"
    assert main(["check", str(deck), "--json"]) == 2
    captured = capsys.readouterr()
    s = json.loads(captured.out)
    assert s["can_run"] is False
    assert s["problems"] == [error]
    assert captured.err.strip().splitlines() == [f"hollowbody check: error: {error}"]
    # every keyword block up to the one holding the error, counted per keyword
    assert s["keywords"] == {"KEYWORD": 1, "TITLE": 1, "CONTROL_TERMINATION": 1,
                             "CONTROL_TIMESTEP": 1, "PART": 3, "SECTION_SOLID": 1,
                             "SECTION_SHELL": 1}
    assert [p["title"] for p in s["parts"]] == ["elastic cube", "rubber cube", "steel plate"]
    assert s["parts"][0]["section"] == "*SECTION_SOLID 1 (ELFORM 1)"
    assert s["parts"][2]["section"] == "2 (not read)"  # its block is the bad one
    assert s["sections"] == {"*SECTION_SOLID": [1]}
    assert s["nodes"] == 0 and s["materials"] == {}  # after the error: not read
    assert s["threads"] is None and s["time_step"] is None
    # the text form prints the same inventory and the error
    assert main(["check", str(deck)]) == 2
    out = capsys.readouterr().out
    for words in ("nodes 0", "elastic cube", "steel plate", "sections: *SECTION_SOLID 1",
                  "*PART 3", "*SECTION_SHELL 1", "cannot run", error):
        assert words in out, words


def test_an_error_in_an_include_file_keeps_what_was_read_before_it(tmp_path, capsys):
    text = (DECKS / "hand_check.k").read_text()
    head, mesh = text.split("*NODE\n", 1)
    mesh = "*NODE\n" + mesh.replace("*ELEMENT_SHELL\n      10       3",
                                    "*ELEMENT_SHELL\n      10     abc", 1)
    (tmp_path / "mesh.k").write_text(mesh)
    deck = tmp_path / "main.k"
    deck.write_text(head + "*INCLUDE\nmesh.k\n*END\n")
    assert main(["check", str(deck), "--json"]) == 2
    s = json.loads(capsys.readouterr().out)
    line = mesh.splitlines().index("      10     abc      21      22      23      24") + 1
    assert len(s["problems"]) == 1
    assert s["problems"][0].startswith(f"{tmp_path / 'mesh.k'}:{line}: *ELEMENT_SHELL: ")
    assert s["nodes"] == 20 and s["elements"]["hexahedra"] == 2  # read before the error
    assert s["elements"]["shells"] == 0
    assert s["materials"] == {"*MAT_ELASTIC": [1, 3], "*MAT_SIMPLIFIED_RUBBER": [2]}
    assert s["keywords"]["INCLUDE"] == 1 and s["keywords"]["ELEMENT_SHELL"] == 1
    assert "ELEMENT_MASS" not in s["keywords"]  # after the error


def test_a_missing_include_file_is_the_reason_and_the_rest_is_counted(tmp_path, capsys):
    text = (DECKS / "hand_check.k").read_text()
    deck = tmp_path / "main.k"
    deck.write_text(text.replace("*END", "*INCLUDE\nnot_there.k\n*END"))
    line = deck.read_text().splitlines().index("not_there.k") + 1
    assert main(["check", str(deck)]) == 2
    captured = capsys.readouterr()
    error = f"{deck}:{line}: *INCLUDE: include file '{tmp_path / 'not_there.k'}' does not exist"
    assert captured.err.strip() == f"hollowbody check: error: {error}"
    assert error in captured.out
    assert "nodes 20" in captured.out and "*INCLUDE 1" in captured.out


def test_a_deck_that_reads_lists_its_keywords_too(capsys):
    assert main(["check", str(DECKS / "hand_check.k"), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["keywords"]["PART"] == 3 and s["keywords"]["MAT_ELASTIC"] == 2
    assert s["keywords"]["MAT_SIMPLIFIED_RUBBER/FOAM"] == 1  # counted as written
    assert s["can_run"] is True


def test_check_reports_the_threads_of_the_run_it_checks(tmp_path, capsys):
    deck = DECKS / "hand_check.k"
    assert main(["check", str(deck), "--json"]) == 0  # --threads auto, as run's default
    s = json.loads(capsys.readouterr().out)
    assert s["threads"]["count"] == 1  # 3 elements: below the auto threshold
    assert s["threads"]["reason"].startswith("auto: small model")
    out = tmp_path / "out"
    assert main(["run", str(deck), "--out", str(out), "--quiet", "--no-vtk", "--end-time",
                 "0.01"]) == 0
    assert json.loads((out / "summary.json").read_text())["threads"] == s["threads"]["count"]
    capsys.readouterr()
    assert main(["check", str(deck)]) == 0
    assert "numba threads: 1 (auto: small model" in capsys.readouterr().out
    assert th.default() is None  # the command's setting does not outlive it


def test_check_threads_option_is_capped_like_the_run(capsys):
    deck = str(DECKS / "hand_check.k")
    assert main(["check", deck, "--json", "--threads", "1"]) == 0
    assert json.loads(capsys.readouterr().out)["threads"] == {"count": 1, "reason": "requested"}
    limit = int(numba.config.NUMBA_NUM_THREADS)
    assert main(["check", deck, "--json", "--threads", str(limit + 1)]) == 0
    t = json.loads(capsys.readouterr().out)["threads"]
    assert t["count"] == limit and "available (NUMBA_NUM_THREADS)" in t["reason"]


def test_check_sets_the_wait_policy_before_its_kernels(monkeypatch, capsys):
    import hollowbody.solver.preflight as preflight

    calls = []
    real_policy, real_first = th.wait_policy, preflight.first_time_step
    monkeypatch.setattr(th, "wait_policy", lambda: calls.append("policy") or real_policy())
    monkeypatch.setattr(preflight, "first_time_step",
                        lambda model: calls.append("first step") or real_first(model))
    assert main(["check", str(DECKS / "hand_check.k"), "--json"]) == 0
    assert calls[0] == "policy" and "first step" in calls


@pytest.mark.parametrize("bad", ["0", "two"])
def test_check_rejects_a_bad_threads_value(bad, capsys):
    assert main(["check", str(DECKS / "hand_check.k"), "--threads", bad]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("hollowbody check: error: threads must be a positive integer")
