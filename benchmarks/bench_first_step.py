"""First time step of solid blocks against LS-DYNA's documented rule.

    python benchmarks/bench_first_step.py [--out DIR]

For the block test's solid blocks (muscle and fat, MAT_181) and elastic
hexahedral blocks (nu 0.3 and 0.45), prints hollowbody's first step (what
``hollowbody check`` reports and the run takes) and LS-DYNA's rule for ELFORM 1
hexahedra with TSSFAC 0.9: ``0.9 min(V / A_max) / c`` with the dilatational wave
speed ``c = sqrt((K + 4G/3) / rho)`` at rest (no bulk-viscosity term), and
their ratio; and, for comparison, the ratio the lone-element factor gives
(``volumetric_step_factor(..., min_axes=0)``, a bound for any mesh; the engine
uses the restrained-axes factor of the mesh, see docs/elements.md, "Time
step"). Cheap (no run): the decks are built and the forces at t = 0 computed once.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from hollowbody.api import load_model
from hollowbody.elements.hex8_kinematics import canonical_connectivity
from hollowbody.elements.solid_step_factor import (
    group_min_axes,
    restrained_axes,
    volumetric_step_factor,
)
from hollowbody.elements.time_step import element_time_steps
from hollowbody.io.keyword import (
    ControlTermination,
    Deck,
    MatElastic,
    Part,
    SectionSolid,
    write_deck,
)
from hollowbody.mesh import standing_block
from hollowbody.scenarios.block import BlockConfig, write_block_deck
from hollowbody.solver.preflight import first_time_step

TSSFAC = 0.9


def lsdyna_step(model, c: float) -> float:  # noqa: ANN001 - Model
    """LS-DYNA's first step (ms) of the model's solids: TSSFAC min(V / A_max) / c."""
    best = np.inf
    for g in model.solid_groups:
        conn, shape = canonical_connectivity(np.asarray(g.conn))
        best = min(best, float(element_time_steps(conn, model.node_x0, c, shape).min()))
    return TSSFAC * best


def elastic_block(path: Path, nu: float, size: float = 90.0, mesh: float = 7.5) -> Path:
    """A free ``size`` mm cube of ``mesh`` mm hexahedra, E 1 GPa, rho 1e-6 kg/mm^3."""
    x, conn = standing_block((size, size, size), mesh)
    d = Deck()
    ids = np.arange(1, x.shape[0] + 1)
    d.add_nodes(ids, x)
    d.add_solids(np.arange(1, conn.shape[0] + 1), 1, ids[conn])
    d.add(Part(pid=1, secid=1, mid=1, title="elastic block"))
    d.add(SectionSolid(secid=1))
    d.add(MatElastic(mid=1, ro=1e-6, e=1.0, pr=nu))
    d.add(ControlTermination(endtim=1.0))
    write_deck(d, path)
    return path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", type=Path, default=None)
    a = ap.parse_args()
    out = a.out or Path(tempfile.mkdtemp(prefix="bench_first_step_"))
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for tissue in ("muscle", "fat"):
        cfg = BlockConfig(tissue=tissue, structure="solid", speed_kmh=40.0)
        (out / tissue).mkdir(exist_ok=True)
        deck = write_block_deck(cfg, out / tissue)
        model = load_model(deck)
        mat = next(m for m in model.materials.values() if m.kind == "rubber181")
        rows.append((f"solid {tissue} block (MAT_181)", model, mat))
    for nu in (0.3, 0.45):
        model = load_model(elastic_block(out / f"elastic_{nu:g}.k", nu))
        rows.append((f"elastic block nu {nu:g}", model, model.materials[1]))
    print(f"{'case':34s} {'hollowbody ms':>14s} {'LS-DYNA rule ms':>16s} {'ratio':>7s} "
          f"{'k':>2s} {'lone-element ratio':>19s}")
    for name, model, mat in rows:
        ours = first_time_step(model, threads=1)["run_dt"]
        c = wave_speed(mat, model)
        ref = lsdyna_step(model, c)
        conns = [np.asarray(g.conn) for g in model.solid_groups]
        k = min(group_min_axes(cn, ax) for cn, ax in zip(conns, restrained_axes(conns)))
        lone = volumetric_step_factor(mat.kind, mat.params, model.curves, 0)
        relaxed = volumetric_step_factor(mat.kind, mat.params, model.curves, k)
        print(f"{name:34s} {ours:14.4e} {ref:16.4e} {ours / ref:7.3f} {k:2d} "
              f"{ours / ref * lone / relaxed:19.3f}")


def wave_speed(mat, model) -> float:  # noqa: ANN001 - MaterialDef, Model
    """Dilatational wave speed at rest (mm/ms) of an elastic or MAT_181 material."""
    p = mat.params
    if mat.kind == "elastic":
        e, nu = p["E"], p["PR"]
        k, g = e / (3.0 * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))
    else:
        curve = model.curves[int(p["LCID"])]
        sgl = p.get("SGL", 1.0) or 1.0
        area = (p.get("SW", 1.0) or 1.0) * (p.get("ST", 1.0) or 1.0)
        strain, stress = curve.x / sgl, curve.y / area
        g = max(float(np.interp(0.0, strain, np.gradient(stress, strain))), 0.0) / 3.0
        k = p["KM"]
    return float(np.sqrt((k + 4.0 * g / 3.0) / mat.density))


if __name__ == "__main__":
    main()
