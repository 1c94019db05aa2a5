"""Registry of the shell (plane-stress) constitutive laws: ``PlaneStressMaterial.kind -> law``.

The shell element loop (:func:`hollowbody.elements.shell_bt_forces.bt_shell_range`)
is compiled once per law module (``make_shell_kernel``), so each group's kernel
contains only its law's code path: the module's ``KIND`` is a compile-time
constant of the loop. The point updates themselves are written in the loop
(elastic: :func:`~hollowbody.materials.plane_stress_plasticity.elastic_plane_stress`;
elastic-plastic: trial, yield check, then
:func:`~hollowbody.materials.plane_stress_plasticity.plane_stress_return`):
called as an inlined function per integration point they cost 1.5x to 3x the
element time (numba, measured), see docs/shells.md. The parameters live in one
packed vector (``P_*`` of :mod:`hollowbody.materials.plane_stress_plasticity`)
with the hardening table and the rate curve; the history is ``(epsp, back,
pfail)``. The deck side (parameters and validation) is a
:class:`~hollowbody.materials.plane_stress_material.PlaneStressMaterial`
builder per keyword (``shell_elastic``, ``mat003_plastic_kinematic``,
``mat024_piecewise_linear``).
"""

from __future__ import annotations

from types import ModuleType

from hollowbody.materials import plane_stress_plasticity, shell_elastic

#: Shell laws by ``PlaneStressMaterial.kind``.
SHELL_LAWS: dict[int, ModuleType] = {
    shell_elastic.KIND: shell_elastic,
    plane_stress_plasticity.KIND: plane_stress_plasticity,
}
