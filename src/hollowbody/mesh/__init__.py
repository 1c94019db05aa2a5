"""Structured meshes as plain arrays (node coordinates, 0-based connectivities).

Generators for hexahedral blocks, quadrilateral plates and thin-walled tubes
(square and circular, :mod:`hollowbody.mesh.tube`), used by
the scenarios, the test models, the tests and the benchmarks. Nothing here
knows about decks or models: callers assign ids.
"""

from hollowbody.mesh.structured import (
    block_counts,
    block_mesh,
    boundary_nodes,
    distort,
    plate_mesh,
    standing_block,
)
from hollowbody.mesh.tube import circular_tube, square_ring, square_tube

__all__ = ["block_counts", "block_mesh", "boundary_nodes", "circular_tube", "distort",
           "plate_mesh", "square_ring", "square_tube", "standing_block"]
