"""Beams in penalty contacts: their nodes meet the other side's segments at half the
section's diameter (the beam's contact thickness), as LS-DYNA's automatic contacts treat
beams.

A steel tube (outer diameter 10 mm, 10 ELFORM 1 elements, 100 mm long) falls flat at
1 m/s onto the top face of a fixed elastic block. With the contact its nodes stop at
z = 5 mm (half the diameter) within 0.5 mm (10 % of the thickness: the penalty spring
gives a little) and the tube bounces back up; without it the tube keeps falling into the
block (the test can fail).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hollowbody.api import run_deck

CONTACT = """*CONTACT_AUTOMATIC_NODES_TO_SURFACE
         1         2         3         3
       0.0       0.0
"""
SINGLE = """*CONTACT_AUTOMATIC_SINGLE_SURFACE
         0         0         5
       0.0       0.0
"""


def _deck(path: Path, contact: str) -> Path:
    lines = ["*KEYWORD", "*CONTROL_TERMINATION", "       4.0", "*CONTROL_TIMESTEP",
             "         0       0.9", "*NODE"]
    nid = 1
    z_beam = 6.0
    for i in range(11):  # the tube, along x, 1 mm above its contact distance
        lines.append(f"{nid:8d}{10.0 * i:16.6f}{0.0:16.6f}{z_beam:16.6f}")
        nid += 1
    block = {}
    for k in range(3):  # block 120 x 40 x 20 mm, 12 x 4 x 2 hexahedra
        for j in range(5):
            for i in range(13):
                block[(i, j, k)] = nid
                lines.append(f"{nid:8d}{-10.0 + 10.0 * i:16.6f}{-20.0 + 10.0 * j:16.6f}"
                             f"{-20.0 + 10.0 * k:16.6f}")
                nid += 1
    lines.append("*ELEMENT_BEAM")
    for e in range(10):
        lines.append(f"{e + 1:8d}{1:8d}{e + 1:8d}{e + 2:8d}")
    lines.append("*ELEMENT_SOLID")
    eid = 100
    for k in range(2):
        for j in range(4):
            for i in range(12):
                c = [block[(i, j, k)], block[(i + 1, j, k)], block[(i + 1, j + 1, k)],
                     block[(i, j + 1, k)], block[(i, j, k + 1)], block[(i + 1, j, k + 1)],
                     block[(i + 1, j + 1, k + 1)], block[(i, j + 1, k + 1)]]
                lines.append(f"{eid:8d}{2:8d}" + "".join(f"{n:8d}" for n in c))
                eid += 1
    bottom = [n for (i, j, k), n in block.items() if k == 0]
    lines += ["*PART", "tube", "         1         1         1",
              "*SECTION_BEAM", "         1         1       1.0         2         1",
              "      10.0      10.0       8.0       8.0",
              "*MAT_ELASTIC", "         1   7.85e-6     200.0       0.3",
              "*PART", "block", "         2         2         2",
              "*SECTION_SOLID", "         2         1",
              "*MAT_ELASTIC", "         2   1.0e-06      0.05       0.3",
              "*SET_NODE_LIST", "         1"]
    for a in range(0, len(bottom), 8):
        lines.append("".join(f"{n:10d}" for n in bottom[a:a + 8]))
    lines += ["*BOUNDARY_SPC_SET", "         1         0         1         1         1",
              "*INITIAL_VELOCITY_GENERATION",
              "         1         2       0.0       0.0       0.0      -1.0",
              "       0.0       0.0       0.0       0.0       0.0       0.0",
              "*DATABASE_HISTORY_NODE", "         1         6        11",
              "*DATABASE_NODOUT", "      0.02"]
    lines += contact.rstrip("\n").split("\n") if contact else []
    lines.append("*END")
    path.write_text("\n".join(lines) + "\n")
    return path


def _z(out: Path) -> np.ndarray:
    data = np.genfromtxt(out / "nodout.csv", delimiter=",", names=True)
    return data["uz_mm"] + 6.0, data["vz_mmms"]


@pytest.mark.parametrize("contact", [CONTACT, SINGLE], ids=["nodes_to_surface", "single"])
def test_tube_stops_at_its_radius(tmp_path: Path, contact: str) -> None:
    deck = _deck(tmp_path / "tube.k", contact)
    res = run_deck(deck, tmp_path / "run", d3plot=False)
    assert res.status == "normal termination"
    z, vz = _z(tmp_path / "run")
    assert z.min() == pytest.approx(5.0, abs=0.5)  # half the diameter above the block
    assert vz[-1] > 0.0  # it bounced
    assert 0.97 < res.summary["energy_ratio"] < 1.03


def test_without_contact_it_falls_through(tmp_path: Path) -> None:
    deck = _deck(tmp_path / "tube.k", "")
    run_deck(deck, tmp_path / "run", d3plot=False)
    z, _ = _z(tmp_path / "run")
    assert z.min() < 4.0  # 6 - 1 mm/ms x 4 ms = 2 mm: well inside the tube's radius
