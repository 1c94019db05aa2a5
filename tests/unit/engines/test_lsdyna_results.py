"""Reading LS-DYNA's results: termination (d3hsp, messag), glstat / rcforc / nodout
(ASCII and binout) into hollowbody's CSV files and summary.json.

No LS-DYNA output file is shipped: the listings and databases below are
SYNTHETIC, written in the layout LS-DYNA's ASCII files and binout use (see
hollowbody.engines.lsdyna_ascii); they test the parsers, not the engine. The
binout is written with lasso-python's own LSDA writer in the folder layout
LS-DYNA uses (/glstat/d000001/time, ...).
"""

# The synthetic listings keep the engines' line widths (over 100 characters).
# ruff: noqa: E501

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from hollowbody.engines.lsdyna_ascii import (
    GLSTAT_ORDER,
    parse_glstat,
    parse_nodout,
    parse_rcforc,
    read_ascii,
)
from hollowbody.engines.lsdyna_status import ERROR, NORMAL, UNKNOWN, parse_listing, read_termination
from hollowbody.engines.results import write_histories, write_summary
from hollowbody.io.results.history import read_history
from hollowbody.solver.outputs import GLSTAT_COLUMNS, NODOUT_COLUMNS, RCFORC_COLUMNS

BANNER = """\
     ___________________________________________________
     |                                                 |
     |  LS-DYNA, A Program for Nonlinear Dynamic       |
     |  Analysis of Structures in Three Dimensions     |
     |  Date    : 12/02/2026    Time: 05:20:00         |
     |  Version : smp d R13.1.1                        |
     |  Revision: 123456                               |
     |_________________________________________________|
"""

D3HSP_ERROR = BANNER + """
      1 t 0.0000E+00 dt 1.00E-04 flush i/o buffers          12/02/26 05:20:01
 *** Error 40509 (SOL+509)
     negative volume in solid element #      1234 part #        2
     cycle       4567   time  1.2345E+00

 E r r o r   t e r m i n a t i o n                     12/02/26 05:21:00

 Problem time       =    1.2345E+00
 Problem cycle      =      4567
"""

D3HSP_NORMAL = BANNER + """
 N o r m a l    t e r m i n a t i o n                   12/02/26 05:21:00

 Problem time       =    1.0000E+01
 Problem cycle      =     10234
"""


def test_termination_normal_and_version():
    t = parse_listing(D3HSP_NORMAL)
    assert (t.status, t.reason) == (NORMAL, "normal termination")
    assert t.end_time_ms == pytest.approx(10.0) and t.cycles == 10234
    assert t.version == "smp d R13.1.1"
    assert t.where == {}


def test_termination_negative_volume_element_part_cycle_time():
    t = parse_listing(D3HSP_ERROR)
    assert t.status == ERROR
    assert t.where == {"element": 1234, "part": 2, "cycle": 4567, "time_ms": 1.2345}
    assert t.reason == "negative volume in solid element 1234 of part 2 at t=1.2345 ms"
    assert t.end_time_ms == pytest.approx(1.2345) and t.cycles == 4567


def test_termination_from_messag_when_d3hsp_lacks_it(tmp_path):
    assert read_termination(tmp_path).status == UNKNOWN
    (tmp_path / "d3hsp").write_text(BANNER + "\n E r r o r   t e r m i n a t i o n\n")
    (tmp_path / "messag").write_text(
        " *** Error 40509 (SOL+509)\n     negative volume in solid element #  77\n")
    t = read_termination(tmp_path)
    assert t.status == ERROR and t.where == {"element": 77}
    assert "solid element 77" in t.reason and t.version == "smp d R13.1.1"
    # MPP: one message file per rank; the element named on another line wording
    (tmp_path / "messag").unlink()
    (tmp_path / "mes0000").write_text(" E r r o r   t e r m i n a t i o n\n")
    (tmp_path / "mes0003").write_text(" solid element     4321 in part   7 has negative volume\n")
    t = read_termination(tmp_path)
    assert t.status == ERROR and t.where == {"element": 4321, "part": 7}


GLSTAT = """\
 dt of cycle       0 is controlled by solid          12 of part        1

 time...........................   0.00000E+00
 time step......................   1.00000E-04
 kinetic energy.................   1.25000E+01
 internal energy................   0.00000E+00
 spring and damper energy.......   0.00000E+00
 hourglass energy ..............   0.00000E+00
 system damping energy..........   0.00000E+00
 sliding interface energy.......   0.00000E+00
 external work..................   0.00000E+00
 eroded kinetic energy..........   0.00000E+00
 total energy...................   1.25000E+01
 total energy / initial energy..   1.00000E+00
 energy ratio w/o eroded energy.   1.00000E+00
 global x velocity..............   0.00000E+00
 time per zone cycle.(nanosec)..         123
 added mass.....................   0.00000E+00
 percentage increase............   0.00000E+00

 dt of cycle     100 is controlled by solid          12 of part        1

 time...........................   1.00000E-02
 time step......................   9.90000E-05
 kinetic energy.................   1.20000E+01
 internal energy................   4.90000E-01
 hourglass energy ..............   1.00000E-02
 sliding interface energy.......   2.00000E-03
 external work..................   1.00000E-03
 total energy...................   1.25020E+01
 total energy / initial energy..   1.00008E+00
 added mass.....................   1.50000E-06
"""

RCFORC = """\
 r e s u l t a n t   i n t e r f a c e   f o r c e s
  master       1 time  1.00000E-02  x force  1.00000E-01  y force -2.00000E-01  z force  3.00000E+00  mass  0.00000E+00
   slave       1 time  1.00000E-02  x force -1.00000E-01  y force  2.00000E-01  z force -3.00000E+00  mass  0.00000E+00
  master       1 time  2.00000E-02  x force  2.00000E-01  y force  0.00000E+00  z force  4.00000E+00  mass  0.00000E+00
   slave       1 time  2.00000E-02  x force -2.00000E-01  y force  0.00000E+00  z force -4.00000E+00  mass  0.00000E+00
"""

NODOUT = """\
 n o d a l   p r i n t   o u t   f o r   t i m e  s t e p       100                              ( at time 1.0000000E-02 )

 nodal point  x-disp     y-disp      z-disp      x-vel       y-vel       z-vel      x-accl      y-accl      z-accl      x-coor      y-coor      z-coor
       5  1.0000E-01 0.0000E+00-2.0000E-01 1.0000E+01 0.0000E+00-1.1100E+01 0.0000E+00 0.0000E+00 0.0000E+00 1.0000E+00 0.0000E+00 2.0000E+00
      17  0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00 0.0000E+00

 nodal point  x-rot      y-rot       z-rot       x-rot vel   y-rot vel   z-rot vel   x-rot acc   y-rot acc   z-rot acc
       5  9.0000E+00 9.0000E+00 9.0000E+00 9.0000E+00 9.0000E+00 9.0000E+00 9.0000E+00 9.0000E+00 9.0000E+00
"""


def test_glstat_rows():
    rows = parse_glstat(GLSTAT)
    assert len(rows) == 2
    r = dict(zip(GLSTAT_ORDER, rows[1]))
    assert r["time [ms]"] == 1e-2 and r["cycle"] == 100 and r["dt [ms]"] == 9.9e-5
    assert (r["kinetic [J]"], r["internal [J]"], r["hourglass [J]"]) == (12.0, 0.49, 0.01)
    assert (r["contact [J]"], r["external_work [J]"], r["total [J]"]) == (2e-3, 1e-3, 12.502)
    assert r["energy_ratio"] == 1.00008 and r["added_mass [kg]"] == 1.5e-6
    assert dict(zip(GLSTAT_ORDER, rows[0]))["cycle"] == 0
    assert GLSTAT_ORDER == GLSTAT_COLUMNS  # the columns hollowbody's own runs write


RCFORC_SHORT = """\
  master          2 time 1.00000E-02  x  5.00000E-01  y  0.00000E+00  z -1.00000E+00 mass  0.00000E+00
  slave           2 time 1.00000E-02  x -5.00000E-01  y  0.00000E+00  z  1.00000E+00 mass  0.00000E+00
"""


def test_rcforc_rows_pair_slave_and_master():
    rows = parse_rcforc(RCFORC)
    assert rows == [[1e-2, 1, -0.1, 0.2, -3.0, 0.1, -0.2, 3.0],
                    [2e-2, 1, -0.2, 0.0, -4.0, 0.2, 0.0, 4.0]]
    # the layout without the word "force" after x, y, z
    assert parse_rcforc(RCFORC_SHORT) == [[1e-2, 2, -0.5, 0.0, 1.0, 0.5, 0.0, -1.0]]


def test_nodout_rows_translational_table_only_with_touching_columns():
    rows = parse_nodout(NODOUT)
    assert rows == [[1e-2, 5, 0.1, 0.0, -0.2, 10.0, 0.0, -11.1],
                    [1e-2, 17, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]


def test_histories_and_summary_written_with_hollowbodys_columns(tmp_path):
    for name, text in (("glstat", GLSTAT), ("rcforc", RCFORC), ("nodout", NODOUT)):
        (tmp_path / name).write_text(text)
    rows = read_ascii(tmp_path)
    files = write_histories(tmp_path, rows)
    assert sorted(f.name for f in files) == ["glstat.csv", "nodout.csv", "rcforc.csv"]
    for name, cols in (("glstat", GLSTAT_COLUMNS), ("rcforc", RCFORC_COLUMNS),
                       ("nodout", NODOUT_COLUMNS)):
        h = read_history(tmp_path / f"{name}.csv")
        assert tuple(h) == cols
    g = read_history(tmp_path / "glstat.csv")
    np.testing.assert_array_equal(g["cycle"], [0, 100])
    n = read_history(tmp_path / "nodout.csv")
    np.testing.assert_array_equal(n["node"], [5, 17])
    s = write_summary(tmp_path, engine="lsdyna", version="smp d R13.1.1", status=NORMAL,
                      reason="normal termination", where={}, end_time_ms=0.01,
                      requested_end_time_ms=0.01, cycles=100, wall_seconds=1.0,
                      glstat=rows["glstat"], commands=[["lsdyna", "i=deck.k"]], notes=[])
    on_disk = json.loads((tmp_path / "summary.json").read_text())
    assert on_disk == s
    assert s["engine"] == "lsdyna" and s["engine_version"] == "smp d R13.1.1"
    assert s["energy_ratio"] == 1.00008 and s["energies_J"]["internal"] == 0.49


def _glstat_row(t, ratio, internal=10.0):
    # time, cycle, dt, kinetic, internal, hourglass, contact, external work, total,
    # energy ratio, added mass
    return [t, 10.0 * t, 1.0e-3, 90.0, internal, 0.5, 0.1, 0.0, 100.0 * ratio, ratio, 0.0]


@pytest.mark.parametrize(("status", "last_ratio", "kept"), [
    (ERROR, 4.9e26, True),          # the collapse in the last interval
    (ERROR, math.nan, True),        # not finite
    (ERROR, 1.3, False),            # drifting out of balance: graded as it ends
    (NORMAL, 4.9e26, False),        # a normal termination is graded as it ends
])
def test_an_engine_collapse_is_graded_on_the_record_before_it(tmp_path, status, last_ratio,
                                                             kept):
    """An external engine's error termination whose last energy record is blown up (an
    element collapsing in the last output interval) keeps the balanced record before it
    as energies_before_error_J, with its time, as a hollowbody run does; the verdict is
    graded on it and names the failing cycle. A drift or a normal end is not excused."""
    from hollowbody.solver.verdict import SUSPECT, WARNING, verdict_of

    glstat = [_glstat_row(0.0, 1.0), _glstat_row(1.0, 1.0001),
              _glstat_row(2.0, last_ratio, internal=1.0e30)]
    s = write_summary(tmp_path, engine="openradioss", version="x", status=status,
                      reason="r", where={}, end_time_ms=2.0, requested_end_time_ms=5.0,
                      cycles=20, wall_seconds=1.0, glstat=glstat, commands=[], notes=[])
    assert json.loads((tmp_path / "summary.json").read_text()) == json.loads(
        json.dumps(s))
    quality, reasons = verdict_of(s)
    if kept:
        before = s["energies_before_error_J"]
        assert before["time_ms"] == 1.0 and before["energy_ratio"] == 1.0001
        assert before["internal"] == 10.0
        assert quality == WARNING
        assert [r["indicator"] for r in reasons] == ["failing_cycle"]
    else:
        assert "energies_before_error_J" not in s
        assert quality == SUSPECT


def test_a_row_of_the_wrong_width_is_refused(tmp_path):
    with pytest.raises(ValueError, match="columns"):
        write_histories(tmp_path, {"glstat": [[0.0, 1.0]]})


def _write_binout(path):
    lsda = pytest.importorskip("lasso.dyna.lsda_py3")
    Lsda = lsda.Lsda
    f = Lsda(str(path), "w")
    times = [0.0, 0.5, 1.0]
    for k, t in enumerate(times):
        f.cd(f"/glstat/d{k + 1:06d}")
        f.write("time", Lsda.R8, [t])
        f.write("cycle", Lsda.I4, [10 * k])
        f.write("kinetic_energy", Lsda.R8, [12.5 - t])
        f.write("internal_energy", Lsda.R8, [t])
        f.write("total_energy", Lsda.R8, [12.5])
        f.write("energy_ratio", Lsda.R8, [1.0])
    f.cd("/nodout/metadata")
    f.write("ids", Lsda.I4, [5, 17])
    f.cd("/rcforc/metadata")
    f.write("ids", Lsda.I4, [1, 1])
    f.write("side", Lsda.I4, [0, 1])
    for k, t in enumerate(times[:2]):
        f.cd(f"/nodout/d{k + 1:06d}")
        f.write("time", Lsda.R8, [t])
        for a in "xyz":
            f.write(f"{a}_displacement", Lsda.R8, [t, 2 * t])
            f.write(f"{a}_velocity", Lsda.R8, [-t, 0.0])
        f.cd(f"/rcforc/d{k + 1:06d}")
        f.write("time", Lsda.R8, [t])
        for a in "xyz":
            f.write(f"{a}_force", Lsda.R8, [-t, t])
    f.close()


def test_binout_rows(tmp_path):
    pytest.importorskip("lasso.dyna")
    from hollowbody.engines.lsdyna_binout import read_binout

    _write_binout(tmp_path / "binout0000")
    rows = read_binout(tmp_path)
    g = [dict(zip(GLSTAT_ORDER, r)) for r in rows["glstat"]]
    assert [r["time [ms]"] for r in g] == [0.0, 0.5, 1.0]
    assert [r["cycle"] for r in g] == [0, 10, 20]
    assert g[2]["kinetic [J]"] == 11.5 and g[2]["internal [J]"] == 1.0
    assert math.isnan(g[2]["hourglass [J]"])  # not in this binout
    assert rows["nodout"] == [[0.0, 5, 0.0, 0.0, 0.0, -0.0, -0.0, -0.0],
                              [0.0, 17, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
                              [0.5, 5, 0.5, 0.5, 0.5, -0.5, -0.5, -0.5],
                              [0.5, 17, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0]]
    assert rows["rcforc"][1] == [0.5, 1, -0.5, -0.5, -0.5, 0.5, 0.5, 0.5]
    assert read_binout(tmp_path / "empty") == {}


def test_a_finished_lsdyna_run_folder_becomes_hollowbodys_files(tmp_path):
    """The runner's last step on a folder as LS-DYNA leaves it (synthetic files)."""
    from pathlib import Path

    from hollowbody.engines.commands import Command, RunPlan
    from hollowbody.engines.runner import Prepared, _collect_lsdyna

    (tmp_path / "d3hsp").write_text(D3HSP_ERROR)
    (tmp_path / "glstat").write_text(GLSTAT)
    cmd = Command("lsdyna", "/opt/lsdyna", ("i=deck.k",), tmp_path)
    prep = Prepared(RunPlan("lsdyna", Path(tmp_path / "deck.k"), tmp_path, (cmd,)),
                    end_time_ms=10.0)
    s = _collect_lsdyna(prep, 3.5, {"lsdyna": 1}, [cmd.argv()])
    assert s["status"] == ERROR and s["error_element"] == 1234 and s["error_part"] == 2
    assert s["end_time_ms"] == 1.2345 and s["requested_end_time_ms"] == 10.0
    assert s["cycles"] == 4567 and s["wall_seconds"] == 3.5
    assert s["engine_version"] == "smp d R13.1.1" and s["commands"] == [["/opt/lsdyna",
                                                                          "i=deck.k"]]
    assert (tmp_path / "glstat.csv").is_file() and not (tmp_path / "nodout.csv").exists()
    # no listing at all and a failed process: an error termination that says so
    for f in ("d3hsp", "glstat", "glstat.csv"):
        (tmp_path / f).unlink()
    s = _collect_lsdyna(prep, 0.1, {"lsdyna": 9}, [])
    assert s["status"] == ERROR and s["reason"] == "LS-DYNA stopped (exit code 9)"
