"""The input OpenRadioss gets from a hollowbody deck.

Choice (docs/engines.md, "OpenRadioss: the deck it gets"): the starter reads
a native starter file ``ROOT_0000.rad`` that includes the keyword deck
(``/INCLUDE_LS-DYNA``), rewritten, and adds native options for what the
keyword translation does not run: the contacts (``/SURF/PART`` +
``/INTER/TYPE25``, :mod:`hollowbody.engines.radioss_contact`) and the time
history of the contacts and the history nodes (``/TH/INTER``, ``/TH/NODE``). The
element, material, part, load and initial-condition keywords go through
OpenRadioss's own translation unchanged (one translation, OpenRadioss's own,
rather than a second one of ours). The rewrite of the keyword deck only does
what the translation does not do as LS-DYNA does:

- includes are written inline (one file: ``*INCLUDE_PATH`` folders and relative
  include names then mean nothing to the starter);
- ``*CONTROL_CONTACT`` is left out (the translation ignores it; its SLSFAC goes
  into the native contacts) and said so;
- ``*CONTACT_...`` and ``*DATABASE_HISTORY_NODE(_SET)`` are left out of the
  keyword file and written natively (the starter stops on the translation of
  every contact of our decks: its error 2087, "reference to undefined group",
  where it turns part and segment sets into its groups); tied contacts are
  refused with a clear error.

The engine file ``ROOT_0001.rad`` (OpenRadioss's engine input) is the one the
starter derives from the deck, merged after the starter with hollowbody's
(:func:`merge_engine_files`: the starter's options are kept, e.g. mass
scaling, except those hollowbody sets), which sets what the translation maps
differently: the end time (``/RUN``), the time-history and
animation intervals (``/TFILE``, ``/ANIM/DT`` from *DATABASE_GLSTAT and
*DATABASE_BINARY_D3PLOT), the listing print interval (``/PRINT``), and DTMIN
(LS-DYNA: stop when the step falls below DTMIN x the initial step; the
translation maps it only through DT2MS) as ``/DT/BRICK/STOP`` and
``/DT/SHELL/STOP`` with TSSFAC and the absolute minimum step (``/DEL`` instead
of ``/STOP`` with *CONTROL_TIMESTEP ERODE = 1: LS-DYNA then deletes the element
whose step falls below DTMIN instead of stopping).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hollowbody.engines.radioss_contact import (
    contact_items,
    native_contact_lines,
    starter_file_text,
)
from hollowbody.io.keyword import (
    ControlContact,
    ControlTermination,
    ControlTimestep,
    DatabaseAscii,
    DatabaseBinaryD3plot,
    DatabaseHistoryNode,
    DatabaseHistoryNodeSet,
    Deck,
    RawKeyword,
    SetNodeList,
    SetNodeListGenerate,
    read_deck,
    write_deck,
)

#: Cycles between two rows of the engine listing.
PRINT_CYCLES = 100
#: Output intervals when the deck asks for none: end time / this count.
DEFAULT_HISTORY_COUNT = 500
DEFAULT_STATE_COUNT = 20


@dataclass(frozen=True)
class EngineSettings:
    """What the engine file sets: end time (ms), time-history and animation intervals
    (ms), TSSFAC, the absolute minimum step (ms; 0: none) and whether an element
    below it is deleted (ERODE = 1) instead of stopping the run."""

    end_time: float
    history_dt: float
    anim_dt: float
    tssfac: float = 0.9
    dtmin_abs: float = 0.0
    erode: bool = False


def starter_input(deck_path: Path, out_dir: Path) -> Path:
    """The file OpenRadioss's starter reads for ``deck_path`` written into ``out_dir``:
    ``out_dir/ROOT_0000.rad`` (ROOT: the deck's name)."""
    return Path(out_dir) / f"{Path(deck_path).stem}_0000.rad"


def check_for_openradioss(deck: Deck) -> list[str]:
    """DeckError (file, line, keyword) for what is not written for OpenRadioss: tied
    contacts, contacts on sets of a kind not written, undefined sets. Returns the
    notes on the contacts written natively."""
    return native_contact_lines(deck, [])[1]


def history_nodes(deck: Deck) -> list[int]:
    """The deck's history nodes (*DATABASE_HISTORY_NODE and the nodes of the sets of
    *DATABASE_HISTORY_NODE_SET), in order, each once."""
    sets = {s.sid: np.asarray(s.nodes, np.int64) for s in deck.of_type(SetNodeList)}
    sets.update({s.sid: s.expand() for s in deck.of_type(SetNodeListGenerate)})
    out: list[int] = []
    for item in deck.of_type(DatabaseHistoryNode):
        out += [int(i) for i in np.asarray(item.ids).reshape(-1)]
    for item in deck.of_type(DatabaseHistoryNodeSet):
        for sid in np.asarray(item.ids).reshape(-1):
            out += [int(i) for i in sets.get(int(sid), [])]
    return list(dict.fromkeys(i for i in out if i > 0))


def rewrite_for_openradioss(deck_path: Path, out: Path) -> tuple[Path, list[str]]:
    """Write the input of OpenRadioss's starter: the keyword deck ``out`` (a .k file,
    rewritten) and the native starter file ``ROOT_0000.rad`` next to it that includes
    it and holds the contacts and history groups (:func:`starter_input`); returns the
    starter file and the notes on what was changed. DeckError when the deck holds what
    is not written for OpenRadioss (:func:`check_for_openradioss`)."""
    deck = read_deck(deck_path)
    nodes = history_nodes(deck)
    contact_lines, notes = native_contact_lines(deck, nodes)
    if deck.includes():
        notes.append(f"{len(deck.includes())} include(s) written inline")
    dropped = _drop(deck, lambda i: isinstance(i, ControlContact))
    if dropped:
        notes.append("*CONTROL_CONTACT left out (OpenRadioss's translation ignores it; "
                     "SLSFAC is in the native contacts)")
    paths = _drop(deck, lambda i: isinstance(i, RawKeyword)
                  and i.keyword.upper().startswith("INCLUDE_PATH"))
    if paths:
        notes.append("*INCLUDE_PATH left out (includes written inline)")
    contacts = {id(i) for i in contact_items(deck)}
    n_contacts = _drop(deck, lambda i: id(i) in contacts)
    if n_contacts:
        notes.append(f"{n_contacts} *CONTACT_ left out of the keyword file (native "
                     "/INTER/TYPE25 in the starter file)")
    _drop(deck, lambda i: isinstance(i, (DatabaseHistoryNode, DatabaseHistoryNodeSet)))
    out = Path(out)
    write_deck(deck, out, flatten=True)
    starter = starter_input(out, out.parent)
    starter.write_text(starter_file_text(out.stem, out.name, contact_lines, deck.title))
    return starter, notes


def _drop(deck: Deck, pred) -> int:
    """Remove the items of ``deck`` (and of its includes) for which ``pred`` holds."""
    n = 0
    decks = [deck, *(inc.deck for inc in deck.includes() if inc.deck is not None)]
    for d in decks:
        keep = [i for i in d.items if not pred(i)]
        n += len(d.items) - len(keep)
        d.items[:] = keep
    return n


def engine_settings(deck: Deck, dt0: float | None = None) -> EngineSettings:
    """The engine file's settings from the deck's *CONTROL_TERMINATION, *CONTROL_TIMESTEP,
    *DATABASE_GLSTAT and *DATABASE_BINARY_D3PLOT; dt0: the initial step (ms) that
    DTMIN is a fraction of (None: no minimum step)."""
    term = (deck.of_type(ControlTermination) or [ControlTermination()])[-1]
    ts = (deck.of_type(ControlTimestep) or [ControlTimestep()])[-1]
    end = float(term.endtim)
    glstat = [d for d in deck.of_type(DatabaseAscii) if d.name == "GLSTAT"]
    hist = float(glstat[-1].dt) if glstat and glstat[-1].dt else 0.0
    d3 = deck.of_type(DatabaseBinaryD3plot)
    anim = float(d3[-1].dt) if d3 and d3[-1].dt else 0.0
    dtmin = float(term.dtmin or 0.0)
    return EngineSettings(
        end_time=end,
        history_dt=hist or (end / DEFAULT_HISTORY_COUNT if end > 0 else 0.0),
        anim_dt=anim or (end / DEFAULT_STATE_COUNT if end > 0 else 0.0),
        tssfac=float(ts.tssfac or 0.9),
        dtmin_abs=dtmin * dt0 if (dt0 and dtmin > 0.0) else 0.0,
        erode=bool(ts.erode))


def _num(v: float) -> str:
    return f"{v:20.6g}"


def engine_file_text(root: str, s: EngineSettings, source: str = "") -> str:
    """OpenRadioss engine input (block format) for run ``root`` with settings ``s``."""
    origin = f" from {source}" if source else ""
    lines = [f"# OpenRadioss engine input written by hollowbody{origin}",
             f"/RUN/{root}/1", _num(s.end_time),
             "/TFILE", _num(s.history_dt),
             "/ANIM/DT", _num(0.0) + _num(s.anim_dt),
             "/ANIM/VECT/DISP", "/ANIM/VECT/VEL", "/ANIM/ELEM/VONM", "/ANIM/ELEM/EPSP",
             "/TH/TITLE",
             f"/PRINT/-{PRINT_CYCLES}"]
    if s.dtmin_abs > 0.0:
        for eltyp in ("BRICK", "SHELL"):
            lines += [f"/DT/{eltyp}/{'DEL' if s.erode else 'STOP'}",
                      _num(s.tssfac) + _num(s.dtmin_abs)]
    return "\n".join(lines) + "\n"


def _blocks(text: str) -> list[tuple[str, list[str]]]:
    """(keyword line, lines) blocks of an engine file; text before the first keyword
    (comments) is dropped."""
    out: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        if line.startswith("/"):
            out.append((line.strip(), [line]))
        elif out:
            out[-1][1].append(line)
    return out


def _family(keyword: str) -> str:
    """The option a block sets: ``/RUN``, ``/TFILE``, ``/PRINT``, ``/ANIM/DT``,
    ``/DT/BRICK``, ... (``/DT/BRICK/STOP`` and ``/DT/BRICK/CST`` are one option),
    or the keyword itself."""
    parts = keyword.split("/")[1:]
    head = parts[0].upper() if parts else ""
    if head in ("RUN", "TFILE", "PRINT"):
        return "/" + head
    if head == "DT" and len(parts) > 1:
        return "/DT/" + parts[1].upper()
    if head == "ANIM" and len(parts) > 1 and parts[1].upper() == "DT":
        return "/ANIM/DT"
    return keyword.upper()


def merge_engine_files(generated: str, ours: str) -> str:
    """The engine file: hollowbody's options (``ours``) and the starter's (``generated``)
    that hollowbody does not set; ``/RUN`` first, as the engine input requires."""
    mine = _blocks(ours)
    taken = {_family(k) for k, _ in mine}
    kept = [b for b in _blocks(generated) if _family(b[0]) not in taken]
    run = [b for b in mine if _family(b[0]) == "/RUN"]
    rest = [b for b in mine if _family(b[0]) != "/RUN"]
    head = [line for line in ours.splitlines() if line.startswith("#")][:1]
    lines = head + [line for _, block in run + kept + rest for line in block]
    return "\n".join(lines) + "\n"
