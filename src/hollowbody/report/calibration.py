"""Report of a calibration: convergence and overlay plots, the best deck, Table 1.

Everything is built from ``calibration.json`` and the run folders it names,
so the report can be rebuilt from a finished (or interrupted) calibration::

    from hollowbody.report.calibration import write_report
    write_report("cal_muscle")

Files (in the calibration folder):

- ``convergence.png`` — best fitness so far and the mean fitness of the
  normally terminated candidates, per generation (log scale when they span a
  decade or more);
- ``overlay.png`` — solid reference vs best hollow force-displacement curve at
  each speed (CFC-filtered lines over the raw curves, the force axis limited
  to 1.3 x the filtered peak when raw first-contact spikes would flatten the
  curves; the paper's Fig. 2; the legend gives the wall shells the hollow run
  eroded);
- ``best_hollow/deck.k`` — the best candidate's hollow block deck at the first
  speed (``deck_<speed>kmh.k`` for further speeds) and ``parameters.json``;
- ``table1.md`` / ``table1.csv`` — like the paper's Table 1: solid bulk
  modulus (MPa) and the calibrated hollow wall material (MPa, mm).
"""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import numpy as np

from hollowbody.calibrate.reference import read_curve_csv
from hollowbody.calibrate.simulate import CELL_MM
from hollowbody.calibrate.wall import WALL_UNITS, effective_wall, wall_geometry
from hollowbody.curves.force_displacement import ForceDisplacement, smoothed
from hollowbody.curves.plot import TURN_LABEL, add_legend, clip_force_axis, draw_curve


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def use_log_scale(values: list[float], decades: float = 1.0) -> bool:
    """A log fitness axis only when the finite positive values span at least ``decades``
    decades (over a narrower range a log axis shows unreadable ticks like 4.8e-1)."""
    v = [float(x) for x in values if x is not None and np.isfinite(x) and x > 0.0]
    return bool(v) and bool(np.log10(max(v) / min(v)) >= decades)


def plot_convergence(history: list[dict], path: str | Path, title: str = "") -> None:
    """Best-so-far and mean fitness per generation (PNG)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=120)
    g = [h["generation"] for h in history]
    best = [np.nan if h["best"] is None else h["best"] for h in history]
    mean = [np.nan if h["mean"] is None else h["mean"] for h in history]
    ax.plot(g, best, "o-", lw=1.8, label="best so far")
    ax.plot(g, mean, "s--", lw=1.2, label="generation mean (normal terminations)")
    failed = [h.get("failed", 0) for h in history]
    suspect = [h.get("suspect", 0) for h in history]
    if any(failed):
        for gi, fi, si, bi in zip(g, failed, suspect, best):
            if fi:
                text = f"{fi} failed" + (f" ({si} suspect)" if si else "")
                ax.annotate(text, (gi, bi), textcoords="offset points",
                            xytext=(0, -14), ha="center", fontsize=7)
    if use_log_scale(best + mean):
        ax.set_yscale("log")
    ax.set_xlabel("generation")
    ax.set_ylabel("fitness (normalised RMS force difference)")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    if g:
        ax.set_xticks(g if len(g) <= 20 else g[:: max(1, len(g) // 10)])
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_overlay(pairs: list[tuple[float, ForceDisplacement, ForceDisplacement | None]],
                 path: str | Path, cfc: float | None = 180.0, title: str = "",
                 eroded: dict[float, int] | None = None) -> None:
    """Solid vs hollow force-displacement, one panel per speed (PNG).

    pairs: [(speed km/h, solid curve, hollow curve or None)]; eroded: {speed:
    wall shells the hollow run deleted} (shown in the hollow curve's legend).
    """
    plt = _plt()
    n = max(1, len(pairs))
    fig, axes = plt.subplots(1, n, figsize=(5.6 * n, 4.4), dpi=120, squeeze=False)
    for ax, (speed, solid, hollow) in zip(axes[0], pairs):
        filtered, raw = [], []
        turn_label: str | None = TURN_LABEL
        for curve, colour, name in ((solid, "C0", "solid"), (hollow, "C3", "hollow")):
            if curve is None or curve.displacement.size < 2:
                continue
            sm = smoothed(curve, cfc)
            filtered.append(sm.force)
            raw.append(curve.force)
            note = ""
            if name == "hollow" and eroded and eroded.get(speed) is not None:
                note = f" ({eroded[speed]} shells eroded)"
            draw_curve(ax, (curve.displacement, curve.force), (sm.displacement, sm.force),
                       colour=colour, label=f"{name}{note}", cfc=cfc, show_raw=bool(cfc),
                       turn_label=turn_label)
            turn_label = None
        ax.set_xlabel("impactor displacement [mm]")
        ax.set_ylabel("contact force [kN]")
        ax.set_title(f"{speed:g} km/h")
        ax.set_xlim(left=0.0)
        clip_force_axis(ax, filtered, raw)
        ax.grid(True, alpha=0.3)
        add_legend(ax)
    if title:
        import textwrap

        fig.suptitle(textwrap.fill(title, 55 * n), fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def table1_row(data: dict) -> dict:
    """One Table 1 row (CSV field -> value) of a calibration's ``calibration.json`` data."""
    from hollowbody.tissues import tissue

    t = tissue(data["tissue"])
    wall = effective_wall(data) or {}
    return {"tissue": data["tissue"], "body_part": t.name,
            "solid_bulk_modulus_MPa": t.bulk_modulus * 1000.0,
            "hollow_E_MPa": wall.get("E"), "hollow_yield_MPa": wall.get("yield"),
            "hollow_etan_MPa": wall.get("etan"), "hollow_thickness_mm": wall.get("thickness"),
            "fitness": data.get("best_fitness"),
            "speeds_kmh": " ".join(f"{s:g}" for s in data["speeds_kmh"]),
            "calibrated": " ".join(data["parameters"]),
            "cell_mm": wall_geometry(data).get("cell", CELL_MM),
            "elements_per_edge": (data.get("simulator") or {}).get("elements_per_edge"),
            "paper_hollow_E_MPa": t.hollow_E * 1000.0,
            "paper_hollow_yield_MPa": t.hollow_yield * 1000.0}


def _num(v: float | None, fmt: str = "{:.4g}") -> str:
    return "n/a" if v is None else fmt.format(v)


def _cells(row: dict) -> str:
    """'30 mm cells, 4 shells per edge' of a Table 1 row."""
    n = row.get("elements_per_edge")
    return f"{row['cell_mm']:g} mm cells" + ("" if n is None else f", {n} shells per edge")


def write_table1(rows: list[dict], md_path: str | Path, csv_path: str | Path) -> None:
    """Table 1 as Markdown (the paper's layout: a solid and a hollow row per tissue) and CSV."""
    lines = ["| Structure | Material model | Body part | Linear bulk modulus [MPa] | "
             "Young's modulus [MPa] | Yield stress [MPa] | Tangent modulus [MPa] | "
             "Wall thickness [mm] | Fitness | Paper's fit E / yield [MPa] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| Solid | Rubber (MAT_181) | {r['body_part']} | "
                     f"{_num(r['solid_bulk_modulus_MPa'])} | / | / | / | / | / | / |")
    for r in rows:
        lines.append(f"| Hollow | Plastic (MAT_003) | {r['body_part']} | / | "
                     f"{_num(r['hollow_E_MPa'])} | {_num(r['hollow_yield_MPa'])} | "
                     f"{_num(r['hollow_etan_MPa'])} | {_num(r['hollow_thickness_mm'])} | "
                     f"{_num(r['fitness'], '{:.3g}')} | {r['paper_hollow_E_MPa']:g} / "
                     f"{r['paper_hollow_yield_MPa']:g} |")
    notes = ", ".join(f"{r['tissue']}: {_cells(r)}, calibrated {r['calibrated']} at "
                      f"{r['speeds_kmh']} km/h" for r in rows)
    lines += ["", f"Hollow walls: elastic-plastic shells; {notes}. Parameters not "
              "calibrated keep the block's values."]
    Path(md_path).write_text("\n".join(lines) + "\n")
    with open(csv_path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]) if rows else ["tissue"])
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if v is None else v) for k, v in r.items()})


def locate_run(run_dir: str | None, out_dir: Path) -> Path | None:
    """A run folder recorded in calibration.json, also after the calibration folder moved
    (the part from ``runs/`` on is looked up under ``out_dir``)."""
    if not run_dir:
        return None
    p = Path(run_dir)
    if p.exists():
        return p
    parts = p.parts
    if "runs" in parts:
        q = out_dir.joinpath(*parts[len(parts) - 1 - parts[::-1].index("runs"):])
        if q.exists():
            return q
    return None


def copy_best_deck(data: dict, out_dir: Path) -> Path | None:
    """Copy the best run's deck(s) into ``out_dir/best_hollow``; returns deck.k or None."""
    dirs = data.get("best_run_dirs") or []
    if data.get("best_parameters") is None or not dirs:
        return None
    dest = out_dir / "best_hollow"
    dest.mkdir(exist_ok=True)
    first = None
    for i, (speed, rd) in enumerate(zip(data["speeds_kmh"], dirs)):
        found = locate_run(rd, out_dir)
        src = found / "deck.k" if found else None
        if src is None or not src.exists():
            continue
        target = dest / ("deck.k" if i == 0 else f"deck_{speed:g}kmh.k")
        shutil.copyfile(src, target)
        first = first or target
    (dest / "parameters.json").write_text(json.dumps(
        {"tissue": data["tissue"], "wall": effective_wall(data),
         "cell_mm": wall_geometry(data).get("cell", CELL_MM),
         "units": WALL_UNITS,
         "fitness": data.get("best_fitness"), "speeds_kmh": data["speeds_kmh"]}, indent=2))
    return first


def overlay_pairs(data: dict, out_dir: Path) -> list[tuple[float, ForceDisplacement,
                                                         ForceDisplacement | None]]:
    """[(speed, solid reference, best hollow or None)] from the calibration's folders."""
    pairs = []
    dirs = data.get("best_run_dirs") or []
    for i, speed in enumerate(data["speeds_kmh"]):
        ref = out_dir / "reference" / f"{speed:g}kmh" / "force_displacement.csv"
        solid = read_curve_csv(ref, "solid") if ref.exists() else None
        hollow = None
        found = locate_run(dirs[i], out_dir) if i < len(dirs) else None
        if found is not None and (found / "force_displacement.csv").exists():
            hollow = read_curve_csv(found / "force_displacement.csv", "hollow")
        if solid is not None:
            pairs.append((float(speed), solid, hollow))
    return pairs


def best_eroded(data: dict, out_dir: Path) -> dict[float, int]:
    """{speed: elements the best candidate's hollow run deleted}, from its run folders'
    summary.json (speeds whose run does not report it are left out)."""
    from hollowbody.calibrate.evaluation import eroded_count

    out: dict[float, int] = {}
    for speed, rd in zip(data["speeds_kmh"], data.get("best_run_dirs") or []):
        found = locate_run(rd, out_dir)
        if found is None or not (found / "summary.json").exists():
            continue
        try:
            n = eroded_count(json.loads((found / "summary.json").read_text()))
        except (json.JSONDecodeError, UnicodeDecodeError):
            continue
        if n is not None:
            out[float(speed)] = n
    return out


def write_report(out_dir: str | Path) -> dict[str, Path]:
    """Write every report file of the calibration in ``out_dir``; returns {name: path}."""
    out = Path(out_dir)
    data = json.loads((out / "calibration.json").read_text())
    files: dict[str, Path] = {}
    wall = effective_wall(data)
    label = (", ".join(f"{k} {v:g} {WALL_UNITS[k]}" for k, v in wall.items()) if wall
             else "no valid candidate")
    plot_convergence(data["generations"], out / "convergence.png",
                     title=f"calibration of the hollow {data['tissue']} block")
    files["convergence"] = out / "convergence.png"
    plot_overlay(overlay_pairs(data, out), out / "overlay.png", cfc=data["fitness"]["cfc"],
                 title=f"{data['tissue']}: solid vs calibrated hollow ({label})",
                 eroded=best_eroded(data, out))
    files["overlay"] = out / "overlay.png"
    deck = copy_best_deck(data, out)
    if deck is not None:
        files["deck"] = deck
    write_table1([table1_row(data)], out / "table1.md", out / "table1.csv")
    files["table1_md"] = out / "table1.md"
    files["table1_csv"] = out / "table1.csv"
    return files
