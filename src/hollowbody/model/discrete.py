"""Discrete elements (springs and dampers) of the Model: one group per part.

Built by :mod:`hollowbody.build.discrete` from *SECTION_DISCRETE,
*ELEMENT_DISCRETE, *DEFINE_SD_ORIENTATION and the spring / damper materials;
run by :mod:`hollowbody.elements.discrete_group`. See docs/discrete.md.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hollowbody.source import Source

#: Material kinds of discrete elements (keys of ``model.MATERIAL_PARAMS``) and the
#: law codes of the kernel (:mod:`hollowbody.elements.discrete_kernels`).
DISCRETE_LAWS = {"spring_elastic": 1, "damper_viscous": 2, "spring_nonlinear": 4,
                 "spring_general": 6}
#: Short names of the laws for summaries (LS-DYNA's S-numbers).
LAW_NAMES = {"spring_elastic": "S01 spring elastic", "damper_viscous": "S02 damper viscous",
             "spring_nonlinear": "S04 spring nonlinear elastic",
             "spring_general": "S06 spring general nonlinear"}


@dataclass
class DiscreteGroup:
    """The *ELEMENT_DISCRETE elements of one part (e elements).

    pid: part id; kind: material kind (a key of :data:`DISCRETE_LAWS`); mid;
    torsional: DRO = 1 (moments on rotational DOFs) else translational (forces);
    elem_ids (e,) int64; n1 (e,) int64 node indices; n2 (e,) int64 node indices,
    -1 for a grounded element (N2 = 0); scale (e,) S force scale factor; offset
    (e,) mm or rad initial deflection; print_flag (e,) int (PF: 0 = written to
    deforc); fixed_axis (e,) bool: the element acts along a fixed direction
    (*DEFINE_SD_ORIENTATION IOP 0) instead of the N1 -> N2 line; axis (e, 3) unit
    vectors of the fixed directions (zeros where not fixed); failure_deflection:
    FD of the section (mm or rad, 0 = none); sources: the deck place of each
    element's card (e,); source: the *SECTION_DISCRETE.
    """

    pid: int
    kind: str
    mid: int
    torsional: bool
    elem_ids: np.ndarray
    n1: np.ndarray
    n2: np.ndarray
    scale: np.ndarray
    offset: np.ndarray
    print_flag: np.ndarray
    fixed_axis: np.ndarray
    axis: np.ndarray
    failure_deflection: float = 0.0
    sources: list = field(default_factory=list)
    source: Source = field(default_factory=Source)

    @property
    def n_elem(self) -> int:
        return int(self.elem_ids.size)
