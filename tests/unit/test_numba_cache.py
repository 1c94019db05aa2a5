"""The numba cache folder follows the kernel sources (hollowbody/__init__.py)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import hollowbody


def _cache_dir(env: dict[str, str]) -> str:
    code = "import os, hollowbody; print(os.environ.get('NUMBA_CACHE_DIR', ''))"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True)
    return out.stdout.strip()


def test_cache_folder_named_by_digest(tmp_path: Path) -> None:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["XDG_CACHE_HOME"] = str(tmp_path)
    folder = Path(_cache_dir(env))
    assert folder.parent == tmp_path / "hollowbody" / "numba"
    assert len(folder.name) == 16 and folder.is_dir()


def test_user_cache_dir_is_kept(tmp_path: Path) -> None:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "mine"))
    assert _cache_dir(env) == str(tmp_path / "mine")


def test_digest_follows_kernel_sources_only(tmp_path: Path) -> None:
    (tmp_path / "a.py").write_text("from numba import njit\n")
    (tmp_path / "b.py").write_text("x = 1\n")
    d0 = hollowbody._kernel_digest(tmp_path)
    (tmp_path / "b.py").write_text("x = 2\n")  # no kernel in it: same cache
    assert hollowbody._kernel_digest(tmp_path) == d0
    (tmp_path / "a.py").write_text("from numba import njit  # edited\n")
    assert hollowbody._kernel_digest(tmp_path) != d0
