"""Thin-walled tubes of quadrilateral shells: square and circular sections.

The tube's axis is z; it stands on z = 0 and ends at z = L (the loaded end).
The mid-surface of the wall is meshed: a square tube of side ``C`` has its
walls at x, y = +-C/2, a circular tube of diameter ``D`` has its wall at
radius D/2 (C and D are the mid-surface dimensions the crush formulas use).

Numbering: the ring of ``m`` nodes at height level k (k = 0 .. nz, bottom to
top) holds nodes ``k * m .. k * m + m - 1``, counter-clockwise seen from +z
(the square's ring starts at the corner (-C/2, -C/2)); element ``k * m + i``
joins ring nodes i, i + 1 of levels k and k + 1 in LS-DYNA order N1..N4
(N1 N2 on level k), so the shell normals point outwards.

Trigger: a geometric imperfection that fixes where the first fold forms. The
ring of level ``trigger_level`` (counted from the loaded end: 1 = the first
ring below the top edge) is moved normal to the wall by ``trigger * t``
(mm) times a shape: for square tubes sin(pi s / C) along each side (zero at the
corners), inwards on the two walls normal to x and outwards on the two normal
to y (adjacent walls fold in opposite directions in the symmetric mode); for
circular tubes cos(lobes theta) with ``lobes`` = 0 a uniform outward ring (the
axisymmetric, concertina mode) and ``lobes`` >= 2 a diamond-mode pattern.

Units: mm. Returns plain arrays, as :mod:`hollowbody.mesh.structured`.
"""

from __future__ import annotations

import math

import numpy as np


def _quads(m: int, nz: int) -> np.ndarray:
    """(nz * m, 4) int32 quads of a closed ring of m nodes over nz levels."""
    k, i = np.meshgrid(np.arange(nz), np.arange(m), indexing="ij")
    k, i = k.ravel(), i.ravel()
    j = (i + 1) % m
    return np.column_stack([k * m + i, k * m + j, (k + 1) * m + j,
                            (k + 1) * m + i]).astype(np.int32)


def _levels(length: float, nz: int) -> np.ndarray:
    if length <= 0.0 or nz < 1:
        raise ValueError(f"tube length {length:g} mm and {nz} elements along it must be > 0")
    return np.linspace(0.0, length, nz + 1)


def _check_trigger(trigger: float, trigger_level: int, nz: int) -> None:
    if trigger != 0.0 and not 1 <= trigger_level < nz:
        raise ValueError(f"trigger level {trigger_level} must be in 1 .. {nz - 1} "
                         "(rings below the loaded end)")


def square_ring(width: float, per_side: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ring of a square section of side ``width`` (mm), ``per_side`` elements per side.

    Returns (xy (4 n, 2) mm, outward normal (4 n, 2), shape (4 n,) the trigger
    shape: +sin(pi s / C) on the walls normal to y, -sin on those normal to x).
    """
    if width <= 0.0 or per_side < 1:
        raise ValueError(f"square tube side {width:g} mm and {per_side} elements per side "
                         "must be > 0")
    h = 0.5 * width
    s = np.linspace(0.0, width, per_side + 1)[:-1]  # arc length from the side's first corner
    sides = [  # (start corner, direction, outward normal, trigger sign)
        ((-h, -h), (1.0, 0.0), (0.0, -1.0), 1.0),
        ((h, -h), (0.0, 1.0), (1.0, 0.0), -1.0),
        ((h, h), (-1.0, 0.0), (0.0, 1.0), 1.0),
        ((-h, h), (0.0, -1.0), (-1.0, 0.0), -1.0),
    ]
    xy, nrm, shape = [], [], []
    for p0, d, n, sign in sides:
        xy.append(np.column_stack([p0[0] + s * d[0], p0[1] + s * d[1]]))
        nrm.append(np.tile(n, (per_side, 1)))
        shape.append(sign * np.sin(math.pi * s / width))
    return np.vstack(xy), np.vstack(nrm), np.concatenate(shape)


def square_tube(width: float, thickness: float, length: float, per_side: int,
                nz: int | None = None, *, trigger: float = 0.0, trigger_level: int = 1
                ) -> tuple[np.ndarray, np.ndarray]:
    """Square tube of mid-surface side ``width`` (mm), wall ``thickness`` (mm, used
    by the trigger only), ``length`` (mm), ``per_side`` elements per side and
    ``nz`` along the axis (default: elements as square as the length allows).

    ``trigger``: amplitude as a fraction of the thickness (0: none); see the
    module doc. Returns x (n, 3) float64 mm and conn (e, 4) int32 (0-based).
    """
    xy, nrm, shape = square_ring(width, per_side)
    if nz is None:
        nz = max(1, int(round(length / (width / per_side))))
    z = _levels(length, nz)
    _check_trigger(trigger, trigger_level, nz)
    m = xy.shape[0]
    x = np.column_stack([np.tile(xy, (nz + 1, 1)), np.repeat(z, m)])
    if trigger != 0.0:
        k = nz - trigger_level
        x[k * m:(k + 1) * m, :2] += (trigger * thickness) * shape[:, None] * nrm
    return x, _quads(m, nz)


def circular_tube(diameter: float, thickness: float, length: float, around: int,
                  nz: int | None = None, *, trigger: float = 0.0, trigger_level: int = 1,
                  lobes: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Circular tube of mid-surface ``diameter`` (mm), wall ``thickness`` (mm, used
    by the trigger only), ``length`` (mm), ``around`` elements round the
    circumference and ``nz`` along the axis (default: about square elements).

    ``trigger``: radial amplitude as a fraction of the thickness times
    cos(lobes theta) (0: none); see the module doc. Returns x (n, 3) float64 mm
    and conn (e, 4) int32 (0-based).
    """
    if diameter <= 0.0 or around < 3:
        raise ValueError(f"circular tube diameter {diameter:g} mm must be > 0 and "
                         f"{around} elements round it >= 3")
    if lobes < 0 or lobes == 1:
        raise ValueError(f"trigger lobes {lobes}: 0 (axisymmetric) or >= 2")
    if nz is None:
        nz = max(1, int(round(length / (math.pi * diameter / around))))
    z = _levels(length, nz)
    _check_trigger(trigger, trigger_level, nz)
    theta = 2.0 * math.pi * np.arange(around) / around
    r = np.full((nz + 1, around), 0.5 * diameter)
    if trigger != 0.0:
        r[nz - trigger_level] += trigger * thickness * np.cos(lobes * theta)
    x = np.column_stack([(r * np.cos(theta)).ravel(), (r * np.sin(theta)).ravel(),
                         np.repeat(z, around)])
    return x, _quads(around, nz)
