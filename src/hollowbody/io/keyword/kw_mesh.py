"""Mesh keywords: *NODE, *ELEMENT_SOLID, *ELEMENT_SHELL, *ELEMENT_MASS.

All four are bulk blocks parsed column-wise (:mod:`.bulk`); ids are kept as
LS-DYNA ids (the builder maps them to indices). ``row_lines`` holds the file
line of every row (for messages; not compared, not written).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from hollowbody.errors import DeckError
from hollowbody.io.keyword import bulk
from hollowbody.io.keyword.base import Block, KeywordItem, register
from hollowbody.io.keyword.cards import field_width


def _eq_arrays(a: np.ndarray | None, b: np.ndarray | None) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return a.shape == b.shape and bool(np.array_equal(a, b))


def _needs_long(*id_arrays: np.ndarray, width: int = 8) -> bool:
    limit = 10 ** width
    return any(a.size and (int(a.max()) >= limit or int(a.min()) <= -limit // 10)
               for a in id_arrays)


def _keyword_line(name: str, fmt: str) -> str:
    return f"*{name}" + {"long": " +", "i10": " %"}.get(fmt, "")


def _rows(a: object, n: int, cols: int) -> np.ndarray:
    """``a`` as an (n, k) int64 array ((0, cols) when empty)."""
    arr = np.asarray(a, dtype=np.int64)
    return arr.reshape(n, -1) if n else np.zeros((0, cols), np.int64)


def solid_conn8(conn: np.ndarray) -> np.ndarray:
    """Connectivity as (e, 8) degenerate hexahedra.

    (e, 8) is returned as is; (e, 6) pentahedra N1..N6 become
    N1 N2 N3 N4 N5 N5 N6 N6; (e, 4) tetrahedra become N1 N2 N3 N4 N4 N4 N4 N4.
    """
    c = np.asarray(conn, dtype=np.int64)
    if c.ndim != 2 or c.shape[1] not in (4, 6, 8):
        raise ValueError(f"solid connectivity must be (e, 8), (e, 6) or (e, 4), got {c.shape}")
    if c.shape[1] == 6:
        return c[:, [0, 1, 2, 3, 4, 4, 5, 5]]
    if c.shape[1] == 4:
        return c[:, [0, 1, 2, 3, 3, 3, 3, 3]]
    return c


@register
@dataclass(kw_only=True, eq=False)
class Nodes(KeywordItem):
    """*NODE: ids (n,) int64, xyz (n, 3) float64 mm, tc / rc (n,) int64 constraint codes."""

    ids: np.ndarray
    xyz: np.ndarray
    tc: np.ndarray | None = None
    rc: np.ndarray | None = None
    row_lines: np.ndarray | None = field(default=None, repr=False)

    KEYWORD: ClassVar[str] = "NODE"

    def __post_init__(self) -> None:
        self.ids = np.asarray(self.ids, dtype=np.int64).reshape(-1)
        self.xyz = np.asarray(self.xyz, dtype=np.float64).reshape(-1, 3)
        if self.xyz.shape[0] != self.ids.shape[0]:
            raise ValueError("Nodes: ids and xyz differ in length")
        for name in ("tc", "rc"):
            v = getattr(self, name)
            if v is not None:
                v = np.asarray(v, dtype=np.int64).reshape(-1)
                setattr(self, name, v if v.any() else None)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Nodes):
            return NotImplemented
        return (_eq_arrays(self.ids, other.ids) and _eq_arrays(self.xyz, other.xyz)
                and _eq_arrays(self.tc, other.tc) and _eq_arrays(self.rc, other.rc))

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        wi, wf = field_width(8, block.fmt), field_width(16, block.fmt)
        t = bulk.row_table(block, 3 * wf + 3 * wi)
        ids = bulk.parse_ints(t, 0, wi, 1, ["nid"], 0)[:, 0]
        xyz = bulk.parse_floats(t, wi, wf, 3, ["x", "y", "z"], 1)
        tc = bulk.parse_ints(t, wi + 3 * wf, wi, 1, ["tc"], 4)[:, 0]
        rc = bulk.parse_ints(t, 2 * wi + 3 * wf, wi, 1, ["rc"], 5)[:, 0]
        line = int(t.lines[0]) if t.n else block.line
        return [cls(ids=ids, xyz=xyz, tc=tc, rc=rc, row_lines=t.lines,
                    source=block.source(line))]

    def to_lines(self, fmt: str = "standard") -> list[str]:
        if fmt == "standard" and _needs_long(self.ids):
            fmt = "long"
        wi, wf = field_width(8, fmt), field_width(16, fmt)
        cols = [bulk.int_texts(self.ids, wi)]
        flat = bulk.float_texts(self.xyz, wf)
        cols += [flat[0::3], flat[1::3], flat[2::3]]
        if self.tc is not None or self.rc is not None:
            zeros = np.zeros_like(self.ids)
            cols.append(bulk.int_texts(self.tc if self.tc is not None else zeros, wi))
            cols.append(bulk.int_texts(self.rc if self.rc is not None else zeros, wi))
        return [_keyword_line("NODE", fmt), *bulk.join_rows(cols)]


@register
@dataclass(kw_only=True, eq=False)
class SolidElements(KeywordItem):
    """*ELEMENT_SOLID: ids (e,), pids (e,), conn (e, 8) node ids (degenerate hex form).

    Read from the one-card form (EID PID N1..N8) or the two-card form (EID
    PID, then N1..N10); 4-node tetrahedra (N5..N8 blank) are expanded to
    N1 N2 N3 N4 N4 N4 N4 N4. Ten-node tetrahedra are rejected.
    """

    ids: np.ndarray
    pids: np.ndarray
    conn: np.ndarray
    row_lines: np.ndarray | None = field(default=None, repr=False)

    KEYWORD: ClassVar[str] = "ELEMENT_SOLID"

    def __post_init__(self) -> None:
        self.ids = np.asarray(self.ids, dtype=np.int64).reshape(-1)
        self.conn = solid_conn8(_rows(self.conn, self.ids.shape[0], 8))
        self.pids = np.broadcast_to(np.asarray(self.pids, dtype=np.int64),
                                    self.ids.shape).copy()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, SolidElements):
            return NotImplemented
        return (_eq_arrays(self.ids, other.ids) and _eq_arrays(self.pids, other.pids)
                and _eq_arrays(self.conn, other.conn))

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        w = field_width(8, block.fmt)
        t = bulk.row_table(block, 10 * w)
        two_card = t.n > 0 and (
            len([p for p in t.free[0].split(",") if p.strip()]) <= 2 if 0 in t.free
            else not (t.mat[0, 2 * w:] != 32).any())
        names = ["eid", "pid"] + [f"n{k}" for k in range(1, 11)]
        if two_card:
            if t.n % 2:
                raise DeckError(f"element {t.text(t.n - 1)[:w].strip()}: missing card 2 "
                                "(N1..N8)", t.file, int(t.lines[-1]), t.keyword)
            head, nodes = t.take(slice(0, None, 2)), t.take(slice(1, None, 2))
            ep = bulk.parse_ints(head, 0, w, 2, names[:2], 0)
            conn = bulk.parse_ints(nodes, 0, w, 10, names[2:], 0)
            lines = head.lines
            bad = np.flatnonzero(conn[:, 8:].any(axis=1))
            if bad.size:
                raise DeckError(f"element {ep[bad[0], 0]}: ten-node tetrahedra are not "
                                "supported", t.file, int(nodes.lines[bad[0]]), t.keyword)
            conn = conn[:, :8]
        else:
            vals = bulk.parse_ints(t, 0, w, 10, names[:10], 0)
            ep, conn, lines = vals[:, :2], vals[:, 2:], t.lines
        tet = (conn[:, 4:] == 0).all(axis=1) & (conn[:, 3] != 0)
        conn[tet, 4:] = conn[tet, 3:4]
        blank = np.flatnonzero((conn == 0).any(axis=1))
        if blank.size:
            r = int(blank[0])
            k = int(np.flatnonzero(conn[r] == 0)[0]) + 1
            raise DeckError(f"element {ep[r, 0]}: node N{k} is blank", t.file,
                            int(lines[r]), t.keyword)
        line = int(lines[0]) if t.n else block.line
        return [cls(ids=ep[:, 0], pids=ep[:, 1], conn=conn, row_lines=lines,
                    source=block.source(line))]

    def to_lines(self, fmt: str = "standard") -> list[str]:
        if fmt == "standard" and _needs_long(self.ids, self.pids, self.conn):
            fmt = "long"
        w = field_width(8, fmt)
        rows = bulk.int_rows(np.column_stack([self.ids, self.pids, self.conn]), w)
        return [_keyword_line("ELEMENT_SOLID", fmt), *rows]


@register
@dataclass(kw_only=True, eq=False)
class ShellElements(KeywordItem):
    """*ELEMENT_SHELL (options _THICKNESS, _BETA, _MCID).

    ids (e,), pids (e,), conn (e, 4) node ids (triangles: N4 = N3);
    thickness (e, 4) mm nodal thicknesses or None (section thickness); beta
    (e,) the BETA / MCID value of the second card; option: the option written.
    """

    ids: np.ndarray
    pids: np.ndarray
    conn: np.ndarray
    thickness: np.ndarray | None = None
    beta: np.ndarray | None = None
    option: str = ""
    row_lines: np.ndarray | None = field(default=None, repr=False)

    KEYWORD: ClassVar[str] = "ELEMENT_SHELL"
    OPTIONS: ClassVar[frozenset[str]] = frozenset({"THICKNESS", "BETA", "MCID"})

    def __post_init__(self) -> None:
        self.ids = np.asarray(self.ids, dtype=np.int64).reshape(-1)
        c = _rows(self.conn, self.ids.shape[0], 4)
        if c.shape[1] == 3:
            c = c[:, [0, 1, 2, 2]]
        if c.shape[1] != 4:
            raise ValueError(f"shell connectivity must be (e, 4) or (e, 3), got {c.shape}")
        c = c.copy()
        tri = c[:, 3] == 0
        c[tri, 3] = c[tri, 2]
        self.conn = c
        self.pids = np.broadcast_to(np.asarray(self.pids, dtype=np.int64),
                                    self.ids.shape).copy()
        if self.thickness is not None:
            self.thickness = np.broadcast_to(np.asarray(self.thickness, dtype=np.float64)
                                             .reshape(-1, 1) if np.ndim(self.thickness) < 2
                                             else np.asarray(self.thickness, np.float64),
                                             (self.ids.shape[0], 4)).copy()
            self.option = self.option or "THICKNESS"
        if self.beta is not None or self.thickness is not None:
            self.beta = np.broadcast_to(np.asarray(0.0 if self.beta is None else self.beta,
                                                   dtype=np.float64), self.ids.shape).copy()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ShellElements):
            return NotImplemented
        return (_eq_arrays(self.ids, other.ids) and _eq_arrays(self.pids, other.pids)
                and _eq_arrays(self.conn, other.conn)
                and _eq_arrays(self.thickness, other.thickness)
                and _eq_arrays(self.beta, other.beta))

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        wi, wf = field_width(8, block.fmt), field_width(16, block.fmt)
        t = bulk.row_table(block, max(10 * wi, 5 * wf))
        option = block.options[0] if block.options else ""
        head = t
        if option:
            if t.n % 2:
                raise DeckError("missing card 2 (THIC1..THIC4, BETA) of the last element",
                                t.file, int(t.lines[-1]), t.keyword)
            head, second = t.take(slice(0, None, 2)), t.take(slice(1, None, 2))
        names = ["eid", "pid"] + [f"n{k}" for k in range(1, 9)]
        vals = bulk.parse_ints(head, 0, wi, 10, names, 0)
        eight = np.flatnonzero(vals[:, 6:].any(axis=1))
        if eight.size:
            r = int(eight[0])
            raise DeckError(f"element {vals[r, 0]}: 8-node shells are not supported", t.file,
                            int(head.lines[r]), t.keyword)
        conn = vals[:, 2:6]
        blank = np.flatnonzero((conn[:, :3] == 0).any(axis=1))
        if blank.size:
            r = int(blank[0])
            raise DeckError(f"element {vals[r, 0]}: fewer than 3 nodes", t.file,
                            int(head.lines[r]), t.keyword)
        thickness = beta = None
        if option:
            th = bulk.parse_floats(second, 0, wf, 5, ["thic1", "thic2", "thic3", "thic4",
                                                      option.lower()], 0)
            thickness, beta = th[:, :4], th[:, 4]
        line = int(head.lines[0]) if head.n else block.line
        return [cls(ids=vals[:, 0], pids=vals[:, 1], conn=conn, thickness=thickness,
                    beta=beta, option=option, row_lines=head.lines,
                    source=block.source(line))]

    def to_lines(self, fmt: str = "standard") -> list[str]:
        if fmt == "standard" and _needs_long(self.ids, self.pids, self.conn):
            fmt = "long"
        wi, wf = field_width(8, fmt), field_width(16, fmt)
        rows = bulk.int_rows(np.column_stack([self.ids, self.pids, self.conn]), wi)
        name = "ELEMENT_SHELL"
        if self.thickness is not None or self.beta is not None:
            option = self.option or "THICKNESS"
            name += "_" + option
            th = self.thickness if self.thickness is not None else np.zeros((len(rows), 4))
            beta = self.beta if self.beta is not None else np.zeros(len(rows))
            flat = bulk.float_texts(np.column_stack([th, beta]), wf)
            second = bulk.join_rows([flat[k::5] for k in range(5)])
            rows = [r for pair in zip(rows, second) for r in pair]
        return [_keyword_line(name, fmt), *rows]


@register
@dataclass(kw_only=True, eq=False)
class MassElements(KeywordItem):
    """*ELEMENT_MASS: ids (k,), nids (k,) node ids, mass (k,) kg, pids (k,) (0 = none)."""

    ids: np.ndarray
    nids: np.ndarray
    mass: np.ndarray
    pids: np.ndarray | None = None
    row_lines: np.ndarray | None = field(default=None, repr=False)

    KEYWORD: ClassVar[str] = "ELEMENT_MASS"

    def __post_init__(self) -> None:
        self.ids = np.asarray(self.ids, dtype=np.int64).reshape(-1)
        self.nids = np.asarray(self.nids, dtype=np.int64).reshape(-1)
        self.mass = np.broadcast_to(np.asarray(self.mass, np.float64), self.ids.shape).copy()
        self.pids = np.zeros_like(self.ids) if self.pids is None else \
            np.broadcast_to(np.asarray(self.pids, np.int64), self.ids.shape).copy()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, MassElements):
            return NotImplemented
        return (_eq_arrays(self.ids, other.ids) and _eq_arrays(self.nids, other.nids)
                and _eq_arrays(self.mass, other.mass) and _eq_arrays(self.pids, other.pids))

    @classmethod
    def read(cls, block: Block) -> list[KeywordItem]:
        wi, wf = field_width(8, block.fmt), field_width(16, block.fmt)
        t = bulk.row_table(block, 3 * wi + wf)
        en = bulk.parse_ints(t, 0, wi, 2, ["eid", "nid"], 0)
        mass = bulk.parse_floats(t, 2 * wi, wf, 1, ["mass"], 2)[:, 0]
        pid = bulk.parse_ints(t, 2 * wi + wf, wi, 1, ["pid"], 3)[:, 0]
        line = int(t.lines[0]) if t.n else block.line
        return [cls(ids=en[:, 0], nids=en[:, 1], mass=mass, pids=pid, row_lines=t.lines,
                    source=block.source(line))]

    def to_lines(self, fmt: str = "standard") -> list[str]:
        if fmt == "standard" and _needs_long(self.ids, self.nids):
            fmt = "long"
        wi, wf = field_width(8, fmt), field_width(16, fmt)
        cols = [bulk.int_texts(self.ids, wi), bulk.int_texts(self.nids, wi),
                bulk.float_texts(self.mass, wf), bulk.int_texts(self.pids, wi)]
        return [_keyword_line("ELEMENT_MASS", fmt), *bulk.join_rows(cols)]
