"""The command line: --version, plain-text help stating every default, consistent
boolean flags (old spellings kept), a closed output pipe ends quietly."""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import hollowbody
from hollowbody.cli.main import build_parser, main
from hollowbody.cli.text import plain

SRC = Path(__file__).resolve().parents[3] / "src"
MARKUP = re.compile(r"``|:(?:class|func|meth|mod|data|attr|exc|ref):`|::\s*$", re.MULTILINE)


def subparsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


def test_version(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--version"])
    assert exc.value.code == 0
    assert capsys.readouterr().out.strip() == f"hollowbody {hollowbody.__version__}"


def test_plain_removes_rest_markup():
    doc = ("``hollowbody rate``: see :func:`~hollowbody.curves.cfc.cfc_filter` and "
           ":class:`hollowbody.rating.corridors.Corridor`.\n\nExample::\n\n    x\n")
    text = plain(doc)
    assert not MARKUP.search(text)
    assert text.startswith("hollowbody rate: see cfc_filter and "
                           "hollowbody.rating.corridors.Corridor.")
    assert "Example:\n" in text


def test_every_subcommand_is_registered():
    assert set(subparsers()) >= {"check", "run", "block", "hollowize", "bending",
                                 "calibrate", "study", "demo", "rate"}


@pytest.mark.parametrize("name", sorted(subparsers()))
def test_help_is_plain_text_and_states_every_default(name):
    p = subparsers()[name]
    text = p.format_help()
    assert not MARKUP.search(text), MARKUP.search(text).group(0)
    assert "DESIGN.md" not in text
    for action in p._actions:
        if isinstance(action, argparse._HelpAction) or not action.option_strings:
            continue
        flag = action.option_strings[-1]
        assert action.help, f"{name} {flag}: no help"
        assert action.required or "default" in action.help.lower(), (
            f"{name} {flag}: the help does not state the default")


@pytest.mark.parametrize(("name", "argv", "dest", "default"), [
    ("block", [], "vtk", True), ("bending", [], "vtk", False), ("study", [], "vtk", False),
    ("bending", [], "erode", True), ("block", [], "mass_preserving", True),
    ("hollowize", [], "self_contact", True), ("bending", [], "self_contact", False),
])
def test_boolean_flags_take_both_spellings(name, argv, dest, default):
    p = subparsers()[name]
    required = {"study": ["--tissue", "muscle", "--out", "x"],
                "hollowize": ["deck.k", "--out", "new.k"]}.get(name, [])
    flag = "--" + dest.replace("_", "-")
    assert getattr(p.parse_args(required), dest) is default
    assert getattr(p.parse_args([*required, flag]), dest) is True
    assert getattr(p.parse_args([*required, "--no-" + flag[2:]]), dest) is False


@pytest.fixture
def curves(tmp_path):
    t = np.arange(0.0, 60.0 + 1e-9, 0.5)
    for name, amp in (("ref.csv", 3.0), ("cand.csv", 3.3)):
        rows = "\n".join(f"{a:.6g},{amp * np.sin(np.pi * a / 60.0) ** 2:.6g}" for a in t)
        (tmp_path / name).write_text("time,force\n" + rows + "\n", encoding="utf-8")
    return tmp_path


def _env():
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), env.get("PYTHONPATH", "")])
    env["NUMBA_NUM_THREADS"] = "1"
    return env


def test_rate_json_into_head_ends_quietly(curves):
    """``hollowbody rate ... --json | head -c 10``: exit code 0 and no traceback."""
    cmd = (f"set -o pipefail; '{sys.executable}' -m hollowbody.cli.main rate ref.csv "
           f"cand.csv --json | head -c 10")
    res = subprocess.run(["bash", "-c", cmd], cwd=curves, env=_env(), capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    assert res.stdout == '{\n  "refer'
    assert "Traceback" not in res.stderr and "BrokenPipe" not in res.stderr


def test_output_closed_before_the_first_write_ends_quietly(curves):
    """The reader is gone before the command prints anything (the write itself fails)."""
    proc = subprocess.Popen([sys.executable, "-m", "hollowbody.cli.main", "rate", "ref.csv",
                             "cand.csv", "--json"], cwd=curves, env=_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 0, err
    assert err == ""
