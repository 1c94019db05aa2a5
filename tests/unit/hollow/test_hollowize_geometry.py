"""Geometry of the conversion: boundary faces, walls, coverage, conformity, shared nodes."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.build import build_model
from hollowbody.hollow.boundary import boundary_faces, solid_tets
from hollowbody.hollow.convert import HollowOptions, Selection, hollowize
from hollowbody.hollow.fill import fill_walls, grid_frame
from hollowbody.hollow.grid import hollow_box
from hollowbody.hollow.spatial import TetLocator, TriangleSurface, quads_to_triangles
from hollowbody.scenarios.limb import PID_BONE, PID_MUSCLE, PID_SKIN, limb_deck
from hollowbody.testing.decks import box_deck, tet_wedge_deck


def _areas(conn, x):
    xe = x[conn]
    return 0.5 * np.linalg.norm(np.cross(xe[:, 2] - xe[:, 0], xe[:, 3] - xe[:, 1]), axis=1)


def _walls(deck, pid, cell=30.0, k=4, axes=None):
    model = build_model(deck)
    g = next(g for g in model.solid_groups if g.pid == pid)
    conn = g.conn.astype(np.int64)
    x = model.node_x0
    faces, _ = boundary_faces(x, conn)
    w = fill_walls(x, solid_tets(conn), np.unique(conn), faces, cell, k,
                   grid_frame(x, axes))
    return model, conn, faces, w


def test_boundary_faces_of_box_are_outward_quads():
    model = build_model(box_deck((30.0, 20.0, 20.0), 10.0))
    x, conn = model.node_x0, model.solid_groups[0].conn.astype(np.int64)
    faces, _ = boundary_faces(x, conn)
    assert faces.shape[0] == 2 * (3 * 2 + 3 * 2 + 2 * 2)
    assert _areas(faces, x).sum() == pytest.approx(2 * (600 + 600 + 400))
    xf = x[faces]
    normal = np.cross(xf[:, 2] - xf[:, 0], xf[:, 3] - xf[:, 1])
    centre = np.array([0.0, 0.0, 10.0])
    assert np.all(np.einsum("ij,ij->i", normal, xf.mean(axis=1) - centre) > 0.0)


def test_boundary_of_tets_and_wedges_is_the_box_surface():
    model = build_model(tet_wedge_deck((60.0, 40.0, 40.0), 10.0))
    x, conn = model.node_x0, model.solid_groups[0].conn.astype(np.int64)
    faces, _ = boundary_faces(x, conn)
    assert _areas(faces, x).sum() == pytest.approx(2 * (60 * 40 * 2 + 40 * 40))
    tri = faces[:, 3] == faces[:, 2]
    assert tri.any() and (~tri).any()  # tetrahedron / wedge triangles, wedge side quads
    loc = TetLocator(x, solid_tets(conn))
    assert loc.inside(np.array([[0.0, 0.0, 20.0], [29.9, 19.9, 39.9]])).all()
    assert not loc.inside(np.array([[0.0, 0.0, 40.1], [30.1, 0.0, 20.0]])).any()


def test_paper_block_gives_the_paper_walls_conforming():
    deck = box_deck((180.0, 180.0, 90.0), 7.5)
    model, conn, faces, w = _walls(deck, 1)
    grid = hollow_box((180.0, 180.0, 90.0), 30.0, 1.5, 4, origin=(-90.0, -90.0, 0.0))
    x = np.vstack([model.node_x0, w.x_new])
    assert faces.shape[0] + w.conn.shape[0] == grid.quads.shape[0]
    assert _areas(faces, x).sum() + _areas(w.conn, x).sum() == pytest.approx(grid.wall_area)
    assert w.tied.size == 0  # every wall edge on the boundary is a boundary node
    assert (w.cells == [6, 6, 3]).all()


@pytest.mark.parametrize("axes", ["global", "principal"])
def test_limb_walls_conform_and_meet_the_boundary(axes):
    deck = limb_deck("leg", length=150.0, n_theta=16, n_radial=3, axial=15.0)
    model0 = build_model(deck)
    inertia = None
    if axes == "principal":
        from hollowbody.hollow.boundary import solid_mass_properties
        g = next(g for g in model0.solid_groups if g.pid == PID_MUSCLE)
        inertia = solid_mass_properties(model0.node_x0, g.conn.astype(np.int64), 1e-6).inertia
    model, conn, faces, w = _walls(deck, PID_MUSCLE, axes=inertia)
    n0 = model.n_nodes
    x = np.vstack([model.node_x0, w.x_new])
    h = w.h
    # no duplicate nodes among the new ones, none on top of an original node
    d = np.linalg.norm(w.x_new[:, None, :] - w.x_new[None, :, :], axis=2)
    np.fill_diagonal(d, np.inf)
    assert d.min() > 1e-3 * h
    # walls are planar pieces of the grid planes (in the grid frame)
    u = x[w.conn] @ w.frame
    for a in range(3):
        sel = w.axis == a
        coord = u[sel][:, :, a]
        assert np.allclose(coord, coord[:, :1], atol=1e-6)
        assert np.abs(coord[:, :1] - w.planes[a][None, :]).min(axis=1).max() < 1e-6
    # every free edge of the walls ends on the boundary: tied (on the surface) or merged
    e = np.sort(np.stack([w.conn, np.roll(w.conn, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    e = e[e[:, 0] != e[:, 1]]
    u_e, cnt = np.unique(e, axis=0, return_counts=True)
    free = np.unique(u_e[cnt == 1])
    assert np.isin(free[free >= n0], w.tied).all()
    assert np.all(np.isin(free[free < n0], faces))
    surf = TriangleSurface.from_shells(model.node_x0, faces)
    assert surf.distance(x[w.tied], radius=h).max() <= 0.25 * h + 1e-9
    # smallest element is not a sliver
    xe = x[w.conn]
    sides = np.linalg.norm(xe - np.roll(xe, -1, axis=1), axis=2).max(axis=1)
    assert (_areas(w.conn, x) / sides).min() > 0.05 * h


def _brute_ray_hits(p, d, tri, length):
    """Reference ray-triangle test (numpy, Moller-Trumbore) for one point and direction."""
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    pv = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, pv)
    ok = np.abs(det) > 1e-12
    tv = p - tri[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.einsum("ij,ij->i", tv, pv) / det
        qv = np.cross(tv, e1)
        v = (qv @ d) / det
        s = np.einsum("ij,ij->i", e2, qv) / det
        return bool(np.any(ok & (u >= -1e-9) & (v >= -1e-9) & (u + v <= 1 + 1e-9)
                           & (s >= -1e-9) & (s <= length * (1 + 1e-9))))


@pytest.mark.parametrize("case", ["box", "limb", "tets-wedges"])
def test_every_removed_solid_is_enclosed_within_one_cell(case):
    """Coverage: from every removed solid's centroid, rays along the six grid directions hit
    the hollow structure (boundary shells or walls) within one cell size."""
    deck, pid, cell = {
        "box": (box_deck((100.0, 70.0, 50.0), 10.0), 1, 30.0),
        "limb": (limb_deck("leg", length=150.0, n_theta=16, n_radial=3, axial=15.0),
                 PID_MUSCLE, 30.0),
        "tets-wedges": (tet_wedge_deck(), 1, 25.0)}[case]
    model, conn, faces, w = _walls(deck, pid, cell=cell)
    x = np.vstack([model.node_x0, w.x_new])
    shells = np.vstack([faces, w.conn])
    xs = model.node_x0[conn]
    centroid = np.array([np.unique(xs[k], axis=0).mean(axis=0) for k in range(conn.shape[0])])
    surf = TriangleSurface.from_shells(x, shells, size=cell / 2)
    dirs = np.vstack([w.frame.T, -w.frame.T])
    hits = surf.ray_hits(centroid, dirs, cell)
    assert hits.all(), f"{(~hits.all(axis=1)).sum()} centroids not enclosed"
    tri = x[quads_to_triangles(shells)]
    for k in range(0, centroid.shape[0], max(1, centroid.shape[0] // 25)):
        for r in range(6):
            assert _brute_ray_hits(centroid[k], dirs[r], tri, cell) == hits[k, r]
    # and far rays miss: the structure is not everywhere (the kernel is not always True)
    assert not surf.ray_hits(np.array([[0.0, 0.0, -500.0]]), dirs[:1], cell).any()


def test_shared_nodes_stay_shared():
    deck = limb_deck("leg", length=150.0, n_theta=16, n_radial=3, axial=15.0)
    new, report = hollowize(deck, Selection(parts=[PID_MUSCLE]), HollowOptions())
    m0, m1 = build_model(deck), build_model(new)

    def nodes_of(model, pid):
        gs = [g for g in model.solid_groups + model.shell_groups if g.pid == pid]
        return set(model.node_ids[np.unique(np.concatenate([g.conn.ravel() for g in gs]))])

    for other in (PID_BONE, PID_SKIN):
        shared0 = nodes_of(m0, PID_MUSCLE) & nodes_of(m0, other)
        assert shared0 and shared0 <= nodes_of(m1, PID_MUSCLE) & nodes_of(m1, other)
    assert report.parts[0].coverage["fraction"] == 1.0
