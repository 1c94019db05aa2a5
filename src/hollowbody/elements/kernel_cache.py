"""Cache keys of the kernels that are compiled once per constitutive law.

numba keys the on-disk cache of a function by its own source file only; a
kernel built by a factory (a closure over a law module) would therefore keep
running stale code after an edit of the law or of a helper module it inlines.
:func:`source_stamp` digests those sources; the factories capture the digest
in their closures, and numba's cache key of a closure includes the captured
values, so any edit of these files compiles the kernel anew.
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from types import ModuleType

_STAMPS: dict[tuple[str, ...], int] = {}


def source_stamp(*modules: ModuleType) -> int:
    """63-bit digest of the source files of ``modules`` and of every module of
    the law's package ``hollowbody.materials`` (the laws' helpers live there)."""
    key = tuple(m.__name__ for m in modules)
    stamp = _STAMPS.get(key)
    if stamp is not None:
        return stamp
    files: list[Path] = []
    for m in modules:
        path = Path(m.__file__) if getattr(m, "__file__", None) else None
        if path is not None:
            files.append(path)
            if m.__name__.startswith("hollowbody.materials."):
                files.extend(sorted(path.parent.glob("*.py")))
    digest = hashlib.sha256("|".join(key).encode())
    for path in dict.fromkeys(files):
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    stamp = int.from_bytes(digest.digest()[:8], "little") >> 1
    _STAMPS[key] = stamp
    return stamp
