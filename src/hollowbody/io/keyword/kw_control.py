"""Control and output keywords.

*CONTROL_TERMINATION, *CONTROL_TIMESTEP, *CONTROL_SHELL, *CONTROL_HOURGLASS,
*CONTROL_CONTACT, *CONTROL_BULK_VISCOSITY, *DATABASE_<ascii> (GLSTAT,
RCFORC, NODOUT, SPCFORC, MATSUM and other one-card ASCII databases),
*DATABASE_BINARY_D3PLOT, *DATABASE_BINARY_D3DUMP, *DATABASE_HISTORY_NODE(_SET). Times in ms. Cards
not read here are kept in ``extra_cards``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from hollowbody.io.keyword.base import ArrayEq, Block, Cursor, SimpleKeyword, read_rows, register
from hollowbody.io.keyword.bulk import int_texts
from hollowbody.io.keyword.cards import field_width


@register
@dataclass(kw_only=True)
class ControlTermination(SimpleKeyword):
    """*CONTROL_TERMINATION: ENDTIM (ms) ENDCYC DTMIN ENDENG ENDMAS NOSOL."""

    endtim: float = 0.0
    endcyc: int = 0
    dtmin: float = 0.0
    endeng: float = 0.0
    endmas: float = 1.0e8
    nosol: int = 0

    KEYWORD: ClassVar[str] = "CONTROL_TERMINATION"
    CARDS: ClassVar[tuple[str, ...]] = ("endtim endcyc dtmin endeng endmas nosol",)
    N_REQUIRED: ClassVar[int] = 0


@register
@dataclass(kw_only=True)
class ControlTimestep(SimpleKeyword):
    """*CONTROL_TIMESTEP: DTINIT TSSFAC ISDO TSLIMT DT2MS LCTM ERODE MS1ST (TSSFAC 0 = 0.9)."""

    dtinit: float = 0.0
    tssfac: float = 0.9
    isdo: int = 0
    tslimt: float = 0.0
    dt2ms: float = 0.0
    lctm: int = 0
    erode: int = 0
    ms1st: int = 0

    KEYWORD: ClassVar[str] = "CONTROL_TIMESTEP"
    CARDS: ClassVar[tuple[str, ...]] = ("dtinit tssfac isdo tslimt dt2ms lctm erode ms1st",)
    N_REQUIRED: ClassVar[int] = 0


@register
@dataclass(kw_only=True)
class ControlShell(SimpleKeyword):
    """*CONTROL_SHELL card 1: WRPANG ESORT IRNXX ISTUPD THEORY BWC MITER PROJ.

    Only ISTUPD is used (1: shell thickness follows the membrane strains);
    further cards are kept as text.
    """

    wrpang: float = 20.0
    esort: int = 0
    irnxx: int = -1
    istupd: int = 0
    theory: int = 2
    bwc: int = 2
    miter: int = 1
    proj: int = 0

    KEYWORD: ClassVar[str] = "CONTROL_SHELL"
    CARDS: ClassVar[tuple[str, ...]] = ("wrpang esort irnxx istupd theory bwc miter proj",)
    N_REQUIRED: ClassVar[int] = 0


@register
@dataclass(kw_only=True)
class ControlHourglass(SimpleKeyword):
    """*CONTROL_HOURGLASS: IHQ (default 1) QH (default 0.1)."""

    ihq: int = 1
    qh: float = 0.1

    KEYWORD: ClassVar[str] = "CONTROL_HOURGLASS"
    CARDS: ClassVar[tuple[str, ...]] = ("ihq qh",)
    N_REQUIRED: ClassVar[int] = 0


@register
@dataclass(kw_only=True)
class ControlContact(SimpleKeyword):
    """*CONTROL_CONTACT: SLSFAC RWPNAL ISLCHK SHLTHK PENOPT THKCHG ORIEN ENMASS;
    USRSTR USRFRC NSBCS INTERM XPENE SSTHK ECDT TIEDPRJ (further cards kept as text).
    """

    slsfac: float = 0.1
    rwpnal: float = 0.0
    islchk: int = 1
    shlthk: int = 0
    penopt: int = 1
    thkchg: int = 0
    orien: int = 1
    enmass: int = 0
    usrstr: int = 0
    usrfrc: int = 0
    nsbcs: int = 0
    interm: int = 0
    xpene: float = 4.0
    ssthk: int = 0
    ecdt: int = 0
    tiedprj: int = 0

    KEYWORD: ClassVar[str] = "CONTROL_CONTACT"
    CARDS: ClassVar[tuple[str, ...]] = (
        "slsfac rwpnal islchk shlthk penopt thkchg orien enmass",
        "usrstr usrfrc nsbcs interm xpene ssthk ecdt tiedprj")
    N_REQUIRED: ClassVar[int] = 0


@register
@dataclass(kw_only=True)
class ControlBulkViscosity(SimpleKeyword):
    """*CONTROL_BULK_VISCOSITY: Q1 (1.5) Q2 (0.06) TYPE BTYPE TSTYPE."""

    q1: float = 1.5
    q2: float = 0.06
    type: int = 1
    btype: int = 0
    tstype: int = 0

    KEYWORD: ClassVar[str] = "CONTROL_BULK_VISCOSITY"
    CARDS: ClassVar[tuple[str, ...]] = ("q1 q2 type btype tstype",)
    N_REQUIRED: ClassVar[int] = 0


#: One-card ASCII databases (DT BINARY LCUR IOOPT) read by :class:`DatabaseAscii`.
ASCII_DATABASES = ("GLSTAT", "RCFORC", "NODOUT", "SPCFORC", "MATSUM", "ELOUT", "DEFORC",
                   "BNDOUT", "RBDOUT", "SLEOUT", "ABSTAT", "SECFORC", "JNTFORC", "SBTOUT",
                   "NCFORC", "RWFORC", "GCEOUT", "SWFORC", "DCFAIL")


@register
@dataclass(kw_only=True)
class DatabaseAscii(SimpleKeyword):
    """*DATABASE_<name>: DT (ms) BINARY LCUR IOOPT; ``name`` e.g. ``GLSTAT``."""

    name: str = "GLSTAT"
    dt: float = 0.0
    binary: int = 0
    lcur: int = 0
    ioopt: int = 1

    KEYWORD: ClassVar[str] = "DATABASE_GLSTAT"
    ALIASES: ClassVar[tuple[str, ...]] = tuple("DATABASE_" + n for n in ASCII_DATABASES)
    CARDS: ClassVar[tuple[str, ...]] = ("dt binary lcur ioopt",)
    N_REQUIRED: ClassVar[int] = 0

    def __post_init__(self) -> None:
        self.name = self.name.upper()

    @classmethod
    def read_prefix(cls, cur: Cursor, block: Block) -> dict[str, object]:
        return {"name": block.base[len("DATABASE_"):]}

    @classmethod
    def build(cls, values: dict[str, object], block: Block) -> DatabaseAscii:
        values.setdefault("name", block.base[len("DATABASE_"):])
        return cls(**values)  # type: ignore[arg-type]

    def keyword_line(self) -> str:
        return "*DATABASE_" + self.name


@register
@dataclass(kw_only=True)
class DatabaseBinaryD3plot(SimpleKeyword):
    """*DATABASE_BINARY_D3PLOT: DT (ms) LCDT BEAM NPLTC PSETID (card 2 kept as text)."""

    dt: float = 0.0
    lcdt: int = 0
    beam: int = 0
    npltc: int = 0
    psetid: int = 0

    KEYWORD: ClassVar[str] = "DATABASE_BINARY_D3PLOT"
    CARDS: ClassVar[tuple[str, ...]] = ("dt lcdt beam npltc psetid",)
    N_REQUIRED: ClassVar[int] = 0


@register
@dataclass(kw_only=True)
class DatabaseBinaryD3dump(SimpleKeyword):
    """*DATABASE_BINARY_D3DUMP: CYCL (cycles between restart dumps; 0 = none) LCDT BEAM
    NPLTC PSETID (only CYCL is used)."""

    cycl: float = 0.0
    lcdt: int = 0
    beam: int = 0
    npltc: int = 0
    psetid: int = 0

    KEYWORD: ClassVar[str] = "DATABASE_BINARY_D3DUMP"
    CARDS: ClassVar[tuple[str, ...]] = ("cycl lcdt beam npltc psetid",)
    N_REQUIRED: ClassVar[int] = 0


@dataclass(kw_only=True, eq=False)
class _HistoryIds(ArrayEq, SimpleKeyword):
    ids: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    id_lines: np.ndarray | None = field(default=None, compare=False, repr=False)

    N_REQUIRED: ClassVar[int] = 0

    def __post_init__(self) -> None:
        self.ids = np.asarray(self.ids, dtype=np.int64).reshape(-1)

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        rows, lines = read_rows(cur, [f"id{k}" for k in range(1, 9)], "i")
        ids = np.array(rows, dtype=np.int64).reshape(-1, 8)
        line_of = np.repeat(np.array(lines, dtype=np.int64), 8).reshape(-1, 8)
        nz = ids != 0
        return {"ids": ids[nz], "id_lines": line_of[nz]}

    def tail_lines(self, fmt: str) -> list[str]:
        texts = int_texts(self.ids, field_width(10, fmt))
        return ["".join(texts[k:k + 8]) for k in range(0, len(texts), 8)]


@register
@dataclass(kw_only=True, eq=False)
class DatabaseHistoryNode(_HistoryIds):
    """*DATABASE_HISTORY_NODE: node ids, 8 per card (``ids``)."""

    KEYWORD: ClassVar[str] = "DATABASE_HISTORY_NODE"


@register
@dataclass(kw_only=True, eq=False)
class DatabaseHistoryNodeSet(_HistoryIds):
    """*DATABASE_HISTORY_NODE_SET: node set ids, 8 per card (``ids``)."""

    KEYWORD: ClassVar[str] = "DATABASE_HISTORY_NODE_SET"
