"""Segment inertias fitted to de Leva's by inertia carriers merged into the rigid parts.

The solver moves lumped nodal masses (each element's mass spread equally on
its nodes; a rigid body moves its nodes' masses, so the deformable elements'
shares on its nodes go with it) and rigid parts with *PART_INERTIA by their
given values. :func:`segment_properties` counts the model that way.

:func:`fit_inertias` moves the fill mass of each rigid body of a trunk third
or limb segment (the spine zones, the pelvis, the limb epiphyses: what the
segment's flesh leaves of de Leva's mass, :func:`hollowbody.body.pedestrian._fill_rigid`)
from the rigid shell (which keeps a negligible density) into an *inertia
carrier*: a small closed rigid shell at the centre of the fill (the shell's
area centroid), merged into the rigid body by *CONSTRAINED_RIGID_BODIES, with
*PART_INERTIA: the fill's mass at the fill's centre (so segment masses and
centres of mass do not change) and an own inertia chosen so that the
segment's moments about its sagittal, transverse and longitudinal axes are
de Leva's: own = target - (nodal masses and carriers' parallel-axis terms),
shared among the segment's carriers by mass. Each own inertia is kept
physical: at least ``FLOOR`` of what the fill had on its shell, per axis, and
each moment at most the sum of the other two (raising the other two where
needed), so where the flesh alone exceeds the target, or the longitudinal
deficit is large, the fit is not exact (the report shows target and model).

What the carriers hold stands for the mass distribution the simple geometry
lacks (no shoulder girdle on the upper trunk, limb flesh rounder and more
slender than a real limb): a mass-property device, not anatomy. Units: kg,
mm, kg*mm^2.
"""

from __future__ import annotations

import numpy as np

from hollowbody.body.pedestrian import LIMBS, Body, element_masses, part_density

#: Lower bound of a carrier's own inertia: this fraction of the fill's on its shell.
FLOOR = 0.05
#: Density (kg/mm^3) left on a rigid shell whose fill went to its carrier.
EMPTY_DENSITY = 1.0e-12
#: Half edge (mm) of a carrier's box.
CARRIER_SIZE = 1.0
#: Trunk third -> keys of its rigid parts that get a carrier.
TRUNK_RIGID = {"upper_trunk": ("trunk_spine_T1", "trunk_spine_T8"),
               "middle_trunk": ("trunk_spine_T12", "trunk_spine_L3"),
               "lower_trunk": ("trunk_pelvis", "trunk_spine_sacrum")}


def rigid_groups(body: Body) -> dict[str, tuple[str, ...]]:
    """Segment label -> keys of its rigid parts that carry fill mass."""
    out = dict(TRUNK_RIGID)
    for side in ("l", "r"):
        for s in LIMBS:
            out[f"{s}_{side}"] = (f"{s}_{side}_proximal", f"{s}_{side}_distal")
    return {k: v for k, v in out.items() if all(p in body.parts for p in v)}


def _shift(d: np.ndarray) -> np.ndarray:
    return float(d @ d) * np.eye(3) - np.outer(d, d)


def _points_tensor(m: np.ndarray, x: np.ndarray, c: np.ndarray) -> np.ndarray:
    d = x - c
    return np.einsum("e,eij->ij", m, np.einsum("ek,ek->e", d, d)[:, None, None] * np.eye(3)
                     - d[:, :, None] * d[:, None, :])


def nodal_masses(body: Body) -> dict[str, np.ndarray]:
    """Segment label -> (n,) kg: the lumped nodal masses of the segment's elements (parts
    without *PART_INERTIA)."""
    x = body.mesh.coords()
    out: dict[str, np.ndarray] = {}
    for p in body.mesh.parts:
        if p.inertia is not None:
            continue
        m, _ = element_masses(x, p, part_density(body, p))
        k = p.conn.shape[1]
        for s in np.unique(p.segment):
            sel = p.segment == s
            arr = out.setdefault(s, np.zeros(x.shape[0]))
            np.add.at(arr, p.conn[sel].ravel(), np.repeat(m[sel] / k, k))
    return out


def segment_properties(body: Body) -> dict[str, dict]:
    """Mass (kg), centre of mass (3,) mm and inertia tensor (3, 3) kg*mm^2 (global axes,
    about the centre) per segment label, as the solver moves them: lumped nodal masses
    as point masses, parts with *PART_INERTIA by their given values."""
    x = body.mesh.coords()
    nm = nodal_masses(body)
    given: dict[str, list] = {}
    for p in body.mesh.parts:
        if p.inertia is not None:
            given.setdefault(str(p.segment[0]), []).append(p.inertia)
    out = {}
    for label in sorted(set(nm) | set(given)):
        ms, cs = [], []
        if label in nm:
            sel = np.flatnonzero(nm[label] > 0.0)
            ms.append(nm[label][sel])
            cs.append(x[sel])
        for m, c, _ in given.get(label, []):
            ms.append(np.array([m]))
            cs.append(np.asarray(c, float)[None, :])
        mm, cc = np.concatenate(ms), np.vstack(cs)
        total = float(mm.sum())
        com = (mm[:, None] * cc).sum(axis=0) / total
        tensor = _points_tensor(mm, cc, com) + sum(
            (np.asarray(i, float) for _, _, i in given.get(label, [])), np.zeros((3, 3)))
        out[label] = {"mass": total, "com": com, "tensor": tensor}
    return out


def _physical(own: np.ndarray) -> np.ndarray:
    """Raise moments (3,) so that each is at most the sum of the other two."""
    own = own.copy()
    for _ in range(3):
        for i in range(3):
            j, k = (i + 1) % 3, (i + 2) % 3
            gap = own[i] - own[j] - own[k]
            if gap > 0.0:
                own[j] += 0.5 * gap
                own[k] += 0.5 * gap
    return own


def fit_inertias(body: Body, targets: dict[str, np.ndarray],
                 frames: dict[str, np.ndarray]) -> dict[str, dict]:
    """Move each fill into an inertia carrier (module docstring) so the segment's moments
    about its axes (``frames[label]``, rows x, y, z) approach ``targets[label]`` (3,)
    kg*mm^2. Adds the carrier parts (key ``<rigid key>_carrier``) and records the
    merges in ``body.carriers`` (rigid pid -> carrier pid). Returns per label the
    moments before (fill on the shells) and after."""
    from hollowbody.body import anatomy as an

    x = body.mesh.coords()
    before = segment_properties(body)
    report = {}
    for label, keys in rigid_groups(body).items():
        fr = frames[label]
        fills = []
        for key in keys:
            part = body.parts[key]
            m, c = element_masses(x, part, part_density(body, part))
            fm = float(m.sum())
            centre = (m[:, None] * c).sum(axis=0) / fm
            fills.append((key, fm, centre, np.diag(fr @ _points_tensor(m, c, centre) @ fr.T)))
            body.rigid_density[part.pid] = EMPTY_DENSITY
        nm = nodal_masses(body)[label]
        sel = np.flatnonzero(nm > 0.0)
        mass = float(nm[sel].sum()) + sum(f[1] for f in fills)
        com = ((nm[sel, None] * x[sel]).sum(axis=0) + sum(f[1] * f[2] for f in fills)) / mass
        rest = _points_tensor(nm[sel], x[sel], com) + sum(f[1] * _shift(f[2] - com)
                                                         for f in fills)
        rest_axes = np.diag(fr @ rest @ fr.T)
        need = np.asarray(targets[label], float) - rest_axes
        m_fill = sum(f[1] for f in fills)
        after = rest_axes.copy()
        for key, fm, centre, own0 in fills:
            own = _physical(np.maximum(need * fm / m_fill, FLOOR * own0))
            after += own
            part = body.parts[key]
            carrier = an.rigid_shell(body.mesh, f"{part.name} inertia", part.region,
                                     label, "box", centre, np.full(3, CARRIER_SIZE),
                                     np.eye(3), 1, fm, centre, fr.T @ np.diag(own) @ fr)
            body.parts[f"{key}_carrier"] = carrier
            body.carriers[part.pid] = carrier.pid
        fr_b = before[label]["tensor"]
        report[label] = {"before": np.diag(fr @ fr_b @ fr.T).copy(), "after": after}
    return report
