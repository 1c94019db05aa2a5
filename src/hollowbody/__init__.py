"""hollowbody: fast, stable human body models (explicit FE solver, hollow soft tissues).

Compiled kernels are cached on disk by numba. numba keys a cached function by
its own source file only, so a kernel that inlines functions of another module
would keep running stale code after an edit of that module. Unless the user
sets ``NUMBA_CACHE_DIR``, the cache therefore lives in a folder named after a
digest of every kernel source of the package (``~/.cache/hollowbody/numba/<digest>``,
or under ``XDG_CACHE_HOME``): any edit of a kernel module compiles them all
anew; the newest few folders are kept, older ones removed.
"""

import hashlib
import os
import shutil
import sys
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

try:
    __version__ = version("hollowbody")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.1.0"

#: cache folders of earlier sources kept besides the current one
_KEEP_CACHES = 3


def _kernel_digest(root: Path) -> str:
    """sha256 (16 hex digits) of the package's modules that define numba kernels."""
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        data = path.read_bytes()
        if b"njit" in data:
            digest.update(str(path.relative_to(root)).encode())
            digest.update(data)
    return digest.hexdigest()[:16]


def _configure_numba_cache() -> None:
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    try:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
        folder = base / "hollowbody" / "numba" / _kernel_digest(Path(__file__).parent)
        folder.mkdir(parents=True, exist_ok=True)
        os.utime(folder)
        others = sorted((p for p in folder.parent.iterdir() if p.is_dir() and p != folder),
                        key=lambda p: p.stat().st_mtime)
        for old in others[:max(len(others) - _KEEP_CACHES, 0)]:
            shutil.rmtree(old, ignore_errors=True)
    except OSError:  # no writable cache folder: numba's default (beside the sources)
        return
    os.environ["NUMBA_CACHE_DIR"] = str(folder)
    numba = sys.modules.get("numba")
    if numba is not None:  # numba imported before hollowbody: set its config too
        numba.config.CACHE_DIR = str(folder)


_configure_numba_cache()
