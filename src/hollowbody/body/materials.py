"""Materials of the pedestrian model (deck units: GPa, kg/mm^3) and their sources.

- cortical bone (long bones, ribs, sternum): *MAT_PLASTIC_KINEMATIC, E 15 GPa,
  PR 0.3, yield 0.1 GPa, tangent 0.5 GPa, density 2.0e-6 kg/mm^3: the values of
  the generated limb (:mod:`hollowbody.scenarios.limb`), representative of
  human femoral cortical bone (Reilly and Burstein, J. Biomech. 8:393-405,
  1975: E about 17 GPa, yield about 0.11 GPa in tension, longitudinal);
- skeletal muscle, gluteal flesh, subcutaneous fat: *MAT_SIMPLIFIED_RUBBER
  with the tissue curves and bulk moduli of :mod:`hollowbody.tissues`;
- abdominal organs: the muscle law (a choice: no organ-specific data are
  used), density 1.0e-6; thoracic organs: lungs (about 0.3e-6 kg/mm^3), heart
  and great vessels (about 1.05e-6) smeared: density 0.6e-6, the fat curve
  (small-strain modulus about 0.17 MPa, of the order of lung parenchyma at
  impact rates, 43-153 kPa: Pydi et al., Biomech. Model. Mechanobiol. 2023)
  and a gas-filled bulk modulus of 0.3 MPa (air's adiabatic 0.14 MPa over an
  air fraction of about one half): the lungs give way to the chest wall
  instead of holding it as an incompressible core;
- skin: *MAT_ELASTIC E 5 MPa, PR 0.45, 1.1e-6 kg/mm^3, 1 mm (as the limb);
- costal cartilage: *MAT_ELASTIC E 30 MPa, PR 0.45, 1.1e-6 kg/mm^3: the mean
  unconfined-compression modulus of human costal cartilage, 32.9 +- 17.9 MPa
  (Weber, Rothschild and Niehoff, Sci. Rep. 11:13618, 2021; their indentation
  moduli are 11-15 MPa);
- intercostal layers (the rib cage's rows between ribs: intercostal muscles
  and membranes): *MAT_ELASTIC E 5 MPa, PR 0.45, 1.1e-6 kg/mm^3 (the skin's
  values, a choice: a fibrous soft-tissue layer, three orders softer than the
  ribs it joins);
- intervertebral discs (the spine tube's deformable rows between rigid
  zones): *MAT_ELASTIC E 10 MPa, PR 0.45, 1.1e-6 (a choice; the spine's
  stiffness is in its joints);
- rigid parts: *MAT_RIGID with E 15 GPa, PR 0.3 (contact stiffness and step
  of the rigid elements), density chosen per part for the segment mass.
"""

from __future__ import annotations

from dataclasses import dataclass

from hollowbody.tissues import tissue


@dataclass(frozen=True)
class BodyMaterial:
    """A material: ``law`` (cortical, rubber, elastic, rigid), density kg/mm^3,
    E and yield GPa (elastic / plastic laws), ``tissue`` name (rubber: its curve),
    ``bulk`` GPa (rubber: the bulk modulus, 0 = the tissue's)."""

    law: str
    density: float
    e: float = 0.0
    pr: float = 0.3
    sigy: float = 0.0
    etan: float = 0.0
    tissue: str = ""
    title: str = ""
    bulk: float = 0.0


MATERIALS = {
    "cortical": BodyMaterial("cortical", 2.0e-6, 15.0, 0.3, 0.1, 0.5, title="cortical bone"),
    "muscle": BodyMaterial("rubber", tissue("muscle").density, tissue="muscle",
                           title="skeletal muscle"),
    "fat": BodyMaterial("rubber", tissue("fat").density, tissue="fat",
                        title="subcutaneous fat"),
    "thoracic_organs": BodyMaterial("rubber", 0.6e-6, tissue="fat", bulk=3.0e-4,
                                    title="thoracic organs"),
    "abdominal_organs": BodyMaterial("rubber", 1.0e-6, tissue="muscle",
                                     title="abdominal organs"),
    "skin": BodyMaterial("elastic", 1.1e-6, 0.005, 0.45, title="skin"),
    "costal_cartilage": BodyMaterial("elastic", 1.1e-6, 0.030, 0.45, title="costal cartilage"),
    "intercostal": BodyMaterial("elastic", 1.1e-6, 0.005, 0.45, title="intercostal layers"),
    "disc": BodyMaterial("elastic", 1.1e-6, 0.010, 0.45, title="intervertebral discs"),
    "rigid": BodyMaterial("rigid", 1.0e-6, 15.0, 0.3, title="rigid"),
}
