"""*MAT_ELASTIC (LS-DYNA 001) for shells: isotropic plane-stress hypoelasticity.

In the co-rotational frame of a shell integration point::

    sigma_xx += E/(1-nu^2) (de_xx + nu de_yy),  sigma_yy += E/(1-nu^2) (de_yy + nu de_xx),
    sigma_xy += G dgamma_xy,                     sigma_zz = 0

(the update itself is :func:`hollowbody.materials.plane_stress_plasticity.elastic_plane_stress`).
Transverse shear is elastic for every shell material (element kernel).

Shell law interface (see :mod:`hollowbody.materials.shell_laws`): the point
update :func:`shell_point_update`; no history is used.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hollowbody.materials.plane_stress_material import PlaneStressMaterial, elastic_constants
from hollowbody.materials.plane_stress_plasticity import (
    FASTMATH,
    KIND_ELASTIC,
    P_E,
    P_NU,
    elastic_plane_stress,
)
from hollowbody.model.model import MaterialDef


def elastic_shell(mat: MaterialDef) -> PlaneStressMaterial:
    """Plane-stress description of a *MAT_ELASTIC (E, PR; DeckError when invalid)."""
    e_mod, nu, rho = elastic_constants(mat, "MAT_ELASTIC")
    return PlaneStressMaterial(kind=KIND_ELASTIC, e_mod=e_mod, nu=nu, density=rho,
                               hard_x=np.zeros(1), hard_y=np.full(1, np.inf),
                               label=f"MAT_ELASTIC {mat.mid}")


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def shell_constants(params):
    """Kernel: the scalars of ``params`` the point update uses (E GPa, nu), read once."""
    mp = params[0]
    return mp[P_E], mp[P_NU]


@njit(cache=True, error_model="numpy", fastmath=FASTMATH, inline="always")
def shell_point_update(i, k, s0, s1, s2, exx, eyy, exy, dt, pm, consts, params, history):
    """Kernel: plane-stress elastic update of point k of element i.

    s0..s2 old local stress (xx, yy, xy) GPa; exx, eyy, exy strain increments
    (engineering shear); dt ms; pm running max of eps_p over the element's
    points; consts from :func:`shell_constants`; params (mp, hx, hy, rx, ry);
    history (epsp, back, pfail), unused. Returns (q0, q1, q2 new stress GPa,
    plastic thickness strain increment 0, pm, 0 failed points).
    """
    e_mod, nu = consts
    q0, q1, q2 = elastic_plane_stress(s0, s1, s2, exx, eyy, exy, e_mod, nu)
    return q0, q1, q2, 0.0, pm, 0
