"""Penalty stiffness of contact segments and nodes (LS-DYNA SOFT=0 and SOFT=1).

SOFT=0 (LS-DYNA "standard penalty formulation"), per segment, from the
element under it:

* solid face: ``k_seg = K * A^2 / V`` (A face area, V element volume),
* shell:      ``k_seg = K * A / d_max`` (A shell area, d_max longest diagonal),

K the bulk modulus of the element's material (``E / (3 (1 - 2 nu))`` for
elastic, elastic-plastic and rigid materials -- LS-DYNA asks for realistic E
and PR on *MAT_RIGID precisely because contact uses them -- ``YM`` and ``PR``
for *MAT_NULL shells, and ``KM`` for MAT_181).
A node's stiffness is the mean of the segments around it.
The kernel combines them as LS-DYNA's default penalty option (PENOPT = 1,
"minimum of master segment and slave node")::

    k0 = SLSFAC * min(SF_node * k_node, SF_seg * k_seg)

so a rigid (steel) impactor against soft tissue gets the tissue's stiffness.
When one side has no element (free segments, isolated nodes) the other
side's value is used alone.

SOFT=1 (LS-DYNA "soft constraint formulation"): ``k1 = 0.5 * m* / dtc^2``
with ``m* = min(m_node, m_seg)``, ``m_seg`` the smallest nodal mass of the
segment, rigid-body nodes left out (the deformable side's mass is used when
one side is rigid); ``dtc`` is the time step of the first contact call,
updated when the step grows by more than 5 %. The stiffness used is
``max(k0, SOFSCL * k1)``.

Set-up only (numpy).
"""

from __future__ import annotations

import numpy as np

from hollowbody.contact.surface import (
    SEG_SHELL,
    SEG_SOLID,
    Surface,
    segment_max_diagonal,
    segment_normals,
)
from hollowbody.errors import DeckError, UserInputError
from hollowbody.model.mass import hex_volumes
from hollowbody.model.model import MaterialDef, Model

#: Smallest 1 - 2 nu used for the bulk modulus (nu -> 0.5 stays finite).
_MIN_ONE_MINUS_2NU = 1.0e-2


def bulk_modulus(mat: MaterialDef) -> float:
    """Bulk modulus (GPa) used for contact stiffness of a material."""
    p = mat.params
    if mat.kind == "rubber181" or ("KM" in p and "E" not in p):
        km = float(p.get("KM", 0.0))
        if km <= 0.0:
            raise UserInputError(f"material {mat.mid}: MAT_181 needs KM > 0 for contact")
        return km
    e = float(p.get("E", 0.0))
    nu = float(p.get("PR", 0.0))
    if mat.kind == "null":  # *MAT_NULL: LS-DYNA takes the contact stiffness from YM, PR
        e = float(p.get("YM", 0.0))
        if e <= 0.0:
            raise DeckError(f"material {mat.mid}: a contact surface of *MAT_NULL needs YM > 0 "
                            "and PR (its contact stiffness)", mat.source.file,
                            mat.source.line, mat.keyword or "MAT_NULL")
    if e <= 0.0:
        raise UserInputError(
            f"material {mat.mid} ({mat.kind}): contact needs a Young's modulus E > 0 "
            "(also for rigid materials: LS-DYNA derives the contact stiffness from it)")
    return e / (3.0 * max(1.0 - 2.0 * nu, _MIN_ONE_MINUS_2NU))


def segment_stiffness(surf: Surface, model: Model, x0: np.ndarray | None = None
                      ) -> tuple[np.ndarray, np.ndarray]:
    """SOFT=0 stiffness and element depth of each segment.

    Returns k_seg (s,) kN/mm (0 where no element is known) and depth (s,) mm,
    the length scale of the release depth (solid faces: V / A of the element
    under the face; shells and free segments: sqrt(A)), both from the
    initial coordinates x0 (n, 3) mm (None: ``model.node_x0``).
    """
    x0 = model.node_x0 if x0 is None else x0
    s = surf.n_segments
    k = np.zeros(s)
    depth = np.zeros(s)
    if s == 0:
        return k, depth
    _, area = segment_normals(surf.seg, x0)
    depth[:] = np.sqrt(area)
    solid = np.nonzero(surf.seg_kind == SEG_SOLID)[0]
    for gi in np.unique(surf.seg_group[solid]):
        sel = solid[surf.seg_group[solid] == gi]
        g = model.solid_groups[int(gi)]
        kb = bulk_modulus(model.material_of(g.pid))
        vol = np.abs(hex_volumes(np.asarray(g.conn)[surf.seg_elem[sel]], x0))
        vol = np.where(vol > 0.0, vol, 1.0)
        k[sel] = kb * area[sel] ** 2 / vol
        depth[sel] = vol / np.where(area[sel] > 0.0, area[sel], 1.0)
    shell = np.nonzero(surf.seg_kind == SEG_SHELL)[0]
    if shell.size:
        dmax = segment_max_diagonal(surf.seg[shell], x0)
        for gi in np.unique(surf.seg_group[shell]):
            m = surf.seg_group[shell] == gi
            sel = shell[m]
            kb = bulk_modulus(model.material_of(model.shell_groups[int(gi)].pid))
            k[sel] = kb * area[sel] / np.where(dmax[m] > 0.0, dmax[m], 1.0)
    return k, depth


def node_stiffness(nodes: np.ndarray, seg: np.ndarray, k_seg: np.ndarray,
                   n_total: int) -> np.ndarray:
    """Mean stiffness of the segments around each node, (m,) kN/mm (0 if none)."""
    ksum = np.zeros(n_total)
    cnt = np.zeros(n_total)
    if seg.shape[0]:
        # distinct corners only (triangles: N4 == N3 counted once)
        valid = np.ones(seg.shape, dtype=bool)
        valid[:, 3] = seg[:, 3] != seg[:, 2]
        known = k_seg > 0.0
        vv = valid & known[:, None]
        np.add.at(ksum, seg[vv], np.broadcast_to(k_seg[:, None], seg.shape)[vv])
        np.add.at(cnt, seg[vv], 1.0)
    out = np.zeros(nodes.shape[0])
    c = cnt[nodes]
    out[c > 0] = ksum[nodes][c > 0] / c[c > 0]
    return out


def segment_mass(seg: np.ndarray, node_mass: np.ndarray, rigid_node: np.ndarray) -> np.ndarray:
    """Smallest deformable nodal mass of each segment (s,) kg; inf if all rigid."""
    m = np.where(rigid_node[seg], np.inf, node_mass[seg])
    return m.min(axis=1) if seg.shape[0] else np.zeros(0)


def node_effective_mass(nodes: np.ndarray, node_mass: np.ndarray,
                        rigid_node: np.ndarray) -> np.ndarray:
    """Nodal mass for SOFT=1 / damping, (m,) kg; inf for rigid-body nodes."""
    return np.where(rigid_node[nodes], np.inf, node_mass[nodes])
