"""Restart files (LS-DYNA's d3dump idea): the whole State of a run, to resume it.

``*DATABASE_BINARY_D3DUMP`` with CYCL > 0 writes a dump every CYCL cycles into
the run folder as ``d3dump01``, ``d3dump02``, ... (numbered, all kept, as
LS-DYNA does); a user interrupt (Ctrl-C, SIGTERM) and an error termination
write one more. ``hollowbody run DECK --out DIR --restart [FILE]`` resumes
from the newest dump of DIR (or FILE).

A dump holds the State (:mod:`hollowbody.solver.state`), the positions of the
run's output files (so the histories continue without duplicated or missing
rows) and a fingerprint of the model it belongs to (nodes, elements, parts).
File layout: the magic line, one JSON header line (format, hollowbody
version, fingerprint, time, cycle, payload size and SHA-256), then the
payload (a pickle of plain Python and numpy data). Each file is written to a
temporary name and renamed, so a run killed while writing keeps its
previous dumps whole. A dump of another model, of another version, truncated
or damaged is refused with :class:`RestartError` (exit 2).
"""

from __future__ import annotations

import hashlib
import json
import os
import pickle
import re
from pathlib import Path

import numpy as np

from hollowbody import __version__
from hollowbody.errors import UserInputError
from hollowbody.model.model import FULL_ELFORMS

MAGIC = b"HOLLOWBODY-D3DUMP\n"
#: 2: contacts carry their kinematic step limit; State its controlling contact.
#: 3: contact lists made for the per-axis re-sort bound (their distance cut allows
#: sqrt(3) margins); format 2 files are read and their contacts re-sort at once
#: (explicit._resume), so that the lists they carry are never relied on.
FORMAT = 3
#: formats this version reads
READABLE = (2, 3)
_NAME = re.compile(r"^d3dump(\d+)$")


class RestartError(UserInputError):
    """A restart file that cannot be used (printed as one line, exit 2)."""


def fingerprint(model) -> str:  # noqa: ANN001 - Model
    """SHA-256 (hex) of what identifies a model: node ids and coordinates, element
    ids and connectivities per part, part materials' kinds, fully integrated solid
    sections. Controls (end time,
    erosion, output intervals) are not in it: they may change on a restart."""
    h = hashlib.sha256()
    for a in (model.node_ids, model.node_x0):
        h.update(np.ascontiguousarray(a).tobytes())
    for g in list(model.solid_groups) + list(model.shell_groups):
        h.update(f"part {g.pid} {model.material_of(g.pid).kind}".encode())
        sec = model.sections.get(model.parts[g.pid].secid) if g.pid in model.parts else None
        if sec is not None and sec.kind == "solid" and sec.elform in FULL_ELFORMS:
            # the fully integrated element keeps other state (ELFORM 1 models keep
            # the fingerprint they had before it existed)
            h.update(b" fully integrated")
        h.update(np.ascontiguousarray(g.elem_ids, dtype=np.int64).tobytes())
        h.update(np.ascontiguousarray(g.conn, dtype=np.int64).tobytes())
    return h.hexdigest()


def dump_files(folder: Path) -> list[Path]:
    """The ``d3dumpNN`` files of ``folder``, oldest first."""
    folder = Path(folder)
    if not folder.is_dir():
        return []
    found = [(int(m.group(1)), p) for p in folder.iterdir()
             if (m := _NAME.match(p.name)) and p.is_file()]
    return [p for _, p in sorted(found)]


def next_dump_path(folder: Path) -> Path:
    """Path of the next dump in ``folder`` (one number past the highest)."""
    files = dump_files(folder)
    k = int(_NAME.match(files[-1].name).group(1)) + 1 if files else 1
    return Path(folder) / f"d3dump{k:02d}"


def write_dump(path: Path, model, payload: dict, t: float, cycle: int) -> Path:  # noqa: ANN001
    """Write ``payload`` as a restart file at ``path`` (atomically); returns path."""
    path = Path(path)
    body = pickle.dumps(payload, protocol=pickle.HIGHEST_PROTOCOL)
    header = {"format": FORMAT, "version": __version__, "fingerprint": fingerprint(model),
              "time_ms": t, "cycle": cycle, "payload_bytes": len(body),
              "payload_sha256": hashlib.sha256(body).hexdigest()}
    tmp = path.with_name(f".{path.name}.tmp")
    with open(tmp, "wb") as fh:
        fh.write(MAGIC)
        fh.write(json.dumps(header).encode() + b"\n")
        fh.write(body)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)
    return path


def read_header(path: Path) -> dict:
    """The JSON header of a restart file (RestartError when it is not one)."""
    path = Path(path)
    try:
        with open(path, "rb") as fh:
            if fh.read(len(MAGIC)) != MAGIC:
                raise RestartError(f"{path}: not a hollowbody restart file")
            line = fh.readline()
    except OSError as exc:
        raise RestartError(f"{path}: cannot read the restart file ({exc.strerror})") from None
    try:
        return json.loads(line)
    except ValueError:
        raise RestartError(f"{path}: the restart file's header is damaged") from None


def read_dump(path: Path, model) -> tuple[dict, dict]:  # noqa: ANN001 - Model
    """(header, payload) of the restart file ``path``, checked against ``model``.

    Raises RestartError when the file is not a restart file, was written by
    another version or format, belongs to another model, or is truncated or
    damaged.
    """
    path = Path(path)
    header = read_header(path)
    if header.get("format") not in READABLE or header.get("version") != __version__:
        raise RestartError(f"{path}: written by hollowbody {header.get('version')} "
                           f"(format {header.get('format')}); this is {__version__} "
                           f"(format {FORMAT}): restart files are read by the version "
                           "that wrote them")
    if header.get("fingerprint") != fingerprint(model):
        raise RestartError(f"{path}: the dump belongs to another model (nodes, elements "
                           "or parts differ from this deck's)")
    with open(path, "rb") as fh:
        fh.readline()
        fh.readline()
        body = fh.read()
    if len(body) != header.get("payload_bytes") or \
            hashlib.sha256(body).hexdigest() != header.get("payload_sha256"):
        raise RestartError(f"{path}: the restart file is truncated or damaged "
                           f"({len(body)} of {header.get('payload_bytes')} bytes)")
    return header, pickle.loads(body)


def find_dump(folder: Path, given: Path | None) -> Path:
    """The dump to resume from: ``given`` or the newest ``d3dumpNN`` of ``folder``."""
    if given is not None:
        if not Path(given).is_file():
            raise RestartError(f"{given}: no such restart file")
        return Path(given)
    files = dump_files(folder)
    if not files:
        raise RestartError(f"{folder}: no restart file (d3dumpNN) to resume from; the run "
                           "writes them with *DATABASE_BINARY_D3DUMP, on Ctrl-C and on an "
                           "error termination")
    return files[-1]
