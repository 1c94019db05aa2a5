"""Bulk-block parsing: the numpy and the compiled paths agree with Python's float/int."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.errors import DeckError
from hollowbody.io.keyword import bulk
from hollowbody.io.keyword.base import Block
from hollowbody.io.keyword.cards import parse_float


def block_of(text: str, name: str = "NODE") -> Block:
    data = b"*" + name.encode() + b"\n" + text.encode("latin-1")
    return Block(name, name, (), "standard", "b.k", 1, data, len(name) + 2, len(data), 2)


def float_texts(rng: np.random.Generator, n: int) -> list[str]:
    out = []
    for _ in range(n):
        v = float(rng.normal() * 10.0 ** rng.integers(-8, 9))
        form = rng.integers(0, 8)
        s = [repr(v), f"{v:.6e}", f"{v:.7f}", f"{v:.5E}".replace("E", "D"),
             f"{v:.4e}".replace("e", ""), f"{v:g}", "", f"{int(v * 1000)}"][form]
        out.append(s if len(s) <= 16 else f"{v:.8e}")
    return out


@pytest.fixture(params=["numpy", "compiled"])
def path(request, monkeypatch):
    monkeypatch.setattr(bulk, "FAST_MIN_FIELDS", 10**9 if request.param == "numpy" else 1)
    return request.param


def test_reals_and_ints_match_python(path):
    rng = np.random.default_rng(7)
    n = 400
    texts = float_texts(rng, 3 * n)
    ids = rng.integers(-10**6, 10**7, size=n)
    just = rng.integers(0, 3, size=n)
    rows = []
    for k in range(n):
        i = str(ids[k])
        i = i.rjust(8) if just[k] == 0 else (i.ljust(8) if just[k] == 1 else " " * 8)
        rows.append(i + "".join(t.rjust(16) if k % 2 else t.ljust(16)
                                for t in texts[3 * k:3 * k + 3]))
    t = bulk.row_table(block_of("\n".join(rows) + "\n"), 56)
    got_i = bulk.parse_ints(t, 0, 8, 1, ["nid"], 0)[:, 0]
    got_f = bulk.parse_floats(t, 8, 16, 3, ["x", "y", "z"], 1)
    want_i = [int(ids[k]) if just[k] < 2 else 0 for k in range(n)]
    want_f = [parse_float(s) if s else 0.0 for s in texts]
    assert got_i.tolist() == want_i
    assert got_f.ravel().tolist() == want_f


def test_exactness_of_long_mantissas(path):
    values = ["0.30000000000000004", "123456789012.345", "1.797693134862e308",
              "4.9e-324", "-0.0", "1e22", "1e23", "9007199254740993"]
    rows = "\n".join(f"{k + 1:8d}" + "".join(v[:20].rjust(20) for v in (s, s, s))
                     for k, s in enumerate(values))
    blk = block_of(rows + "\n")
    blk.fmt = "long"
    t = bulk.row_table(blk, 68)
    got = bulk.parse_floats(t, 8, 20, 3, ["x", "y", "z"], 1)
    assert got[:, 0].tolist() == [float(s) for s in values]
    assert np.signbit(got[4, 0])


@pytest.mark.parametrize("bad, field", [("1.2.3", "Y"), ("1e", "Y"), ("abc", "Y"),
                                        ("--1", "Y"), ("1.0f", "Y")])
def test_bad_reals_are_located(path, bad, field):
    rows = [f"{k:8d}{1.0:16}{2.0:16}{3.0:16}" for k in range(1, 50)]
    rows[30] = f"{31:8d}{1.0:16}{bad:>16}{3.0:16}"
    t = bulk.row_table(block_of("\n".join(rows) + "\n"), 56)
    with pytest.raises(DeckError) as err:
        bulk.parse_floats(t, 8, 16, 3, ["x", "y", "z"], 1)
    assert str(err.value) == f"b.k:32: *NODE: field {field}: '{bad}' is not a number"


def test_bad_ints_are_located(path):
    rows = [f"{k:8d}{k:8d}" for k in range(1, 50)]
    rows[10] = f"{11:8d}{'1x':>8}"
    t = bulk.row_table(block_of("\n".join(rows) + "\n", "ELEMENT_SOLID"), 16)
    with pytest.raises(DeckError) as err:
        bulk.parse_ints(t, 0, 8, 2, ["eid", "pid"], 0)
    assert str(err.value) == "b.k:12: *ELEMENT_SOLID: field PID: '1x' is not an integer"


def test_uniform_and_ragged_bodies_give_the_same_table():
    rows = [f"{k:8d}{float(k):16}{0.0:16}{0.0:16}" for k in range(1, 6)]
    uniform = bulk.row_table(block_of("\n".join(rows) + "\n"), 56)
    ragged = bulk.row_table(block_of("$ header\n" + "\n".join(r.rstrip() for r in rows)
                                     + "\n\n"), 56)
    assert np.array_equal(uniform.mat, ragged.mat)
    assert uniform.lines.tolist() == [2, 3, 4, 5, 6] and ragged.lines.tolist() == [3, 4, 5, 6, 7]


@pytest.mark.parametrize("width", [8, 10, 20])
def test_int_rows_match_printf(width):
    rng = np.random.default_rng(3)
    a = rng.integers(0, 10 ** min(width, 18), size=(50, 4))
    a[0] = [0, 9, 10, 10 ** min(width, 18) - 1]
    assert bulk.int_rows(a, width) == [(f"%{width}d" * 4) % tuple(r) for r in a.tolist()]
    neg = np.array([[-5, 3]])
    assert bulk.int_rows(neg, width) == [f"{-5:>{width}d}{3:>{width}d}"]
    if width < 18:
        with pytest.raises(ValueError, match="does not fit"):
            bulk.int_rows(np.array([[10 ** width]]), width)
