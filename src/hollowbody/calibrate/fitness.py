"""Least-squares distance between two force-displacement curves (the GA's fitness).

Definition (one speed)
----------------------

1. **Filter.** Contact forces of explicit runs carry high-frequency noise
   (single-cycle spikes several times the mean force). The force is resampled
   on a uniform time grid and low-pass filtered with the SAE J211 channel
   frequency class filter (:func:`hollowbody.curves.cfc.cfc_filter`: a 2-pole
   Butterworth applied forward and backward), CFC 180 by default
   (:func:`hollowbody.curves.force_displacement.smoothed`). Displacements are
   not filtered.
2. **Normalise.** Displacements are divided by the reference's maximum
   displacement ``D`` (mm), forces by the reference's peak filtered force
   ``P`` (kN), so curves of soft fat and stiff muscle, at 40 or 100 km/h, give
   fitness values of the same scale.
3. **Split into branches.** The impactor is only decelerated by the contact
   force, so its displacement rises to a maximum and then falls: each curve is
   split at its maximum displacement into a *loading* branch (before) and an
   *unloading* branch (after, down to where the impactor leaves the tissue).
   Each branch is a function force(displacement).
4. **Common grid.** Both branches of both curves are sampled at ``points``
   normalised displacements uniformly spaced on ``[0, u_top]``,
   ``u_top = max(1, D_c / D)`` (the deeper of the two curves), plus the
   branches' end points. Beyond its maximum displacement a branch keeps its
   last force (the force at maximum displacement, where loading and
   unloading meet): a candidate that goes deeper than the reference is
   compared there with the force the reference reached, which keeps the
   fitness smooth near the optimum. Below its lowest displacement (before
   contact, after the impactor left) a branch's force is zero, so a
   candidate that rebounds less than the reference is charged for the force
   it still carries.
5. **Distance.** ``fitness = sqrt((I_load + I_unload) / 2)``,
   ``I = integral over u of (f_cand - f_ref)^2 du``, integrated exactly for
   branches that are linear between grid points and may jump to zero at
   their lower ends. It is a root-mean-square force difference in units of the
   reference peak force over the reference's displacement range: 0 for
   identical curves, ``|a - 1| * rms(f_ref)`` for a candidate whose force is
   ``a`` times the reference's.

With several speeds the fitness is the sum over speeds. A candidate whose
run does not end normally (or an empty curve) gets :attr:`FitnessSettings.penalty`
per speed, well above the fitness of any curve that resembles the reference
(a curve of zero force scores about 0.5).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from hollowbody.curves.force_displacement import ForceDisplacement, smoothed


@dataclass(frozen=True)
class FitnessSettings:
    """points: grid points per branch; cfc: SAE J211 filter class of the force (Hz
    class number, e.g. 180; None: no filter); penalty: fitness per speed of a failed
    run."""

    points: int = 201
    cfc: float | None = 180.0
    penalty: float = 10.0

    def to_dict(self) -> dict:
        return asdict(self)


def _branch(d: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A branch as strictly increasing displacements (j,) and their forces (j,)."""
    if d.size == 0:
        return d, f
    d = np.maximum.accumulate(d)
    d, first = np.unique(d, return_index=True)
    return d, f[first]


def _one_sided(x: np.ndarray, y: np.ndarray, grid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Right and left limits (m,) at ``grid`` of the branch (x, y).

    The branch is linear between its points, zero below x[0] and constant
    (y[-1]) beyond x[-1]; the two limits differ only at x[0].
    """
    if x.size < 2:
        z = np.zeros_like(grid)
        return z, z.copy()
    v = np.interp(grid, x, y)
    return np.where(grid >= x[0], v, 0.0), np.where(grid > x[0], v, 0.0)


def branches(curve: ForceDisplacement, d_scale: float, f_scale: float
             ) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """((x, y) loading, (x, y) unloading): normalised displacement and force of each branch.

    ``curve`` is already smoothed; displacements are divided by ``d_scale`` (mm),
    forces by ``f_scale`` (kN); x increases along both branches.
    """
    d = np.asarray(curve.displacement, dtype=float) / d_scale
    f = np.asarray(curve.force, dtype=float) / f_scale
    if d.size == 0:
        return (d, f), (d, f)
    i = int(np.argmax(d))
    return _branch(d[: i + 1], f[: i + 1]), _branch(d[i:][::-1], f[i:][::-1])


def _squared_difference_integral(a: tuple[np.ndarray, np.ndarray],
                                 b: tuple[np.ndarray, np.ndarray], grid: np.ndarray) -> float:
    """Integral over u of (branch a - branch b)^2, exact for the piecewise-linear branches
    sampled on ``grid`` (which holds both branches' end points)."""
    ar, al = _one_sided(*a, grid)
    br, bl = _one_sided(*b, grid)
    p = (ar - br)[:-1]  # value just right of each grid point
    q = (al - bl)[1:]  # value just left of the next one
    h = np.diff(grid)
    return float(np.sum(h * (p * p + p * q + q * q) / 3.0))


def curve_distance(reference: ForceDisplacement, candidate: ForceDisplacement,
                   settings: FitnessSettings | None = None) -> float:
    """Normalised least-squares distance of two force-displacement curves (module doc).

    Both curves: time (k,) ms, displacement (k,) mm, force (k,) kN. Returns a
    dimensionless number >= 0; ``settings.penalty`` if the candidate is empty.
    Raises ValueError if the reference has no positive displacement or force.
    """
    s = settings or FitnessSettings()
    ref = smoothed(reference, s.cfc)
    if candidate.displacement.size < 2:
        return float(s.penalty)
    cand = smoothed(candidate, s.cfc)
    d_scale = float(np.max(ref.displacement)) if ref.displacement.size else 0.0
    f_scale = float(np.max(ref.force)) if ref.force.size else 0.0
    if not (d_scale > 0.0 and f_scale > 0.0):
        raise ValueError("reference curve has no positive displacement or force")
    rl, ru = branches(ref, d_scale, f_scale)
    cl, cu = branches(cand, d_scale, f_scale)
    u_top = max(1.0, float(np.max(cand.displacement)) / d_scale)
    ends = [x[k] for x, _ in (rl, ru, cl, cu) if x.size for k in (0, -1)]
    grid = np.unique(np.concatenate([np.linspace(0.0, u_top, s.points),
                                     np.clip(ends, 0.0, u_top)]))
    total = (_squared_difference_integral(cl, rl, grid)
             + _squared_difference_integral(cu, ru, grid))
    value = float(np.sqrt(0.5 * total))
    return value if np.isfinite(value) else float(s.penalty)
