"""Editing a keyword deck without touching the input: a copy of the include tree, free id
ranges above the deck's maxima, the node references of a deck, the tied contact of the
walls, and comments (written as raw text).

The copy shares every unchanged keyword item with the input (items are never mutated;
an edit replaces an item in the copy's list), so the input deck stays as read.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from hollowbody.io.keyword import (
    BoundarySpcNode,
    Contact,
    DatabaseHistoryNode,
    Deck,
    ElementDiscrete,
    Hourglass,
    Include,
    InitialVelocityNode,
    KeywordItem,
    MassElements,
    Material,
    Nodes,
    PartInertia,
    PrescribedMotionNode,
    RawKeyword,
    SectionDiscrete,
    SectionShell,
    SectionSolid,
    SetNodeList,
    SetNodeListGenerate,
    SetPartList,
    SetPartListGenerate,
    SetSegment,
    ShellElements,
    SolidElements,
    TiedContact,
)

# ---------------------------------------------------------------------------
# the include tree


def copy_tree(deck: Deck) -> Deck:
    """A copy of ``deck`` and its includes: new Deck and Include objects, shared items."""
    new = Deck(deck.path)
    new.keyword_args = deck.keyword_args
    for item in deck.items:
        if isinstance(item, Include):
            new.items.append(Include(filename=item.filename, deck=copy_tree(item.deck),
                                     source=item.source))
        else:
            new.items.append(item)
    return new


def file_decks(deck: Deck) -> Iterator[Deck]:
    """``deck`` and every included deck (depth first, reading order)."""
    yield deck
    for item in deck.items:
        if isinstance(item, Include):
            yield from file_decks(item.deck)


def parents(deck: Deck) -> dict[int, Deck]:
    """{id(child deck): including deck} over the whole tree."""
    out: dict[int, Deck] = {}
    for d in file_decks(deck):
        for item in d.items:
            if isinstance(item, Include):
                out[id(item.deck)] = d
    return out


# ---------------------------------------------------------------------------
# ids


def _raw_ids(deck: Deck, prefixes: tuple[str, ...], every_line: bool) -> list[int]:
    """First integer field of raw keywords starting with ``prefixes`` (first data card, or
    every card with ``every_line``); fields that are not integers are skipped."""
    out = []
    for r in deck.of_type(RawKeyword):
        name = r.keyword.split()[0].upper() if r.keyword.split() else ""
        if not name.startswith(prefixes):
            continue
        title = name.endswith("_TITLE") or name.endswith("_ID")
        data = [t for t in r.lines if t.strip() and not t.startswith("$")]
        if title and name.startswith("CONTACT"):
            data = data[:1]
        elif title:
            data = data[1:]
        for text in (data if every_line else data[:1]):
            field = text.split(",")[0] if "," in text else text[:10]
            try:
                out.append(int(field))
            except ValueError:
                continue
    return out


class IdAllocator:
    """Free id ranges above a deck's maxima, per kind (node, element, section, material,
    node_set, segment_set, part_set, contact, hourglass). The first id of a kind is the
    next multiple of 1000 above the maximum, plus one."""

    def __init__(self, deck: Deck) -> None:
        items = list(deck.iter_items())

        def ids(cls: type, attr: str) -> list[int]:
            vals: list[int] = []
            for it in items:
                if isinstance(it, cls):
                    v = getattr(it, attr)
                    if isinstance(v, np.ndarray):
                        if v.size:
                            vals.append(int(v.max()))
                    elif v is not None:
                        vals.append(int(v))
            return vals

        elem = (ids(SolidElements, "ids") + ids(ShellElements, "ids") + ids(MassElements, "ids")
                + ids(ElementDiscrete, "eid") + _raw_ids(deck, ("ELEMENT_",), True))
        self.next = {
            "node": ids(Nodes, "ids") + _raw_ids(deck, ("NODE",), True),
            "element": elem,
            "section": ids(SectionSolid, "secid") + ids(SectionShell, "secid")
            + ids(SectionDiscrete, "secid") + _raw_ids(deck, ("SECTION_",), False),
            "material": ids(Material, "mid") + _raw_ids(deck, ("MAT_",), False),
            "node_set": ids(SetNodeList, "sid") + ids(SetNodeListGenerate, "sid")
            + _raw_ids(deck, ("SET_NODE",), False),
            "segment_set": ids(SetSegment, "sid") + _raw_ids(deck, ("SET_SEGMENT",), False),
            "part_set": ids(SetPartList, "sid") + ids(SetPartListGenerate, "sid")
            + _raw_ids(deck, ("SET_PART",), False),
            "contact": ids(Contact, "cid") + ids(TiedContact, "cid")
            + _raw_ids(deck, ("CONTACT_",), False),
            "hourglass": ids(Hourglass, "hgid") + _raw_ids(deck, ("HOURGLASS",), False),
        }
        self.next = {k: (max(v, default=0) // 1000 + 1) * 1000 + 1 for k, v in self.next.items()}
        n_contacts = sum(1 for it in items if isinstance(it, (Contact, TiedContact)))
        self.next["contact"] = max(self.next["contact"], n_contacts + 1)

    def take(self, kind: str, count: int = 1) -> int:
        """First of ``count`` consecutive free ids of ``kind``."""
        first = self.next[kind]
        self.next[kind] = first + max(int(count), 0)
        return first


# ---------------------------------------------------------------------------
# node references


def referenced_nodes(deck: Deck, skip_pids: set[int]) -> np.ndarray:
    """Node ids (sorted unique) referred to by anything but the solids of ``skip_pids``:
    other elements, mass elements, discrete elements, node and segment sets, SPCs, motions,
    velocities, histories, *PART_INERTIA nodes. (*SET_NODE_LIST_GENERATE ranges and raw
    keywords are not counted: the builder skips missing nodes of generated sets.)"""
    parts: list[np.ndarray] = []
    for it in deck.iter_items():
        if isinstance(it, SolidElements):
            keep = ~np.isin(it.pids, list(skip_pids))
            parts.append(it.conn[keep].ravel())
        elif isinstance(it, ShellElements):
            parts.append(it.conn.ravel())
        elif isinstance(it, MassElements):
            parts.append(it.nids)
        elif isinstance(it, ElementDiscrete):
            parts.append(np.array([n for n in (it.n1, it.n2) if n], dtype=np.int64))
        elif isinstance(it, SetNodeList):
            parts.append(it.nodes)
        elif isinstance(it, SetSegment):
            parts.append(it.segments.ravel())
        elif isinstance(it, DatabaseHistoryNode):
            parts.append(np.asarray(it.ids, dtype=np.int64))
        elif isinstance(it, (BoundarySpcNode, PrescribedMotionNode, InitialVelocityNode)):
            parts.append(np.array([it.nid], dtype=np.int64))
        elif isinstance(it, PartInertia) and it.nodeid:
            parts.append(np.array([it.nodeid], dtype=np.int64))
    if not parts:
        return np.zeros(0, dtype=np.int64)
    return np.unique(np.concatenate(parts).astype(np.int64))


# ---------------------------------------------------------------------------
# raw keywords


def tied_shell_edge_contact(cid: int, heading: str, node_set: int, segment_set: int,
                            master_thickness: float) -> TiedContact:
    """*CONTACT_TIED_SHELL_EDGE_TO_SURFACE_ID: the nodes of ``node_set`` (slave, SSTYP 4)
    tied to the segments of ``segment_set`` (master, MSTYP 0); MST = ``master_thickness`` mm
    (the contact thickness that bounds the search for the nodes to tie)."""
    return TiedContact(type="TIED_SHELL_EDGE_TO_SURFACE", cid=cid, heading=heading[:70],
                       ssid=node_set, msid=segment_set, sstyp=4, mstyp=0,
                       mst=float(master_thickness))


def comment(lines: list[str]) -> RawKeyword:
    """*COMMENT with ``lines`` (read back as an ignored keyword)."""
    return RawKeyword(keyword="COMMENT", lines=[t[:80] for t in lines], unsupported=False)


def replace_item(deck: Deck, old: KeywordItem, new: KeywordItem | None) -> None:
    """Replace ``old`` (by identity) in ``deck.items`` by ``new``, or remove it (None)."""
    for k, item in enumerate(deck.items):
        if item is old:
            if new is None:
                del deck.items[k]
            else:
                deck.items[k] = new
            return
    raise ValueError("item not in deck")
