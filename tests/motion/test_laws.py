"""The motion laws of VDI 2143 against their published characteristic values, their
derivatives against central differences of the position, their ends against their class."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.errors import InputError
from dyade.motion.laws import LAWS, law

PI = math.pi

# VDI 2143 Blatt 1 (and every cam book): C_v, C_a, C_j, C_M to the digits printed there
PUBLISHED = {
    "cycloid": (2.0, 2 * PI, 4 * PI**2, 8.16),
    "polynomial-345": (1.875, 5.7735, 60.0, 6.69),
    "polynomial-4567": (2.1875, 7.5132, 52.5, 10.75),
    "modified-sine": (1.7596, 5.5280, 69.47, 5.46),
    "modified-trapezoid": (2.0000, 4.8881, 61.43, 8.09),
    "simple-harmonic": (PI / 2, PI**2 / 2, PI**3 / 2, PI**3 / 8),
    "harmonic-combination": (2.04, PI**2, None, None),
    "acceleration-trapezoid": (2.0, 16 / 3, 128 / 3, None),   # ramps of 1/8: A = 16/3
}


def digits(published: float) -> float:
    """Half a unit of the last printed digit (absolute)."""
    text = f"{published:.6g}"
    decimals = len(text.split(".")[1]) if "." in text else 0
    return 0.5 * 10.0 ** -decimals if decimals < 5 else 1e-9 * max(1.0, abs(published))


@pytest.mark.parametrize("name", PUBLISHED)
def test_characteristic_values_as_published(name):
    found = LAWS[name]
    for symbol, value, published in zip(("C_v", "C_a", "C_j", "C_M"),
                                        (found.C_v, found.C_a, found.C_j, found.C_M),
                                        PUBLISHED[name]):
        if published is not None:
            assert abs(value - published) <= digits(published), (name, symbol, value)


def test_exact_values_to_machine_precision():
    assert LAWS["cycloid"].C_a == pytest.approx(2 * PI, rel=1e-12)
    assert LAWS["cycloid"].C_j == pytest.approx(4 * PI**2, rel=1e-12)
    assert LAWS["cycloid"].C_M == pytest.approx(3 * math.sqrt(3) * PI / 2, rel=1e-12)
    assert LAWS["polynomial-345"].C_a == pytest.approx(10 / math.sqrt(3), rel=1e-12)
    assert LAWS["modified-sine"].C_v == pytest.approx(4 * PI / (PI + 4), rel=1e-12)
    assert LAWS["modified-sine"].C_j == pytest.approx(16 * PI**3 / (PI + 4), rel=1e-12)


# interior points away from every piece's join (1/8, 3/8, 1/2, 5/8, 7/8, 0.3, 0.7)
POINTS = np.array([0.06, 0.21, 0.33, 0.44, 0.58, 0.66, 0.81, 0.93])
CUSTOM = {"polynomial-b": law("polynomial", v0=0.4, a0=-1.0, v1=1.2, a1=2.0),
          "spline-3": law("quintic-spline", points=[[0.3, 0.2], [0.7, 0.9]]),
          "inclined-0.5": law("inclined-sine", velocity=0.5),
          "triangle": law("acceleration-trapezoid", ramp=0.25)}
ALL = {**LAWS, **CUSTOM}


@pytest.mark.parametrize("name", ALL)
def test_derivatives_are_central_differences_of_second_order(name):
    f = ALL[name]
    values = f(POINTS)
    for order in (1, 2, 3):                       # v from s, a from v, j from a
        errors = []
        for h in (2e-3, 1e-3):
            ahead, behind = f(POINTS + h)[order - 1], f(POINTS - h)[order - 1]
            errors.append(np.max(np.abs((ahead - behind) / (2 * h) - values[order])))
        scale = 1.0 + np.max(np.abs(values[order]))
        assert errors[1] < 1e-4 * scale, (name, order, errors)
        if errors[0] > 1e-9 * scale:              # not exact: the error falls as h²
            assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.05), (name, order)


@pytest.mark.parametrize("name", ALL)
def test_ends_and_class(name):
    f = ALL[name]
    s, v, a, _ = f(np.array([0.0, 1.0]))
    assert s[0] == pytest.approx(0.0, abs=1e-14) and s[1] == pytest.approx(1.0, abs=1e-13)
    for end, letter in zip((0, 1), (f.start_class, f.end_class)):
        assert (abs(v[end]) < 1e-12) == (letter in "RU"), (name, end, letter)
        assert (abs(a[end]) < 1e-12) == (letter in "RG"), (name, end, letter)


@pytest.mark.parametrize("name", ALL)
def test_continuous_inside(name):
    f = ALL[name]
    for left, right in zip(f.pieces[:-1], f.pieces[1:]):
        z = np.array(right.z0)
        for order in range(3):                   # s, v, a continuous at every join
            assert float(left(z)[order]) == pytest.approx(float(right(z)[order]), abs=1e-12)


def test_classes():
    assert LAWS["cycloid"].boundary == "R-R"
    assert LAWS["simple-harmonic"].boundary == "U-U"
    assert LAWS["harmonic-combination"].boundary == "R-U"
    assert LAWS["constant-velocity"].boundary == "G-G"
    assert CUSTOM["inclined-0.5"].boundary == "G-G"
    assert CUSTOM["polynomial-b"].boundary == "B-B"


def test_general_polynomial_meets_its_end_conditions():
    _, v, a, _ = CUSTOM["polynomial-b"](np.array([0.0, 1.0]))
    np.testing.assert_allclose([v[0], a[0], v[1], a[1]], [0.4, -1.0, 1.2, 2.0], atol=1e-13)


def test_spline_through_its_points():
    s = CUSTOM["spline-3"](np.array([0.3, 0.7]))[0]
    np.testing.assert_allclose(s, [0.2, 0.9], atol=1e-14)


def test_misspelt_law_and_parameter():
    with pytest.raises(InputError, match="Did you mean `modified-sine`"):
        law("modifed sine")
    with pytest.raises(InputError, match="Did you mean `ramp`"):
        law("acceleration-trapezoid", rmp=0.1)
    with pytest.raises(InputError, match="strictly increasing"):
        law("quintic-spline", points=[[0.6, 0.5], [0.4, 0.6]])
    assert law("Polynomial 3-4-5").name == "polynomial-345"


def test_every_piece_scales_its_position_and_derivatives():
    """``scaled`` (which ``chain`` uses to end a law at s = 1) multiplies s, v, a and j,
    for the double harmonic as for the polynomial and sine pieces."""
    from dyade.motion.laws import DoubleHarmonic

    z = np.linspace(0.0, 1.0, 11)
    piece = DoubleHarmonic()
    for got, want in zip(piece.scaled(2.5)(z), piece(z)):
        np.testing.assert_allclose(got, 2.5 * want, rtol=1e-15, atol=1e-15)
