"""The segment tests' report: one figure and one table per case, Markdown and HTML.

:func:`write_report` takes the :class:`~hollowbody.validation.runner.RunRecord`
list of one or more cases and writes into ``out``:

- ``<case>.png``: one row per speed, one panel per quantity (force-time,
  force-deflection, moment-deflection) in the paper's style: the test corridor
  shaded, the specimens thin and grey, the solid and hollow curves with their
  ratings in the legend;
- ``report.md`` and ``report.html`` (same content): per case its source, the
  set-up notes, the figure and a table (peak force, time of peak, ratings
  against the test and hollow against solid, status, quality, wall time,
  cycles), the runs that did not end normally with why and where, and the
  efficiency summary (wall-time ratio solid/hollow per case and speed);
- ``report.json``: the records (without the curves).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from hollowbody.report.index import markdown_to_html
from hollowbody.validation.cases import CASES, ORDER
from hollowbody.validation.ratings import LABELS, reference_data
from hollowbody.validation.runner import RunRecord

COLOURS = {"solid": "tab:blue", "hollow": "tab:red", "user": "tab:green"}
TITLES = {"force": "force-time", "force_deflection": "force-deflection",
          "moment_deflection": "moment-deflection"}


def _plt() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _legend(rec: RunRecord, quantity: str) -> str:
    parts = [rec.tissue]
    for r in rec.ratings:
        if r.quantity == quantity and r.error is None:
            who = "test" if r.against != "solid" else "vs solid"
            parts.append(f"{who}: CORA {r.cora:.2f} ISO {r.iso:.2f}")
    return "; ".join(parts)


def y_limits(trusted: list[float], suspects: list[float]) -> tuple[float, float] | None:
    """Force-axis limits when a suspect run's peak (absolute) is over twice the largest
    trusted one (test data, runs not suspect), else None (matplotlib's own)."""
    if not trusted or not suspects or max(suspects) <= 2.0 * max(trusted):
        return None
    top = max(trusted)
    return -0.15 * top, 1.3 * top


def plot_case(records: list[RunRecord], path: str | Path, corridor=None) -> Path:  # noqa: ANN001
    """The case's figure (see the module doc); ``corridor``: a user corridor."""
    plt = _plt()
    case = CASES[records[0].case]
    speeds = sorted({r.speed for r in records})
    quantities = case.quantities
    fig, axes = plt.subplots(len(speeds), len(quantities), squeeze=False,
                             figsize=(5.2 * len(quantities), 3.6 * len(speeds)))
    for i, speed in enumerate(speeds):
        for j, q in enumerate(quantities):
            ax = axes[i][j]
            data = reference_data(case, speed, q, corridor)
            if data is not None and data.corridor is not None:
                ring = data.corridor.outline
                ax.fill(ring[:, 0], ring[:, 1], color="0.6", alpha=0.3, lw=0,
                        label=f"corridor ({data.source.split(',')[0]})")
            if data is not None:
                for k, (x, y) in enumerate(data.specimens):
                    ax.plot(x, y, color="0.45", lw=0.7,
                            label="specimens" if k == 0 else None)
            trusted = [float(np.max(y)) for _, y in (data.specimens if data else [])]
            if data is not None and data.corridor is not None:
                trusted.append(float(np.max(data.corridor.upper)))
            suspects: list[float] = []
            for rec in records:
                if rec.speed != speed or rec.signals is None:
                    continue
                x, y = rec.signals.curve(q)
                suspect = rec.quality == "suspect"
                if y.size:
                    (suspects if suspect else trusted).append(float(np.max(np.abs(y))))
                label = _legend(rec, q) + (" (run suspect)" if suspect else "")
                ax.plot(x, y, color=COLOURS.get(rec.tissue, "k"), lw=1.8,
                        ls="--" if suspect else "-", label=label)
            limits = y_limits(trusted, suspects)
            if limits is not None:  # a run that blew up must not flatten the others
                ax.set_ylim(*limits)
                ax.annotate("suspect run off scale", xy=(0.99, 0.02), ha="right",
                            xycoords="axes fraction", fontsize=7)
            xl, yl = LABELS[q]
            ax.set_xlabel(xl)
            ax.set_ylabel(yl)
            ax.set_title(f"{case.name} {speed:g} m/s: {TITLES[q]}", fontsize=10)
            ax.grid(True, lw=0.4, alpha=0.6)
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def _num(v: float | None, fmt: str = "{:.2f}") -> str:
    return "-" if v is None else fmt.format(v)


def _rating_cell(rec: RunRecord, against: str) -> str:
    cells = []
    for r in rec.ratings:
        if (r.against == "solid") != (against == "solid"):
            continue
        if r.error:
            cells.append(f"{r.quantity}: not rated")
        else:
            txt = f"{r.quantity}: {r.cora:.2f} / {r.iso:.2f}"
            if r.inside is not None:
                txt += f" ({100 * r.inside:.0f} % in)"
            cells.append(txt)
    return "; ".join(cells) or "-"


def _status(rec: RunRecord) -> str:
    status = "normal" if rec.status == "normal termination" else rec.status
    if rec.resumed:
        status += f" (resumed {rec.resumed}x)"
    return status


def case_table(records: list[RunRecord]) -> list[str]:
    """Markdown table rows of one case."""
    rows = ["| speed [m/s] | model | peak force [kN] | at [ms] | vs test: CORA / ISO | "
            "hollow vs solid: CORA / ISO | status | quality | wall [s] | cycles |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for r in records:
        rows.append(f"| {r.speed:g} | {r.tissue} | {_num(r.peak_force)} | "
                    f"{_num(r.peak_time, '{:.1f}')} | {_rating_cell(r, 'test')} | "
                    f"{_rating_cell(r, 'solid')} | {_status(r)} | {r.quality or '-'} | "
                    f"{_num(r.wall_seconds, '{:.0f}')} | {r.cycles or '-'} |")
    return rows


def problems(records: list[RunRecord]) -> list[str]:
    """One line per run that did not end normally with quality ok: why and where."""
    out = []
    for r in records:
        if r.ok or r.status.startswith("not run"):
            continue
        where = ", ".join(f"{k} {v}" for k, v in r.where.items())
        why = r.reason if r.status != "normal termination" else ""
        if r.quality and r.quality != "ok":
            why += (" " if why else "") + f"(quality {r.quality}: " \
                + "; ".join(map(str, r.quality_reasons)) + ")"
        out.append(f"- {r.case} {r.speed:g} m/s {r.tissue}: {r.status}"
                   + (f" at {where}" if where else "") + (f": {why}" if why else ""))
    return out


def efficiency(records: list[RunRecord]) -> list[str]:
    """Markdown rows: wall time solid, hollow and their ratio per case and speed."""
    rows = ["| case | speed [m/s] | solid wall [s] | hollow wall [s] | solid / hollow |",
            "|---|---|---|---|---|"]
    keys = sorted({(r.case, r.speed) for r in records},
                  key=lambda k: (ORDER.index(k[0]) if k[0] in ORDER else 99, k[1]))
    any_row = False
    for c, s in keys:
        w = {r.tissue: r.wall_seconds for r in records if r.case == c and r.speed == s}
        ws, wh = w.get("solid"), w.get("hollow")
        if ws is None and wh is None:
            continue
        ratio = f"{ws / wh:.2f}" if ws and wh else "-"
        rows.append(f"| {c} | {s:g} | {_num(ws, '{:.0f}')} | {_num(wh, '{:.0f}')} | {ratio} |")
        any_row = True
    return rows if any_row else []


def report_markdown(records: list[RunRecord], figures: dict[str, str]) -> str:
    """The report's Markdown."""
    lines = ["# Segment tests: solid and hollow against cadaver data", "",
             "Force: the impactor contact force, CFC 180. Ratings: CORA (CORAplus "
             "defaults, interval from the reference) and ISO/TS 18571 (range both curves "
             "cover), against the specimen mean (force-time) or the corridor mid-line "
             "(force-deflection) with the corridor as CORA's inner corridor; hollow rated "
             "against solid. Time zero: the impactor reaches the skin.", ""]
    by_case: dict[str, list[RunRecord]] = {}
    for r in records:
        by_case.setdefault(r.case, []).append(r)
    for name in sorted(by_case, key=lambda n: ORDER.index(n) if n in ORDER else 99):
        recs = by_case[name]
        c = CASES[name]
        lines += [f"## {name}", "", f"Source: {c.source}. Location: {c.location}.", ""]
        if not c.data:
            lines += ["No test data ship with hollowbody for this case: it is rated hollow "
                      "against solid (and against a corridor given with --corridor).", ""]
        notes = recs[0].setup.get("notes", [])
        if notes:
            lines += ["Set-up notes:", ""] + [f"- {n}" for n in notes] + [""]
        if name in figures:
            lines += [f"![{name}]({figures[name]})", ""]
        lines += case_table(recs) + [""]
    bad = problems(records)
    lines += ["## Runs that did not end normally with quality ok", ""]
    lines += (bad or ["None."]) + [""]
    eff = efficiency(records)
    if eff:
        lines += ["## Efficiency: wall time solid / hollow", ""] + eff + [""]
    return "\n".join(lines)


def write_report(records: list[RunRecord], out: str | Path, corridor=None  # noqa: ANN001
                 ) -> dict[str, Path]:
    """Write the figures, ``report.md``, ``report.html`` and ``report.json`` in ``out``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    figures: dict[str, str] = {}
    by_case: dict[str, list[RunRecord]] = {}
    for r in records:
        by_case.setdefault(r.case, []).append(r)
    for name, recs in by_case.items():
        if any(r.signals is not None for r in recs):
            plot_case(recs, out / f"{name}.png", corridor)
            figures[name] = f"{name}.png"
    md = report_markdown(records, figures)
    final = {"markdown": out / "report.md", "html": out / "report.html"}
    final["markdown"].write_text(md)
    final["html"].write_text(markdown_to_html(md, "Segment tests"))
    (out / "report.json").write_text(json.dumps([r.to_dict() for r in records], indent=1,
                                                default=str) + "\n")
    final["json"] = out / "report.json"
    return final
