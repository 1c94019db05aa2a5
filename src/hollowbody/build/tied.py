"""Tied contacts of a deck -> :class:`~hollowbody.model.model.TiedContactDef`.

Called by :func:`hollowbody.build.build_model` once the sets are
resolved. Sides: slave SSTYP 0 (segment set: its nodes), 2 (part set), 3
(part), 4 (node set); master MSTYP 0 (segment set), 2 (part set), 3 (part).
Anything else, contact boxes included, is a :class:`DeckError` at the
contact's card (``deck.k:12: *CONTACT_TIED_SHELL_EDGE_TO_SURFACE_ID: ...``).
"""

from __future__ import annotations

from hollowbody.build.surface_refs import defined_surface
from hollowbody.errors import DeckError
from hollowbody.io.keyword import TiedContact
from hollowbody.model import model as m

_KINDS = {"TIED_NODES_TO_SURFACE": "nodes_to_surface",
          "TIED_SHELL_EDGE_TO_SURFACE": "shell_edge_to_surface",
          "TIED_SURFACE_TO_SURFACE": "surface_to_surface"}
_NAMES = {0: "segment set", 1: "shell element set", 2: "part set", 3: "part", 4: "node set",
          5: "all", 6: "part set excluded", 7: "branch id"}


def _err(item: TiedContact, message: str) -> DeckError:
    return DeckError(message, item.source.file, item.source.line,
                     item.keyword_line().lstrip("*") + ("_ID" if item.cid is not None else ""))


def _side(c: TiedContact, model: m.Model, sid: int, typ: int, name: str,
          master: bool) -> m.SurfaceRef:
    allowed = (0, 2, 3) if master else (0, 2, 3, 4)
    what = _NAMES.get(typ)
    if typ not in allowed:
        raise _err(c, f"{name}={typ}" + (f" ({what})" if what else "") + " is not supported "
                   "for a tied contact (0 segment set, 2 part set, 3 part"
                   + ("" if master else ", 4 node set") + ")")
    ref = defined_surface(model, sid, typ)
    if ref is not None:
        return ref
    raise _err(c, f"tied contact refers to {what} {sid} ({name}={typ}) which is not defined")


def tied_contacts(items: list[TiedContact], model: m.Model,
                  first_cid: int = 1) -> list[m.TiedContactDef]:
    """Resolve the tied-contact keyword items against ``model``'s sets and parts.

    ``first_cid``: number given to the first contact without an ID card (the
    automatic contacts are numbered first, so ids stay unique).
    """
    out = []
    for k, c in enumerate(items, start=first_cid):
        if c.sboxid or c.mboxid:
            raise _err(c, "SBOXID/MBOXID (contact boxes) are not supported")
        slave = _side(c, model, c.ssid, c.sstyp, "SSTYP", False)
        master = _side(c, model, c.msid, c.mstyp, "MSTYP", True)
        out.append(m.TiedContactDef(
            cid=c.cid if c.cid else k, kind=_KINDS[c.type], slave=slave, master=master,
            offset=bool(c.offset), sst=c.sst, mst=c.mst, sfst=c.sfst or 1.0,
            sfmt=c.sfmt or 1.0, title=c.heading, source=c.source))
    return out
