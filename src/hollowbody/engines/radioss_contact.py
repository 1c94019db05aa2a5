"""Native OpenRadioss input for the contacts of a keyword deck.

OpenRadioss's starter translates LS-DYNA keyword decks, but stops on the
contacts of hollowbody's decks (its error 2087, "reference to undefined
group", docs/engines.md). Its native starter input, however, can include a
keyword file (``/INCLUDE_LS-DYNA``, translated as a whole deck is) next to
native options. So the deck OpenRadioss gets for a deck with contacts is a
native starter file ``ROOT_0000.rad``::

    #RADIOSS STARTER
    /BEGIN                      run name, input version, units kg mm ms
    /INCLUDE_LS-DYNA            ROOT.k: the keyword deck without its contacts
    /SURF/PART(/EXT)            one surface per contact side (part lists)
    /GRNOD/NODE                 slave node sets of nodes-to-surface contacts
    /INTER/TYPE25               one interface per *CONTACT_AUTOMATIC_...
    /TH/INTER, /TH/NODE         contact forces and history nodes
    /END

written here from the parsed deck (no id of the translation is referred to:
part ids and node ids only, which the translation keeps; sets are expanded
into lists). The surfaces and groups take ids from :data:`NATIVE_ID0` on.

LS-DYNA meaning kept (``*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE``,
``_NODES_TO_SURFACE``, ``_SINGLE_SURFACE``; TYPE25 is a penalty node-to-surface
contact, symmetric when both sides are surfaces):

- stiffness: the smaller of the two sides' (``Istf = 4``, LS-DYNA's PENOPT = 1)
  times ``Stfac = SLSFAC min(SFS, SFM)`` (*CONTROL_CONTACT SLSFAC, default
  0.1: both codes compute the side stiffness as ``bulk modulus x area^2 /
  volume`` for solids); SOFT = 1 adds the mass and time-step stiffness
  (``IPSTIF = 1``, ``Stfac_mdt = SOFSCL / 2``: ``k = Stfac_mdt m* / dt^2`` with m*
  the harmonic mean of the two nodal masses, against LS-DYNA's ``SOFSCL m /
  (2 dt^2)``; equal for a node against a much heavier side, half for two
  equal masses), and the larger of the two stiffnesses is used as in LS-DYNA;
- friction: ``mu = FD + (FS - FD) exp(-DC |v|)``: Coulomb ``Fric = FS`` when
  DC = 0 (``Ifric = 0``), else the exponential law ``Ifric = 2`` with
  ``Fric = FD``, ``C5 = FS - FD``, ``C6 = -DC``; FSF scales both;
- thickness: the shell thickness, zero for solids (``Igap = 2``, gap scale
  (SFST + SFMT) / 2); SST / MST given: those thicknesses (``Igap = 5``);
- BT / DT: ``Tstart`` / ``Tstop``; initial penetrations are not pushed out
  (``Inacti = 5``: the gap starts at the penetration), eroded elements leave
  the contact (``Idel = 2``).

What differs: OpenRadioss damps the contact stiffness by 5 % of critical when
VDC = 0 (its default ``VISs``; VDC > 0 gives ``VISs = VDC / 100``), and its
shell-side penalty stiffness is its own formula; see docs/engines.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hollowbody.build.common import item_error
from hollowbody.io.keyword import (
    Contact,
    ControlContact,
    Deck,
    Part,
    RawKeyword,
    SectionSolid,
    SetNodeList,
    SetNodeListGenerate,
    SetPartList,
    SetPartListGenerate,
    SetSegment,
    TiedContact,
)

#: First id of the surfaces and node groups written here (far above the deck's).
NATIVE_ID0 = 900_000_001
#: Title of the time-history groups written here (what the converter looks for).
TH_INTER_TITLE = "hollowbody contacts"
TH_NODE_TITLE = "hollowbody nodes"
#: Contact variables and node variables of the time history.
TH_INTER_VARS = ("FNX", "FNY", "FNZ", "FTX", "FTY", "FTZ")
TH_NODE_VARS = ("DX", "DY", "DZ", "VX", "VY", "VZ")
#: The input version of the native file (OpenRadioss's 2026 input format).
INPUT_VERSION = 2026


def _f(v: float) -> str:
    """A real in a 20-character field."""
    return f"{float(v):20.10g}"


def _i(v: int) -> str:
    return f"{int(v):10d}"


def _rows(ids, per: int = 10) -> list[str]:
    ids = [int(i) for i in ids]
    return ["".join(_i(v) for v in ids[k:k + per]) for k in range(0, len(ids), per)]


@dataclass
class _Side:
    """One side of a contact as native input: its surface or node-group id and
    the lines that define it."""

    surface: int = 0
    nodes: int = 0
    lines: tuple[str, ...] = ()


class _Writer:
    """Native surfaces, node groups and interfaces of a deck's contacts."""

    def __init__(self, deck: Deck) -> None:
        self.deck = deck
        self.next_id = NATIVE_ID0
        solid_secs = {s.secid for s in deck.of_type(SectionSolid)}
        self.parts = {p.pid: p for p in deck.of_type(Part)}
        self.solid_parts = {pid for pid, p in self.parts.items() if p.secid in solid_secs}
        self.part_sets: dict[int, np.ndarray] = {}
        for s in deck.of_type(SetPartList):
            self.part_sets[s.sid] = np.asarray(s.parts, np.int64)
        for s in deck.of_type(SetPartListGenerate):
            self.part_sets[s.sid] = s.expand()
        self.node_sets: dict[int, np.ndarray] = {}
        for s in deck.of_type(SetNodeList):
            self.node_sets[s.sid] = np.asarray(s.nodes, np.int64)
        for s in deck.of_type(SetNodeListGenerate):
            self.node_sets[s.sid] = s.expand()
        self.segment_sets = {s.sid: np.asarray(s.segments, np.int64)
                             for s in deck.of_type(SetSegment)}

    def _new_id(self) -> int:
        self.next_id += 1
        return self.next_id - 1

    def _parts(self, item, set_id: int, set_type: int, what: str) -> list[int]:  # noqa: ANN001
        """The part ids of a part (3), part set (2) or all-parts (5) side."""
        if set_type == 3:
            parts = [int(set_id)]
        elif set_type == 2:
            if set_id not in self.part_sets:
                raise item_error(item, f"{what}: part set {set_id} is not defined")
            parts = [int(p) for p in self.part_sets[set_id]]
        else:
            parts = sorted(self.parts)
        missing = [p for p in parts if p not in self.parts]
        if missing or not parts:
            raise item_error(item, f"{what}: part {missing[0] if missing else '(none)'} is "
                             "not defined in the deck")
        return parts

    def node_side(self, item, set_id: int, set_type: int, what: str) -> _Side:  # noqa: ANN001
        """The native node group of a nodes-to-surface contact's slave side: a node set
        (type 4) or the nodes of parts (types 2, 3, 5)."""
        if set_type == 4:
            if set_id not in self.node_sets:
                raise item_error(item, f"{what}: node set {set_id} is not defined")
            gid = self._new_id()
            return _Side(nodes=gid, lines=(f"/GRNOD/NODE/{gid}", what[:100],
                                           *_rows(self.node_sets[set_id])))
        if set_type not in (2, 3, 5):
            self.side(item, set_id, set_type, what)  # its error for unknown sets and types
            raise item_error(item, f"{what}: a segment set as slave nodes is not written "
                             "for OpenRadioss")
        parts = self._parts(item, set_id, set_type, what)
        gid = self._new_id()
        return _Side(nodes=gid, lines=(f"/GRNOD/PART/{gid}", what[:100], *_rows(parts)))

    def side(self, item, set_id: int, set_type: int, what: str) -> _Side:  # noqa: ANN001
        """The native surface of one contact side."""
        if set_type in (2, 3, 5):
            parts = self._parts(item, set_id, set_type, what)
            sid = self._new_id()
            ext = "/EXT" if any(p in self.solid_parts for p in parts) else ""
            return _Side(surface=sid, lines=(f"/SURF/PART{ext}/{sid}", what[:100],
                                             *_rows(parts)))
        if set_type == 0:
            if set_id not in self.segment_sets:
                raise item_error(item, f"{what}: segment set {set_id} is not defined")
            sid = self._new_id()
            segs = self.segment_sets[set_id]
            rows = [_i(0) + "".join(_i(n) for n in s) for s in segs.tolist()]
            return _Side(surface=sid, lines=(f"/SURF/SEG/{sid}", what[:100], *rows))
        raise item_error(item, f"{what}: set type {set_type} is not written for OpenRadioss "
                         "(part, part set, all parts or segment set only; node sets for "
                         "the slave side of nodes-to-surface contacts)")


def _slsfac(deck: Deck) -> float:
    cc = deck.of_type(ControlContact)
    return float(cc[-1].slsfac) if cc and cc[-1].slsfac else 0.1


def interface_lines(c: Contact, iid: int, slave: _Side, master: _Side,
                    slsfac: float) -> list[str]:
    """``/INTER/TYPE25`` of one automatic contact (cards of OpenRadioss's starter
    input, 2026 format); the mapping is the module's."""
    soft = int(c.soft or 0)
    sofscl = float(c.sofscl) if c.sofscl else 0.1
    thick = c.sst != 0.0 or c.mst != 0.0
    igap = 5 if thick else 2
    ipstif = 1 if soft == 1 else 0
    stfac_mdt = 0.5 * sofscl if soft == 1 else 0.0
    sfs = c.sfs or 1.0
    sfm = c.sfm or 1.0
    stfac = slsfac * min(sfs, sfm)
    fsf = c.fsf or 1.0
    if c.dc == 0.0 or c.fs == c.fd:
        ifric, fric = 0, c.fs * fsf
    else:
        ifric, fric = 2, c.fd * fsf
    gap_scale = 0.5 * ((c.sfst or 1.0) + (c.sfmt or 1.0))
    viss = c.vdc / 100.0 if c.vdc > 0.0 else 0.0
    title = (c.heading or f"contact {iid}")[:100]
    lines = [f"/INTER/TYPE25/{iid}", title,
             _i(slave.surface) + _i(master.surface) + _i(4) + _i(0) + _i(igap) + _i(0)
             + " " * 10 + _i(2) + _i(0) + _i(ipstif),
             _i(slave.nodes) + " " * 10 + _f(gap_scale) + _f(0.0) + _f(0.0) + _f(0.0),
             _f(0.0) + _f(0.0) + _i(0) + _i(0) + _f(0.0) + _f(stfac_mdt),
             _f(stfac) + _f(fric) + _f(0.0) + _f(c.bt) + _f(c.dt or 1.0e20),
             " " * 7 + "000" + " " * 10 + _i(0) + _i(5) + _f(viss) + _i(0) + " " * 10
             + _f(0.0),
             _i(ifric) + _i(0) + _f(0.0) + " " * 10 + _i(0) + _f(0.0) + " " * 10 + _i(0)]
    if ifric > 0:
        lines.append(_f(0.0) * 4 + _f((c.fs - c.fd) * fsf))
        lines.append(_f(-c.dc))
    if thick:
        lines.append(_f(c.sst) + _f(c.sfst or 1.0) + _f(c.mst) + _f(c.sfmt or 1.0))
    return lines


def contact_items(deck: Deck) -> list:
    """The contact definitions of a deck (automatic, tied, and unread ``*CONTACT_``)."""
    items = [*deck.of_type(Contact), *deck.of_type(TiedContact)]
    items += [i for i in deck.iter_items()
              if isinstance(i, RawKeyword) and i.keyword.upper().startswith("CONTACT")]
    return items


def check_contacts(deck: Deck) -> None:
    """DeckError (file, line, keyword) for a contact that is not written natively:
    tied contacts and contact keywords hollowbody does not read."""
    for item in contact_items(deck):
        if not isinstance(item, Contact):
            raise item_error(item, "this contact is not written for OpenRadioss (automatic "
                             "surface-to-surface, nodes-to-surface and single-surface "
                             "contacts are); run this deck with --engine hollowbody or lsdyna")


def native_contact_lines(deck: Deck, history_nodes: list[int]) -> tuple[list[str], list[str]]:
    """(lines, notes): the native surfaces, node groups, ``/INTER/TYPE25`` cards and
    ``/TH/INTER`` + ``/TH/NODE`` groups of ``deck``'s contacts and history nodes.
    DeckError for what is not written (:func:`check_contacts`, unknown sets)."""
    check_contacts(deck)
    w = _Writer(deck)
    slsfac = _slsfac(deck)
    lines: list[str] = []
    inters: list[int] = []
    used = {int(c.cid) for c in deck.of_type(Contact) if c.cid}
    auto = iter(k for k in range(1, 10**9) if k not in used)
    for c in deck.of_type(Contact):
        iid = int(c.cid) if c.cid else next(auto)
        name = c.heading or f"contact {iid}"
        if c.type == "AUTOMATIC_NODES_TO_SURFACE":  # one-way: slave nodes on master
            slave = w.node_side(c, c.ssid, c.sstyp, f"{name}: slave nodes")
            master = w.side(c, c.msid, c.mstyp, f"{name}: master")
        elif c.type == "AUTOMATIC_SINGLE_SURFACE":
            slave = w.side(c, c.ssid, c.sstyp if c.ssid or c.sstyp else 5, f"{name}: surface")
            master = _Side()
        else:
            slave = w.side(c, c.ssid, c.sstyp, f"{name}: slave")
            master = w.side(c, c.msid, c.mstyp, f"{name}: master")
        lines += [*slave.lines, *master.lines]
        lines += interface_lines(c, iid, slave, master, slsfac)
        inters.append(iid)
    if inters:
        lines += [f"/TH/INTER/{NATIVE_ID0 - 1}", TH_INTER_TITLE,
                  "".join(f"{v:<10s}" for v in TH_INTER_VARS), *_rows(inters)]
    if history_nodes:
        lines += [f"/TH/NODE/{NATIVE_ID0 - 2}", TH_NODE_TITLE,
                  "".join(f"{v:<10s}" for v in TH_NODE_VARS)]
        lines += [_i(n) + _i(0) for n in history_nodes]
    notes = [f"{len(inters)} contact(s) written as native /INTER/TYPE25 (SLSFAC {slsfac:g}; "
             "docs/engines.md)"] if inters else []
    return lines, notes


def starter_file_text(root: str, keyword_file: str, contact_lines: list[str],
                      title: str = "") -> str:
    """The native starter input: /BEGIN (units kg mm ms), the keyword file through
    /INCLUDE_LS-DYNA, then ``contact_lines`` and /END."""
    units = f"{'kg':>20s}{'mm':>20s}{'ms':>20s}"
    lines = ["#RADIOSS STARTER",
             f"# written by hollowbody{': ' + title if title else ''}"[:100],
             "/BEGIN", root[:100], _i(INPUT_VERSION), units, units,
             "/INCLUDE_LS-DYNA", keyword_file,
             *contact_lines, "/END"]
    return "\n".join(lines) + "\n"
