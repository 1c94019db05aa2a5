"""Report of the efficiency and stability study: tables and force-displacement plots.

Files written by :func:`write_study_report` in the study folder:

- ``study.md`` / ``study.csv`` — one row per run: structure, speed (km/h),
  status and reason, end time (ms), cycles, wall time (s), element counts,
  eroded elements (the hollow block deletes wall shells crushed in their
  plane), peak force (kN; CFC-filtered and raw), maximum impactor
  displacement (mm), energy ratio, hourglass energy (% of total and of
  internal), contact energy (% of total), contact wall time (% of the run's)
  and contact pass-through nodes;
  the Markdown adds the solid/hollow wall-time ratio at every speed where
  both runs ended normally;
- ``fd_<speed>kmh.png`` — solid vs hollow at one speed (raw curves faint, the
  force axis limited to 1.3 x the filtered peak when raw first-contact spikes
  would flatten the curves);
- ``fd_all.png`` — every curve (filtered), colour by speed, line style by
  structure.
"""

from __future__ import annotations

import csv
from pathlib import Path

from hollowbody.calibrate.study import load_curves
from hollowbody.curves.force_displacement import smoothed
from hollowbody.curves.plot import (
    RUN_CFC,
    TURN_LABEL,
    add_legend,
    clip_force_axis,
    draw_curve,
    filter_label,
)
from hollowbody.scenarios.block import THROUGH_BASE

COLUMNS = ("structure", "speed_kmh", "status", "quality", "reason", "end_time_ms", "cycles",
           "wall_seconds", "hexahedra", "shells", "eroded_elements", "peak_force_kN",
           "peak_force_raw_kN", "max_displacement_mm", "energy_ratio", "hourglass_percent",
           "hourglass_internal_percent", "contact_energy_percent", "contact_time_percent",
           "pass_through_nodes", "outcome", "fitness_vs_solid")
HEADERS = ("structure", "speed [km/h]", "status", "quality****", "reason", "end time [ms]",
           "cycles",
           "wall [s]", "hexahedra", "shells*", "eroded**", "peak force [kN] (filtered)",
           "peak force raw [kN]", "max displacement [mm]", "energy ratio",
           "hourglass [% of total]", "hourglass [% of internal]",
           "contact energy [% of total]", "contact time [% of wall]",
           "pass-through nodes", "impactor***",
           "fitness vs solid*****")


def _cell(v: object) -> str:
    if v is None:
        return "n/a"
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v).replace("|", "/")


def _quality_cell(r: dict) -> str:
    q = r.get("quality")
    if q is None:
        return "n/a"
    why = r.get("quality_reasons")
    text = "**SUSPECT**" if q == "suspect" else str(q)
    return _cell(f"{text}: {why}" if why and q != "ok" else text)


def wall_time_ratios(rows: list[dict]) -> dict[float, float]:
    """{speed: solid wall s / hollow wall s} where both ended normally (and neither
    is suspect)."""
    by = {(r["structure"], r["speed_kmh"]): r for r in rows}
    out = {}
    for (st, v), r in sorted(by.items(), key=lambda kv: kv[0][1]):
        if st != "solid":
            continue
        h = by.get(("hollow", v))
        if (h and r["status"] == "normal termination" and h["status"] == "normal termination"
                and "suspect" not in (r.get("quality"), h.get("quality"))
                and r["wall_seconds"] and h["wall_seconds"]
                and THROUGH_BASE not in (r.get("outcome"), h.get("outcome"))):
            out[v] = r["wall_seconds"] / h["wall_seconds"]
    return out


def study_markdown(rows: list[dict], title: str = "Efficiency and stability study",
                   cfc: float | None = 180.0) -> str:
    """The study table in Markdown with the wall-time ratios and notes."""
    headers = [h.replace("(filtered)", f"({filter_label(cfc)})") for h in HEADERS]
    lines = [f"## {title}", "", "| " + " | ".join(headers) + " |",
             "|" + "---|" * len(HEADERS)]
    for r in rows:
        lines.append("| " + " | ".join(_quality_cell(r) if c == "quality" else _cell(r.get(c))
                                       for c in COLUMNS) + " |")
    ratios = wall_time_ratios(rows)
    lines.append("")
    if ratios:
        lines.append("Solid/hollow wall-time ratio (both normal terminations): "
                     + ", ".join(f"{v:g} km/h: {q:.2f}" for v, q in ratios.items()) + ".")
    else:
        lines.append("Solid/hollow wall-time ratio: no speed where both runs ended normally.")
    filt = f"filtered with the SAE J211 CFC {cfc:g} filter" if cfc else "not filtered"
    lines += ["", f"\\* shells include the rigid impactor's. Peak force (filtered) is the "
              f"contact force {filt}; raw peaks include single-cycle contact spikes. The "
              f"force_displacement.csv/.png of each run folder show that run alone with "
              f"the run's own {filter_label(RUN_CFC)} filter.",
              "", "\\*\\* elements deleted during the run (erosion is on for the hollow block: "
              "a wall shell crushed until its time step is below DTMIN, 5 % of the initial "
              "step by default, or to 1 % of its area, is removed; off for the solid block, "
              "where a collapsing element ends the run).",
              "", "Energy ratio: total / initial energy at the end of the run. Hourglass: "
              "hourglass energy at the end in % of the total and of the internal energy "
              "(above ~10 % of the internal energy the curve is questionable: the verdict "
              "warns). Contact energy: the contacts' energy at the end in % of the total "
              "(penalty springs store and friction dissipates: a negative value is energy "
              "the contacts created; the verdict grades it). "
              "Contact time: the contacts' search, forces and step limit in % of the run's "
              "wall time (set-up and output included in the wall time). Pass-through "
              "nodes: nodes the contacts reported pushed through a surface (the contact "
              "lost them).",
              "", "\\*\\*\\* how far the impactor got: stopped (by the tissue, travel below "
              "90 % of the block height), reached the base (crushed the block onto its fixed "
              "base: the force peak is the base's), through the base (travel beyond the "
              "height + 5 mm: fixed base nodes were pushed through the impactor's contact "
              "surface; the curve after that is not valid and the run is left out of the "
              "wall-time ratio).",
              "", "\\*\\*\\*\\* the run's verdict (energy balance, hourglass and negative "
              "contact energy, time-step collapse, added mass, pass-through; see the solver "
              "documentation): ok, warning, or **SUSPECT** (its curve is not trusted and the "
              "run is left out of the wall-time ratio), with the reasons.",
              "", "\\*\\*\\*\\*\\* hollow runs: the calibration's fitness of the hollow "
              "force-displacement curve against the solid one at the same speed (both "
              f"{filt}): the root-mean-square force difference over the loading and the "
              "unloading branch, in units of the solid peak force, over the solid's "
              "displacement range (0: the same curve; 0.1: 10 % of the peak on average)."]
    return "\n".join(lines) + "\n"


def write_study_csv(rows: list[dict], path: str | Path) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([*COLUMNS, "run_dir"])
        for r in rows:
            w.writerow(["" if r.get(c) is None else r.get(c) for c in (*COLUMNS, "run_dir")])


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_speed(rows: list[dict], curves: dict, speed: float, path: str | Path,
               cfc: float | None = 180.0) -> None:
    """Solid vs hollow at one speed (raw faint, filtered bold with the filter class and
    the run's status in the legend; arrows mark loading and unloading)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4.6), dpi=120)
    status = {(r["structure"], r["speed_kmh"]): r["status"]
              + (", SUSPECT" if r.get("quality") == "suspect" else "") for r in rows}
    filtered, raw = [], []
    turn_label: str | None = TURN_LABEL
    for st, colour in (("solid", "C0"), ("hollow", "C3")):
        c = curves.get((st, speed))
        if c is None or c.displacement.size < 2:
            continue
        sm = smoothed(c, cfc)
        filtered.append(sm.force)
        raw.append(c.force)
        draw_curve(ax, (c.displacement, c.force), (sm.displacement, sm.force), colour=colour,
                   label=f"{st} ({status.get((st, speed), '?')})", cfc=cfc,
                   show_raw=bool(cfc), turn_label=turn_label)
        turn_label = None
    ax.set_xlabel("impactor displacement [mm]")
    ax.set_ylabel("contact force [kN]")
    ax.set_title(f"block test at {speed:g} km/h: solid vs hollow")
    ax.set_xlim(left=0.0)
    clip_force_axis(ax, filtered, raw)
    ax.grid(True, alpha=0.3)
    add_legend(ax)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def plot_all(curves: dict, path: str | Path, cfc: float | None = 180.0,
             rows: list[dict] | None = None) -> None:
    """Every curve, filtered: colour by speed, solid line solid, dashed hollow; arrows
    mark loading and unloading; with the study ``rows``, suspect runs are marked in the
    legend."""
    suspect = {(r["structure"], r["speed_kmh"]): r.get("quality") == "suspect"
               for r in rows or ()}
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.0, 4.8), dpi=120)
    speeds = sorted({v for _, v in curves})
    turn_label: str | None = TURN_LABEL
    for (st, v), c in sorted(curves.items(), key=lambda kv: (kv[0][1], kv[0][0])):
        if c.displacement.size < 2:
            continue
        sm = smoothed(c, cfc)
        draw_curve(ax, (c.displacement, c.force), (sm.displacement, sm.force),
                   colour=f"C{speeds.index(v)}",
                   label=f"{st} {v:g} km/h" + (" (SUSPECT)" if suspect.get((st, v)) else ""),
                   cfc=cfc, ls="-" if st == "solid" else "--", show_raw=False,
                   turn_label=turn_label)
        turn_label = None
    ax.set_xlabel("impactor displacement [mm]")
    ax.set_ylabel("contact force [kN]")
    ax.set_title("block test: all force-displacement curves")
    ax.set_xlim(left=0.0)
    ax.grid(True, alpha=0.3)
    add_legend(ax)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def add_fitness_vs_solid(rows: list[dict], curves: dict, cfc: float | None = 180.0) -> None:
    """Set ``fitness_vs_solid`` of each hollow row whose speed has a solid curve (the
    calibration's :func:`~hollowbody.calibrate.fitness.curve_distance`, same filter);
    None where either curve is missing or either run did not end normally."""
    from hollowbody.calibrate.fitness import FitnessSettings, curve_distance

    status = {(r["structure"], r["speed_kmh"]): r.get("status") for r in rows}
    for r in rows:
        r["fitness_vs_solid"] = None
        v = r["speed_kmh"]
        ref, cand = curves.get(("solid", v)), curves.get(("hollow", v))
        if (r["structure"] != "hollow" or ref is None or cand is None
                or status.get(("solid", v)) != "normal termination"
                or r.get("status") != "normal termination"):
            continue
        try:
            r["fitness_vs_solid"] = curve_distance(ref, cand, FitnessSettings(cfc=cfc))
        except ValueError:  # a solid curve without positive force or displacement
            pass


def write_study_report(rows: list[dict], out_dir: str | Path,
                       cfc: float | None = 180.0) -> dict[str, Path]:
    """Write study.md, study.csv and the plots into ``out_dir``; returns {name: path}."""
    out = Path(out_dir)
    files = {"table_md": out / "study.md", "table_csv": out / "study.csv"}
    curves = load_curves(rows)
    add_fitness_vs_solid(rows, curves, cfc)
    files["table_md"].write_text(study_markdown(rows, cfc=cfc))
    write_study_csv(rows, files["table_csv"])
    for v in sorted({r["speed_kmh"] for r in rows}):
        p = out / f"fd_{v:g}kmh.png"
        plot_speed(rows, curves, v, p, cfc)
        files[f"fd_{v:g}kmh"] = p
    plot_all(curves, out / "fd_all.png", cfc, rows)
    files["fd_all"] = out / "fd_all.png"
    return files
