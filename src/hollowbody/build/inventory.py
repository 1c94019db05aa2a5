"""What a deck holds, counted from the keyword items without building a Model.

``hollowbody check`` prints this inventory when the deck cannot be built (a
reference to an undefined id, a duplicate, ...) or read (of the items read
before the error): the counts still tell what was read. The keys are those
of :func:`hollowbody.model.summary.summarize` for the same things (nodes,
elements by kind, parts, materials and sections by keyword, unsupported
keywords); masses, extent and time steps need a Model and are None.
"""

from __future__ import annotations

import numpy as np

from hollowbody.io.keyword import (
    Deck,
    MassElements,
    Material,
    Nodes,
    Part,
    SectionShell,
    SectionSolid,
    ShellElements,
    SolidElements,
)
from hollowbody.model.summary import by_keyword, solid_kinds, unsupported_entries


def deck_inventory(deck: Deck, missing: str = "not defined") -> dict:
    """JSON-ready counts of ``deck``'s items (see the module docstring).

    ``missing``: what a part's section or material that is not in ``deck`` is
    called (``"not read"`` for the items read before an error).
    """
    elements = {"hexahedra": 0, "wedges": 0, "tetrahedra": 0, "other_solids": 0, "shells": 0,
                "triangles": 0, "mass_elements": 0}
    count: dict[int, int] = {}
    for it in deck.of_type(SolidElements):
        for k, v in solid_kinds(np.asarray(it.conn).reshape(-1, 8)).items():
            elements[k] += v
        for pid in np.atleast_1d(it.pids).tolist():
            count[pid] = count.get(pid, 0) + 1
    for it in deck.of_type(ShellElements):
        conn = np.asarray(it.conn)
        if conn.ndim != 2 or not conn.size:
            continue
        tri = int((conn[:, 3] == conn[:, 2]).sum()) if conn.shape[1] == 4 else conn.shape[0]
        elements["triangles"] += tri
        elements["shells"] += conn.shape[0] - tri
        for pid in np.atleast_1d(it.pids).tolist():
            count[pid] = count.get(pid, 0) + 1
    elements["mass_elements"] = sum(int(np.size(it.ids)) for it in deck.of_type(MassElements))
    materials = deck.of_type(Material)
    mat_kw = {m.mid: "*" + m.KEYWORD for m in materials}
    sections = [*deck.of_type(SectionSolid), *deck.of_type(SectionShell)]
    sec_kw = {s.secid: f"*{s.KEYWORD} {s.secid} (ELFORM {s.elform})" for s in sections}
    parts = [{"pid": p.pid, "title": p.title, "elements": count.get(p.pid, 0),
              "section": sec_kw.get(p.secid, f"{p.secid} ({missing})"),
              "material": f"{mat_kw[p.mid]} {p.mid}" if p.mid in mat_kw
              else f"{p.mid} ({missing})", "mass_kg": None}
             for p in deck.of_type(Part)]
    return {
        "title": deck.title,
        "nodes": sum(int(np.size(it.ids)) for it in deck.of_type(Nodes)),
        "elements": elements,
        "parts": parts,
        "materials": by_keyword([("*" + m.KEYWORD, m.mid) for m in materials]),
        "sections": by_keyword([("*" + s.KEYWORD, s.secid) for s in sections]),
        "mass_kg": None,
        "element_mass_kg": None,
        "bounding_box": {"min": None, "max": None},
        "unsupported": unsupported_entries(deck),
    }
