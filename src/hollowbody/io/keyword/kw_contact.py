"""Automatic contacts: *CONTACT_AUTOMATIC_SURFACE_TO_SURFACE, _NODES_TO_SURFACE,
_SINGLE_SURFACE (options ``_ID``/``_TITLE`` and ``_MPP``).

Card order: ID card (CID HEADING), MPP cards (kept as text), card 1 (SSID
MSID SSTYP MSTYP SBOXID MBOXID SPR MPR), card 2 (FS FD DC VC VDC PENCHK BT
DT), card 3 (SFS SFM SST MST SFST SFMT FSF VSF), optional card A (SOFT
SOFSCL LCIDAB MAXPAR SBOPT DEPTH BSORT FRCFRQ). Further optional cards
(B, C, ...) are kept in ``extra_cards``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from hollowbody.io.keyword.base import Block, Cursor, SimpleKeyword, register

#: Contact types read (keyword = ``CONTACT_`` + type).
CONTACT_TYPES = ("AUTOMATIC_SURFACE_TO_SURFACE", "AUTOMATIC_NODES_TO_SURFACE",
                 "AUTOMATIC_SINGLE_SURFACE")


@register
@dataclass(kw_only=True)
class Contact(SimpleKeyword):
    """One automatic contact; ``type`` is one of :data:`CONTACT_TYPES`.

    SSTYP / MSTYP: 0 segment set, 1 shell element set, 2 part set, 3 part,
    4 node set, 5 all, 6 part set excluded. Fields of card A that are None
    are left blank (LS-DYNA defaults).
    """

    type: str = "AUTOMATIC_SINGLE_SURFACE"
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
    OPTIONS: ClassVar[frozenset[str]] = frozenset({"MPP"})
    CARDS: ClassVar[tuple[str, ...]] = ("ssid msid sstyp mstyp sboxid mboxid spr mpr",
                                        "fs fd dc vc vdc penchk bt dt",
                                        "sfs sfm sst mst sfst sfmt fsf vsf",
                                        "soft sofscl lcidab maxpar sbopt depth bsort frcfrq")
    ID_ATTRS: ClassVar[tuple[str, str] | None] = ("cid", "heading")

    def __post_init__(self) -> None:
        self.type = self.type.upper()
        if self.type not in CONTACT_TYPES:
            raise ValueError(f"contact type {self.type!r} is not one of {CONTACT_TYPES}")

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        out: dict[str, object] = {"type": block.base[len("CONTACT_"):]}
        if block.has("MPP"):
            mpp = [cur.take("MPP card 1")[1]]
            nxt = cur.peek()
            if nxt is not None and nxt[1].strip().startswith("&"):
                mpp.append(cur.take("MPP card 2")[1])
            out["mpp"] = mpp
        return out

    def keyword_line(self) -> str:
        return "*CONTACT_" + self.type + ("_MPP" if self.mpp else "")

    def prefix_lines(self, fmt: str) -> list[str]:
        return list(self.mpp)
