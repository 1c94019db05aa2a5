"""Mass properties of the pedestrian, segment by segment, against de Leva's targets.

Per de Leva segment (sides separate): mass (kg), centre of mass (mm, global)
and the moments of inertia about the centre of mass (kg*mm^2) about the
segment's sagittal (x, anterior-posterior), transverse (y, medio-lateral) and
longitudinal (z) axes, for the target (de Leva's table scaled, the centre of
mass on the line between the model's landmarks) and the model as the solver
moves it (element masses lumped at their nodes; rigid parts with *PART_INERTIA
by their given values: :mod:`hollowbody.body.inertia_fit`). The foot's
longitudinal axis is x (heel to toe): its target is
(longitudinal, transverse, sagittal) about (x, y, z), and its target centre of
mass is lifted to half the foot's height (de Leva's HEEL-TTIP line is on the
floor here).
"""

from __future__ import annotations

import numpy as np

from hollowbody.body.pedestrian import Body

#: Segment -> (proximal landmark, distal landmark) of de Leva's centre of mass.
COM_LINE = {"head": ("VERT", "CERV"), "upper_trunk": ("CERV", "XYPH"),
            "middle_trunk": ("XYPH", "OMPH"), "lower_trunk": ("OMPH", "MIDH"),
            "upper_arm": ("SJC", "EJC"), "forearm": ("EJC", "WJC"), "hand": ("WJC", "MET3"),
            "thigh": ("HJC", "KJC"), "shank": ("KJC", "AJC"), "foot": ("HEEL", "TTIP")}


def _base(label: str) -> tuple[str, str]:
    if label[-2:] in ("_l", "_r"):
        return label[:-2], label[-1]
    return label, ""


def _frame(body: Body, label: str) -> np.ndarray:
    base, side = _base(label)
    fr = body.skeleton.frames
    if side and f"{base}_{side}" in fr:
        return fr[f"{base}_{side}"]
    return fr["trunk"] if base.endswith("trunk") else fr.get(base, np.eye(3))


def segment_properties(body: Body) -> dict[str, dict]:
    """Model mass, centre of mass and inertia (segment axes) per segment label, counted as
    the solver moves them (:func:`hollowbody.body.inertia_fit.segment_properties`)."""
    from hollowbody.body.inertia_fit import segment_properties as props

    out = {}
    for label, v in props(body).items():
        fr = _frame(body, label)
        out[label] = {"mass": v["mass"], "com": v["com"],
                      "inertia": np.diag(fr @ v["tensor"] @ fr.T).copy()}
    return out


def targets(body: Body) -> dict[str, dict]:
    """de Leva's mass, centre of mass and inertia per segment label of the model."""
    sk = body.skeleton
    out = {}
    labels = ["head", "upper_trunk", "middle_trunk", "lower_trunk"] + [
        f"{s}_{side}" for side in ("l", "r")
        for s in ("upper_arm", "forearm", "hand", "thigh", "shank", "foot")]
    for label in labels:
        base, side = _base(label)
        seg = sk.segments[base]
        a, b = COM_LINE[base]
        pa = sk.point(f"{a}_{side}" if side else a)
        pb = sk.point(f"{b}_{side}" if side else b)
        com = pa + (pb - pa) * seg.com / seg.length
        inertia = np.array(seg.inertia)
        if base == "foot":
            ajc = sk.point(f"AJC_{side}")
            com = com + np.array([0.0, 0.0, 0.5 * (ajc[2] - pa[2] - 6.0)])
            inertia = inertia[::-1].copy()
        out[label] = {"mass": seg.mass, "com": com, "inertia": inertia}
    return out


def mass_table(body: Body) -> list[dict]:
    """Rows: segment, target and model mass (kg), their error (%), the distance between
    the centres of mass (mm), target and model inertia (kg mm^2, x y z)."""
    t = targets(body)
    m = segment_properties(body)
    rows = []
    for label, tv in t.items():
        mv = m.get(label, {"mass": 0.0, "com": np.full(3, np.nan),
                           "inertia": np.full(3, np.nan)})
        rows.append({
            "segment": label, "target_kg": tv["mass"], "model_kg": mv["mass"],
            "mass_error_pct": 100.0 * (mv["mass"] / tv["mass"] - 1.0),
            "target_com_mm": tv["com"].round(1).tolist(),
            "model_com_mm": np.asarray(mv["com"]).round(1).tolist(),
            "com_offset_mm": float(np.linalg.norm(mv["com"] - tv["com"])),
            "target_inertia": tv["inertia"].round(0).tolist(),
            "model_inertia": np.asarray(mv["inertia"]).round(0).tolist(),
        })
    return rows
