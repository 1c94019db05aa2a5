"""Small decks to try (and test) the solid -> hollow conversion on.

- :func:`box_deck`: a box of hexahedra (one MAT_181 part);
- :func:`tet_wedge_deck`: a box of tetrahedra over wedges (one part, conforming);
- :func:`write_multipart_deck`: a main file with includes: a muscle box (part 1, in
  ``mesh/muscle.k``) on an elastic organ box (part 2, ``mesh/organ.k``) sharing the
  interface nodes, a skin of shells on the muscle's top (part 3, ``mesh/skin.k``), the
  organ's and skin's properties in ``props.k``.

Units mm, ms, kg, GPa.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hollowbody.hollow.boundary import HEX_TETS
from hollowbody.io.keyword import (
    BoundarySpcSet,
    ControlTermination,
    Deck,
    DefineCurve,
    MatElastic,
    MatSimplifiedRubber,
    Part,
    SectionShell,
    SectionSolid,
    SetNodeList,
    write_deck,
)
from hollowbody.mesh import standing_block
from hollowbody.model.mass import hex_volumes
from hollowbody.tissues import tissue


def _tissue_props(deck: Deck, pid: int, name: str = "muscle", mid: int = 1, secid: int = 1,
                  lcid: int = 1) -> None:
    t = tissue(name)
    deck.add(Part(pid=pid, secid=secid, mid=mid, title=f"{name} (solid)"))
    deck.add(SectionSolid(secid=secid))
    deck.add(MatSimplifiedRubber(mid=mid, ro=t.density, km=t.bulk_modulus, lcid=lcid,
                                 title=name))
    deck.add(DefineCurve(lcid=lcid, points=np.column_stack([t.strain, t.stress]).tolist()))


def box_deck(size: tuple[float, float, float] = (90.0, 60.0, 60.0), h: float = 10.0,
             tissue_name: str = "muscle", origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
             ) -> Deck:
    """A box of hexahedra of edge ``h`` (part 1), x, y centred on ``origin``, z from it."""
    x, c = standing_block(size, h)
    x = x + np.asarray(origin, dtype=float)
    deck = Deck()
    deck.title = f"box {size[0]:g} x {size[1]:g} x {size[2]:g} mm of {tissue_name}"
    deck.add_nodes(np.arange(1, x.shape[0] + 1), x)
    deck.add_solids(np.arange(1, c.shape[0] + 1), 1, c + 1)
    _tissue_props(deck, 1, tissue_name)
    deck.add(ControlTermination(endtim=1.0))
    return deck


def tet_wedge_deck(size: tuple[float, float, float] = (90.0, 60.0, 60.0), h: float = 10.0
                   ) -> Deck:
    """A box split at mid-height: tetrahedra above (6 per cube), wedges below (2 per cube),
    conforming, one MAT_181 part (fat)."""
    x, c = standing_block(size, h)
    top = x[c][:, :, 2].mean(axis=1) > 0.5 * size[2]
    tets = c[top][:, HEX_TETS].reshape(-1, 4)
    cubes = c[~top]

    def wedges(p: np.ndarray) -> np.ndarray:  # prism bottom (a, b, c), top (d, e, f)
        a, b, cc, d, e, f = p.T
        w = np.column_stack([a, b, e, d, cc, cc, f, f])
        neg = hex_volumes(w, x) < 0.0
        w[neg] = w[neg][:, [1, 0, 3, 2, 4, 5, 6, 7]]
        return w

    ww = np.vstack([wedges(cubes[:, [0, 1, 2, 4, 5, 6]]), wedges(cubes[:, [0, 2, 3, 4, 6, 7]])])
    deck = Deck()
    deck.title = "box of tetrahedra over wedges"
    deck.add_nodes(np.arange(1, x.shape[0] + 1), x)
    deck.add_solids(np.arange(1, tets.shape[0] + 1), 1, tets + 1)
    deck.add_solids(np.arange(1, ww.shape[0] + 1) + 100000, 1, ww + 1)
    _tissue_props(deck, 1, "fat")
    deck.add(ControlTermination(endtim=1.0))
    return deck


def write_multipart_deck(folder: str | Path, h: float = 10.0) -> Path:
    """Write the multi-part deck with includes into ``folder``; returns the main file."""
    folder = Path(folder)
    xm, cm = standing_block((60.0, 60.0, 60.0), h)
    xo, co = standing_block((60.0, 60.0, 30.0), h)
    xm = xm + np.array([0.0, 0.0, 30.0])  # muscle on top of the organ, interface z = 30
    muscle = Deck()
    ids_m = np.arange(1, xm.shape[0] + 1)
    muscle.add_nodes(ids_m, xm)
    muscle.add_solids(np.arange(1, cm.shape[0] + 1), 1, ids_m[cm])
    _tissue_props(muscle, 1, "muscle")
    # organ: its own nodes except the interface (z = 30), which are the muscle's
    top = np.abs(xo[:, 2] - 30.0) < 1e-9
    key = {tuple(np.round(p, 6)): int(i) for p, i in zip(xm, ids_m)}
    ids_o = np.where(top, 0, 0)
    ids_o[top] = [key[tuple(np.round(p, 6))] for p in xo[top]]
    ids_o[~top] = 10001 + np.arange(int((~top).sum()))
    organ = Deck()
    organ.add_nodes(ids_o[~top], xo[~top])
    organ.add_solids(np.arange(1, co.shape[0] + 1) + 10000, 2, ids_o[co])
    organ.add(SetNodeList(sid=1, nodes=ids_o[np.abs(xo[:, 2]) < 1e-9], title="organ bottom"))
    # skin: shells on the muscle's top face
    nx = int(round(60.0 / h)) + 1
    on_top = np.flatnonzero(np.abs(xm[:, 2] - 90.0) < 1e-9)
    grid = on_top[np.lexsort((xm[on_top, 0], xm[on_top, 1]))].reshape(nx, nx)
    quads = np.column_stack([grid[:-1, :-1].ravel(), grid[:-1, 1:].ravel(),
                             grid[1:, 1:].ravel(), grid[1:, :-1].ravel()])
    skin = Deck()
    skin.add_shells(np.arange(1, quads.shape[0] + 1) + 20000, 3, ids_m[quads])
    props = Deck()
    props.add(Part(pid=2, secid=2, mid=2, title="organ"))
    props.add(SectionSolid(secid=2))
    props.add(MatElastic(mid=2, ro=1.05e-6, e=0.01, pr=0.45, title="organ"))
    props.add(Part(pid=3, secid=3, mid=3, title="skin"))
    props.add(SectionShell(secid=3, t1=1.0, nip=3))
    props.add(MatElastic(mid=3, ro=1.1e-6, e=0.005, pr=0.45, title="skin"))
    main = Deck()
    main.title = "multi-part deck with includes"
    main.add_include("mesh/muscle.k", muscle)
    main.add_include("mesh/organ.k", organ)
    main.add_include("mesh/skin.k", skin)
    main.add_include("props.k", props)
    main.add(BoundarySpcSet(nsid=1, dofx=1, dofy=1, dofz=1))
    main.add(ControlTermination(endtim=1.0))
    write_deck(main, folder / "main.k", flatten=False)
    return folder / "main.k"
