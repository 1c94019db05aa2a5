"""Restart files: a resumed run continues the uninterrupted one.

On one numba thread the arithmetic of a resumed run is the same as that of the
uninterrupted run (the State holds every array that carries information from
one cycle to the next, saved and restored exactly), so the histories must be
equal to the last printed digit: the tests compare the CSV files as text.
Dumps that do not belong to the deck, truncated or damaged dumps and dumps of
another version are refused (exit 2) without touching the run folder.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest
from solver_decks import crushed_column, cube_and_plate

from hollowbody.api import run_model
from hollowbody.build import build_model
from hollowbody.cli.main import main as cli_main
from hollowbody.io.keyword.writer import write_deck
from hollowbody.solver import explicit
from hollowbody.solver.restart import RestartError, dump_files, read_dump

HISTORIES = ("glstat.csv", "rcforc.csv", "nodout.csv", "spcforc.csv", "matsum.csv",
             "rbdout.csv")


pytestmark = pytest.mark.usefixtures("one_thread")


def _deck(**kw):
    return cube_and_plate(e=0.1, speed=3.0, end=1.5, friction=0.2, **kw)


def _run(deck, out, **kw):
    return run_model(build_model(deck), out, vtk=False, **kw)


def _same_histories(a: Path, b: Path) -> None:
    for name in HISTORIES:
        ta, tb = (a / name).read_text(), (b / name).read_text()
        assert ta == tb, f"{name} differs"


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("uninterrupted")
    res = run_model(build_model(_deck()), out, vtk=False)
    assert res.status == "normal termination" and res.cycles > 100
    return out, res


def _interrupt_at(monkeypatch, cycle: int) -> None:
    """Deliver SIGINT (as Ctrl-C does) while cycle ``cycle`` runs."""
    original = explicit.step

    def step(model, plan, state, dt):
        original(model, plan, state, dt)
        if state.cycle == cycle:
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(explicit, "step", step)


def test_ctrl_c_writes_a_dump_and_the_resumed_run_equals_the_uninterrupted(
        tmp_path, monkeypatch, reference):
    ref_out, ref = reference
    _interrupt_at(monkeypatch, 57)
    res = _run(_deck(), tmp_path)
    assert res.status == "user interrupt" and res.cycles == 57
    assert [p.name for p in dump_files(tmp_path)] == ["d3dump01"]
    monkeypatch.undo()
    res2 = _run(_deck(), tmp_path, restart="newest")
    assert res2.status == "normal termination"
    assert res2.cycles == ref.cycles
    _same_histories(ref_out, tmp_path)
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["resumed_from"] == {"file": "d3dump01", "time_ms": pytest.approx(res.end_time_ms),
                                 "cycle": 57}
    assert "resumed from restart file d3dump01" in (tmp_path / "messages.log").read_text()


def test_periodic_dumps_and_resume_from_a_chosen_one(tmp_path, reference):
    ref_out, ref = reference
    res = _run(_deck(), tmp_path, dump_cycles=40)
    files = dump_files(tmp_path)
    assert len(files) == (ref.cycles - 1) // 40
    assert res.summary["restart_files"][1]["cycle"] == 80
    # resume from the second dump: everything after cycle 80 is computed again
    res2 = _run(_deck(), tmp_path, restart=files[1], dump_cycles=0)
    assert res2.cycles == ref.cycles
    _same_histories(ref_out, tmp_path)


_KILLER = textwrap.dedent("""
    import os, signal, sys
    sys.path.insert(0, {tests!r})
    import numba
    numba.set_num_threads(1)
    from solver_decks import cube_and_plate
    from hollowbody.api import run_model
    from hollowbody.build import build_model
    from hollowbody.solver import explicit
    original = explicit.step
    def step(model, plan, state, dt):
        original(model, plan, state, dt)
        if state.cycle == {kill}:
            os.kill(os.getpid(), signal.SIGKILL)
    explicit.step = step
    deck = cube_and_plate(e=0.1, speed=3.0, end=1.5, friction=0.2)
    run_model(build_model(deck), {out!r}, vtk=False, dump_cycles={every})
""")


def test_resume_after_sigkill_between_dumps(tmp_path, reference):
    ref_out, ref = reference
    script = _KILLER.format(tests=str(Path(__file__).parent), kill=95, out=str(tmp_path),
                            every=30)
    env = dict(os.environ, NUMBA_NUM_THREADS="1")
    proc = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                          timeout=600)
    assert proc.returncode == -signal.SIGKILL, proc.stderr.decode()[-2000:]
    assert [p.name for p in dump_files(tmp_path)] == ["d3dump01", "d3dump02", "d3dump03"]
    # rows up to cycle 95 were written after the last dump (cycle 90): they are cut
    res = _run(_deck(), tmp_path, restart="newest")
    assert res.status == "normal termination" and res.cycles == ref.cycles
    _same_histories(ref_out, tmp_path)


def test_error_termination_writes_a_dump_that_resumes(tmp_path):
    deck = crushed_column(crush=30.0, end=1.0, dtmin=0.5)
    res = _run(deck, tmp_path)
    assert res.status == "error termination" and "DTMIN" in res.reason
    files = dump_files(tmp_path)
    assert len(files) == 1
    header, _ = read_dump(files[0], build_model(deck))
    assert header["cycle"] == res.cycles
    # resumed with erosion on, the run goes past the element that ended it
    res2 = _run(deck, tmp_path, restart="newest", erode=True)
    assert res2.end_time_ms > res.end_time_ms


def _one_dump(tmp_path: Path) -> Path:
    _run(_deck(), tmp_path, dump_cycles=10, end_time=0.3)
    return dump_files(tmp_path)[-1]  # the newest: the one --restart takes


def _cli(argv: list[str], capsys) -> tuple[int, str]:
    code = cli_main(argv)
    cap = capsys.readouterr()
    return code, cap.out + cap.err


@pytest.mark.parametrize("damage", ["foreign", "truncated", "version", "garbage"])
def test_unusable_dumps_are_refused_without_touching_the_run(tmp_path, capsys, damage):
    dump = _one_dump(tmp_path)
    deck_file = tmp_path / "deck.k"
    write_deck(_deck(n=3 if damage == "foreign" else 4), deck_file)
    data = dump.read_bytes()
    if damage == "truncated":
        dump.write_bytes(data[: len(data) * 2 // 3])
    elif damage == "version":
        dump.write_bytes(data.replace(b'"version": "', b'"version": "0.0.0-', 1))
    elif damage == "garbage":
        dump.write_bytes(b"not a restart file\n" + data[:100])
    before = {p.name: p.read_bytes() for p in tmp_path.iterdir() if p.is_file()}
    code, text = _cli(["run", str(deck_file), "--out", str(tmp_path), "--restart", "--quiet",
                       "--no-vtk"], capsys)
    assert code == 2
    expected = {"foreign": "belongs to another model", "truncated": "truncated or damaged",
                "version": "written by hollowbody 0.0.0-", "garbage": "not a hollowbody"}
    assert expected[damage] in text and dump.name in text
    assert "Traceback" not in text
    after = {p.name: p.read_bytes() for p in tmp_path.iterdir() if p.is_file()}
    assert after == before


def test_restart_without_any_dump_is_refused(tmp_path, capsys):
    deck_file = tmp_path / "deck.k"
    write_deck(_deck(), deck_file)
    code, text = _cli(["run", str(deck_file), "--out", str(tmp_path / "run"), "--restart"],
                      capsys)
    assert code == 2 and "no restart file" in text
    assert not (tmp_path / "run").exists()


def test_read_dump_checks_the_model(tmp_path):
    dump = _one_dump(tmp_path)
    with pytest.raises(RestartError, match="another model"):
        read_dump(dump, build_model(cube_and_plate(n=3)))


def test_a_dump_of_the_previous_format_resumes_and_re_sorts(tmp_path, monkeypatch, reference):
    """A format 2 dump (contact lists cut for the older, Euclidean re-sort bound) is
    read; its contacts rebuild their lists in the first cycle after the resume, and
    the run still ends as the uninterrupted one (the lists only have to be
    complete)."""
    from hollowbody.contact.runtime import ContactRuntime

    ref_out, ref = reference
    _interrupt_at(monkeypatch, 57)
    _run(_deck(), tmp_path)
    monkeypatch.undo()
    dump = dump_files(tmp_path)[0]
    data = dump.read_bytes()
    assert b'"format": 3' in data
    dump.write_bytes(data.replace(b'"format": 3', b'"format": 2', 1))
    sorts = []
    original = ContactRuntime._sort

    def counting_sort(self, dt, cycle):
        sorts.append(cycle)
        original(self, dt, cycle)

    monkeypatch.setattr(ContactRuntime, "_sort", counting_sort)
    res = _run(_deck(), tmp_path, restart="newest")
    assert res.status == "normal termination" and res.cycles == ref.cycles
    assert sorts and sorts[0] == 58  # at once, not at the next interval or bound
    _same_histories(ref_out, tmp_path)


@pytest.mark.parametrize("structure", ["solid", "hollow"])
def test_block_resumed_after_ctrl_c_continues_bit_for_bit(structure, tmp_path, monkeypatch):
    """The paper's block (hexahedra with MAT_181, or shell walls with MAT_024, self-contact
    and the rigid impactor) stopped and resumed: histories equal to the last digit."""
    from hollowbody.scenarios.block import BlockConfig, build_block_deck

    deck = build_block_deck(BlockConfig(tissue="muscle", structure=structure, speed_kmh=40,
                                        mesh=15.0 if structure == "solid" else 7.5))
    end = 1.5
    ref = _run(deck, tmp_path / "ref", end_time=end)
    assert ref.status == "normal termination"
    _interrupt_at(monkeypatch, ref.cycles // 2)
    res = _run(deck, tmp_path / "cut", end_time=end)
    assert res.status == "user interrupt"
    monkeypatch.undo()
    res2 = _run(deck, tmp_path / "cut", end_time=end, restart="newest")
    assert res2.cycles == ref.cycles
    _same_histories(tmp_path / "ref", tmp_path / "cut")


def test_a_dump_without_the_step_control_resumes(tmp_path, monkeypatch, reference):
    """A dump written before the step control (no ``dt_stable`` / ``dt_control`` in the
    State) is read: the control starts over from the stable step at the resume (here
    above the step it held: the steps differ from there on) and the run ends normally
    at the end time, its energy as balanced as the uninterrupted run's."""
    from hollowbody.solver.restart import write_dump

    ref_out, ref = reference
    _interrupt_at(monkeypatch, 57)
    _run(_deck(), tmp_path)
    monkeypatch.undo()
    dump = dump_files(tmp_path)[0]
    model = build_model(_deck())
    header, payload = read_dump(dump, model)
    own = payload["state"]["state"]
    assert own.pop("dt_stable") > 0.0 and own.pop("dt_control")[0] > 0.0
    write_dump(dump, model, payload, header["time_ms"], header["cycle"])
    res = _run(_deck(), tmp_path, restart="newest")
    assert res.status == "normal termination"
    assert abs(res.cycles - ref.cycles) <= 0.05 * ref.cycles
    a = json.loads((tmp_path / "summary.json").read_text())
    b = json.loads((ref_out / "summary.json").read_text())
    assert a["end_time_ms"] == pytest.approx(b["end_time_ms"], rel=1e-12)
    assert abs(a["energy_ratio"] - b["energy_ratio"]) < 1e-3
