"""What a generated pedestrian did while standing under gravity: the settling report.

Reads a run of a deck written by ``hollowbody pedestrian`` (its ``report.json``
beside the deck, the run's ``summary.json``, ``glstat.csv``, ``nodout.csv``,
``rbdout.csv`` and ``rwforc.csv``) and returns the figures a user checks before
trusting the model in an impact: does the run end normally with a closed energy
balance, do the feet stay on the floor, how far do the head and the trunk sink,
has the body come to rest. Units: mm, ms, kN, J.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from hollowbody.body.deck import GRAVITY
from hollowbody.io.results.history import read_history

LANDMARKS = ("head_cg", "T1", "T8", "sacrum", "knee_l", "knee_r")


def _by_id(cols: dict[str, np.ndarray], key: str, ident: int) -> dict[str, np.ndarray]:
    """The rows of one node (``key`` "node") or part (``key`` "part")."""
    mask = cols[key].astype(int) == ident
    return {name: v[mask] for name, v in cols.items()}


def foot_parts(deck: Path) -> dict[str, int]:
    """Part ids of the feet, from the region decks' part titles (``foot_l``, ``foot_r``)."""
    from hollowbody.io.keyword import Part, PartInertia, read_deck

    d = read_deck(deck)
    parts = d.of_type(PartInertia) + d.of_type(Part)
    return {p.title: p.pid for p in parts if p.title.startswith("foot_")}


def settling_summary(model_dir: Path, run_dir: Path) -> dict:
    """The settling figures of one run (``run_dir``) of the model in ``model_dir``.

    Returns a JSON-able dict: the run's status, quality and energy ratio (final and
    largest deviation from 1 over the run), cycles, first and smallest step (ms) and
    wall time (s); per landmark (head centre of gravity, T1, T8, sacrum, knees) the
    vertical displacement at the end and the lowest (mm, negative down) and the
    horizontal displacement at the end (mm); per foot its rigid body's largest
    vertical and horizontal displacement (mm); the floor's normal force at the end
    against the body weight (kN); the kinetic energy at the end and its largest (J);
    hourglass energy over internal energy at the end.
    """
    model_dir, run_dir = Path(model_dir), Path(run_dir)
    report = json.loads((model_dir / "report.json").read_text())
    summary = json.loads((run_dir / "summary.json").read_text())
    gl = read_history(run_dir / "glstat.csv")
    nod = read_history(run_dir / "nodout.csv")
    rbd = read_history(run_dir / "rbdout.csv")
    wall = read_history(run_dir / "rwforc.csv")
    hist = report["history_nodes"]
    out: dict = {
        "model": report["options"],
        "elements": report["elements"],
        "status": summary["status"],
        "reason": summary["reason"],
        "quality": summary["quality"],
        "quality_reasons": summary["quality_reasons"],
        "end_time_ms": summary["end_time_ms"],
        "cycles": summary["cycles"],
        "dt_initial_ms": summary["dt_initial_ms"],
        "dt_min_ms": summary["dt_min_ms"],
        "wall_seconds": summary["wall_seconds"],
        "energy_ratio": summary["energy_ratio"],
        "energy_ratio_worst": float(gl["energy_ratio"][np.argmax(np.abs(gl["energy_ratio"] - 1.0))])
        if gl["energy_ratio"].size else None,
    }
    marks, node_rows = {}, {}
    for name in LANDMARKS:
        rows = _by_id(nod, "node", int(hist[name]))
        if not rows["time [ms]"].size:
            continue
        node_rows[name] = rows
        marks[name] = {
            "uz_end_mm": float(rows["uz [mm]"][-1]),
            "uz_lowest_mm": float(rows["uz [mm]"].min()),
            "ux_end_mm": float(rows["ux [mm]"][-1]),
            "uy_end_mm": float(rows["uy [mm]"][-1]),
        }
    out["landmarks"] = marks
    feet = {}
    for name, pid in sorted(foot_parts(model_dir / "pedestrian.k").items()):
        rows = _by_id(rbd, "part", pid)
        if not rows["time [ms]"].size:
            continue
        feet[name] = {
            "uz_largest_mm": float(np.abs(rows["uz [mm]"]).max()),
            "horizontal_largest_mm": float(np.hypot(rows["ux [mm]"], rows["uy [mm]"]).max()),
        }
    out["feet"] = feet
    weight = report["mass"]["model_kg"] * GRAVITY
    out["weight_kN"] = weight
    out["floor_normal_end_kN"] = (float(wall["normal [kN]"][-1])
                                  if wall.get("normal [kN]", np.zeros(0)).size else None)
    ke = gl["kinetic [J]"]
    out["kinetic_end_J"] = float(ke[-1])
    out["kinetic_largest_J"] = float(ke.max())
    out["kinetic_largest_at_ms"] = float(gl["time [ms]"][int(np.argmax(ke))])
    internal = float(gl["internal [J]"][-1])
    out["hourglass_over_internal_end"] = (float(gl["hourglass [J]"][-1]) / internal
                                          if internal > 0.0 else None)
    out["curves"] = {
        "time_ms": [float(t) for t in gl["time [ms]"]],
        "kinetic_J": [float(v) for v in ke],
        **{f"uz_{name}": [float(v) for v in node_rows[name]["uz [mm]"]]
           for name in ("head_cg", "sacrum") if name in node_rows},
        "node_time_ms": [float(t) for t in node_rows["head_cg"]["time [ms]"]],
    }
    return out


def settling_table(runs: dict[str, dict]) -> str:
    """A Markdown table of several settling summaries (label -> summary)."""
    head = ("| run | status | quality | energy ratio | cycles | wall s | head drop mm "
            "(lowest) | sacrum drop mm | feet uz mm | floor / weight | kinetic end J "
            "(largest) |\n|---|---|---|---|---|---|---|---|---|---|---|\n")
    lines = []
    for label, s in runs.items():
        m = s["landmarks"]
        feet = max((f["uz_largest_mm"] for f in s["feet"].values()), default=float("nan"))
        floor = s["floor_normal_end_kN"]
        lines.append(
            f"| {label} | {s['status']} | {s['quality']} | {s['energy_ratio']:.7f} | "
            f"{s['cycles']:,} | {s['wall_seconds']:,.0f} | "
            f"{-m['head_cg']['uz_end_mm']:.3f} ({-m['head_cg']['uz_lowest_mm']:.3f}) | "
            f"{-m['sacrum']['uz_end_mm']:.3f} | {feet:.3f} | "
            f"{(floor or 0.0) / s['weight_kN']:.2f} | {s['kinetic_end_J']:.3f} "
            f"({s['kinetic_largest_J']:.3f}) |")
    return head + "\n".join(lines) + "\n"


def plot_settling(runs: dict[str, dict], path: Path) -> Path:
    """Head and sacrum sinking and kinetic energy against time, one line per run (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    for label, s in runs.items():
        c = s["curves"]
        line, = a.plot(c["node_time_ms"], c["uz_head_cg"], label=f"{label}: head")
        if "uz_sacrum" in c:
            a.plot(c["node_time_ms"], c["uz_sacrum"], ls="--", color=line.get_color(),
                   label=f"{label}: sacrum")
        b.plot(c["time_ms"], c["kinetic_J"], color=line.get_color(), label=label)
    a.set_xlabel("time [ms]")
    a.set_ylabel("vertical displacement [mm]")
    a.set_title("sinking under gravity")
    b.set_xlabel("time [ms]")
    b.set_ylabel("kinetic energy [J]")
    b.set_title("coming to rest")
    for ax in (a, b):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
