"""A run's d3plot (LS-PrePost): what of the State goes into each d3plot state.

:func:`make_series` builds the geometry of the d3plot from the Model (solid
and shell elements of every part, rigid ones included, part titles);
:func:`state_fields` takes one state from the run's State and element
runtimes: solid stress (global, GPa) and alive flags; shell stress at the
inner, middle and outer layer (the first, middle and last through-thickness
point; global axes, GPa), plastic strain per layer, thickness, alive flags;
global energies; beams: axial force, shear forces, torsion and bending moments
(the section resultants), alive flags. Rigid parts have no runtime: zero stress,
alive. Discrete elements are not written.
Written through :mod:`hollowbody.io.results.d3plot` (optional extra lasso-python).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hollowbody.io.results.d3plot import D3plotSeries, Geometry, StateFields
from hollowbody.solver.energies import energies

FILE_NAME = "d3plot"


def make_series(out: Path, model, asm) -> D3plotSeries:  # noqa: ANN001 - Model, Assembly
    """The d3plot series of a run writing into folder ``out``."""
    pids = np.array(sorted(model.parts), dtype=np.int64)
    index = {int(p): k for k, p in enumerate(pids)}

    def block(groups: list, width: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if not groups:
            return (np.zeros((0, width), np.int64), np.zeros(0, np.int64),
                    np.zeros(0, np.int64))
        return (np.concatenate([g.conn for g in groups]).astype(np.int64),
                np.concatenate([np.full(g.conn.shape[0], index[g.pid]) for g in groups]),
                np.concatenate([g.elem_ids for g in groups]).astype(np.int64))

    sc, sp, si = block(model.solid_groups, 8)
    hc, hp, hi = block(model.shell_groups, 4)
    beams = [g for g in model.beam_groups if g.conn.shape[0]]
    bc = bp = bi = None
    if beams:
        bc = np.concatenate([g.conn for g in beams]).astype(np.int64)
        bc[:, 2] = np.where(bc[:, 2] >= 0, bc[:, 2], bc[:, 1])  # no N3: N2, as LS-DYNA
        bp = np.concatenate([np.full(g.conn.shape[0], index[g.pid]) for g in beams])
        bi = np.concatenate([g.elem_ids for g in beams]).astype(np.int64)
    geometry = Geometry(node_ids=model.node_ids, x0=asm.node_x0, solid_conn=sc, solid_part=sp,
                        solid_ids=si, shell_conn=hc, shell_part=hp, shell_ids=hi,
                        part_ids=pids,
                        part_titles=[model.parts[int(p)].title or f"part {p}" for p in pids],
                        beam_conn=bc, beam_part=bp, beam_ids=bi)
    return D3plotSeries(Path(out) / FILE_NAME, geometry)


def shell_frames(conn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(e, 3, 3) rows e1, e2, e3 of the Belytschko-Tsay co-rotational frame (e3 along
    r31 x r42, e1 the bisector of the diagonal directions; see
    :mod:`hollowbody.elements.shell_bt_kinematics`) of shells conn (e, 4) at x (n, 3) mm."""
    xe = x[conn]
    r31, r42 = xe[:, 2] - xe[:, 0], xe[:, 3] - xe[:, 1]
    e3 = np.cross(r31, r42)
    e3 /= np.maximum(np.linalg.norm(e3, axis=1), 1e-300)[:, None]
    s = (r31 / np.maximum(np.linalg.norm(r31, axis=1), 1e-300)[:, None]
         - r42 / np.maximum(np.linalg.norm(r42, axis=1), 1e-300)[:, None])
    s -= np.einsum("ij,ij->i", s, e3)[:, None] * e3
    e1 = s / np.maximum(np.linalg.norm(s, axis=1), 1e-300)[:, None]
    return np.stack([e1, np.cross(e3, e1), e3], axis=1)


def _shell_layers(rt, conn: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:  # noqa: ANN001
    """(e, 3, 6) global stress (GPa) and (e, 3) plastic strain at the inner, middle and
    outer layer: the first, middle and last through-thickness point."""
    e = conn.shape[0]
    stress = np.zeros((e, 3, 6))
    eps = np.zeros((e, 3))
    if rt is None:
        return stress, eps
    sig = np.asarray(rt.sig)  # (e, nip, 3) local xx, yy, xy
    nip = sig.shape[1]
    pick = [0, nip // 2, nip - 1]
    loc = np.zeros((e, 3, 3, 3))
    loc[:, :, 0, 0] = sig[:, pick, 0]
    loc[:, :, 1, 1] = sig[:, pick, 1]
    loc[:, :, 0, 1] = loc[:, :, 1, 0] = sig[:, pick, 2]
    tau = np.asarray(rt.tau)  # (e, 2) transverse shear xz, yz
    loc[:, :, 0, 2] = loc[:, :, 2, 0] = tau[:, None, 0]
    loc[:, :, 1, 2] = loc[:, :, 2, 1] = tau[:, None, 1]
    r = shell_frames(conn, x)[:, None]  # rows e1 e2 e3: global = R^T S R
    glob = np.swapaxes(r, 2, 3) @ loc @ r
    stress[:] = glob[:, :, [0, 1, 2, 0, 1, 2], [0, 1, 2, 1, 2, 0]]
    eps[:] = np.asarray(rt.epsp)[:, pick]
    return stress, eps


def state_fields(model, asm, state) -> StateFields:  # noqa: ANN001 - Model, Assembly, State
    """The d3plot state of ``state`` (see the module docstring)."""
    runtimes = {rt.pid: rt for rt in asm.elements}
    s_stress, s_eps, s_alive = [], [], []
    for g in model.solid_groups:
        e = g.conn.shape[0]
        rt = runtimes.get(g.pid)
        s_stress.append(np.asarray(rt.stress) if rt is not None else np.zeros((e, 6)))
        eps = getattr(rt, "plastic_strain", None)
        s_eps.append(np.asarray(eps) if eps is not None and np.shape(eps) == (e,)
                     else np.zeros(e))
        s_alive.append(np.asarray(rt.alive) if rt is not None else np.ones(e, bool))
    h_stress, h_eps, h_thick, h_alive = [], [], [], []
    for g in model.shell_groups:
        e = g.conn.shape[0]
        rt = runtimes.get(g.pid)
        stress, eps = _shell_layers(rt, g.conn, state.x)
        h_stress.append(stress)
        h_eps.append(eps)
        thick = getattr(rt, "thickness", None)
        h_thick.append(np.asarray(thick) if thick is not None and np.shape(thick) == (e,)
                       else g.thickness.mean(axis=1))
        h_alive.append(np.asarray(rt.alive) if rt is not None else np.ones(e, bool))

    def cat(parts: list, shape: tuple[int, ...]) -> np.ndarray:
        return np.concatenate(parts) if parts else np.zeros(shape)

    beam_rts = [rt for rt in asm.elements if getattr(rt, "family", "") == "beams"]
    by_pid = {rt.pid: rt for rt in beam_rts}
    beams = [g for g in model.beam_groups if g.conn.shape[0]]
    b_res = b_alive = None
    if beams:  # the beam runtimes' order may differ from the Model's groups
        b_res = np.concatenate([by_pid[g.pid].resultants for g in beams])
        b_alive = np.concatenate([by_pid[g.pid].alive for g in beams])
    en = energies(asm, state)
    return StateFields(t=state.t, x=state.x, v=state.v,
                       solid_stress=cat(s_stress, (0, 6)), solid_eps=cat(s_eps, (0,)),
                       solid_alive=cat(s_alive, (0,)), shell_stress=cat(h_stress, (0, 3, 6)),
                       shell_eps=cat(h_eps, (0, 3)), shell_thickness=cat(h_thick, (0,)),
                       shell_alive=cat(h_alive, (0,)), kinetic=en["kinetic"],
                       internal=en["internal"] + en["hourglass"], total=en["total"],
                       beam_resultants=b_res, beam_alive=b_alive)
