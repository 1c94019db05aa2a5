"""``hollowbody hollowize``: a successful run, materials, and bad requests (exit 2, one line)."""

from __future__ import annotations

import hashlib
import json
import warnings

import pytest

import hollowbody.cli.main as cli_main
from hollowbody.io.keyword import (
    Material,
    MatPlasticKinematic,
    MatRigid,
    SectionShell,
    read_deck,
    write_deck,
)
from hollowbody.testing.decks import box_deck, write_multipart_deck


@pytest.fixture(autouse=True)
def _with_hollowize(monkeypatch):
    """Make sure the subcommand is registered (independent of the SUBCOMMANDS list)."""
    if "hollowize" not in cli_main.SUBCOMMANDS:
        monkeypatch.setattr(cli_main, "SUBCOMMANDS", cli_main.SUBCOMMANDS + ("hollowize",))


def _digest(folder):
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in folder.rglob("*.k")}


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "Traceback" not in err[0]
    return err[0]


@pytest.fixture(scope="module")
def multipart(tmp_path_factory):
    root = tmp_path_factory.mktemp("cli")
    return write_multipart_deck(root / "in")


def test_cli_converts_and_writes_the_report(multipart, tmp_path, capsys):
    out = tmp_path / "new.k"
    before = _digest(multipart.parent)
    code = cli_main.main(["hollowize", str(multipart), "--out", str(out), "--parts", "1",
                          "--report", str(tmp_path / "rep.md")])
    assert code == 0
    printed = capsys.readouterr().out
    assert "part 1:" in printed and "shells" in printed
    md = (tmp_path / "rep.md").read_text()
    data = json.loads((tmp_path / "rep.json").read_text())
    assert "principal moments" in md and "smallest shell" in md
    p = data["parts"][0]
    assert p["pid"] == 1 and p["within_tolerance"]
    assert p["solids_removed"]["hexahedra"] == 216
    assert p["smallest_shell"]["dt_ms"] > 0.0
    assert sorted(f.rsplit("/", 1)[-1] for f in data["files"]) == ["muscle_hollow.k", "new.k"]
    assert _digest(multipart.parent) == before


def test_cli_material_options(tmp_path, capsys):
    deck = tmp_path / "fat.k"
    write_deck(box_deck((90.0, 60.0, 60.0), 10.0, tissue_name="fat"), deck)

    def wall_material(*extra):
        out = tmp_path / "o.k"
        assert cli_main.main(["hollowize", str(deck), "--out", str(out), *extra]) == 0
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mats = read_deck(out).of_type(MatPlasticKinematic)
        assert len(mats) == 1
        return mats[0]

    m = wall_material()  # default by bulk modulus: fat (KM 4.59 MPa) -> 50 / 2 MPa
    assert (m.e, m.sigy, m.pr) == pytest.approx((0.05, 0.002, 0.3))
    m = wall_material("--material", "80,3", "--etan", "1")
    assert (m.e, m.sigy, m.etan) == pytest.approx((0.08, 0.003, 0.001))
    cal = tmp_path / "calibration.json"
    cal.write_text(json.dumps({"best": {"E": 120.0, "yield": 5.5}, "fitness": 0.1}))
    m = wall_material("--calibration", str(cal), "--material-type", "181", "--cell", "25")
    assert (m.e, m.sigy) == pytest.approx((0.12, 0.0055))
    # the calibration driver's file: best_parameters, fixed values fill in (thickness too)
    cal.write_text(json.dumps({"best_parameters": {"E": 90.0, "yield": 3.5},
                               "simulator": {"fixed": {"etan": 1.0, "thickness": 2.0}}}))
    m = wall_material("--calibration", str(cal))
    assert (m.e, m.sigy, m.etan) == pytest.approx((0.09, 0.0035, 0.001))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sec = list(read_deck(tmp_path / "o.k").of_type(SectionShell))
    assert [x.t1 for x in sec] == [2.0]
    wall_material("--calibration", str(cal), "--thickness", "1.5")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert [x.t1 for x in read_deck(tmp_path / "o.k").of_type(SectionShell)] == [1.5]


def _bad(tmp_path, multipart, case):
    out = str(tmp_path / "x.k")
    bad = tmp_path / "bad.k"
    bad.write_text("*KEYWORD\n*NODE\n       1     0.0abc     0.0     0.0\n*END\n")
    cal = tmp_path / "cal.json"
    cal.write_text('{"best": {"E": 100}}')
    rigid = box_deck((60.0, 60.0, 60.0), 10.0)
    rigid.items = [MatRigid(mid=1, ro=7.8e-6, e=210.0, pr=0.3) if isinstance(it, Material)
                   else it for it in rigid.items]
    write_deck(rigid, tmp_path / "rigid.k")
    return {
        "missing part": ([str(multipart), "--out", out, "--parts", "99"], "part 99"),
        "part without solids": ([str(multipart), "--out", out, "--parts", "3"],
                                "no solid elements"),
        "missing part set": ([str(multipart), "--out", out, "--part-set", "7"], "part set 7"),
        "no such material": ([str(multipart), "--out", out, "--material-type", "24"],
                             "type 24"),
        "cell too large": ([str(multipart), "--out", out, "--cell", "100"],
                           "bounding box"),
        "deck does not parse": ([str(bad), "--out", out], "bad.k:3"),
        "deck missing": ([str(tmp_path / "nope.k"), "--out", out], "nope.k"),
        "out is the input": ([str(multipart), "--out", str(multipart)], "input"),
        "out is an include": ([str(multipart), "--out",
                               str(multipart.parent / "props.k")], "input"),
        "bad calibration": ([str(multipart), "--out", out, "--calibration", str(cal)],
                            "yield"),
        "bad thickness": ([str(multipart), "--out", out, "--thickness", "0"], "thickness"),
        "rigid part": ([str(tmp_path / "rigid.k"), "--out", out, "--parts", "1"], "rigid"),
    }[case]


@pytest.mark.parametrize("case", ["missing part", "part without solids", "missing part set",
                                  "no such material", "cell too large", "deck does not parse",
                                  "deck missing", "out is the input", "out is an include",
                                  "bad calibration", "bad thickness", "rigid part"])
def test_cli_bad_requests_exit_2_with_one_line(case, multipart, tmp_path, capsys):
    args, words = _bad(tmp_path, multipart, case)
    before = _digest(multipart.parent)
    code = cli_main.main(["hollowize", *args])
    assert code == 2
    line = _one_line_error(capsys)
    assert line.startswith("hollowbody hollowize: error:")
    assert words in line
    assert _digest(multipart.parent) == before
    assert not (tmp_path / "x.k").exists()


def test_cli_builds_the_calibrated_walls_geometry(tmp_path):
    """Walls calibrated with 15 mm cells and 2 shells per cell edge are built so; --cell or
    --elements-per-edge given: the options, with the defaults for the one not given."""
    deck = tmp_path / "fat.k"
    write_deck(box_deck((90.0, 60.0, 60.0), 10.0, tissue_name="fat"), deck)
    cal = tmp_path / "calibration.json"
    cal.write_text(json.dumps({"best_parameters": {"E": 90.0, "yield": 3.5},
                               "simulator": {"fixed": {}, "options": {"cell": 15.0},
                                             "elements_per_edge": 2}}))

    def geometry(*extra):
        rep = tmp_path / "rep.md"
        assert cli_main.main(["hollowize", str(deck), "--out", str(tmp_path / "o.k"),
                              "--calibration", str(cal), "--report", str(rep), *extra]) == 0
        opts = json.loads(rep.with_suffix(".json").read_text())["options"]
        return opts["cell"], opts["elements_per_edge"]

    assert geometry() == (15.0, 2)
    assert geometry("--cell", "20") == (20.0, 4)
    assert geometry("--elements-per-edge", "3") == (30.0, 3)
