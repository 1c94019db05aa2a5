"""Body mechanics of a deck -> the Model (docs/mechanics.md).

Called by :func:`hollowbody.build.build_model` once parts, elements, sets,
boundary conditions and contacts are built. Each family has its own module,
which reads its keywords from the builder ``b`` (``b.of(KeywordClass)``,
``b.node_list(ids, item, what)``) and fills its fields of the Model:

- ``build.beams``: *SECTION_BEAM, *ELEMENT_BEAM -> ``beam_groups``;
- ``build.discrete``: *SECTION_DISCRETE, *ELEMENT_DISCRETE, *MAT_SPRING_* /
  *MAT_DAMPER_* (S01, S02, S04, S06) -> ``discrete_groups``;
- ``build.loads``: *LOAD_BODY_*, *LOAD_NODE_*, *LOAD_RIGID_BODY,
  *RIGIDWALL_PLANAR -> ``loads``, ``rigid_walls``;
- ``build.rigid_constraints``: *CONSTRAINED_RIGID_BODIES, _NODAL_RIGID_BODY,
  _EXTRA_NODES -> ``rigid_merges``, ``nodal_rigid_bodies``, ``extra_nodes``;
- ``build.joints``: *DEFINE_COORDINATE_*, *CONSTRAINED_JOINT_*,
  *DATABASE_JNTFORC -> ``coordinate_systems``, ``joints``, ``joint_stiffness``.

The order matters only where one family refers to another: rigid bodies
(merges, nodal rigid bodies) before the joints that connect them.
"""

from __future__ import annotations

from hollowbody.build import beams, discrete, joints, loads, rigid_constraints
from hollowbody.model.model import Model


def build_mechanics(b, model: Model) -> None:  # noqa: ANN001 - builder.Builder
    """Fill the Model's body-mechanics fields from the deck held by ``b``."""
    beams.build(b, model)
    discrete.build(b, model)
    rigid_constraints.build(b, model)
    loads.build(b, model)
    joints.build(b, model)
