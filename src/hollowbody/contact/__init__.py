"""Penalty contact: surfaces, bucket-sort broad phase, node-to-segment forces.

The solver uses :class:`ContactRuntime` (one per ``ContactDef``); see
``docs/contact.md`` for the formulation and the stiffness formulas.
"""

from hollowbody.contact.runtime import ContactRuntime
from hollowbody.contact.surface import Surface, build_surface, solid_exterior_faces

__all__ = ["ContactRuntime", "Surface", "build_surface", "solid_exterior_faces"]
