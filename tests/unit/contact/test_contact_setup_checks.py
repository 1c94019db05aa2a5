"""Contact set-up on degenerate meshes: skipped with one warning, never a traceback."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from hollowbody.contact import ContactRuntime
from hollowbody.contact.geometry import project_triangle
from hollowbody.mesh import plate_mesh
from hollowbody.model.model import ContactDef, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model


def _folded_sheet_with_bad_shells():
    """A 4 x 4 shell sheet folded over itself (two layers 1 mm apart) plus three bad
    shells: collinear corners (zero area), zero thickness, massless corners."""
    x, c = plate_mesh((4, 4), (8.0, 8.0), (0.0, 0.0, 0.0))
    x2 = x + np.array([0.0, 0.0, 1.0])
    xs = np.concatenate([x, x2])
    cs = np.concatenate([c, c + x.shape[0]])
    n0 = xs.shape[0]
    bad = np.array([[20.0, 0, 0], [21.0, 0, 0], [22.0, 0, 0], [23.0, 0, 0],  # collinear
                    [30.0, 0, 0], [31.0, 0, 0], [31.0, 1, 0], [30.0, 1, 0],  # zero thickness
                    [40.0, 0, 0], [41.0, 0, 0], [41.0, 1, 0], [40.0, 1, 0]])  # no mass
    cb = np.arange(12).reshape(3, 4) + n0
    model = assemble_model([PartSpec(1, np.concatenate([xs, bad]), np.concatenate([cs, cb]),
                                     "shell", "elastic", {"E": 0.01, "PR": 0.3}, 1e-6, 1.5)])
    g = model.shell_groups[0]
    g.thickness[-2] = 0.0  # shell 1034: zero thickness
    mass = np.full(model.n_nodes, 1e-5)
    mass[n0 + 8:] = 0.0  # shell 1035: massless corners
    return model, mass, g.elem_ids


def test_single_surface_skips_degenerate_segments_with_one_warning():
    model, mass, eids = _folded_sheet_with_bad_shells()
    cd = ContactDef(cid=4, kind="single_surface", slave=SurfaceRef(kind="parts", pids=[1]),
                    master=None, soft=1, vdc=20.0, fs=0.2)
    rt = ContactRuntime(cd, model, mass, np.zeros(model.n_nodes, bool))
    (msg,) = rt.warnings
    assert msg.startswith("contact 4 surface: 3 degenerate segment(s) left out")
    assert f"zero area: shell {eids[-3]} (part 1)" in msg
    assert f"zero thickness: shell {eids[-2]} (part 1)" in msg
    assert f"zero mass: shell {eids[-1]} (part 1)" in msg
    assert "massless node(s)" in msg and rt.slave_surface.n_segments == 32
    (ev,) = rt.pop_events()
    assert ev["kind"] == "contact_setup" and ev["contact"] == 4 and ev["message"] == msg
    assert rt.pop_events() == []
    # runs: the folded layers (1 mm apart, 1.5 mm shells) push apart, no exception
    f = np.zeros((model.n_nodes, 3))
    v = np.zeros((model.n_nodes, 3))
    v[:25, 2] = 0.5
    for cycle in range(3):
        rt.add_forces(model.node_x0, v, 1e-3 * (cycle > 0), cycle, f)
    assert np.all(np.isfinite(f)) and rt.n_active > 0


def test_clean_surfaces_give_no_warning():
    model, mass, _ = _folded_sheet_with_bad_shells()
    model.shell_groups[0].conn = model.shell_groups[0].conn[:32]
    model.shell_groups[0].elem_ids = model.shell_groups[0].elem_ids[:32]
    model.shell_groups[0].thickness = model.shell_groups[0].thickness[:32]
    cd = ContactDef(cid=4, kind="single_surface", slave=SurfaceRef(kind="parts", pids=[1]),
                    master=None, soft=1)
    mass[:] = 1e-5
    rt = ContactRuntime(cd, model, mass, np.zeros(model.n_nodes, bool))
    assert rt.warnings == [] and rt.pop_events() == []


def test_sliver_triangle_projection_does_not_divide_by_zero():
    # nearly collinear corners: |e1 x e2| > 0 but e1.e1 e2.e2 - (e1.e2)^2 rounds to 0
    # (numba raises ZeroDivisionError on a float division by zero): must not raise
    project_triangle(0.5, 0.1, 0.0, 0.0, 0.0, 0.0, 1.0, 1e-9, 0.0, 2.0, 2e-9 + 1e-17, 0.0)
    ok, *_ = project_triangle(0.5, 0.1, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0)
    assert not ok


def _tied_walls(tie: bool):
    """A 1.5 mm 'boundary' sheet and a 'wall' standing on it, its bottom edge nodes
    on the sheet (not shared; tied as in a hollowized part)."""
    xb, cb = plate_mesh((4, 4), (8.0, 8.0), (-4.0, -4.0, 0.0))
    xw = np.array([[-4.0, 0.0, 0.0], [0.0, 0.0, 0.0], [4.0, 0.0, 0.0],
                   [-4.0, 0.0, 4.0], [0.0, 0.0, 4.0], [4.0, 0.0, 4.0]])
    cw = np.array([[0, 1, 4, 3], [1, 2, 5, 4]]) + xb.shape[0]
    model = assemble_model([PartSpec(1, np.concatenate([xb, xw]), np.concatenate([cb, cw]),
                                     "shell", "elastic", {"E": 0.01, "PR": 0.3}, 1e-6, 1.5)])
    if tie:
        n0 = xb.shape[0]
        model.tied_contacts = [SimpleNamespace(
            slave=SurfaceRef(kind="nodes", nodes=np.arange(n0, n0 + 3)),
            master=SurfaceRef(kind="segments", segments=cb), sst=0.0, mst=0.0)]
    cd = ContactDef(cid=2, kind="single_surface", slave=SurfaceRef(kind="parts", pids=[1]),
                    master=None, soft=1)
    return model, ContactRuntime(cd, model, np.full(model.n_nodes, 1e-5),
                                 np.zeros(model.n_nodes, bool))


def test_tied_wall_edges_are_junctions_not_initial_penetrations():
    # without the tie the wall's bottom edge overlaps the sheet (kept: pushes apart);
    # with it they are joined like shared nodes and left out
    assert _tied_walls(tie=False)[1].n_initial_penetrations > 0
    model, rt = _tied_walls(tie=True)
    assert rt.n_initial_penetrations == 0
    x = model.node_x0
    f = np.zeros_like(x)
    rt.add_forces(x, np.zeros_like(x), 0.0, 0, f)
    assert rt.n_active == 0 and np.all(f == 0.0)
