"""Deck -> Model for joints: *DEFINE_COORDINATE_NODES / _SYSTEM, *CONSTRAINED_JOINT_*,
*CONSTRAINED_JOINT_STIFFNESS_*, *DATABASE_JNTFORC (docs/joints.md).

What is checked here (DeckError at the card): nodes, curves and coordinate
systems exist; each joint has the nodes its type needs; the node pairs the
joint holds together are coincident within :data:`COINCIDENCE_TOL` of the
model's size; axes have a length; a universal joint's arms are perpendicular.
Which rigid body each joint node is on (and that a pair joins two different
bodies) is checked when the run is set up, where the rigid bodies (parts,
merges, nodal rigid bodies) are known: :mod:`hollowbody.solver.joints`.
"""

from __future__ import annotations

import numpy as np

from hollowbody.build.common import item_error, or_default
from hollowbody.io.keyword import (
    JOINT_TYPES,
    ConstrainedJoint,
    DatabaseAscii,
    DefineCoordinateNodes,
    DefineCoordinateSystem,
    JointStiffnessFlexionTorsion,
    JointStiffnessGeneralized,
)
from hollowbody.model.joints import (
    JOINT_NODE_COUNT,
    JOINT_PAIRS,
    CoordinateSystem,
    Joint,
    JointStiffness,
    axes_from_points,
)
from hollowbody.model.model import Model

#: Largest distance between the two nodes of a pair, relative to the diagonal of
#: the model's bounding box (1e-4: 0.17 mm for a 1.75 m body), and never below
#: :data:`COINCIDENCE_FLOOR` mm.
COINCIDENCE_TOL = 1.0e-4
COINCIDENCE_FLOOR = 1.0e-6
#: Largest |cos| of the angle between a universal joint's arms N1->N3 and N2->N4.
UNIVERSAL_COS_TOL = 1.0e-2
_DIRS = {"X": 0, "Y": 1, "Z": 2}


def build(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """Fill ``coordinate_systems``, ``joints``, ``joint_stiffness`` and the JNTFORC
    interval from the deck held by ``b``."""
    _coordinate_systems(b, model)
    _joints(b, model)
    _stiffnesses(b, model)
    for d in b.of(DatabaseAscii):
        if d.name.upper() == "JNTFORC":
            model.output.intervals["jntforc"] = d.dt


def _coordinate_systems(b, model: Model) -> None:  # noqa: ANN001
    x0 = model.node_x0
    for it in b.of(DefineCoordinateNodes):
        if it.cid in model.coordinate_systems:
            raise item_error(it, f"coordinate system {it.cid} is defined twice")
        if it.dir not in _DIRS:
            raise item_error(it, f"DIR={it.dir!r}: must be X, Y or Z")
        if it.flag not in (0, 1):
            raise item_error(it, f"FLAG={it.flag}: must be 0 or 1")
        nodes = b.node_list(np.array([it.n1, it.n2, it.n3]), it, f"coordinate system {it.cid}")
        try:
            axes = axes_from_points(x0[nodes[0]], x0[nodes[1]], x0[nodes[2]], _DIRS[it.dir])
        except ValueError as exc:
            raise item_error(it, f"coordinate system {it.cid}: nodes {it.n1}, {it.n2}, "
                             f"{it.n3} do not define axes ({exc})") from None
        model.coordinate_systems[it.cid] = CoordinateSystem(
            cid=it.cid, axes=axes, origin=x0[nodes[0]].copy(), nodes=nodes,
            dir=_DIRS[it.dir], follow=it.flag == 1, keyword="DEFINE_COORDINATE_NODES",
            source=it.source)
    for it in b.of(DefineCoordinateSystem):
        if it.cid in model.coordinate_systems:
            raise item_error(it, f"coordinate system {it.cid} is defined twice")
        if it.cidl:
            raise item_error(it, f"CIDL={it.cidl}: points given in another local system "
                             "are not supported (give them in global coordinates)")
        o = np.array([it.xo, it.yo, it.zo])
        try:
            axes = axes_from_points(o, np.array([it.xl, it.yl, it.zl]),
                                    np.array([it.xp, it.yp, it.zp]), 0)
        except ValueError as exc:
            raise item_error(it, f"coordinate system {it.cid}: O, L, P do not define axes "
                             f"({exc})") from None
        model.coordinate_systems[it.cid] = CoordinateSystem(
            cid=it.cid, axes=axes, origin=o, keyword="DEFINE_COORDINATE_SYSTEM",
            source=it.source)


def _tolerance(model: Model) -> float:
    """mm: the largest gap allowed between the two nodes of a joint pair."""
    x = model.node_x0
    diag = float(np.linalg.norm(x.max(axis=0) - x.min(axis=0))) if x.size else 0.0
    return max(COINCIDENCE_TOL * diag, COINCIDENCE_FLOOR)


def _joints(b, model: Model) -> None:  # noqa: ANN001
    x0 = model.node_x0
    tol = _tolerance(model)
    seen: dict[int, ConstrainedJoint] = {}
    for k, it in enumerate(b.of(ConstrainedJoint)):
        kind = it.kind
        if kind not in JOINT_TYPES:
            raise item_error(it, f"joint type {kind} is not supported")
        jid = it.jid if it.jid else k + 1
        if jid in seen:
            raise item_error(it, f"joint id {jid} is used twice")
        seen[jid] = it
        need = JOINT_NODE_COUNT[kind]
        given = it.nodes()[:need]
        for j, nid in enumerate(given):
            if nid <= 0:
                raise item_error(it, f"{kind} joint {jid}: N{j + 1} is required "
                                 f"({kind} joints use N1..N{need})")
        nodes = b.node_list(np.array(given, dtype=np.int64), it, f"joint {jid}")
        for a, c, _full in JOINT_PAIRS[kind]:
            gap = float(np.linalg.norm(x0[nodes[a]] - x0[nodes[c]]))
            if gap > tol:
                raise item_error(it, f"{kind} joint {jid}: nodes N{a + 1}={given[a]} and "
                                 f"N{c + 1}={given[c]} are {gap:.4g} mm apart; they must "
                                 f"coincide (within {tol:.3g} mm)")
        if need >= 4:
            axis = x0[nodes[2]] - x0[nodes[0]]
            if float(np.linalg.norm(axis)) <= tol:
                raise item_error(it, f"{kind} joint {jid}: N1={given[0]} and N3={given[2]} "
                                 "coincide; they must define the joint's axis")
        if kind == "TRANSLATIONAL":
            u = (x0[nodes[2]] - x0[nodes[0]]) / np.linalg.norm(x0[nodes[2]] - x0[nodes[0]])
            r = x0[nodes[4]] - x0[nodes[0]]
            if float(np.linalg.norm(r - (r @ u) * u)) <= tol:
                raise item_error(it, f"TRANSLATIONAL joint {jid}: N5={given[4]} is on the "
                                 "axis N1-N3; it must lie off the axis")
        if kind == "UNIVERSAL":
            a1 = x0[nodes[2]] - x0[nodes[0]]
            a2 = x0[nodes[3]] - x0[nodes[1]]
            n2 = float(np.linalg.norm(a2))
            if n2 <= tol:
                raise item_error(it, f"UNIVERSAL joint {jid}: N2={given[1]} and "
                                 f"N4={given[3]} coincide; they must define body B's arm")
            cos = float(a1 @ a2) / (float(np.linalg.norm(a1)) * n2)
            if abs(cos) > UNIVERSAL_COS_TOL:
                raise item_error(it, f"UNIVERSAL joint {jid}: the arms N1->N3 and N2->N4 "
                                 f"must be perpendicular (cos = {cos:.3g})")
        model.joints.append(Joint(
            jid=jid, kind=kind, nodes=nodes, rps=or_default(it.rps, 1.0),
            damp=0.0 if 0.0 < it.damp <= 0.01 else or_default(it.damp, 1.0),
            heading=it.heading, keyword=it.keyword_line().lstrip("*"), source=it.source))


def _curve(model: Model, item, lcid: int, what: str) -> int:  # noqa: ANN001
    if lcid and lcid not in model.curves:
        raise item_error(item, f"{what}={lcid}: curve {lcid} is not defined")
    return int(lcid)


def _stop(deg: float, sign: float) -> float:
    """Stop angle (rad, signed) of a card value in degrees; nan when 0 (no stop)."""
    return sign * np.radians(abs(deg)) if deg else np.nan


def _stiffnesses(b, model: Model) -> None:  # noqa: ANN001
    jids = {j.jid for j in model.joints}
    seen: set[int] = set()
    items = [*b.of(JointStiffnessGeneralized), *b.of(JointStiffnessFlexionTorsion)]
    for it in items:
        gen = isinstance(it, JointStiffnessGeneralized)
        kind = "GENERALIZED" if gen else "FLEXION-TORSION"
        if it.jsid in seen:
            raise item_error(it, f"joint stiffness id {it.jsid} is used twice")
        seen.add(it.jsid)
        if it.pida == it.pidb:
            raise item_error(it, f"joint stiffness {it.jsid}: PIDA and PIDB are both "
                             f"{it.pida}; they must be two rigid bodies")
        for name, cid in (("CIDA", it.cida), ("CIDB", it.cidb)):
            if name == "CIDA" and not cid:
                raise item_error(it, f"joint stiffness {it.jsid}: CIDA is required")
            if cid and cid not in model.coordinate_systems:
                raise item_error(it, f"joint stiffness {it.jsid}: {name}={cid}: coordinate "
                                 "system not defined")
        if it.jid and it.jid not in jids:
            raise item_error(it, f"joint stiffness {it.jsid}: JID={it.jid}: joint not "
                             "defined")
        if gen:
            names = (("LCIDPH", it.lcidph), ("LCIDT", it.lcidt), ("LCIDPS", it.lcidps))
            dnames = (("DLCIDPH", it.dlcidph), ("DLCIDT", it.dlcidt), ("DLCIDPS", it.dlcidps))
            es = (it.esph, it.est, it.esps)
            fm = (it.fmph, it.fmt, it.fmps)
            neg = (it.nsaph, it.nsat, it.nsaps)
            pos = (it.psaph, it.psat, it.psaps)
            lcg = dlcg = 0
        else:
            names = (("LCIDAL", it.lcidal), ("-", 0), ("LCIDBT", it.lcidbt))
            dnames = (("DLCIDAL", it.dlcidal), ("-", 0), ("DLCIDBT", it.dlcidbt))
            es = (it.esal, 0.0, it.esbt)
            fm = (it.fmal, 0.0, it.fmbt)
            neg = (0.0, 0.0, it.nsabt)
            pos = (it.saal, 0.0, it.psabt)
            lcg = _curve(model, it, it.lcidg, "LCIDG")
            if it.dlcidg:
                raise item_error(it, f"joint stiffness {it.jsid}: DLCIDG={it.dlcidg} (a scale "
                                 "factor on the alpha damping) is not supported")
            dlcg = 0
        for name, v in zip(("ES", "ES", "ES"), es):
            if v < 0.0:
                raise item_error(it, f"joint stiffness {it.jsid}: {name} must not be negative")
        if any(v < 0.0 for v in fm):
            raise item_error(it, f"joint stiffness {it.jsid}: a negative friction moment (a "
                             "curve of friction against angle) is not supported")
        model.joint_stiffness.append(JointStiffness(
            jsid=it.jsid, kind=kind, pida=it.pida, pidb=it.pidb, cida=it.cida,
            cidb=it.cidb or it.cida, jid=it.jid,
            lc=np.array([_curve(model, it, v, n) for n, v in names], dtype=np.int64),
            dlc=np.array([_curve(model, it, v, n) for n, v in dnames], dtype=np.int64),
            es=np.array(es, float), fm=np.array(fm, float),
            neg_stop=np.array([_stop(v, -1.0) for v in neg]),
            pos_stop=np.array([_stop(v, 1.0) for v in pos]),
            lc_gamma=lcg, dlc_gamma=dlcg, keyword="CONSTRAINED_JOINT_STIFFNESS_" + kind,
            source=it.source))
