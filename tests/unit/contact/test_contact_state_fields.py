"""STATE_FIELDS of the contact and tie runtimes: saving them and putting them back into
freshly built runtimes continues a run bit for bit.

Each test runs a runtime some cycles, saves its STATE_FIELDS (deep copies), runs on;
then builds the runtime again from the model, puts the saved fields back and runs the
same cycles: every force, position and counter must be identical. A fresh runtime
without the saved fields must differ (the history matters, so the test can fail).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

from hollowbody.build import build_model
from hollowbody.contact import ContactRuntime
from hollowbody.contact.tied import build_ties
from hollowbody.mesh import block_mesh
from hollowbody.testing.models import PartSpec, assemble_model, part_contact

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "verification" / "solver"))
from tied_decks import rotating_plate  # noqa: E402


def _save(obj) -> dict:
    return {name: copy.deepcopy(getattr(obj, name)) for name in type(obj).STATE_FIELDS}


def _restore(obj, saved: dict) -> None:
    """Arrays of unchanged shape in place, everything else (scalars, containers, lists
    rebound with a new length) by assignment."""
    for name, value in saved.items():
        cur = getattr(obj, name)
        if (isinstance(value, np.ndarray) and isinstance(cur, np.ndarray)
                and cur.shape == value.shape and cur.dtype == value.dtype):
            cur[...] = value
        else:
            setattr(obj, name, copy.deepcopy(value))


def _contact_state(rt: ContactRuntime) -> list[dict]:
    return [_save(rt)] + [_save(p) for p in rt.passes]


def _put_contact_state(rt: ContactRuntime, saved: list[dict]) -> None:
    _restore(rt, saved[0])
    for p, s in zip(rt.passes, saved[1:]):
        _restore(p, s)


# -- contact -----------------------------------------------------------------------


def _sliding_block():
    """An elastic block (pid 2) sliding with friction over a larger block (pid 1)."""
    xb, cb = block_mesh((4, 4, 1), (20.0, 20.0, 5.0), (-10.0, -10.0, -5.0))
    xt, ct = block_mesh((2, 2, 1), (6.0, 6.0, 3.0), (-4.5, -2.5, 0.2))
    model = assemble_model([PartSpec(1, xb, cb), PartSpec(2, xt, ct)], sort_interval=7)
    cdef = part_contact(1, "surface_to_surface", [2], [1], fs=0.3, fd=0.2, dc=0.5, vdc=10.0)
    n = model.n_nodes
    mass = np.full(n, 2e-4)
    fixed = np.zeros(n, bool)
    fixed[:xb.shape[0]] = xb[:, 2] < -4.9  # the base's bottom held
    v = np.zeros((n, 3))
    v[xb.shape[0]:] = [2.0, 0.5, -1.5]
    return model, cdef, mass, fixed, v


def _contact_cycles(rt, x, v, mass, fixed, cycle0, n_cycles, dt=2e-3):
    """Central differences under contact forces only; returns per-cycle records."""
    f = np.zeros_like(x)
    out = []
    for c in range(cycle0, cycle0 + n_cycles):
        f[:] = 0.0
        rt.add_forces(x, v, dt, c, f)
        out.append((f.copy(), rt.energy, rt.n_active, rt.slave_force.copy(), rt.n_sorts,
                    rt.n_filters))
        v += dt * f / mass[:, None]
        v[fixed] = 0.0
        x += dt * v
    return out


def _same(a, b) -> bool:
    return all(np.array_equal(np.asarray(p), np.asarray(q)) for r, s in zip(a, b)
               for p, q in zip(r, s))


def test_contact_restored_from_state_fields_continues_bit_for_bit():
    model, cdef, mass, fixed, v = _sliding_block()
    rigid = np.zeros(model.n_nodes, bool)
    rt = ContactRuntime(cdef, model, mass, rigid, fixed)
    x = model.node_x0.copy()
    _contact_cycles(rt, x, v, mass, fixed, 0, 150)
    assert rt.n_active > 0 and rt.n_sorts > 1  # in sliding contact, re-sorted
    saved, xs, vs = _contact_state(rt), x.copy(), v.copy()
    ref = _contact_cycles(rt, x, v, mass, fixed, 150, 60)
    assert any(np.abs(r[3]).max() > 0.0 for r in ref)

    again = ContactRuntime(cdef, model, mass, rigid, fixed)
    _put_contact_state(again, saved)
    x2, v2 = xs.copy(), vs.copy()
    assert _same(_contact_cycles(again, x2, v2, mass, fixed, 150, 60), ref)
    assert np.array_equal(x2, x) and np.array_equal(v2, v)

    fresh = ContactRuntime(cdef, model, mass, rigid, fixed)  # no history: differs
    assert not _same(_contact_cycles(fresh, xs.copy(), vs.copy(), mass, fixed, 150, 60), ref)


# -- ties ------------------------------------------------------------------------------


def _tie_cycles(ties, x, v, w, n_cycles, t0, dt=0.01):
    """The plate's nodes (0-8) turned about x and translated (a prescribed rigid
    motion), the tie's slaves placed by ``follow``, slave forces passed on."""
    rng = np.random.default_rng(int(round(t0 / dt)))
    out = []
    xc0 = np.zeros(3)
    x_ref = np.array([[i, j, 0.0] for j in (-10.0, 0.0, 10.0) for i in (-10.0, 0.0, 10.0)])
    for k in range(1, n_cycles + 1):
        t = t0 + k * dt
        a = 0.3 * t * (1.0 + 0.5 * t)
        c, s = np.cos(a), np.sin(a)
        rot = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
        new = xc0 + np.array([1.0, -2.0, 0.5]) * t + x_ref @ rot.T
        v[:9] = (new - x[:9]) / dt
        w[:9] = [0.3 * (1.0 + t), 0.0, 0.0]
        x[:9] = new
        ties.follow(x, v, w, dt)
        f = rng.normal(size=x.shape)
        mom = rng.normal(size=x.shape)
        ties.distribute(f, mom)
        out.append((x.copy(), v.copy(), w.copy(), f, mom))
    return out


def test_tie_set_restored_from_state_fields_continues_bit_for_bit():
    model = build_model(rotating_plate(height=1.0, offset="OFFSET"))
    ties = build_ties(model)
    assert ties.n_tied == 4 and ties.has_offset  # kept offsets: the frames matter
    mass, inertia = np.ones(model.n_nodes), np.ones(model.n_nodes)
    ties.transfer_mass(mass, inertia)
    x, v, w = ties.node_x0.copy(), np.zeros((model.n_nodes, 3)), np.zeros((model.n_nodes, 3))
    ties.start(x, v, w)
    _tie_cycles(ties, x, v, w, 40, 0.0)
    saved, state = _save(ties), (x.copy(), v.copy(), w.copy())
    ref = _tie_cycles(ties, x, v, w, 40, 0.4)

    again = build_ties(model)
    again.transfer_mass(np.ones(model.n_nodes), np.ones(model.n_nodes))
    _restore(again, saved)
    x2, v2, w2 = (a.copy() for a in state)
    assert _same(_tie_cycles(again, x2, v2, w2, 40, 0.4), ref)
