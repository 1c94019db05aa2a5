"""Registry of the shell (plane-stress) constitutive laws: ``PlaneStressMaterial.kind -> law``.

A shell law is one module providing ``shell_constants(params) -> tuple`` (the
scalars it needs, read once per kernel call) and the ``@njit`` point update
``shell_point_update(i, k, s0, s1, s2, exx, eyy, exy, dt, pm, consts, params,
history) -> (q0, q1, q2, dsp, pm, nfail)`` of integration point k of element i
in the co-rotational frame (see :mod:`hollowbody.materials.shell_elastic`). ``params``
is ``(mp, hx, hy, rx, ry)``: the packed vector of
:mod:`hollowbody.materials.plane_stress_plasticity` (the element reads E, nu,
G and the wave speed from it for transverse shear, hourglass and time step),
the hardening table and the rate curve; ``history`` is ``(epsp, back,
pfail)``. The deck side (parameters and validation) is a
:class:`~hollowbody.materials.plane_stress_material.PlaneStressMaterial`
builder per keyword (``shell_elastic``, ``mat003_plastic_kinematic``,
``mat024_piecewise_linear``). The shell kernel
(:func:`hollowbody.elements.shell_bt_forces.make_shell_kernel`) is compiled
once per law. Adding a law = one module + one line in :data:`SHELL_LAWS`.
"""

from __future__ import annotations

from types import ModuleType

from hollowbody.materials import plane_stress_plasticity, shell_elastic
from hollowbody.materials.plane_stress_plasticity import KIND_ELASTIC, KIND_PLASTIC

#: Shell laws by ``PlaneStressMaterial.kind``.
SHELL_LAWS: dict[int, ModuleType] = {
    KIND_ELASTIC: shell_elastic,
    KIND_PLASTIC: plane_stress_plasticity,
}
