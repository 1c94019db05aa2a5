"""Initial velocities of a deck -> ``Model.node_v0`` / ``node_w0``.

*INITIAL_VELOCITY, then *INITIAL_VELOCITY_NODE, then
*INITIAL_VELOCITY_GENERATION (later ones override). Called by
:func:`hollowbody.build.build_model` after the body mechanics, so a part's
nodes include those of its beams and discrete elements. mm/ms, rad/ms.
"""

from __future__ import annotations

import numpy as np

from hollowbody.build.common import item_error, no_cid, node_set
from hollowbody.io.keyword import (
    InitialVelocity,
    InitialVelocityGeneration,
    InitialVelocityNode,
)
from hollowbody.model import model as m
from hollowbody.model.mass import part_nodes


def _part_nodes(model: m.Model, pids: list[int]) -> np.ndarray:
    nodes = [part_nodes(model, pid) for pid in pids]
    return np.unique(np.concatenate(nodes)).astype(np.int64) if nodes else np.zeros(0, np.int64)


def initial_velocities(b, model: m.Model) -> None:  # noqa: ANN001 - builder.Builder
    """*INITIAL_VELOCITY, then _NODE, then _GENERATION (later ones override)."""
    v0, w0, everything = model.node_v0, model.node_w0, slice(None)
    for it in b.of(InitialVelocity):
        if it.boxid:
            raise item_error(it, "BOXID is not supported")
        no_cid(it, it.icid, "ICID")
        nodes = node_set(model, it.nsid, it) if it.nsid else everything
        v0[nodes], w0[nodes] = (it.vx, it.vy, it.vz), (it.vxr, it.vyr, it.vzr)
        if it.nsidex:
            ex = node_set(model, it.nsidex, it)
            v0[ex], w0[ex] = (it.vxe, it.vye, it.vze), (it.vxre, it.vyre, it.vzre)
    for it in b.of(InitialVelocityNode):
        no_cid(it, it.icid, "ICID")
        idx = b.node_list([it.nid], it, "initial velocity")
        v0[idx], w0[idx] = (it.vx, it.vy, it.vz), (it.vxr, it.vyr, it.vzr)
    for it in b.of(InitialVelocityGeneration):
        no_cid(it, it.icid, "ICID")
        if it.id == 0:
            nodes = np.arange(model.n_nodes)
        elif it.styp == 1:
            if it.id not in model.part_sets:
                raise item_error(it, f"part set {it.id} is not defined")
            nodes = _part_nodes(model, model.part_sets[it.id])
        elif it.styp == 2:
            if it.id not in model.parts:
                raise item_error(it, f"part {it.id} is not defined")
            nodes = _part_nodes(model, [it.id])
        elif it.styp == 3:
            nodes = node_set(model, it.id, it)
        else:
            raise item_error(it, f"STYP={it.styp} is not supported (1 part set, 2 part, "
                             "3 node set)")
        v = np.broadcast_to(np.array([it.vx, it.vy, it.vz]), (nodes.size, 3))
        if it.omega:
            axis = np.array([it.nx, it.ny, it.nz])
            if not np.linalg.norm(axis):
                raise item_error(it, "OMEGA is given but the rotation axis NX, NY, NZ is zero",
                           it.source.line + 1)
            w = it.omega * axis / np.linalg.norm(axis)
            v = v + np.cross(w, model.node_x0[nodes] - np.array([it.xc, it.yc, it.zc]))
            w0[nodes] = w
        v0[nodes] = v
