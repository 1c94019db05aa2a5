"""Contacts: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE, _NODES_TO_SURFACE,
_SINGLE_SURFACE (:class:`Contact`) and the tied contacts
*CONTACT_TIED_NODES_TO_SURFACE, _SHELL_EDGE_TO_SURFACE, _SURFACE_TO_SURFACE with
``_OFFSET`` / ``_CONSTRAINED_OFFSET`` (:class:`TiedContact`); options
``_ID``/``_TITLE`` and ``_MPP``.

Card order: ID card (CID HEADING), MPP cards (kept as text), card 1 (SSID
MSID SSTYP MSTYP SBOXID MBOXID SPR MPR), card 2 (FS FD DC VC VDC PENCHK BT
DT), card 3 (SFS SFM SST MST SFST SFMT FSF VSF), optional card A (SOFT
SOFSCL LCIDAB MAXPAR SBOPT DEPTH BSORT FRCFRQ). Further optional cards
(B, C, ...) are kept in ``extra_cards``. Tied contacts have cards 1-3 only
(later cards are kept in ``extra_cards``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from hollowbody.io.keyword.base import Block, Cursor, SimpleKeyword, register

#: Contact types read (keyword = ``CONTACT_`` + type).
CONTACT_TYPES = ("AUTOMATIC_SURFACE_TO_SURFACE", "AUTOMATIC_NODES_TO_SURFACE",
                 "AUTOMATIC_SINGLE_SURFACE")


@dataclass(kw_only=True)
class _ContactCards(SimpleKeyword):
    """Fields shared by every contact: the ID card, MPP cards and cards 1-3.

    SSTYP / MSTYP: 0 segment set, 1 shell element set, 2 part set, 3 part,
    4 node set, 5 all, 6 part set excluded.
    """

    cid: int | None = None
    heading: str = ""
    mpp: list[str] = field(default_factory=list)
    ssid: int = 0
    msid: int = 0
    sstyp: int = 0
    mstyp: int = 0
    sboxid: int = 0
    mboxid: int = 0
    spr: int = 0
    mpr: int = 0
    fs: float = 0.0
    fd: float = 0.0
    dc: float = 0.0
    vc: float = 0.0
    vdc: float = 0.0
    penchk: int = 0
    bt: float = 0.0
    dt: float = 1.0e20
    sfs: float = 1.0
    sfm: float = 1.0
    sst: float = 0.0
    mst: float = 0.0
    sfst: float = 1.0
    sfmt: float = 1.0
    fsf: float = 1.0
    vsf: float = 1.0

    OPTIONS: ClassVar[frozenset[str]] = frozenset({"MPP"})
    ID_ATTRS: ClassVar[tuple[str, str] | None] = ("cid", "heading")

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        out: dict[str, object] = {}
        if block.has("MPP"):
            mpp = [cur.take("MPP card 1")[1]]
            nxt = cur.peek()
            if nxt is not None and nxt[1].strip().startswith("&"):
                mpp.append(cur.take("MPP card 2")[1])
            out["mpp"] = mpp
        return out

    def prefix_lines(self, fmt: str) -> list[str]:
        return list(self.mpp)


@register
@dataclass(kw_only=True)
class Contact(_ContactCards):
    """One automatic contact; ``type`` is one of :data:`CONTACT_TYPES`.

    SSTYP / MSTYP: 0 segment set, 1 shell element set, 2 part set, 3 part,
    4 node set, 5 all, 6 part set excluded. Fields of card A that are None
    are left blank (LS-DYNA defaults).
    """

    type: str = "AUTOMATIC_SINGLE_SURFACE"
    soft: int | None = None
    sofscl: float | None = None
    lcidab: int | None = None
    maxpar: float | None = None
    sbopt: int | None = None
    depth: int | None = None
    bsort: int | None = None
    frcfrq: int | None = None

    KEYWORD: ClassVar[str] = "CONTACT_AUTOMATIC_SINGLE_SURFACE"
    ALIASES: ClassVar[tuple[str, ...]] = tuple("CONTACT_" + t for t in CONTACT_TYPES)
    CARDS: ClassVar[tuple[str, ...]] = ("ssid msid sstyp mstyp sboxid mboxid spr mpr",
                                        "fs fd dc vc vdc penchk bt dt",
                                        "sfs sfm sst mst sfst sfmt fsf vsf",
                                        "soft sofscl lcidab maxpar sbopt depth bsort frcfrq")

    def __post_init__(self) -> None:
        self.type = self.type.upper()
        if self.type not in CONTACT_TYPES:
            raise ValueError(f"contact type {self.type!r} is not one of {CONTACT_TYPES}")

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        out = super().read_prefix(cur, block)
        out["type"] = block.base[len("CONTACT_"):]
        return out

    def keyword_line(self) -> str:
        return "*CONTACT_" + self.type + ("_MPP" if self.mpp else "")


#: Tied contact types read (keyword = ``CONTACT_`` + type [+ ``_`` + offset]).
TIED_TYPES = ("TIED_NODES_TO_SURFACE", "TIED_SHELL_EDGE_TO_SURFACE",
              "TIED_SURFACE_TO_SURFACE")
#: Offset forms of the tied types ("" = none).
TIED_OFFSETS = ("", "OFFSET", "CONSTRAINED_OFFSET")


@register
@dataclass(kw_only=True)
class TiedContact(_ContactCards):
    """One tied contact: ``type`` is one of :data:`TIED_TYPES`, ``offset`` one of
    :data:`TIED_OFFSETS` (``*CONTACT_TIED_NODES_TO_SURFACE_OFFSET_ID`` is
    ``type="TIED_NODES_TO_SURFACE", offset="OFFSET"`` with an ID card).

    SSID/SSTYP: the slave side (0 segment set, 2 part set, 3 part, 4 node set),
    MSID/MSTYP: the master surface (0 segment set, 2 part set, 3 part). SST /
    MST: contact thicknesses (mm) that set the search tolerance (negative: the
    tolerance itself), SFST / SFMT their scale factors. Friction, penalty and
    the optional cards are read and written back but a tied contact ignores
    them.
    """

    type: str = "TIED_NODES_TO_SURFACE"
    offset: str = ""

    KEYWORD: ClassVar[str] = "CONTACT_TIED_NODES_TO_SURFACE"
    ALIASES: ClassVar[tuple[str, ...]] = tuple(
        "CONTACT_" + t + ("_" + o if o else "") for t in TIED_TYPES for o in TIED_OFFSETS)
    CARDS: ClassVar[tuple[str, ...]] = ("ssid msid sstyp mstyp sboxid mboxid spr mpr",
                                        "fs fd dc vc vdc penchk bt dt",
                                        "sfs sfm sst mst sfst sfmt fsf vsf")

    def __post_init__(self) -> None:
        self.type = self.type.upper()
        self.offset = self.offset.upper()
        if self.type not in TIED_TYPES:
            raise ValueError(f"tied contact type {self.type!r} is not one of {TIED_TYPES}")
        if self.offset not in TIED_OFFSETS:
            raise ValueError(f"tied contact offset {self.offset!r} is not one of "
                             f"{TIED_OFFSETS}")

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        out = super().read_prefix(cur, block)
        name = block.base[len("CONTACT_"):]
        out["type"] = next(t for t in TIED_TYPES if name.startswith(t))
        out["offset"] = name[len(out["type"]):].lstrip("_")
        return out

    def keyword_line(self) -> str:
        return ("*CONTACT_" + self.type + ("_" + self.offset if self.offset else "")
                + ("_MPP" if self.mpp else ""))
