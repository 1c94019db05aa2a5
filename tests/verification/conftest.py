"""Fixtures shared by the verification tests."""

from __future__ import annotations

from collections.abc import Iterator

import numba
import pytest


@pytest.fixture
def one_thread() -> Iterator[None]:
    """Run the test on one numba thread (results then equal bit for bit between runs:
    restart tests compare history files as text)."""
    old = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(old)
