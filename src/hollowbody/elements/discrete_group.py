"""Runtimes of discrete element groups (see :mod:`hollowbody.solver.setup`)."""

from __future__ import annotations

import numpy as np


def discrete_runtimes(model, x0: np.ndarray) -> list:  # noqa: ANN001 - Model
    """One runtime per discrete group of ``model`` (none yet); x0 (n, 3) mm."""
    return []
