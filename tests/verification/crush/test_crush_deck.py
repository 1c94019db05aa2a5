"""The crush deck: only keywords hollowbody reads, references that resolve, the set-up
the benchmark describes (clamped base ring, rigid plate on a prescribed speed,
the two contacts, MAT_024 ELFORM 2 NIP 5 walls)."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.io.keyword import (
    Contact,
    MatPiecewiseLinearPlasticity,
    PrescribedMotionRigid,
    SectionShell,
    read_deck,
    write_deck,
)
from hollowbody.scenarios.crush import CLEARANCE, PLATE_T, CrushCase, crush_deck


@pytest.mark.parametrize("case", [CrushCase(), CrushCase(shape="circular", size=60.0,
                                                         length=100.0, material="steel",
                                                         trigger=0.0, per_half_fold=2.0)])
def test_crush_deck_reads_back_strictly_and_builds(tmp_path, case):
    deck, setup = crush_deck(case)
    path = tmp_path / "crush.k"
    write_deck(deck, path)
    back = read_deck(path, strict=True)  # any unsupported keyword is an error
    model = build_model(back)
    assert not model.unsupported
    sec = {s.secid: s for s in back.of_type(SectionShell)}
    assert sec[1].elform == 2 and sec[1].nip == 5
    mat = back.of_type(MatPiecewiseLinearPlasticity)[0]
    assert mat.sigy == 0.25 and mat.etan == 0.0
    kinds = sorted(c.type for c in back.of_type(Contact))
    assert kinds == ["AUTOMATIC_SINGLE_SURFACE", "AUTOMATIC_SURFACE_TO_SURFACE"]
    pm = back.of_type(PrescribedMotionRigid)[0]
    assert pm.pid == 2 and pm.dof == 3 and pm.sf == -case.speed
    # the plate's contact surface starts CLEARANCE above the tube's top edge
    x = model.node_x0
    tube = model.node_ids < 1_000_001
    gap = x[~tube, 2].min() - x[tube, 2].max() - 0.5 * (case.t + PLATE_T)
    assert gap == pytest.approx(CLEARANCE, abs=1e-6)
    assert setup.plate_node in set(model.node_ids[~tube].tolist())
    fixed = np.flatnonzero(np.abs(x[:, 2]) < 1e-9)
    assert fixed.size == setup.around
    assert len(model.shell_groups) == 2


def test_bad_case_is_refused():
    with pytest.raises(ValueError, match="material"):
        crush_deck(CrushCase(material="wood"))
    with pytest.raises(ValueError, match="shape"):
        crush_deck(CrushCase(shape="hexagonal"))
