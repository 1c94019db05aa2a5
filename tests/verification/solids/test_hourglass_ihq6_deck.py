"""*HOURGLASS IHQ=6 (and 7) in a deck: read, checked and run as the assumed-strain form.

hand_check.k's two solid cubes (MAT_ELASTIC, MAT_181) get an *HOURGLASS card with
IHQ 6 (7), QM 1 and an initial velocity in an hourglass pattern
(*INITIAL_VELOCITY_NODE, v_z = +-0.5 mm/ms by the xi-eta pattern of the nodes):
``check`` accepts it without an hourglass warning and the run uses it (no fallback
message in messages.log, hourglass energy accounted, energy balance kept); an IHQ
the solids do not have (9) still warns, naming the part and the form used instead.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from hollowbody.cli.main import main as cli_main

DECKS = Path(__file__).resolve().parents[2] / "regression" / "decks"


def deck_with_hourglass(tmp_path: Path, ihq: int) -> Path:
    text = (DECKS / "hand_check.k").read_text()
    for pid in (1, 2):  # PART card: pid secid mid eosid hgid
        old = f"         {pid}         1         {pid}\n"
        assert old in text
        text = text.replace(old, f"         {pid}         1         {pid}         0         1\n",
                            1)
    pattern = (1, -1, 1, -1, 1, -1, 1, -1)  # xi * eta at the nodes N1..N8
    lines = [f"{n:10d}{0.0:10.3f}{0.0:10.3f}{0.5 * h:10.3f}"
             for first in (1, 11) for n, h in zip(range(first, first + 8), pattern)]
    text = text.replace("*END", "*INITIAL_VELOCITY_NODE\n" + "\n".join(lines) + "\n*END")
    text = text.replace("*SECTION_SOLID", f"*HOURGLASS\n         1         {ihq}       1.0\n"
                        "*SECTION_SOLID", 1)
    path = tmp_path / f"ihq{ihq}.k"
    path.write_text(text)
    return path


@pytest.mark.parametrize("ihq", [6, 7])
def test_ihq6_deck_is_checked_and_run_without_fallback(ihq, tmp_path, capsys):
    path = deck_with_hourglass(tmp_path, ihq)
    code = cli_main(["check", str(path), "--json"])
    s = json.loads(capsys.readouterr().out)
    assert code == 0 and s["can_run"], s["problems"]
    assert not [w for w in s["warnings"] if "IHQ" in w]
    assert s["time_step"]["run_dt"] > 0.0
    out = tmp_path / "run"
    code = cli_main(["run", str(path), "--out", str(out), "--quiet", "--no-vtk",
                     "--end-time", "0.5"])
    assert code == 0
    assert "IHQ" not in (out / "messages.log").read_text()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "normal termination"
    assert summary["energy_ratio"] == pytest.approx(1.0, abs=0.02)
    e = summary["energies_J"]
    assert e["hourglass"] > 0.1 * (e["kinetic"] + e["internal"] + e["hourglass"])


def test_unavailable_ihq_warns_and_runs_as_ihq6(tmp_path, capsys):
    path = deck_with_hourglass(tmp_path, 9)
    code = cli_main(["check", str(path), "--json"])
    s = json.loads(capsys.readouterr().out)
    assert code == 0
    hg = [w for w in s["warnings"] if "IHQ=9" in w]
    assert len(hg) == 2 and all("IHQ=6" in w for w in hg)  # parts 1 and 2
