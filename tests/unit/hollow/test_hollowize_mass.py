"""hollowize keeps mass, centre of mass and principal inertia (re-read from the written deck)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.hollow.boundary import solid_mass_properties
from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
from hollowbody.hollow.mass_match import TOL_CENTRE, TOL_INERTIA, TOL_MASS
from hollowbody.hollow.output import write_converted
from hollowbody.io.keyword import read_deck
from hollowbody.model.mass import (
    hex_volumes,
    point_mass_properties,
    quad_areas,
    spread_element_mass,
)
from hollowbody.scenarios.limb import PID_MUSCLE, limb_deck
from hollowbody.testing.decks import box_deck, tet_wedge_deck


def _solid_props(model, pid):
    g = next(g for g in model.solid_groups if g.pid == pid)
    return solid_mass_properties(model.node_x0, g.conn.astype(np.int64),
                                 model.material_of(pid).density), g


def _shell_props(model, pid):
    """Lumped mass properties of part pid's shells plus all *ELEMENT_MASS of the model."""
    g = next(g for g in model.shell_groups if g.pid == pid)
    m = np.zeros(model.n_nodes)
    rho = model.material_of(pid).density
    spread_element_mass(m, g.conn, rho * quad_areas(g.conn, model.node_x0)
                        * g.thickness.mean(axis=1))
    m += model.node_extra_mass
    nodes = np.flatnonzero(m)
    return point_mass_properties(model.node_x0[nodes], m[nodes])


def _check(before, after):
    assert abs(after.mass - before.mass) <= TOL_MASS * before.mass
    assert np.linalg.norm(after.centre - before.centre) <= TOL_CENTRE
    pb = np.sort(np.linalg.eigvalsh(before.inertia))
    pa = np.sort(np.linalg.eigvalsh(after.inertia))
    assert np.all(np.abs(pa - pb) <= TOL_INERTIA * pb), (pa, pb)


CASES = {
    "box": (lambda: box_deck((90.0, 60.0, 60.0), 10.0), 1, {}),
    "box-nodal": (lambda: box_deck((90.0, 60.0, 60.0), 10.0, origin=(5.0, -3.0, 2.0)), 1,
                  {"mass_mode": "nodal"}),
    "limb": (lambda: limb_deck("leg", length=150.0, n_theta=16, n_radial=3, axial=15.0),
             PID_MUSCLE, {}),
    "limb-principal-nodal": (lambda: limb_deck("leg", length=150.0, n_theta=16, n_radial=3,
                                               axial=15.0),
                             PID_MUSCLE, {"grid_axes": "principal", "mass_mode": "nodal"}),
    "tets-wedges": (tet_wedge_deck, 1, {"cell": 25.0}),
}


@pytest.mark.parametrize("case", list(CASES))
def test_mass_centre_inertia_kept(case, tmp_path):
    make, pid, opts = CASES[case]
    deck = make()
    model0 = build_model(deck)
    before, g = _solid_props(model0, pid)
    # the exact mass is the solver's (lumped) mass of the solids
    lumped = model0.material_of(pid).density * np.abs(hex_volumes(g.conn, model0.node_x0)).sum()
    assert before.mass == pytest.approx(lumped, rel=1e-12)
    new, report = hollowize(deck, Selection(parts=[pid]), HollowOptions(**opts))
    write_converted(new, tmp_path / "out.k", report.changed_decks, inputs=[])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model1 = build_model(read_deck(tmp_path / "out.k"))
    assert not any(g.pid == pid for g in model1.solid_groups)
    after = _shell_props(model1, pid)
    _check(before, after)
    part = report.parts[0]
    assert part.ok
    assert part.mass_after["mass_kg"] == pytest.approx(after.mass, rel=1e-5)
    assert np.allclose(part.mass_before["centre_mm"], before.centre)


def test_nodal_mode_keeps_tissue_density():
    deck = box_deck((90.0, 60.0, 60.0), 10.0)
    _, report = hollowize(deck, Selection(parts=[1]), HollowOptions(mass_mode="nodal"))
    p = report.parts[0]
    assert p.mass_plan["density"] == pytest.approx(1.0e-6)  # muscle density
    assert p.mass_plan["count"] > 0
    assert p.mass_plan["nodal_kg"] > 0.5 * p.mass_before["mass_kg"]


def test_density_mode_uses_one_density_without_correction_when_enough():
    # a long thin slab: walls close to the solid's distribution -> no point masses needed
    deck = box_deck((300.0, 60.0, 60.0), 10.0)
    _, report = hollowize(deck, Selection(parts=[1]), HollowOptions(cell=15.0))
    p = report.parts[0]
    assert p.ok
    if p.mass_plan["count"] == 0:
        assert p.mass_plan["phi"] == 1.0
    else:  # correction used: most of the mass still in the density
        assert p.mass_plan["phi"] > 0.5
