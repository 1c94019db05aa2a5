"""*MAT_ELASTIC (LS-DYNA 001) for shells: isotropic plane-stress hypoelasticity.

In the co-rotational frame of a shell integration point::

    sigma_xx += E/(1-nu^2) (de_xx + nu de_yy),  sigma_yy += E/(1-nu^2) (de_yy + nu de_xx),
    sigma_xy += G dgamma_xy,                     sigma_zz = 0

(the update itself is :func:`hollowbody.materials.plane_stress_plasticity.elastic_plane_stress`).
Transverse shear is elastic for every shell material (element kernel).

Shell law ``KIND_ELASTIC`` (see :mod:`hollowbody.materials.shell_laws`); no
history is used.
"""

from __future__ import annotations

import numpy as np

from hollowbody.materials.plane_stress_material import PlaneStressMaterial, elastic_constants
from hollowbody.materials.plane_stress_plasticity import KIND_ELASTIC
from hollowbody.model.model import MaterialDef

#: Shell law kind (``PlaneStressMaterial.kind``); the element loop's code path.
KIND = KIND_ELASTIC


def elastic_shell(mat: MaterialDef) -> PlaneStressMaterial:
    """Plane-stress description of a *MAT_ELASTIC (E, PR; DeckError when invalid)."""
    e_mod, nu, rho = elastic_constants(mat, "MAT_ELASTIC")
    return PlaneStressMaterial(kind=KIND_ELASTIC, e_mod=e_mod, nu=nu, density=rho,
                               hard_x=np.zeros(1), hard_y=np.full(1, np.inf),
                               label=f"MAT_ELASTIC {mat.mid}")

