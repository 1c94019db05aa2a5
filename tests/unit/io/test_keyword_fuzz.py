"""Mutated real decks: every input ends in a model or in one located user error.

The decks of ``tests/regression/decks`` are mutated (truncated cards, shifted
columns, wrong types, huge ids, missing includes, deleted / repeated lines,
random bytes) with a fixed seed and driven through the reader, the builder,
the model summary and the deck inventory of ``hollowbody check``; every 8th
also through ``hollowbody check --json``. Anything other than a Model or a
:class:`~hollowbody.errors.UserInputError` (another exception type) fails.
"""

from __future__ import annotations

import random
import shutil
import warnings
from pathlib import Path

import pytest

from hollowbody.build import build_model
from hollowbody.build.inventory import deck_inventory
from hollowbody.cli.main import main
from hollowbody.errors import UserInputError
from hollowbody.io.keyword import read_deck
from hollowbody.model.summary import summarize

DECKS = Path(__file__).parents[2] / "regression" / "decks"
SOURCES = ["hand_check.k", "shapes.k", "unsupported_mix.k", "block/main.k",
           "block/mesh/nodes.k", "block/mesh/elements.k"]
N_MUTATIONS = 300
SEED = 13


def _data_lines(lines: list[str]) -> list[int]:
    return [k for k, t in enumerate(lines) if t.strip() and not t.startswith(("*", "$"))]


def _mutate(text: str, rng: random.Random) -> str:
    lines = text.split("\n")
    data = _data_lines(lines) or [0]
    k = rng.choice(data)
    t = lines[k]
    kind = rng.randrange(10)
    if kind == 0:  # truncated card
        lines[k] = t[:rng.randrange(len(t) + 1)]
    elif kind == 1:  # shifted columns
        lines[k] = " " * rng.randint(1, 5) + t if rng.random() < 0.5 else t[rng.randint(1, 5):]
    elif kind == 2:  # wrong type in a field
        a = rng.randrange(max(len(t) - 4, 1))
        lines[k] = t[:a] + rng.choice(["abc", "1.5", "-", "nan", "inf", "1e999", ",", "+"]) + \
            t[a + 3:]
    elif kind == 3:  # huge or negative ids
        a = 10 * rng.randrange(max(len(t) // 10, 1))
        lines[k] = t[:a] + rng.choice(["9" * 10, "-" + "9" * 9, "99999999", "-1", "0"]) \
            .rjust(10) + t[a + 10:]
    elif kind == 4:  # missing include
        lines = [("missing_" + s if not s.startswith(("*", "$")) and s.strip().endswith(".k")
                  else s) for s in lines]
    elif kind == 5:  # deleted line (cards or keyword lines)
        del lines[rng.randrange(len(lines))]
    elif kind == 6:  # repeated line
        j = rng.randrange(len(lines))
        lines.insert(j, lines[j])
    elif kind == 7:  # a keyword line renamed or cut
        kws = [j for j, s in enumerate(lines) if s.startswith("*")] or [0]
        j = rng.choice(kws)
        s = lines[j]
        lines[j] = s[:rng.randrange(1, len(s) + 1)] if s else "*"
    elif kind == 8:  # a blank line anywhere
        lines.insert(rng.randrange(len(lines) + 1), "")
    else:  # random bytes
        out = "\n".join(lines).encode("latin-1")
        a = rng.randrange(len(out) + 1)
        junk = bytes(rng.randrange(256) for _ in range(rng.randint(1, 12)))
        return (out[:a] + junk + out[a:]).decode("latin-1")
    return "\n".join(lines)


def _cases() -> list[tuple[int, str, int]]:
    rng = random.Random(SEED)
    return [(k, rng.choice(SOURCES), rng.randrange(1, 4)) for k in range(N_MUTATIONS)]


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("fuzz")


def _drive(path: Path, with_check: bool) -> str:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            deck = read_deck(path)
            deck_inventory(deck)
            summarize(build_model(deck))
    except UserInputError as exc:
        message = str(exc)
        assert message.startswith(str(path.parent)) or "deck '" in message, message
        return "error"
    if with_check:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert main(["check", str(path), "--json"]) in (0, 2)
    return "model"


def test_mutated_decks_end_in_a_model_or_a_located_error(workdir, capsys):
    outcomes = {"model": 0, "error": 0}
    for k, source, n in _cases():
        rng = random.Random(SEED * 100_003 + k)
        case = workdir / f"case{k:03d}"
        shutil.copytree(DECKS / "block", case / "block")
        for name in ("hand_check.k", "shapes.k", "unsupported_mix.k"):
            shutil.copy(DECKS / name, case / name)
        target = case / source
        text = target.read_bytes().decode("latin-1")
        for _ in range(n):
            text = _mutate(text, rng)
        target.write_bytes(text.encode("latin-1"))
        top = case / ("block/main.k" if source.startswith("block/") else source)
        try:
            outcomes[_drive(top, with_check=k % 8 == 0)] += 1
        except AssertionError:
            raise
        except Exception as exc:  # the defect this test looks for
            pytest.fail(f"case {k} ({source}, {n} mutations): {type(exc).__name__}: {exc}\n"
                        f"{text}")
        capsys.readouterr()
    # the mutations reach both outcomes (the test would be void otherwise)
    assert outcomes["model"] > 20 and outcomes["error"] > 50, outcomes


# ---------------------------------------------------------------------------
# Crashes the mutations found, kept as their own cases


def test_an_id_beyond_64_bits_is_a_located_error(deck_file):
    path = deck_file("*NODE\n99999999999999999999999,0.0,0.0,0.0\n")
    with pytest.raises(UserInputError, match=r"deck.k:2: \*NODE: field NID: "
                       r"'99999999999999999999999' is not an integer of at most 18 digits"):
        read_deck(path)


def test_a_generated_set_of_a_billion_ids_is_a_located_error(deck_file):
    path = deck_file("*SET_NODE_LIST_GENERATE\n         1\n         11000000000\n")
    with pytest.raises(UserInputError, match=r"deck.k:3: .*the ranges hold more than"):
        read_deck(path)


def test_inventory_of_an_empty_shell_block(deck_file):
    deck = read_deck(deck_file("*KEYWORD\n*ELEMENT_SHELL\n*END\n"))
    assert deck_inventory(deck)["elements"]["shells"] == 0
