"""Cache of finished evaluations: a JSON-lines file, one evaluation record a line.

A record (see :func:`hollowbody.calibrate.evaluation.evaluate_candidate`) is
keyed by its *context* (a hash of everything that changes a run: simulator
description, tissue, speeds, fitness settings) and its rounded parameters.
Only *finished* evaluations are stored: normal and error terminations. An
evaluation that raised a Python exception, lost its worker or was interrupted
is not stored, so a later run (or ``--resume``) tries it again.

Records are appended and flushed as evaluations finish, so a calibration
killed mid-generation keeps every evaluation it completed; a torn last line
(killed while writing) is ignored when the file is read back.
"""

from __future__ import annotations

import json
from pathlib import Path

from hollowbody.calibrate.simulate import ERROR, NORMAL, SUSPECT

#: Statuses of records that are stored (finished, repeatable results).
CACHED_STATUSES = (NORMAL, ERROR, SUSPECT)


def cacheable(record: dict) -> bool:
    """True for a finished evaluation (normal or error termination, or a suspect run)."""
    return record.get("status") in CACHED_STATUSES


class EvaluationCache:
    """Evaluation records by (context, key), backed by ``path`` (JSON lines)."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self._records: dict[tuple[str, str], dict] = {}
        self.skipped_lines = 0
        if self.path.exists():
            self._load()

    def _load(self) -> None:
        with self.path.open("r", encoding="utf-8") as fh:
            for line in fh:
                line = line.strip()
                if not line:
                    continue
                try:
                    rec = json.loads(line)
                    self._records[(rec["context"], rec["key"])] = rec
                except (json.JSONDecodeError, KeyError, TypeError):
                    self.skipped_lines += 1

    def __len__(self) -> int:
        return len(self._records)

    def get(self, context: str, key: str) -> dict | None:
        """The stored record of ``key`` in ``context``, or None."""
        return self._records.get((context, key))

    def put(self, record: dict) -> bool:
        """Store and append ``record`` if it is cacheable; returns whether it was stored."""
        if not cacheable(record):
            return False
        self._records[(record["context"], record["key"])] = record
        self.path.parent.mkdir(parents=True, exist_ok=True)
        text = json.dumps(record, separators=(",", ":"), default=float)
        with self.path.open("a", encoding="utf-8") as fh:
            # a torn line from a killed writer must not swallow this record
            if fh.tell() > 0 and not _ends_with_newline(self.path):
                fh.write("\n")
            fh.write(text + "\n")
            fh.flush()
        return True

    def records(self, context: str) -> list[dict]:
        """All stored records of ``context`` (in file order)."""
        return [r for (c, _), r in self._records.items() if c == context]


def _ends_with_newline(path: Path) -> bool:
    with path.open("rb") as fh:
        fh.seek(-1, 2)
        return fh.read(1) == b"\n"
