"""VTK output for ParaView: one ``.vtu`` per state plus a ``.pvd`` collection.

Point data: displacement (mm), velocity (mm/ms). Cell data: part id, element
id, alive flag, Cauchy stress (GPa, Voigt xx yy zz xy yz zx), von Mises
stress (GPa) and, for shells, effective plastic strain when the runtime has
it. The ``.pvd`` file is rewritten after every state so that a run that dies
still opens in ParaView with all states written so far.
"""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np


def von_mises(s: np.ndarray) -> np.ndarray:
    """Von Mises stress of Voigt stresses s (e, 6) -> (e,)."""
    sx, sy, sz, txy, tyz, tzx = (s[:, i] for i in range(6))
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                   + 3.0 * (txy ** 2 + tyz ** 2 + tzx ** 2))


class VtkSeries:
    """Writes states ``<stem>_NNNN.vtu`` into ``folder`` and ``<stem>.pvd``.

    blocks: list of (cell type, conn (e, k) int node indices, cell data
    provider) where the provider is a callable returning {name: (e, ...)}.
    """

    def __init__(self, folder: Path, stem: str = "states") -> None:
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.stem = stem
        self.entries: list[tuple[float, str]] = []

    def write(self, time: float, points: np.ndarray, point_data: dict[str, np.ndarray],
              cells: list[tuple[str, np.ndarray]], cell_data: dict[str, list[np.ndarray]]
              ) -> Path:
        """Write one state at ``time`` (ms). cell_data: {name: one array per cell block}."""
        name = f"{self.stem}_{len(self.entries):04d}.vtu"
        mesh = meshio.Mesh(points=points, cells=cells, point_data=point_data,
                           cell_data=cell_data)
        path = self.folder / name
        mesh.write(path, file_format="vtu", binary=True)
        self.entries.append((time, name))
        self._write_pvd()
        return path

    def _write_pvd(self) -> None:
        lines = ['<?xml version="1.0"?>',
                 '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
                 "  <Collection>"]
        for t, name in self.entries:
            lines.append(f'    <DataSet timestep="{t:.9g}" group="" part="0" file="{name}"/>')
        lines += ["  </Collection>", "</VTKFile>", ""]
        (self.folder / f"{self.stem}.pvd").write_text("\n".join(lines))
