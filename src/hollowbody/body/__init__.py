"""The open pedestrian model: anthropometry (:mod:`hollowbody.body.anthropometry`)."""
