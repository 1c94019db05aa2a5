"""``hollowbody rate``: bad files give one clear line and exit code 2; good runs work."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hollowbody.cli.main import main

T = np.arange(0.0, 60.0 + 1e-9, 0.5)


def write_curve(path, t, y, header="time,force", sep=","):
    lines = [header] + [f"{a:.6g}{sep}{b:.6g}" for a, b in zip(t, y)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return str(path)


@pytest.fixture
def curves(tmp_path):
    ref = write_curve(tmp_path / "ref.csv", T, 3.0 * np.sin(np.pi * T / 60.0) ** 2)
    cand = write_curve(tmp_path / "cand.csv", T, 3.3 * np.sin(np.pi * (T - 1.0) / 60.0) ** 2,
                       header="time;force", sep=";")
    return ref, cand


def run_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err
    assert code == 2
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hollowbody rate: error: ")
    return lines[0]


def test_missing_file(capsys, curves, tmp_path):
    ref, _ = curves
    missing = str(tmp_path / "nope.csv")
    msg = run_error(capsys, ["rate", ref, missing])
    assert missing in msg and "file not found" in msg


def test_missing_column(capsys, curves):
    ref, cand = curves
    msg = run_error(capsys, ["rate", ref, cand, "--columns", "time", "accel"])
    assert ref in msg and "no column 'accel'" in msg and "time, force" in msg
    msg = run_error(capsys, ["rate", ref, cand, "--columns", "1", "5"])
    assert "no column 5" in msg


def test_non_numeric_cell_names_line_and_column(capsys, curves, tmp_path):
    ref, _ = curves
    bad = tmp_path / "bad.csv"
    bad.write_text("time,force\n0,0\n1,abc\n2,1\n", encoding="utf-8")
    msg = run_error(capsys, ["rate", ref, str(bad)])
    assert f"{bad}:3:" in msg and "'force'" in msg and "'abc' is not a finite number" in msg


def test_non_monotonic_time_names_the_line(capsys, curves, tmp_path):
    ref, _ = curves
    bad = tmp_path / "back.csv"
    bad.write_text("time,force\n0,0\n1,1\n# comment\n0.5,2\n2,1\n", encoding="utf-8")
    msg = run_error(capsys, ["rate", str(bad), ref])
    assert f"{bad}:5:" in msg and "increase" in msg


@pytest.mark.parametrize(("text", "words"), [
    ("", "file is empty"),
    ("time,force\n", "no data rows"),
    ("time,force\n,\n,\n", "no numbers"),
    ("time,force\n0,1\n", "only 1 sample"),
    ("time,force\n0,1\n1,\n2,3\n", "column 'force' is blank"),
])
def test_empty_or_incomplete_curves(capsys, curves, tmp_path, text, words):
    ref, _ = curves
    bad = tmp_path / "empty.csv"
    bad.write_text(text, encoding="utf-8")
    msg = run_error(capsys, ["rate", ref, str(bad)])
    assert str(bad) in msg and words in msg


def test_curve_that_never_reaches_the_thresholds(capsys, curves, tmp_path):
    _, cand = curves
    flat = write_curve(tmp_path / "flat.csv", T, np.zeros_like(T))
    msg = run_error(capsys, ["rate", flat, cand, "--method", "cora"])
    assert flat in msg and "never reaches the thresholds" in msg
    msg = run_error(capsys, ["rate", flat, cand, "--method", "iso18571"])
    assert flat in msg and "zero" in msg


def test_curves_without_common_time_range(capsys, curves, tmp_path):
    ref, _ = curves
    late = write_curve(tmp_path / "late.csv", T + 100.0, np.ones_like(T))
    msg = run_error(capsys, ["rate", ref, late])
    assert ref in msg and late in msg and "do not overlap" in msg


def test_bad_settings(capsys, curves):
    ref, cand = curves
    assert "unknown parameter" in run_error(capsys, ["rate", ref, cand, "--set", "FOO=1"])
    assert "NAME=VALUE" in run_error(capsys, ["rate", ref, cand, "--set", "K_V"])
    assert "not a number" in run_error(capsys, ["rate", ref, cand, "--set", "K_V=x"])
    assert "D_MIN" in run_error(capsys, ["rate", ref, cand, "--set", "D_MIN=0.5"])


def test_table_output(capsys, curves):
    ref, cand = curves
    assert main(["rate", ref, cand]) == 0
    out = capsys.readouterr().out
    for word in ("ISO/TS 18571", "CORA", "corridor", "magnitude", "progression", "overall"):
        assert word in out


def test_json_and_plot(capsys, curves, tmp_path):
    ref, cand = curves
    png = tmp_path / "rating.png"
    code = main(["rate", ref, ref, "--json", "--plot", str(png), "--set", "K_V=5",
                 "--set", "iso.eps_p=0.1"])
    assert code == 0
    report = json.loads(capsys.readouterr().out)
    assert report["iso18571"]["overall"] == pytest.approx(1.0)
    assert report["cora"]["total"] == pytest.approx(1.0)
    assert report["cora"]["parameters"]["K_V"] == 5.0
    assert report["iso18571"]["parameters"]["eps_p"] == 0.1
    assert report["plot"] == str(png)
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_corridor_file_and_single_method(capsys, curves, tmp_path):
    ref, cand = curves
    corr = tmp_path / "corr.csv"
    corr.write_text("t;lo;up\n0;-1;1\n30;2;4\n60;-1;1\n", encoding="utf-8")
    assert main(["rate", ref, cand, "--method", "cora", "--corridor", str(corr), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert "iso18571" not in report and report["cora"]["user_corridors"] is True
    assert 0.0 < report["corridor"]["fraction_inside"] <= 1.0
    poly = tmp_path / "poly.csv"
    poly.write_text("t,f\n0,0\n30,5\n60,0\n30,1\n", encoding="utf-8")
    assert main(["rate", ref, cand, "--corridor", str(poly)]) == 0
    assert "fraction inside" in capsys.readouterr().out
    bad = tmp_path / "badcorr.csv"
    bad.write_text("t\n1\n2\n", encoding="utf-8")
    msg = run_error(capsys, ["rate", ref, cand, "--corridor", str(bad)])
    assert str(bad) in msg and "corridor needs" in msg


def test_read_curve_decimal_comma_named_columns_and_ragged_end(tmp_path):
    from hollowbody.rating.csvio import read_curve

    f = tmp_path / "eu.csv"
    f.write_text("a;Time;Force\n9;0,0;1,5\n9;0,5;2,5\n9;;\n9;;\n", encoding="utf-8")
    t, y = read_curve(f, ("time", "FORCE"))
    assert t.tolist() == [0.0, 0.5] and y.tolist() == [1.5, 2.5]
