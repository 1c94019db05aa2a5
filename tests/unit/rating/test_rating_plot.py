"""``rate --plot``: axis labels from the CSV headers, file names in the legend, corridor."""

from __future__ import annotations

import numpy as np

import hollowbody.rating.plot as rating_plot
from hollowbody.cli.main import main

T = np.arange(0.0, 60.0 + 1e-9, 0.5)


def write_csv(path, header, columns, sep=","):
    rows = [sep.join(f"{v:.6g}" for v in r) for r in zip(*columns)]
    path.write_text("\n".join([header, *rows]) + "\n", encoding="utf-8")
    return str(path)


def captured_figures(monkeypatch):
    figures = []
    original = rating_plot.corridor_figure

    def capture(**kwargs):
        fig = original(**kwargs)
        figures.append(fig)
        return fig

    monkeypatch.setattr(rating_plot, "corridor_figure", capture)
    return figures


def test_rate_plot_labels_legend_and_corridor(tmp_path, monkeypatch, capsys):
    ref = write_csv(tmp_path / "viano_test.csv", "time [ms],deflection [mm]",
                    (T, 3.0 * np.sin(np.pi * T / 60.0) ** 2))
    cand = write_csv(tmp_path / "sim_run.csv", "time [ms];deflection [mm]",
                     (T, 3.3 * np.sin(np.pi * (T - 1.0) / 60.0) ** 2), sep=";")
    corr = write_csv(tmp_path / "bounds.csv", "x,lower,upper",
                     (T, 2.4 * np.sin(np.pi * T / 60.0) ** 2,
                      3.6 * np.sin(np.pi * T / 60.0) ** 2 + 0.2))
    out = tmp_path / "rating.png"
    figures = captured_figures(monkeypatch)
    assert main(["rate", ref, cand, "--corridor", corr, "--plot", str(out)]) == 0
    assert out.stat().st_size > 0
    (fig,) = figures
    ax = fig.axes[0]
    assert ax.get_xlabel() == "time [ms]"
    assert ax.get_ylabel() == "deflection [mm]"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["corridor: bounds.csv", "reference: viano_test.csv",
                      "candidate: sim_run.csv"]
    assert ax.patches  # the corridor band is drawn
    note = [t for t in ax.texts if "CORA R" in t.get_text()]
    assert len(note) == 1 and "ISO 18571 R" in note[0].get_text()
    fig.canvas.draw()
    assert note[0].get_window_extent().y1 < ax.get_window_extent().y0  # below the data
    capsys.readouterr()


def test_rate_plot_names_both_headers_when_they_differ(tmp_path, monkeypatch, capsys):
    ref = write_csv(tmp_path / "a.csv", "t,force", (T, np.sin(np.pi * T / 60.0) ** 2))
    cand = write_csv(tmp_path / "b.csv", "time,F", (T, np.sin(np.pi * T / 60.0) ** 2))
    figures = captured_figures(monkeypatch)
    assert main(["rate", ref, cand, "--plot", str(tmp_path / "p.png")]) == 0
    ax = figures[0].axes[0]
    assert ax.get_xlabel() == "t / time" and ax.get_ylabel() == "force / F"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["reference: a.csv", "candidate: b.csv"]
    assert not ax.patches  # no corridor given, none drawn
    capsys.readouterr()
