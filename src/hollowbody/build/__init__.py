"""Deck -> Model: the build layer on the reading side, beside the keyword reader.

:func:`build_model` turns a parsed keyword :class:`~hollowbody.io.keyword.Deck`
into the static :class:`~hollowbody.model.model.Model`: ids become indices,
defaults are applied and every reference is checked. This package is the only
place that knows both the keyword classes and the Model, so ``io.keyword``
(deck syntax) and ``model`` (the solver's input) stay independent of each
other.
"""

from hollowbody.build.builder import build_model

__all__ = ["build_model"]
