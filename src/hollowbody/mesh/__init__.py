"""Structured meshes as plain arrays (node coordinates, 0-based connectivities).

One generator for hexahedral blocks and one for quadrilateral plates, used by
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

__all__ = ["block_counts", "block_mesh", "boundary_nodes", "distort", "plate_mesh",
           "standing_block"]
