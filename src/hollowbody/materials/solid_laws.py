"""Registry of the solid constitutive laws: ``MaterialDef.kind -> law module``.

A solid law is one module that provides

* ``KIND``, ``KEYWORD``: material kind and LS-DYNA keyword;
* ``solid_params(mat, curves) -> tuple[np.ndarray, ...]``: the parameters
  packed for the kernel, validated (``DeckError`` naming file, line and keyword);
* ``solid_wave_speed0(params) -> float``: initial wave speed, mm/ms;
* ``solid_hourglass_moduli(params) -> (G0, K)``: small-strain shear and bulk
  moduli (GPa), for the assumed-strain hourglass stiffness (IHQ 6);
* ``HISTORY_FIELDS`` and ``solid_history(params, n_elem) -> dict[str, ndarray]``:
  the per-element history arrays by name, in the order of the kernel's history
  tuple (the group runtime stores each one under its name and lists it in its
  ``STATE_FIELDS``);
* ``solid_erode(history, idx)``: reset the history of eroded elements;
* ``solid_constants(params) -> tuple``: the ``@njit(inline="always")`` read of
  the scalar parameters, once per kernel call (loop-invariant values stay in
  registers);
* ``solid_update(e, dt, vol, vol0, l, xe, b0, lm, rot, work, stress, consts,
  params, history) -> (s0..s5, rho, modulus, c)``: the ``@njit(inline="always")``
  stress update of one element (see :mod:`hollowbody.materials.mat001_elastic`).

The element loop (:func:`hollowbody.elements.hex8_solid_kernels.make_hex8_kernel`)
is compiled once per law. Adding a law = one module + one line in :data:`SOLID_LAWS`.
"""

from __future__ import annotations

from types import ModuleType

from hollowbody.materials import mat001_elastic, mat181_simplified_rubber

#: Solid laws by material kind.
SOLID_LAWS: dict[str, ModuleType] = {
    mat001_elastic.KIND: mat001_elastic,
    mat181_simplified_rubber.KIND: mat181_simplified_rubber,
}

#: Names of the history arrays of every registered law (union, in registry order).
HISTORY_FIELDS: tuple[str, ...] = tuple(dict.fromkeys(
    name for law in SOLID_LAWS.values() for name in law.HISTORY_FIELDS))
