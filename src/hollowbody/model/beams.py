"""Beam elements of the Model (*ELEMENT_BEAM with *SECTION_BEAM; docs/beams.md).

A :class:`BeamGroup` holds the beams of one part. The beam's local frame
(r, s, t): r from N1 to N2; s in the plane of N1, N2 and the orientation node
N3, normal to r, on N3's side; t = r x s. Without N3 the s axis is the global
axis least aligned with r, made normal to r (the axis with the smallest
``|r . e_i|``, ties going to Y, then X: global Y for beams along X or Z,
global X for beams along Y) - a fixed, documented default: give N3 where the
section is not symmetric.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: An orientation node closer to the beam's axis than this fraction of the beam
#: length (its distance from the N1-N2 line) is collinear.
COLLINEAR_TOL = 1.0e-6


@dataclass
class BeamGroup:
    """Beams of one part.

    elem_ids: (e,) int64 LS-DYNA ids; conn: (e, 3) int32 node indices N1, N2 and
    the orientation node N3 (-1 where the card has none). rule: (p, 3) float64
    user integration points of the section (*INTEGRATION_BEAM: S and T in
    [-1, 1], fractions of the half widths TS / 2 and TT / 2, and WF x RA, the
    point's area as a fraction of TS TT), or None for the section's QR rule.
    """

    pid: int
    elem_ids: np.ndarray  # (e,) int64
    conn: np.ndarray  # (e, 3) int32
    rule: np.ndarray | None = None


def default_reference(axis: np.ndarray) -> np.ndarray:
    """(e, 3) global unit axes least aligned with the unit vectors ``axis`` (e, 3)."""
    k = np.argmin(np.abs(axis) + np.array([1e-9, 0.0, 2e-9]), axis=1)
    # ties broken towards Y, then X, then Z (beams along X get Y, along Z get Y)
    out = np.zeros_like(axis)
    out[np.arange(axis.shape[0]), k] = 1.0
    return out


def beam_frames(conn: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Local frames of beams from N1, N2 and N3 (or the default reference axis).

    conn: (e, 3) int node indices (N3 = -1 for none); x: (n, 3) mm. Returns
    ``frames`` (e, 3, 3) with rows r, s, t (unit), ``length`` (e,) mm and
    ``bad`` (e,) bool: N3 collinear with N1-N2 (distance from the axis below
    :data:`COLLINEAR_TOL` times the length) or a zero length.
    """
    x1, x2 = x[conn[:, 0]], x[conn[:, 1]]
    d = x2 - x1
    length = np.linalg.norm(d, axis=1)
    r = d / np.where(length > 0.0, length, 1.0)[:, None]
    has3 = conn[:, 2] >= 0
    ref = default_reference(r)
    ref[has3] = x[conn[has3, 2]] - x1[has3]
    s = ref - np.einsum("ij,ij->i", ref, r)[:, None] * r
    ns = np.linalg.norm(s, axis=1)
    bad = (length <= 0.0) | (ns <= COLLINEAR_TOL * np.maximum(length, 1e-300))
    s = s / np.where(ns > 0.0, ns, 1.0)[:, None]
    t = np.cross(r, s)
    return np.stack([r, s, t], axis=1), length, bad


def section_constants(elform: int, params: dict[str, float]
                      ) -> tuple[float, float, float, float]:
    """(A mm^2, ISS, ITT, J mm^4) of a beam section (SectionDef params, LS-DYNA names).

    ELFORM 2: the card's A, ISS, ITT, J. ELFORM 1: exact for the shape from the
    mean of the nodes' dimensions: rectangle TS x TT (ISS = TS TT^3 / 12 about
    s, ITT = TT TS^3 / 12), tube (CST 1) of outer / inner diameter TS / TT;
    J is the polar moment ISS + ITT (what the integrated torsion uses).
    """
    if elform == 2:
        return params["A"], params["ISS"], params["ITT"], params["J"]
    ts = 0.5 * (params["TS1"] + params["TS2"])
    tt = 0.5 * (params["TT1"] + params["TT2"])
    if int(params.get("CST", 0)) == 1:
        i = math.pi * (ts ** 4 - tt ** 4) / 64.0
        return 0.25 * math.pi * (ts * ts - tt * tt), i, i, 2.0 * i
    ra = float(params.get("RA", 1.0))  # a user rule's relative area (*INTEGRATION_BEAM)
    iss = ra * ts * tt ** 3 / 12.0
    itt = ra * tt * ts ** 3 / 12.0
    return ra * ts * tt, iss, itt, iss + itt


def beam_masses(group: BeamGroup, rho: float, section_elform: int,
                params: dict[str, float], x0: np.ndarray) -> np.ndarray:
    """(e,) kg: rho A L0 + NSM L0 of each beam (x0 (n, 3) mm)."""
    area = section_constants(section_elform, params)[0]
    c = group.conn
    length = np.linalg.norm(x0[c[:, 1]] - x0[c[:, 0]], axis=1)
    return (rho * area + float(params.get("NSM", 0.0))) * length
