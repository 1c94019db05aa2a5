"""Contact surfaces by set type (LS-DYNA's SSTYP / MSTYP), shared by the penalty and the
tied contacts' builders."""

from __future__ import annotations

from hollowbody.model import model as m


def defined_surface(model: m.Model, sid: int, typ: int) -> m.SurfaceRef | None:
    """The surface of set or part ``sid`` of type ``typ`` (0 segment set, 2 part set, 3 part,
    4 node set), None when the type is another one or ``sid`` is not defined."""
    if typ == 0 and sid in model.segment_sets:
        return m.SurfaceRef("segments", segments=model.segment_sets[sid])
    if typ == 2 and sid in model.part_sets:
        return m.SurfaceRef("parts", pids=list(model.part_sets[sid]))
    if typ == 3 and sid in model.parts:
        return m.SurfaceRef("parts", pids=[sid])
    if typ == 4 and sid in model.node_sets:
        return m.SurfaceRef("nodes", nodes=model.node_sets[sid])
    return None
