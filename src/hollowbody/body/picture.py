"""Front and section views of a keyword deck's shells, parts coloured (PNG).

Reads the deck as built (:func:`hollowbody.build.build_model`), so the
picture shows what a run gets. The front view shows every shell (skin, rigid
shells); the second view looks from the body's right at the shells of the
left half only (centroid y > 0), so the trunk and head are cut at the
mid-plane and their inside shows: spine, rib cage, pelvis and, for a hollow
model, the walls of the hollow structures. Solids are not drawn (their
surfaces carry the skin and bone shells). Faces are drawn back to front
(painter's algorithm), shaded by the angle to the view direction. Units mm.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hollowbody.io.keyword import Deck


def deck_faces(deck: Deck) -> tuple[np.ndarray, np.ndarray]:
    """(quads (f, 4, 3) mm, part id per face (f,)) of every shell."""
    from hollowbody.build import build_model

    model = build_model(deck)
    x = model.node_x0
    quads, pids = [], []
    for g in model.shell_groups:
        quads.append(x[g.conn])
        pids.append(np.full(g.conn.shape[0], g.pid))
    return np.concatenate(quads), np.concatenate(pids)


def _draw(ax, quads: np.ndarray, pids: np.ndarray, view: np.ndarray, right: np.ndarray,
          colours: dict[int, tuple]) -> None:
    from matplotlib.collections import PolyCollection

    depth = quads.mean(axis=1) @ view
    order = np.argsort(depth)  # far first (view points towards the viewer)
    q = quads[order]
    n = np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-12)[:, None]
    shade = 0.45 + 0.55 * np.abs(n @ view)
    base = np.array([colours[int(p)] for p in pids[order]])
    face = np.clip(base[:, :3] * shade[:, None], 0.0, 1.0)
    xy = np.stack([q @ right, q[..., 2]], axis=-1)
    ax.add_collection(PolyCollection(xy, facecolors=face, edgecolors=(0, 0, 0, 0.15),
                                     linewidths=0.2))
    ax.set_xlim(xy[..., 0].min() - 30, xy[..., 0].max() + 30)
    ax.set_ylim(-20, xy[..., 1].max() + 30)
    ax.set_aspect("equal")
    ax.set_xlabel("mm")


def picture(decks: dict[str, Deck], path: str | Path, title: str = "") -> Path:
    """Front and side views of each deck in ``decks`` (label -> deck) side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(decks)
    fig, axes = plt.subplots(1, 2 * n, figsize=(4.2 * n * 2 * 0.62, 7.0), dpi=110,
                             squeeze=False)
    cmap = plt.get_cmap("tab20")
    for k, (label, deck) in enumerate(decks.items()):
        quads, pids = deck_faces(deck)
        colours = {int(p): cmap(i % 20) for i, p in enumerate(np.unique(pids))}
        front, side = axes[0, 2 * k], axes[0, 2 * k + 1]
        # front view: looking along -x (the viewer in front), right of picture = body's left
        _draw(front, quads, pids, np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]),
              colours)
        half = quads.mean(axis=1)[:, 1] > 0.0
        _draw(side, quads[half], pids[half], np.array([0.0, -1.0, 0.0]),
              np.array([1.0, 0.0, 0.0]), colours)
        front.set_title(f"{label}: front")
        side.set_title(f"{label}: left half from the right")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path)
    plt.close(fig)
    return path
