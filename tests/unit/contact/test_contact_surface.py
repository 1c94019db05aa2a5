"""Contact surfaces: exterior faces of solids, shells as segments, SurfaceRef kinds."""

from __future__ import annotations

import numpy as np
import pytest

from hollowbody.contact.stiffness import bulk_modulus, segment_stiffness
from hollowbody.contact.surface import (
    SEG_FREE,
    SEG_SHELL,
    SEG_SOLID,
    build_surface,
    segment_centroids,
    segment_normals,
    solid_exterior_faces,
)
from hollowbody.errors import UserInputError
from hollowbody.mesh import block_mesh, plate_mesh
from hollowbody.model.model import MaterialDef, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model


def _outward(faces, x, inside_point):
    n, a = segment_normals(faces, x)
    c = segment_centroids(faces, x)
    return np.einsum("ij,ij->i", n, c - inside_point) > 0, a


def test_hex_block_has_24_outward_exterior_quads():
    x, conn = block_mesh((2, 2, 2), (2.0, 2.0, 2.0))
    faces, grp, elem = solid_exterior_faces([conn], x)
    assert faces.shape == (24, 4)
    assert np.all(faces[:, 3] != faces[:, 2])  # all quads
    out, area = _outward(faces, x, np.array([1.0, 1.0, 1.0]))
    assert np.all(out)
    np.testing.assert_allclose(area, 1.0)
    # normals are axis-aligned unit vectors
    n, _ = segment_normals(faces, x)
    np.testing.assert_allclose(np.sort(np.abs(n), axis=1), [[0, 0, 1]] * 24, atol=1e-14)
    assert set(elem.tolist()) == set(range(8))


def test_inverted_element_numbering_still_gives_outward_faces():
    x, conn = block_mesh((1, 1, 1), (1.0, 1.0, 1.0))
    flipped = conn[:, [4, 5, 6, 7, 0, 1, 2, 3]]  # negative-volume numbering
    faces, _, _ = solid_exterior_faces([flipped], x)
    out, _ = _outward(faces, x, np.array([0.5, 0.5, 0.5]))
    assert faces.shape[0] == 6 and np.all(out)


def _wedge():
    # triangular prism: N1..N6, stored N1 N2 N3 N4 N5 N5 N6 N6
    x = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0, 1], [0.5, 1, 1]], float)
    conn = np.array([[0, 1, 2, 3, 4, 4, 5, 5]])
    return x, conn


def test_wedge_gives_three_quads_and_two_triangles():
    x, conn = _wedge()
    faces, _, _ = solid_exterior_faces([conn], x)
    tri = faces[:, 3] == faces[:, 2]
    assert faces.shape[0] == 5 and tri.sum() == 2
    out, area = _outward(faces, x, x.mean(axis=0))
    assert np.all(out)
    # closed surface: sum of area-weighted normals vanishes
    n, a = segment_normals(faces, x)
    np.testing.assert_allclose((n * a[:, None]).sum(axis=0), 0.0, atol=1e-14)


@pytest.mark.parametrize("storage", [[0, 1, 2, 3, 3, 3, 3, 3], [0, 1, 2, 2, 3, 3, 3, 3]])
def test_tetrahedron_gives_four_outward_triangles(storage):
    x = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    faces, _, _ = solid_exterior_faces([np.array([storage])], x)
    assert faces.shape[0] == 4 and np.all(faces[:, 3] == faces[:, 2])
    assert sorted(map(tuple, np.sort(faces[:, :3], axis=1))) == [
        (0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]
    out, area = _outward(faces, x, x.mean(axis=0))
    assert np.all(out)
    np.testing.assert_allclose(area.sum(), 1.5 + np.sqrt(3) / 2)


def test_faces_shared_by_wedge_tet_and_hex_are_interior():
    # two tets glued on a face, and a wedge glued to a hex on a quad face
    x = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, -1]], float)
    conn = np.array([[0, 1, 2, 3, 3, 3, 3, 3], [0, 2, 1, 4, 4, 4, 4, 4]])
    faces, _, _ = solid_exterior_faces([conn], x)
    assert faces.shape[0] == 6
    xh, ch = block_mesh((1, 1, 1), (1.0, 1.0, 1.0), (0.0, 0.0, -1.0))
    xw, cw = _wedge()
    xall = np.concatenate([xh, xw[4:]])
    # wedge bottom quad = top face of the hex (nodes 1,5,7,3 of the block: z = 0)
    top = [int(np.nonzero(np.all(np.isclose(xh, p), axis=1))[0][0]) for p in xw[:4]]
    wedge = np.array([[top[0], top[1], top[2], top[3], 8, 8, 9, 9]])
    faces, grp, _ = solid_exterior_faces([ch, wedge], xall)
    assert faces.shape[0] == 5 + 4  # hex loses its top, wedge its bottom
    assert set(grp.tolist()) == {0, 1}


def _two_part_model():
    xb, cb = block_mesh((2, 2, 1), (2.0, 2.0, 1.0))
    xp, cp = plate_mesh((2, 2), (2.0, 2.0), (0.0, 0.0, 3.0))
    return assemble_model([PartSpec(1, xb, cb, "solid", "rubber181", {"KM": 0.001, "MU": 0.1}),
                           PartSpec(2, xp, cp, "shell", "elastic", {"E": 0.2, "PR": 0.25},
                                    1e-6, 1.5)])


def test_build_surface_parts_all_nodes_segments():
    model = _two_part_model()
    s1 = build_surface(SurfaceRef(kind="parts", pids=[1]), model)
    assert s1.n_segments == 2 * 4 + 4 * 2 and np.all(s1.seg_kind == SEG_SOLID)
    assert np.all(s1.node_thick == 0.0) and np.all(s1.seg_thick == 0.0)
    assert s1.nodes.shape[0] == 18
    s2 = build_surface(SurfaceRef(kind="parts", pids=[2]), model)
    assert s2.n_segments == 4 and np.all(s2.seg_kind == SEG_SHELL)
    np.testing.assert_allclose(s2.seg_thick, 1.5)
    np.testing.assert_allclose(s2.node_thick, 1.5)
    s2o = build_surface(SurfaceRef(kind="parts", pids=[2]), model, shell_thick_override=0.5)
    np.testing.assert_allclose(s2o.seg_thick, 0.5)
    sa = build_surface(SurfaceRef(kind="all"), model)
    assert sa.n_segments == s1.n_segments + 4
    sn = build_surface(SurfaceRef(kind="nodes", nodes=np.array([19, 0, 19])), model)
    assert sn.n_segments == 0 and sn.nodes.tolist() == [0, 19]
    np.testing.assert_allclose(sn.node_thick, [0.0, 1.5])
    # segment set: one solid face given inward + one unknown segment
    face = s1.seg[0][::-1].copy()
    free = np.array([0, 1, 19, 19])
    ss = build_surface(SurfaceRef(kind="segments", segments=np.array([face, free])), model)
    assert ss.seg_kind.tolist() == [SEG_SOLID, SEG_FREE]
    np.testing.assert_array_equal(ss.seg[0], s1.seg[0])  # re-oriented outward
    with pytest.raises(UserInputError):
        build_surface(SurfaceRef(kind="parts", pids=[9]), model)


def test_segment_stiffness_formulas():
    model = _two_part_model()
    s1 = build_surface(SurfaceRef(kind="parts", pids=[1]), model)
    k, depth = segment_stiffness(s1, model)
    np.testing.assert_allclose(k, 0.001 * 1.0**2 / 1.0)  # KM A^2 / V, unit cubes
    np.testing.assert_allclose(depth, 1.0)
    s2 = build_surface(SurfaceRef(kind="parts", pids=[2]), model)
    k, depth = segment_stiffness(s2, model)
    kb = 0.2 / (3 * (1 - 0.5))
    np.testing.assert_allclose(k, kb * 1.0 / np.sqrt(2.0))  # K A / max diagonal
    np.testing.assert_allclose(depth, 1.0)  # sqrt(A)


def test_bulk_modulus_of_materials():
    assert bulk_modulus(MaterialDef(1, "elastic", 1e-6, {"E": 3.0, "PR": 0.0})) == 1.0
    assert bulk_modulus(MaterialDef(1, "rubber181", 1e-6, {"KM": 0.5, "MU": 0.1})) == 0.5
    assert bulk_modulus(MaterialDef(1, "rigid", 1e-6, {"E": 210.0, "PR": 0.3})) == \
        pytest.approx(175.0)
    assert np.isfinite(bulk_modulus(MaterialDef(1, "elastic", 1e-6, {"E": 1.0, "PR": 0.5})))
    with pytest.raises(UserInputError):
        bulk_modulus(MaterialDef(1, "rigid", 1e-6, {"E": 0.0, "PR": 0.3}))
