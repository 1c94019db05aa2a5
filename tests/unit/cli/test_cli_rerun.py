"""``hollowbody study`` and ``hollowbody bending`` in a folder of an earlier run:
refused unless --overwrite, which replaces that run's outputs."""

from __future__ import annotations

import json

from hollowbody.cli.main import main

#: The smallest study: one speed, 30 mm elements, 1 us of contact-free time.
STUDY = ["study", "--tissue", "muscle", "--speeds", "40", "--mesh", "30", "--end-time",
         "0.001", "--threads", "1"]


def test_study_refuses_an_earlier_study_unless_overwrite(tmp_path, capsys):
    out = tmp_path / "st"
    assert main([*STUDY, "--out", str(out)]) == 0
    (out / "notes.txt").write_text("mine")
    (out / "hollow" / "70kmh").mkdir()  # a run of another speed, from an earlier study
    (out / "hollow" / "70kmh" / "summary.json").write_text("{}")
    first = (out / "study.json").read_text()
    capsys.readouterr()
    assert main([*STUDY, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"hollowbody study: error: {out} holds the "
                                               "outputs of an earlier run (")
    assert "--overwrite" in err[0] and "study.json" in err[0]
    assert (out / "study.json").read_text() == first  # nothing touched
    assert main([*STUDY, "--out", str(out), "--overwrite"]) == 0
    assert not (out / "hollow" / "70kmh" / "summary.json").exists()  # cleared
    assert (out / "notes.txt").read_text() == "mine"  # other files are kept
    rows = json.loads((out / "study.json").read_text())["rows"]
    assert [(r["structure"], r["speed_kmh"]) for r in rows] == [("solid", 40.0),
                                                                ("hollow", 40.0)]
    assert all(r["status"] == "normal termination" for r in rows)


def test_study_never_deletes_its_calibration_input(tmp_path, capsys):
    out = tmp_path / "st"
    out.mkdir()
    (out / "study.json").write_text('{"best_parameters": {}}')
    assert main([*STUDY, "--out", str(out), "--overwrite", "--hollow-from",
                 str(out / "study.json")]) == 2
    assert "has the name of an output" in capsys.readouterr().err
    assert (out / "study.json").read_text() == '{"best_parameters": {}}'


def test_bending_refuses_an_earlier_run_before_building_anything(tmp_path, capsys):
    out = tmp_path / "bd"
    (out / "solid").mkdir(parents=True)
    (out / "solid" / "summary.json").write_text("{}")
    (out / "solid" / "deck.k").write_text("*KEYWORD\n*END\n")
    assert main(["bending", "--out", str(out), "--structures", "solid"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"hollowbody bending: error: {out} holds the outputs of an earlier run "
                   "(solid/): use --overwrite to replace them, or another output folder")
    assert (out / "solid" / "deck.k").read_text() == "*KEYWORD\n*END\n"
    (out / "bending.csv").write_text("old")
    (out / "solid" / "summary.json").unlink()
    assert main(["bending", "--out", str(out), "--structures", "solid"]) == 2
    assert "(bending.csv)" in capsys.readouterr().err


def test_bending_overwrite_reruns_in_the_folder(tmp_path, capsys):
    out = tmp_path / "bd"
    args = ["bending", "--out", str(out), "--structures", "solid", "--end-time", "0.01"]
    assert main(args) == 0
    (out / "solid" / "d3dump01").write_bytes(b"stale")
    (out / "notes.txt").write_text("mine")
    assert main(args) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert main([*args, "--overwrite"]) == 0
    assert not (out / "solid" / "d3dump01").exists()
    assert (out / "notes.txt").read_text() == "mine"
    assert json.loads((out / "solid" / "summary.json").read_text())["status"] == \
        "normal termination"
    assert (out / "bending.csv").exists()
