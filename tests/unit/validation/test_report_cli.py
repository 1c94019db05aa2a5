"""The segment tests' report and the ``validate`` command's input checks."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hollowbody.cli.main import main
from hollowbody.report.validation import efficiency, problems, write_report
from hollowbody.validation.cases import CASES, ORDER, end_time_of, speeds_of
from hollowbody.validation.ratings import rate_run
from hollowbody.validation.runner import RunRecord
from hollowbody.validation.signals import Signals


def _signals(peak: float) -> Signals:
    t = np.arange(-0.5, 60.0, 0.1)
    f = np.where((t > 0) & (t < 40), peak * np.sin(np.pi * t / 40.0), 0.0)
    d = np.clip(4.4 * t - 0.05 * t * t, 0.0, None)
    return Signals(t, f, f, d, None, 180.0)


def _records(tmp_path) -> list[RunRecord]:
    case = CASES["thorax"]
    solid = RunRecord("thorax", 4.4, "solid", tmp_path / "s", status="normal termination",
                      quality="ok", wall_seconds=200.0, cycles=40000, signals=_signals(2.2),
                      setup={"notes": ["standing, not seated as the subjects were"]})
    hollow = RunRecord("thorax", 4.4, "hollow", tmp_path / "h", status="error termination",
                       reason="element 1234 of part 56 inverted", quality="suspect",
                       quality_reasons=["energy ratio 1.4"],
                       where={"element": 1234, "part": 56, "time_ms": 31.2},
                       wall_seconds=100.0, cycles=9000, signals=_signals(2.0))
    for r, twin in ((solid, None), (hollow, solid.signals)):
        r.ratings = rate_run(case, 4.4, r.signals, twin)
        r.peak_force = float(r.signals.force.max())
        r.peak_time = 20.0
    return [solid, hollow]


def test_report_has_figure_tables_problems_and_efficiency(tmp_path):
    recs = _records(tmp_path)
    paths = write_report(recs, tmp_path / "out")
    md = paths["markdown"].read_text()
    assert (tmp_path / "out" / "thorax.png").stat().st_size > 10_000
    assert "![thorax](thorax.png)" in md and "Viano" in md
    assert "| 4.4 | solid | 2.20 | 20.0 |" in md
    assert "standing, not seated" in md
    # the failed run: why and where
    assert "thorax 4.4 m/s hollow: error termination at element 1234, part 56, time_ms 31.2" \
        in md and "inverted" in md
    assert "| thorax | 4.4 | 200 | 100 | 2.00 |" in md
    html = paths["html"].read_text()
    assert "<table>" in html and 'src="thorax.png"' in html
    data = json.loads(paths["json"].read_text())
    assert data[1]["where"]["element"] == 1234 and data[0]["ratings"][0]["cora"] > 0.0


def test_a_run_that_blew_up_does_not_flatten_the_figure(tmp_path):
    """A suspect run 1000 times the test force is drawn dashed, off scale: the axis
    keeps the test data and the trusted runs readable."""
    from hollowbody.report.validation import plot_case, y_limits

    recs = _records(tmp_path)
    recs[1].signals, recs[1].quality = _signals(-2000.0), "suspect"
    path = plot_case(recs, tmp_path / "fig.png")
    assert path.stat().st_size > 10_000
    assert y_limits([3.2, 2.2], [2000.0]) == pytest.approx((-0.48, 4.16))
    assert y_limits([3.2], [6.0]) is None  # within twice: the axis shows it
    assert y_limits([3.2], []) is None and y_limits([], [9.0]) is None


def test_problems_and_efficiency_skip_what_is_fine(tmp_path):
    recs = _records(tmp_path)
    assert len(problems(recs)) == 1
    recs[1].wall_seconds = None
    assert efficiency(recs)[-1].endswith("| - |")
    dry = RunRecord("pelvis", 5.2, "solid", tmp_path, status="not run (dry run)")
    assert problems([dry]) == [] and efficiency([dry]) == []


def test_cases_speeds_and_end_times():
    assert set(ORDER) == set(CASES)
    assert speeds_of(CASES["thorax"], None) == (4.4, 6.5, 9.5)
    assert speeds_of(CASES["thorax"], 5.0) == (5.0,)
    with pytest.raises(ValueError):
        speeds_of(CASES["thorax"], -1.0)
    # the test data of each Viano speed end within the simulated time
    assert end_time_of(CASES["pelvis"], 5.2) == 40.0
    assert end_time_of(CASES["thorax"], 6.0) == 50.0  # nearest test speed 6.5
    assert CASES["pelvis"].impactor_mass == 23.4 and CASES["shoulder"].impactor_mass == 23.0


@pytest.mark.parametrize("argv, message", [
    (["validate"], "give one or more cases"),
    (["validate", "knee"], "unknown case 'knee'"),
    (["validate", "thorax", "--speed", "-2"], "--speed must be positive"),
    (["validate", "thorax", "--model", "x.k"], "--model and --landmarks go together"),
    (["validate", "thorax", "pelvis", "--corridor", "c.csv"], "one case"),
    (["validate", "thorax", "--mesh", "5"], "--mesh must be between"),
])
def test_bad_input_exits_2_with_a_reason(argv, message, capsys):
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_list_and_refusal_of_an_earlier_report(tmp_path, capsys):
    assert main(["validate", "--list"]) == 0
    assert "Viano" not in capsys.readouterr().err
    (tmp_path / "report.md").write_text("earlier")
    assert main(["validate", "thorax", "--out", str(tmp_path), "--dry-run"]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert (tmp_path / "report.md").read_text() == "earlier"


def test_landmark_file_errors_name_the_file(tmp_path, capsys):
    model = tmp_path / "m.k"
    model.write_text("*KEYWORD\n*END\n")
    lm = tmp_path / "lm.json"
    lm.write_text('{"thorax": {"point": [0, 0,\n 0}')
    assert main(["validate", "thorax", "--model", str(model), "--landmarks", str(lm),
                 "--out", str(tmp_path / "o")]) == 2
    assert f"{lm}:2: not valid JSON" in capsys.readouterr().err
    lm.write_text('{"pelvis": {}}')
    assert main(["validate", "thorax", "--model", str(model), "--landmarks", str(lm),
                 "--out", str(tmp_path / "o")]) == 2
    assert "no entry for case 'thorax'" in capsys.readouterr().err


def test_validate_runs_a_case_end_to_end(tmp_path, capsys):
    """The command on the coarsest pedestrian, 2.5 ms of the thorax impact: the set-up is
    written, run, read, rated and reported; then ``--report`` reads the same run again.
    2.5 ms is past first contact (0.45 ms) so the hub force is rising (> 0.1 kN); the run
    must end normally with the energy balanced within 2 % (a short run has no reason to
    lose or gain energy: the contact's damping and the tissue take a few joules)."""
    out = tmp_path / "val"
    code = main(["validate", "thorax", "--speed", "4.4", "--tissue", "solid", "--mesh", "50",
                 "--end-time", "2.5", "--out", str(out)])
    printed = capsys.readouterr().out
    run = out / "thorax" / "4.4ms" / "solid"
    summary = json.loads((run / "summary.json").read_text())
    assert summary["status"] == "normal termination"
    assert abs(summary["energy_ratio"] - 1.0) < 0.02
    assert code == (0 if summary["quality"] == "ok" else 1)
    data = json.loads((out / "report.json").read_text())
    assert data[0]["peak_force"] > 0.1 and data[0]["setup"]["impactor_mass"] == 23.4
    assert "thorax 4.4 m/s solid: normal termination" in printed
    md = (out / "report.md").read_text()
    assert "![thorax](thorax.png)" in md and (out / "thorax.png").is_file()
    # the same runs rated again, nothing run
    assert main(["validate", "--report", "--out", str(out)]) == code
    again = json.loads((out / "report.json").read_text())
    assert again[0]["peak_force"] == data[0]["peak_force"]
    # an earlier report is kept unless --overwrite
    assert main(["validate", "thorax", "--dry-run", "--out", str(out)]) == 2
