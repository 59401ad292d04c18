"""tribo.hertz against the closed forms of Hertz theory (Johnson 1985, ch. 4)."""

import math

import numpy as np
import pytest

import tribo


def test_circular_contact_matches_closed_form():
    # Sphere on flat: a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2), delta = a^2 / R
    # (Johnson 1985 eqs. (4.22)-(4.23)). The library solves the general elliptical case by
    # elliptic integrals (AGM), which reduce to these at m = 0: agreement to a few ulp is
    # expected, 1e-12 leaves room for the cube root and the quadrature's round-off.
    F, R, E = 100.0, 0.01, 115e9
    h = tribo.hertz(load=F, radius=R, composite_modulus=E)
    a = (3 * F * R / (4 * E)) ** (1 / 3)
    assert h.semi_major == pytest.approx(a, rel=1e-12)
    assert h.semi_minor == pytest.approx(a, rel=1e-12)
    assert h.radius == pytest.approx(a, rel=1e-12)
    assert h.max_pressure == pytest.approx(3 * F / (2 * math.pi * a * a), rel=1e-12)
    assert h.mean_pressure == pytest.approx(F / (math.pi * a * a), rel=1e-12)
    assert h.approach == pytest.approx(a * a / R, rel=1e-12)
    assert h.contact_area == pytest.approx(math.pi * a * a, rel=1e-12)
    assert h.normal_load == F


def test_approach_control_inverts_load_control():
    # delta -> F -> delta: the same contact both ways (to round-off).
    h = tribo.hertz(load=250.0, radii1=(0.02, 0.05), radii2=(0.03, math.inf),
                    composite_modulus=1.1e11)
    g = tribo.hertz(approach=h.approach, radii1=(0.02, 0.05), radii2=(0.03, math.inf),
                    composite_modulus=1.1e11)
    assert g.normal_load == pytest.approx(250.0, rel=1e-10)
    assert g.semi_major == pytest.approx(h.semi_major, rel=1e-10)


def test_elliptical_pressure_integrates_to_the_load():
    # p0 = 3 F / (2 pi a b) and the ellipsoidal pressure integrates to F exactly; on a
    # 1200^2 midpoint grid the integral of the square-root edge converges like h^1.5:
    # 1e-3 relative is about 10x the measured error.
    h = tribo.hertz(load=500.0, radii1=(0.01, 0.04), composite_modulus=2.3e11)
    assert h.semi_major > h.semi_minor
    n = 1200
    xa = (np.arange(n) + 0.5) / n * 2 * h.semi_major - h.semi_major
    ya = (np.arange(n) + 0.5) / n * 2 * h.semi_minor - h.semi_minor
    X, Y = np.meshgrid(xa, ya)
    # The long axis lies along x' at h.angle from x.
    c, s = math.cos(h.angle), math.sin(h.angle)
    p = h.pressure(c * X - s * Y, s * X + c * Y)
    force = p.sum() * (2 * h.semi_major / n) * (2 * h.semi_minor / n)
    assert force == pytest.approx(500.0, rel=1e-3)
    assert p.max() == pytest.approx(h.max_pressure, rel=1e-4)
    assert h.max_pressure == pytest.approx(
        3 * 500.0 / (2 * math.pi * h.semi_major * h.semi_minor), rel=1e-12)


def test_composite_modulus():
    # 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson 1985 eq. (4.22)).
    e = tribo.composite_modulus(210e9, 0.3, 110e9, 0.25)
    assert e == pytest.approx(1 / ((1 - 0.09) / 210e9 + (1 - 0.0625) / 110e9), rel=1e-15)


def test_bad_input_names_the_field():
    with pytest.raises(tribo.InputError) as err:
        tribo.composite_modulus(210e9, 0.7, 110e9, 0.25)
    assert err.value.field == "body1.nu"
    assert isinstance(err.value, ValueError)
    with pytest.raises(ValueError):
        tribo.hertz(load=1.0, approach=1e-6, radius=0.01, composite_modulus=1e11)
    with pytest.raises(tribo.InputError):
        tribo.hertz(load=1.0, composite_modulus=1e11)
