"""Force terms of one body-mechanics family (see :mod:`hollowbody.solver.terms`)."""

from __future__ import annotations


def load_terms(model, plan) -> list:  # noqa: ANN001 - Model, Assembly
    """The terms of ``model`` of this family (none yet)."""
    return []
