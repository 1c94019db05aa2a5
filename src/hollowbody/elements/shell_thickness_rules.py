"""Through-thickness integration rules of shell sections.

A rule is a pair ``(zeta, weight)`` of ``(nip,)`` float64 arrays on the
reference interval ``[-1, 1]`` (``zeta = 2 z / t``); the weights sum to 2, so a
point at ``z = zeta * t / 2`` carries the thickness share ``weight * t / 2``.

Supported ``*SECTION_SHELL`` settings (``QR``/``IRID`` field as stored in
:class:`~hollowbody.model.model.SectionDef` ``params["QR"]``):

====== ============================================ ============
QR     rule                                         NIP
====== ============================================ ============
0      Gauss-Legendre (LS-DYNA default)             1 .. 10
-1     Gauss-Lobatto (surface points included)      2 .. 10
1      trapezoidal (equally spaced, ends at +-t/2)   2 .. 10
====== ============================================ ============

``NIP`` 0 or missing means 2 (LS-DYNA's default). NIP = 1 gives a membrane
(one point on the mid-surface, no bending stiffness). User-defined rules
(``QR < -1``, *INTEGRATION_SHELL) are not supported.
"""

from __future__ import annotations

import numpy as np

MAX_NIP = 10


def gauss_rule(nip: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre points and weights on [-1, 1] (exact for degree 2 nip - 1)."""
    z, w = np.polynomial.legendre.leggauss(nip)
    return z.astype(np.float64), w.astype(np.float64)


def lobatto_rule(nip: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Lobatto points and weights on [-1, 1] (ends included; exact for degree 2 nip - 3).

    Interior points are the roots of P'_{nip-1}; weights 2 / (n (n - 1) P_{n-1}(z)^2).
    """
    if nip < 2:
        raise ValueError("a Lobatto rule needs at least 2 points")
    n = nip
    leg = np.polynomial.legendre.Legendre.basis(n - 1)
    inner = np.sort(leg.deriv().roots().real) if n > 2 else np.zeros(0)
    z = np.concatenate(([-1.0], inner, [1.0]))
    w = 2.0 / (n * (n - 1) * leg(z) ** 2)
    return z.astype(np.float64), w.astype(np.float64)


def trapezoid_rule(nip: int) -> tuple[np.ndarray, np.ndarray]:
    """Equally spaced points including both surfaces, trapezoidal weights."""
    if nip < 2:
        raise ValueError("a trapezoidal rule needs at least 2 points")
    z = np.linspace(-1.0, 1.0, nip)
    w = np.full(nip, 2.0 / (nip - 1))
    w[0] *= 0.5
    w[-1] *= 0.5
    return z, w


def through_thickness_rule(nip: int, qr: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """The rule of a *SECTION_SHELL: ``nip`` points (0 = 2), ``qr`` as in the module table.

    Returns ``(zeta, weight)``, each (nip,) float64. Raises ValueError for what is
    not supported.
    """
    n = int(round(nip)) if nip else 2
    if n < 1 or n > MAX_NIP:
        raise ValueError(f"NIP = {nip} is not supported (1 to {MAX_NIP})")
    q = int(round(qr))
    if q == 0:
        return gauss_rule(n)
    if n == 1:
        raise ValueError("NIP = 1 needs the Gauss rule (QR = 0)")
    if q == -1:
        return lobatto_rule(n)
    if q == 1:
        return trapezoid_rule(n)
    raise ValueError(f"QR/IRID = {qr:g} is not supported (0 Gauss, -1 Lobatto, 1 trapezoidal)")
