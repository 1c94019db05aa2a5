"""Deck -> Model for one body-mechanics family (see :mod:`hollowbody.build.mechanics`)."""

from __future__ import annotations

from hollowbody.model.model import Model


def build(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """Read this family's keywords from ``b`` into ``model`` (nothing yet)."""
