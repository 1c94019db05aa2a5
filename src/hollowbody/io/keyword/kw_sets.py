"""Curves and sets: *DEFINE_CURVE, *SET_NODE_LIST(_GENERATE), *SET_PART_LIST(_GENERATE),
*SET_SEGMENT.

One curve or set per keyword block (the list runs to the next keyword);
ids are LS-DYNA ids (the builder resolves them).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.io.keyword.base import ArrayEq, Block, Cursor, SimpleKeyword, read_rows, register
from hollowbody.io.keyword.bulk import float_texts, int_texts, join_rows
from hollowbody.io.keyword.cards import field_width

#: Most ids the ranges of one *SET_..._GENERATE may hold (a larger range is a typo).
MAX_GENERATED = 20_000_000


@register
@dataclass(kw_only=True, eq=False)
class DefineCurve(ArrayEq, SimpleKeyword):
    """*DEFINE_CURVE(_TITLE): LCID SIDR SFA SFO OFFA OFFO DATTYP LCINT, then A O pairs.

    points: (m, 2) float64 raw abscissa / ordinate as in the deck (scale
    factors and offsets are applied by the builder); the abscissa must be
    strictly increasing. ``point_lines``: file line of each point.
    """

    lcid: int = 0
    sidr: int = 0
    sfa: float = 1.0
    sfo: float = 1.0
    offa: float = 0.0
    offo: float = 0.0
    dattyp: int = 0
    lcint: int = 0
    points: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    title: str = ""
    point_lines: list[int] = field(default_factory=list, compare=False, repr=False)

    KEYWORD: ClassVar[str] = "DEFINE_CURVE"
    CARDS: ClassVar[tuple[str, ...]] = ("lcid sidr sfa sfo offa offo dattyp lcint",)
    TITLE_ATTR: ClassVar[str | None] = "title"

    def __post_init__(self) -> None:
        self.points = np.asarray(self.points, dtype=np.float64).reshape(-1, 2)

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        rows, lines = read_rows(cur, ["a1", "o1"], "f", width=20)
        pts = np.array(rows, dtype=np.float64).reshape(-1, 2)
        if pts.shape[0] == 0:
            raise block.error(f"curve {values.get('lcid', 0)} has no points")
        bad = np.flatnonzero(np.diff(pts[:, 0]) <= 0.0)
        if bad.size:
            k = int(bad[0]) + 1
            raise DeckError(f"curve {values.get('lcid', 0)}: abscissa {pts[k, 0]:g} does not "
                            f"increase (previous point {pts[k - 1, 0]:g})", block.file,
                            lines[k], block.name)
        return {"points": pts, "point_lines": lines}

    def tail_lines(self, fmt: str) -> list[str]:
        w = field_width(20, fmt)
        flat = float_texts(self.points, w)
        return join_rows([flat[0::2], flat[1::2]])


@dataclass(kw_only=True, eq=False)
class _IdListSet(ArrayEq, SimpleKeyword):
    """Base of list sets: SID DA1 DA2 DA3 DA4 SOLVER, then ids 8 per card."""

    sid: int = 0
    da1: float = 0.0
    da2: float = 0.0
    da3: float = 0.0
    da4: float = 0.0
    solver: str = "MECH"
    title: str = ""

    CARDS: ClassVar[tuple[str, ...]] = ("sid da1 da2 da3 da4 solver",)
    TITLE_ATTR: ClassVar[str | None] = "title"
    #: Attribute of the id array and the field name used in messages.
    LIST_ATTR: ClassVar[str] = "ids"
    FIELD: ClassVar[str] = "id"

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        rows, lines = read_rows(cur, [f"{cls.FIELD}{k}" for k in range(1, 9)], "i")
        ids = np.array(rows, dtype=np.int64).reshape(-1, 8)
        line_of = np.repeat(np.array(lines, dtype=np.int64), 8).reshape(-1, 8)
        nz = ids != 0
        return {cls.LIST_ATTR: ids[nz], "id_lines": line_of[nz]}

    def tail_lines(self, fmt: str) -> list[str]:
        ids = np.asarray(getattr(self, self.LIST_ATTR), dtype=np.int64).reshape(-1)
        texts = int_texts(ids, field_width(10, fmt))
        return ["".join(texts[k:k + 8]) for k in range(0, len(texts), 8)]


@register
@dataclass(kw_only=True, eq=False)
class SetNodeList(_IdListSet):
    """*SET_NODE_LIST(_TITLE) / *SET_NODE: ``nodes`` (k,) node ids."""

    nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    id_lines: np.ndarray | None = field(default=None, compare=False, repr=False)

    KEYWORD: ClassVar[str] = "SET_NODE_LIST"
    ALIASES: ClassVar[tuple[str, ...]] = ("SET_NODE",)
    LIST_ATTR: ClassVar[str] = "nodes"
    FIELD: ClassVar[str] = "nid"

    def __post_init__(self) -> None:
        self.nodes = np.asarray(self.nodes, dtype=np.int64).reshape(-1)


@register
@dataclass(kw_only=True, eq=False)
class SetPartList(_IdListSet):
    """*SET_PART_LIST(_TITLE) / *SET_PART: ``parts`` (k,) part ids."""

    parts: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    id_lines: np.ndarray | None = field(default=None, compare=False, repr=False)

    KEYWORD: ClassVar[str] = "SET_PART_LIST"
    ALIASES: ClassVar[tuple[str, ...]] = ("SET_PART",)
    LIST_ATTR: ClassVar[str] = "parts"
    FIELD: ClassVar[str] = "pid"

    def __post_init__(self) -> None:
        self.parts = np.asarray(self.parts, dtype=np.int64).reshape(-1)


@dataclass(kw_only=True, eq=False)
class _GenerateSet(_IdListSet):
    """Base of _GENERATE sets: ranges B1BEG B1END ... (4 ranges per card)."""

    ranges: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), np.int64))
    range_lines: list[int] = field(default_factory=list, compare=False, repr=False)

    def __post_init__(self) -> None:
        self.ranges = np.asarray(self.ranges, dtype=np.int64).reshape(-1, 2)

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        names = [f"b{k}{e}" for k in range(1, 5) for e in ("beg", "end")]
        rows, lines = read_rows(cur, names, "i")
        r = np.array(rows, dtype=np.int64).reshape(-1, 2)
        line_of = np.repeat(np.array(lines, dtype=np.int64), 4)
        used = (r != 0).any(axis=1)
        r, line_of = r[used], line_of[used]
        bad = np.flatnonzero(r[:, 1] < r[:, 0])
        if bad.size:
            k = int(bad[0])
            raise DeckError(f"range {r[k, 0]}..{r[k, 1]} is empty (end before begin)",
                            block.file, int(line_of[k]), block.name)
        total = np.cumsum(r[:, 1] - r[:, 0] + 1) if r.size else np.zeros(0, np.int64)
        if total.size and total[-1] > MAX_GENERATED:
            k = int(np.argmax(total > MAX_GENERATED))
            raise DeckError(f"range {r[k, 0]}..{r[k, 1]}: the ranges hold more than "
                            f"{MAX_GENERATED} ids", block.file, int(line_of[k]), block.name)
        return {"ranges": r, "range_lines": line_of.tolist()}

    def tail_lines(self, fmt: str) -> list[str]:
        texts = int_texts(self.ranges, field_width(10, fmt))
        return ["".join(texts[k:k + 8]) for k in range(0, len(texts), 8)]

    def expand(self) -> np.ndarray:
        """All ids of the ranges, (k,) int64 (in range order)."""
        if not len(self.ranges):
            return np.zeros(0, np.int64)
        return np.concatenate([np.arange(a, b + 1) for a, b in self.ranges.tolist()])


@register
@dataclass(kw_only=True, eq=False)
class SetNodeListGenerate(_GenerateSet):
    """*SET_NODE_LIST_GENERATE: node id ranges."""

    KEYWORD: ClassVar[str] = "SET_NODE_LIST_GENERATE"


@register
@dataclass(kw_only=True, eq=False)
class SetPartListGenerate(_GenerateSet):
    """*SET_PART_LIST_GENERATE: part id ranges."""

    KEYWORD: ClassVar[str] = "SET_PART_LIST_GENERATE"


@register
@dataclass(kw_only=True, eq=False)
class SetSegment(ArrayEq, SimpleKeyword):
    """*SET_SEGMENT(_TITLE): SID DA1..DA4 SOLVER, then N1 N2 N3 N4 (A1..A4) per segment.

    segments: (s, 4) node ids, triangles with N4 = N3.
    """

    sid: int = 0
    da1: float = 0.0
    da2: float = 0.0
    da3: float = 0.0
    da4: float = 0.0
    solver: str = "MECH"
    segments: np.ndarray = field(default_factory=lambda: np.zeros((0, 4), np.int64))
    title: str = ""
    segment_lines: list[int] = field(default_factory=list, compare=False, repr=False)

    KEYWORD: ClassVar[str] = "SET_SEGMENT"
    CARDS: ClassVar[tuple[str, ...]] = ("sid da1 da2 da3 da4 solver",)
    TITLE_ATTR: ClassVar[str | None] = "title"

    def __post_init__(self) -> None:
        seg = np.asarray(self.segments, dtype=np.int64).reshape(-1, 4).copy()
        tri = seg[:, 3] == 0
        seg[tri, 3] = seg[tri, 2]
        self.segments = seg

    @classmethod
    def read_tail(cls, cur: Cursor, block: Block, values: dict[str, object]) -> dict[str, object]:
        rows, lines = read_rows(cur, ["n1", "n2", "n3", "n4"], "i")
        seg = np.array(rows, dtype=np.int64).reshape(-1, 4)
        bad = np.flatnonzero((seg[:, :3] == 0).any(axis=1))
        if bad.size:
            raise DeckError("segment with fewer than 3 nodes", block.file, lines[int(bad[0])],
                            block.name)
        return {"segments": seg, "segment_lines": lines}

    def tail_lines(self, fmt: str) -> list[str]:
        texts = int_texts(self.segments, field_width(10, fmt))
        return join_rows([texts[k::4] for k in range(4)])
