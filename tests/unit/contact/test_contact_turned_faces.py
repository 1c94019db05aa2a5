"""The stiffened zone across a change of segment, and faces turned against a node.

Prescribed paths of one 1 g node against rigid segments (frictionless, node
thickness 0), so that the contact energy is the work the node did on the
contact: a passive contact ends a closed path with an energy >= 0, never < 0.
The stiffened zone is on (as in every contact): its tangent stiffness
here is ``0.25 m / dt^2`` = 250 kN/mm, a thousand times the spring's.

* Behind a face turned against it: a node pressed into the top of a rigid
  frustum (a flesh layer round a bone, made small: top face 20 x 20 mm, bore
  face 7.6 x 7.6 mm, 6 mm below, so that PENMAX 0.4 of the bore face's V / A,
  8.4 mm, reaches past the top) leaves the top face and comes back. On its way
  out it is 6 mm behind the bore face, whose normal points away from the side
  it was pushed to, deep in that face's stiffened zone. Taken as a penetration
  there (the contact as it was), the stiffened-zone force jumped from 0 to
  ~190 kN in one cycle (0 -> 6 mm of gap) and gave the node the energy of a
  spring it had never loaded: -75 J. The node did not pass through that face: it
  is not in contact with it.
* Change of segment: a node pushed 3.5 mm past the mid-surface of one rigid
  shell (in the stiffened zone) slides on under a second shell 1 mm higher,
  and back out. Its stiffening force goes on from where it was with the
  node's motion (none across the step), not with the 1 mm difference of the
  two gaps (that made the force jump by ~0.9 x 250 kN/mm x 1 mm, and created
  ~140 J).

Tolerance: the energy is summed by the trapezoidal rule from the prescribed
positions; it is exact for a force linear along the path, and the error of a
kinked one (the ramp of the zone) is below 1e-3 of the work stored.
"""

from __future__ import annotations

import numpy as np

from hollowbody.contact import ContactRuntime
from hollowbody.model.model import ContactDef, SurfaceRef
from hollowbody.testing.models import PartSpec, assemble_model

DT = 1.0e-3  # ms
MASS = 1.0e-3  # kg


def _runtime(parts: list[PartSpec], start: np.ndarray, master: list[int]) -> ContactRuntime:
    node = PartSpec(9, start[None, :], np.zeros((0, 8), np.int32), "solid")
    model = assemble_model([*parts, node])
    n = model.n_nodes
    cd = ContactDef(cid=1, kind="nodes_to_surface",
                    slave=SurfaceRef(kind="nodes", nodes=np.array([n - 1])),
                    master=SurfaceRef(kind="parts", pids=master))
    mass = np.full(n, MASS)
    rigid = np.ones(n, bool)
    rigid[n - 1] = False
    return ContactRuntime(cd, model, mass, rigid, x0=model.node_x0)


def _lead(rt: ContactRuntime, x0: np.ndarray, path: np.ndarray):
    """Lead the last node of x0 (n, 3) mm along path (m, 3) mm, one point per cycle;
    returns its contact force (m, 3) kN and segment (m,) per cycle."""
    x = x0.copy()
    v = np.zeros_like(x)
    f = np.zeros_like(x)
    forces, segs = [], []
    for c, p in enumerate(path):
        v[-1] = (p - x[-1]) / DT
        x[-1] = p
        f[:] = 0.0
        rt.add_forces(x, v, DT, c, f)
        forces.append(f[-1].copy())
        segs.append(int(rt.passes[0].oseg[0]))
    return np.array(forces), np.array(segs)


def _line(a, b, n):
    return np.linspace(np.asarray(a, float), np.asarray(b, float), n)


def _frustum():
    """One rigid hexahedron: top face 20 x 20 mm at z = 0, bore face 7.6 x 7.6 at z = -6."""
    t, b = 10.0, 3.8
    x = np.array([[-b, -b, -6.0], [b, -b, -6.0], [b, b, -6.0], [-b, b, -6.0],
                  [-t, -t, 0.0], [t, -t, 0.0], [t, t, 0.0], [-t, t, 0.0]])
    return PartSpec(1, x, np.arange(8, dtype=np.int32)[None, :], "solid", "rigid",
                    {"E": 210.0, "PR": 0.3}, 7.8e-6)


def test_node_behind_a_face_turned_against_it_is_not_caught():
    # from 3 mm above (beyond the bore face's release depth) in 0.3 mm, out 0.2 mm
    # above the top face, in again and out
    path = np.vstack([_line([0, 0, 3.0], [0, 0, -0.3], 100),
                      _line([0, 0, -0.3], [0, 0, 0.2], 20)[1:],
                      _line([0, 0, 0.2], [0, 0, -0.3], 20)[1:],
                      _line([0, 0, -0.3], [0, 0, 1.0], 40)[1:]])
    block = _frustum()
    rt = _runtime([block], path[0], [1])
    f, segs = _lead(rt, np.vstack([assemble_model([block]).node_x0, path[0]]), path)
    top = segs[99]
    assert top >= 0 and segs[0] == -1
    # after the top face pushed it, out of that face's reach the node touches
    # nothing (the bore face 6 mm below holds it within its release depth, but
    # faces away from the side it was pushed to)
    out = np.arange(path.shape[0]) > 99
    out &= path[:, 2] > 0.0
    assert out.sum() > 20 and (segs[out] == -1).all()
    assert np.abs(f[out]).max() == 0.0
    # only ever pushed upward: the bore face (pushing down) never acts
    assert f[:, 2].min() >= 0.0
    k_ref = f[99, 2] / 0.3  # kN/mm, the spring at 0.3 mm
    assert k_ref > 0.0
    # a closed path, frictionless: it gave back what it was given (2 x 0.5 k 0.3^2
    # loaded), nothing more (before: -75 J)
    assert rt.energy > -1.0e-3 * k_ref * 0.3**2
    assert rt.energy < 1.0e-2 * k_ref * 0.3**2


def _step():
    """Rigid 1 mm shells A (z = 0, y in [-10, 0]) and B (z = 1, y in [0, 10]), 20 mm
    wide in x, and a rigid hexahedron far away (a solid part in the contact; the
    stiffened zone is on in every contact)."""
    g = np.array([[-10.0, -10.0, 0.0], [10.0, -10.0, 0.0], [10.0, 0.0, 0.0],
                  [-10.0, 0.0, 0.0], [-10.0, 0.0, 1.0], [10.0, 0.0, 1.0], [10.0, 10.0, 1.0],
                  [-10.0, 10.0, 1.0]])
    shells = PartSpec(1, g, np.array([[0, 1, 2, 3], [4, 5, 6, 7]], np.int32), "shell",
                      "rigid", {"E": 210.0, "PR": 0.3}, 7.8e-6, 1.0)
    c = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1],
                  [0, 1, 1]], float) * 10.0 + np.array([200.0, 0.0, 0.0])
    far = PartSpec(2, c, np.arange(8, dtype=np.int32)[None, :], "solid", "rigid",
                   {"E": 210.0, "PR": 0.3}, 7.8e-6)
    return [shells, far]


def test_stiffening_force_does_not_jump_on_a_change_of_segment():
    # down 3.5 mm past A's mid-surface (gap 4.0, stiffened zone from 3.08), along
    # under B (gap 5.0 there), and out of B upward
    path = np.vstack([_line([0, -5.0, 2.0], [0, -5.0, -3.5], 300),
                      _line([0, -5.0, -3.5], [0, 5.0, -3.5], 101)[1:],
                      _line([0, 5.0, -3.5], [0, 5.0, 2.0], 300)[1:]])
    parts = _step()
    rt = _runtime(parts, path[0], [1, 2])
    f, segs = _lead(rt, np.vstack([assemble_model(parts).node_x0, path[0]]), path)
    a, b = segs[299], segs[-300]
    assert a >= 0 and b >= 0 and a != b  # it did move on to the other shell
    fa = f[299, 2]  # kN, the force at the end of the push into A
    assert fa > 0.0
    # along under B the force stays the one reached under A (no normal motion)
    along = slice(300, 399)
    assert f[along, 2].max() <= fa * (1.0 + 1.0e-9)
    # a closed path, frictionless: the contact gave back no more than it was given
    assert rt.energy > -1.0e-3 * abs(0.5 * fa * 4.0)
