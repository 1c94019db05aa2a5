"""Deck -> Model for beams: *SECTION_BEAM and *ELEMENT_BEAM (docs/beams.md)."""

from __future__ import annotations

import numpy as np

from hollowbody.build.common import item_error
from hollowbody.errors import DeckError
from hollowbody.io.keyword import ElementBeam, IntegrationBeam, SectionBeam
from hollowbody.model.beams import BeamGroup, beam_frames
from hollowbody.model.model import Model, SectionDef

#: *SECTION_BEAM ELFORM values this version runs.
SUPPORTED_ELFORM = (1, 2)
#: cross-section types of ELFORM 1 (0 rectangular, 1 tubular).
SUPPORTED_CST = (0, 1)
#: QR of ELFORM 1: points per direction of the Gauss rule (1 one point, 2 2x2,
#: 3 3x3, 5 4x4) or 3x3 Lobatto (4).
SUPPORTED_QR = (1, 2, 3, 4, 5)


def section_def(s: SectionBeam) -> SectionDef:
    """The Model's section record of a *SECTION_BEAM card (kind ``"beam"``).

    params: SHRF (blank 1.0), QR (blank 2), CST, NSM (kg/mm), and TS1 TS2 TT1
    TT2 (mm) for ELFORM 1 or A (mm^2) ISS ITT J (mm^4) SA (mm^2) for ELFORM 2
    (LS-DYNA names). Checked here: ELFORM, CST, QR and positive dimensions.
    """
    elform = int(s.elform or 1)
    if elform not in SUPPORTED_ELFORM:
        raise item_error(s, f"section {s.secid}: beam ELFORM {elform} is not supported "
                         "(ELFORM 1 Hughes-Liu-type integrated, 2 Belytschko-Schwer resultant)")
    p = {"SHRF": float(s.shrf or 1.0), "QR": float(s.qr if s.qr else 2), "CST": float(s.cst),
         "NSM": float(s.nsm)}
    if s.nsm < 0.0:
        raise item_error(s, f"section {s.secid}: NSM must be >= 0 (got {s.nsm})")
    if elform == 1:
        if int(s.cst) not in SUPPORTED_CST:
            raise item_error(s, f"section {s.secid}: CST {s.cst} is not supported (0 "
                             "rectangular, 1 tubular)")
        if int(p["QR"]) not in SUPPORTED_QR and int(p["QR"]) >= 0:
            raise item_error(s, f"section {s.secid}: QR/IRID {int(p['QR'])} is not supported "
                             "(1, 2, 3, 4 or 5, or -IRID for an *INTEGRATION_BEAM rule)")
        if int(p["QR"]) < 0 and int(s.cst) != 0:
            raise item_error(s, f"section {s.secid}: a user integration rule (QR < 0) needs a "
                             "rectangular section here (CST 0)")
        ts1, tt1 = float(s.ts1), float(s.tt1)
        ts2, tt2 = float(s.ts2 or ts1), float(s.tt2 or tt1)
        if int(s.cst) == 0 and not min(ts1, ts2, tt1, tt2) > 0.0:
            raise item_error(s, f"section {s.secid}: a rectangular section needs TS1, TT1 > 0")
        if int(s.cst) == 1:
            if not min(ts1, ts2) > 0.0:
                raise item_error(s, f"section {s.secid}: a tubular section needs the outer "
                                 "diameter TS1 > 0")
            if not (0.0 <= tt1 < ts1 and 0.0 <= tt2 < ts2):
                raise item_error(s, f"section {s.secid}: the inner diameter TT1 must be in "
                                 "[0, TS1)")
        if s.nsloc or s.ntloc:
            raise item_error(s, f"section {s.secid}: reference-surface offsets NSLOC/NTLOC "
                             "are not supported (give 0)")
        p.update(TS1=ts1, TS2=ts2, TT1=tt1, TT2=tt2)
    else:
        if not (s.a > 0.0 and s.iss > 0.0 and s.itt > 0.0 and s.j > 0.0):
            raise item_error(s, f"section {s.secid}: a resultant beam needs A, ISS, ITT and J "
                             "> 0")
        if s.sa < 0.0:
            raise item_error(s, f"section {s.secid}: SA must be >= 0")
        p.update(A=float(s.a), ISS=float(s.iss), ITT=float(s.itt), J=float(s.j),
                 SA=float(s.sa))
    return SectionDef(int(s.secid), "beam", elform, p, s.title, s.source)


def build(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """*ELEMENT_BEAM -> ``model.beam_groups`` (one group per part), vectorised over
    all rows; a DeckError names the row's file line."""
    items = b.of(ElementBeam)
    if not items:
        return
    ids = np.concatenate([it.ids for it in items])
    pids = np.concatenate([it.pids for it in items])
    conn_ids = np.concatenate([it.conn for it in items])
    rel = np.concatenate([it.releases for it in items])
    owner = np.concatenate([np.full(it.ids.size, k) for k, it in enumerate(items)])
    first = np.concatenate([[0], np.cumsum([it.ids.size for it in items])])

    def fail(r: int, message: str) -> DeckError:
        it = items[int(owner[r])]
        return item_error(it, message, it.line_of(int(r - first[owner[r]])))

    order = np.argsort(ids, kind="stable")
    dup = np.nonzero(np.diff(ids[order]) == 0)[0]
    if dup.size:
        raise fail(int(order[dup[0] + 1]), f"beam element id {ids[order[dup[0]]]} is defined "
                   "twice")
    for pid in np.unique(pids).tolist():
        r = int(np.nonzero(pids == pid)[0][0])
        part = model.parts.get(pid)
        if part is None:
            raise fail(r, f"beam element {ids[r]} refers to part {pid} which is not defined")
        sec = model.sections.get(part.secid)
        if sec is None or sec.kind != "beam":
            kind = "no section" if sec is None else f"a {sec.kind} section"
            raise fail(r, f"beam element {ids[r]}: its part {pid} has {kind} "
                       f"(section {part.secid}), not a *SECTION_BEAM")
    bad = np.nonzero(rel.any(axis=1))[0]
    if bad.size:
        raise fail(int(bad[0]), f"beam element {ids[bad[0]]}: release codes RT1/RR1/RT2/RR2 "
                   "are not supported (give 0; model a hinge with a joint instead)")
    bad = np.nonzero((conn_ids[:, 0] == 0) | (conn_ids[:, 1] == 0))[0]
    if bad.size:
        raise fail(int(bad[0]), f"beam element {ids[bad[0]]}: N1 and N2 must be given")
    bad = np.nonzero(conn_ids[:, 0] == conn_ids[:, 1])[0]
    if bad.size:
        raise fail(int(bad[0]), f"beam element {ids[bad[0]]}: N1 and N2 are the same node")
    idx, missing = b.index(conn_ids)
    missing &= conn_ids != 0
    if missing.any():
        r, k = (int(v[0]) for v in np.nonzero(missing))
        raise fail(r, f"beam element {ids[r]} refers to node {conn_ids[r, k]} which is not "
                   "defined")
    conn = np.where(conn_ids == 0, -1, idx).astype(np.int32)
    _frames, length, degenerate = beam_frames(conn, model.node_x0)
    if degenerate.any():
        r = int(np.nonzero(degenerate)[0][0])
        what = ("N1 and N2 are at the same place" if length[r] <= 0.0 else
                f"orientation node N3 {conn_ids[r, 2]} is collinear with N1-N2")
        raise fail(r, f"beam element {ids[r]}: {what}")
    rules = _user_rules(b, model)
    for pid in np.unique(pids).tolist():
        sel = np.nonzero(pids == pid)[0]
        sec = model.sections[model.parts[pid].secid]
        irid = -int(sec.params.get("QR", 2)) if sec.elform == 1 else 0
        if irid > 0 and irid not in rules:
            raise DeckError(f"section {sec.secid}: integration rule IRID {irid} "
                            "(*INTEGRATION_BEAM) is not defined", sec.source.file,
                            sec.source.line, "SECTION_BEAM")
        model.beam_groups.append(BeamGroup(pid=pid, elem_ids=ids[sel].copy(),
                                           conn=conn[sel].copy(),
                                           rule=rules[irid] if irid > 0 else None))


def _user_rules(b, model: Model) -> dict[int, np.ndarray]:  # noqa: ANN001 - builder.Builder
    """*INTEGRATION_BEAM rules by IRID: (p, 3) rows S, T (normalised), WF x RA.

    Sets ``RA`` in the params of the sections that use them (their area is
    RA TS TT). Only user-defined points (ICST 0) with no per-point part.
    """
    out: dict[int, np.ndarray] = {}
    for it in b.of(IntegrationBeam):
        if it.irid in out:
            raise item_error(it, f"integration rule IRID {it.irid} is defined twice")
        if it.icst:
            raise item_error(it, f"integration rule {it.irid}: standard sections (ICST "
                             f"{it.icst}) are not supported (give the points, ICST 0)")
        pts = np.asarray(it.points, dtype=np.float64).reshape(-1, 4)
        if pts.shape[0] == 0 or pts.shape[0] != it.nip:
            raise item_error(it, f"integration rule {it.irid}: NIP must be > 0 with one card "
                             "per point")
        if np.any(pts[:, 3] != 0):
            raise item_error(it, f"integration rule {it.irid}: a material part per point "
                             "(PID) is not supported")
        if np.any(np.abs(pts[:, :2]) > 1.0) or np.any(pts[:, 2] <= 0.0):
            raise item_error(it, f"integration rule {it.irid}: S and T must be in [-1, 1] and "
                             "WF > 0")
        ra = float(it.ra) if it.ra else 1.0
        rule = pts[:, :3].copy()
        rule[:, 2] *= ra
        out[int(it.irid)] = rule
        for sec in model.sections.values():
            if sec.kind == "beam" and sec.elform == 1 and -int(sec.params.get("QR", 2)) == it.irid:
                sec.params["RA"] = ra
    return out
