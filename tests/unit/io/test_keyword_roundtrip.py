"""read -> write -> read gives the same deck and the same model."""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    Contact,
    ControlTermination,
    Deck,
    DefineCurve,
    Include,
    MatElastic,
    Nodes,
    Part,
    RawKeyword,
    SectionShell,
    SectionSolid,
    read_deck,
    write_deck,
)
from hollowbody.source import Source

DECKS = Path(__file__).resolve().parents[2] / "regression" / "decks"

ALL_KEYWORDS = """\
*KEYWORD
*TITLE
every supported keyword
*NODE
       1             0.0             0.0             0.0       0       0
       2             1.0             0.0             0.0
       3             1.0             1.0             0.0
       4             0.0             1.0             0.0
       5             0.0             0.0             1.0       7       7
       6             1.0             0.0             1.0
       7             1.0             1.0             1.0
       8             0.0             1.0             1.0
       9             0.0             0.0             2.0
      10             1.0             0.0             2.0
      11             1.0             1.0             2.0
*ELEMENT_SOLID
       1       1       1       2       3       4       5       6       7       8
*ELEMENT_SHELL_THICKNESS
       2       2       9      10      11
             1.5             1.5             1.5             1.5             0.0
*ELEMENT_SHELL
       3       3       9      10      11       9
*ELEMENT_MASS
       1       9             0.5
*PART
solid
1,1,1,0,7
*PART
shell
2,2,2
*PART_INERTIA
rigid shell
3,2,3
0.5,0.5,2.0,5.0
1.,0.,0.,1.,0.,1.
0.,0.,-1.,0.,0.,0.
*SECTION_SOLID_TITLE
solid section
1,1
*SECTION_SHELL
2,2,0.8333,5
1.5,1.5,1.5,1.5
*HOURGLASS
7,4,0.05
*MAT_SIMPLIFIED_RUBBER_TITLE
muscle
1,1.0e-6,1.0,0.1
,,,10
*MAT_PLASTIC_KINEMATIC
2,1.0e-6,0.1,0.3,0.004
*MAT_RIGID
3,7.85e-6,210.,0.3
1.0,4.0,7.0
*MAT_ELASTIC
4,1e-6,0.1,0.3
*MAT_PIECEWISE_LINEAR_PLASTICITY
5,1e-6,0.1,0.3,0.004
0,0,11
*DEFINE_CURVE_TITLE
muscle
10,0,1.0,0.001
-0.8,-11.8
0.0,0.0
1.0,0.148
*DEFINE_CURVE
11
0.0,0.004
1.0,0.01
*SET_NODE_LIST
1
1,2,3,4
*SET_NODE_LIST_GENERATE
2
9,11
*SET_PART_LIST
3
1,2
*SET_PART_LIST_GENERATE
4
1,3
*SET_SEGMENT
5
5,6,7,8
*BOUNDARY_SPC_SET
1,0,1,1,1
*BOUNDARY_SPC_NODE_ID
3,corner
2,0,1
*BOUNDARY_PRESCRIBED_MOTION_RIGID
3,3,0,11,-1.0
*BOUNDARY_PRESCRIBED_MOTION_SET
1,1,2,11
*BOUNDARY_PRESCRIBED_MOTION_NODE
8,2,0,11
*INITIAL_VELOCITY
2
1.0
*INITIAL_VELOCITY_NODE
8,0,0,2.0
*INITIAL_VELOCITY_GENERATION
4,1,0.01,0,0,-5.0
0.5,0.5,0.0,0.0,0.0,1.0
*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE_ID
1,impactor
3,1,3,3
0.2,0.2
*CONTACT_AUTOMATIC_NODES_TO_SURFACE_MPP
0,200
2,5,4,0
*CONTACT_AUTOMATIC_SINGLE_SURFACE
3,0,2
0.1,0.1
1.0,1.0
1,0.2
*CONTROL_TERMINATION
10.0
*CONTROL_TIMESTEP
0.0,0.8
*CONTROL_HOURGLASS
5,0.05
*CONTROL_BULK_VISCOSITY
1.2,0.05
*CONTROL_CONTACT
0.2
0,0,25
*DATABASE_GLSTAT
0.01
*DATABASE_RCFORC
0.01
*DATABASE_NODOUT
0.02
*DATABASE_SPCFORC
0.03
*DATABASE_MATSUM
0.04
*DATABASE_BINARY_D3PLOT
1.0
*DATABASE_HISTORY_NODE
8
*DATABASE_HISTORY_NODE_SET
2
*SECTION_SPH
$ kept as text
         9       1.2
*END
"""


def assert_same(a, b, path="model"):
    """Recursive equality of dataclasses / dicts / lists / arrays (Source ignored)."""
    if isinstance(a, Source):
        return
    if dataclasses.is_dataclass(a) and not isinstance(a, type):
        assert type(a) is type(b), path
        for f in dataclasses.fields(a):
            assert_same(getattr(a, f.name), getattr(b, f.name), f"{path}.{f.name}")
    elif isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            assert_same(a[k], b[k], f"{path}[{k!r}]")
    elif isinstance(a, (list, tuple)) and not (a and isinstance(a[0], tuple)):
        assert len(a) == len(b), path
        for k, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{path}[{k}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b), path
    elif path.endswith(".unsupported"):
        assert [u[0] for u in a] == [u[0] for u in b], path
    else:
        assert a == b, path


def roundtrip(path: Path, tmp_path: Path, **kw) -> tuple:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        first = read_deck(path)
        out = tmp_path / "out" / "written.k"
        write_deck(first, out, **kw)
        second = read_deck(out)
    return first, second


def test_every_keyword_round_trips(tmp_path):
    src = tmp_path / "all.k"
    src.write_text(ALL_KEYWORDS)
    first, second = roundtrip(src, tmp_path)
    assert len(list(first.iter_items())) == len(list(second.iter_items()))
    for x, y in zip(first.iter_items(), second.iter_items()):
        assert x == y, (x, y)
    assert first == second
    assert_same(build_model(first), build_model(second))
    raw = second.of_type(RawKeyword)[0]
    assert raw.lines == ["$ kept as text", "         9       1.2"]


@pytest.mark.parametrize("name", ["hand_check.k", "shapes.k", "unsupported_mix.k",
                                  "block/main.k"])
def test_regression_decks_round_trip(name, tmp_path):
    first, second = roundtrip(DECKS / name, tmp_path)
    assert first == second
    assert_same(build_model(first), build_model(second))


def test_includes_can_be_kept(tmp_path):
    first, second = roundtrip(DECKS / "block" / "main.k", tmp_path, flatten=False)
    out = tmp_path / "out"
    assert (out / "mesh" / "nodes.k").exists() and (out / "mesh" / "elements.k").exists()
    assert [type(i) for i in second.items][:2] == [type(i) for i in first.items][:2]
    assert isinstance(second.items[1], Include) and second.items[1].filename == "mesh/nodes.k"
    assert first == second


def test_long_format_output_round_trips(tmp_path):
    src = tmp_path / "all.k"
    src.write_text(ALL_KEYWORDS)
    first, second = roundtrip(src, tmp_path, fmt="long")
    assert first == second
    assert "*KEYWORD long=y" in (tmp_path / "out" / "written.k").read_text()


def test_large_ids_switch_to_long_format(tmp_path):
    deck = Deck()
    deck.add_nodes([123456789012], [[1.0, 2.0, 3.0]])
    write_deck(deck, tmp_path / "big.k")
    assert "*NODE +" in (tmp_path / "big.k").read_text()
    assert read_deck(tmp_path / "big.k") == deck


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 40), st.integers(0, 2**31), st.sampled_from(["standard", "long"]))
def test_generated_meshes_round_trip(n, seed, fmt):
    import tempfile

    rng = np.random.default_rng(seed)
    ids = rng.choice(np.arange(1, 10**7), size=n, replace=False)
    xyz = np.round(rng.normal(scale=100.0, size=(n, 3)), rng.integers(0, 8))
    deck = Deck()
    deck.add_nodes(ids, xyz)
    conn = rng.choice(ids, size=(n, 8))
    deck.add_solids(np.arange(1, n + 1), rng.integers(1, 5, size=n), conn)
    deck.add_shells(np.arange(1, n + 1), 7, conn[:, :4],
                    thickness=np.round(rng.uniform(0.5, 3, n), 6))
    y = np.round(rng.normal(size=n), 10)
    deck.add(DefineCurve(lcid=1, points=np.column_stack([np.arange(n), y])))
    deck.add(Part(pid=1, secid=1, mid=1, title="p, with comma"))
    # values that fit their 10-column fields (the writer keeps what the width allows)
    deck.add(SectionShell(secid=1, t1=round(float(rng.uniform(0.1, 5.0)), 4)))
    deck.add(SectionSolid(secid=2))
    deck.add(MatElastic(mid=1, ro=float(f"{rng.uniform(1e-7, 1e-5):.4e}"), e=210.0, pr=0.3))
    deck.add(Contact(type="AUTOMATIC_SINGLE_SURFACE", ssid=1, sstyp=2, fs=0.2, soft=1))
    deck.add(ControlTermination(endtim=round(float(rng.uniform(1, 100)), 5)))
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "gen.k"
        write_deck(deck, path, fmt=fmt)
        back = read_deck(path)
    assert back == deck
    assert np.allclose(back.of_type(Nodes)[0].xyz, xyz, rtol=1e-12, atol=0)
