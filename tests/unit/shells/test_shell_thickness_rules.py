"""Through-thickness rules of shell sections (hollowbody.elements.shell_thickness_rules)."""

import numpy as np
import pytest

from hollowbody.elements.shell_thickness_rules import (
    gauss_rule,
    lobatto_rule,
    through_thickness_rule,
    trapezoid_rule,
)


@pytest.mark.parametrize("n", range(1, 11))
def test_gauss_integrates_degree_2n_minus_1(n):
    z, w = gauss_rule(n)
    for p in range(2 * n):
        exact = 0.0 if p % 2 else 2.0 / (p + 1)
        assert np.dot(w, z ** p) == pytest.approx(exact, abs=1e-13)


@pytest.mark.parametrize("n", range(2, 11))
def test_lobatto_has_surface_points_and_degree_2n_minus_3(n):
    z, w = lobatto_rule(n)
    assert z[0] == -1.0 and z[-1] == 1.0
    assert np.all(np.diff(z) > 0)
    for p in range(2 * n - 2):
        exact = 0.0 if p % 2 else 2.0 / (p + 1)
        assert np.dot(w, z ** p) == pytest.approx(exact, abs=1e-12)


def test_trapezoid_and_section_conventions():
    z, w = trapezoid_rule(5)
    assert z == pytest.approx([-1, -0.5, 0, 0.5, 1])
    assert w.sum() == pytest.approx(2.0)
    # NIP 0 means 2 (LS-DYNA default), QR 0 Gauss, -1 Lobatto, 1 trapezoidal
    z, _ = through_thickness_rule(0)
    assert z == pytest.approx([-1 / np.sqrt(3), 1 / np.sqrt(3)])
    assert through_thickness_rule(3, -1)[0] == pytest.approx([-1, 0, 1])
    assert through_thickness_rule(3, 1)[1] == pytest.approx([0.5, 1.0, 0.5])


@pytest.mark.parametrize("nip, qr", [(11, 0), (-1, 0), (3, -2), (1, -1), (3, 2)])
def test_unsupported_rules_raise(nip, qr):
    with pytest.raises(ValueError):
        through_thickness_rule(nip, qr)
