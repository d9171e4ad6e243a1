"""An open path without crank angles (a part of a coupler curve, where it starts and
how much of the curve it covers unknown): the window match finds the part on the
curve that drew it from any start and recovers the similarity; the fit from there
passes through the points; too few points are refused."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.errors import InputError
from dyade.files.synthesis import parse
from dyade.synthesis.partial import polish
from dyade.synthesis.search import fit
from dyade.synthesis.shape import FINE_FRACTIONS, OPEN_SAMPLES, open_match, resample
from dyade.synthesis.topology import FourBar, Placement

VALUES = np.array([0.35, 1.2, 0.9, 1.0, 0.6, 0.4])
PLACE = Placement(0.03 + 0.02j, 0.2, 0.5)  # 200 mm frame, turned by 0.5 rad
TURN = np.linspace(0.0, 2 * np.pi, 100, endpoint=False)


def part(start: float, points: int = 30) -> np.ndarray:
    """``points`` of the placed coupler curve over a third of a crank turn from ``start``."""
    crank = start + np.linspace(0.0, 2 * np.pi / 3, points)
    return PLACE.apply(FourBar().path(VALUES, 1, crank)[0])


@pytest.fixture(scope="module")
def others() -> np.ndarray:
    """Curves of 60 other four-bars, and the one that drew the target last."""
    rng = np.random.default_rng(3)
    values = VALUES * (1 + 0.3 * rng.uniform(-1, 1, (60, 6)))
    values[:, 3] = 1.0
    values = np.vstack([values, VALUES])
    return FourBar().path(values, 1, TURN)


@pytest.mark.parametrize("start", [0.7, pytest.param(3.9, marks=pytest.mark.slow)])
def test_the_window_match_finds_the_part_from_any_start(others, start):
    target = resample(part(start)[None, :], 32, closed=False)[0]
    match = open_match(target, others, fractions=FINE_FRACTIONS)
    # a third of a curve is near many four-bars' (30 % apart, 3e-3 of its size): the
    # first pass ranks the one that drew it among the best, the fit decides
    assert np.sum(match.error < match.error[-1]) <= 3
    assert match.error[-1] < 5e-3  # the fractions and samples are 8 % and 1/100 turn apart
    assert abs(match.factor[-1]) == pytest.approx(0.2, rel=5e-2)  # the scale (the fractions 8 % apart)
    assert np.angle(match.factor[-1]) == pytest.approx(0.5, abs=5e-2)  # the rotation
    # ... and the same curve run backwards is found reversed, as well
    back = open_match(target[::-1], others[-1:], fractions=FINE_FRACTIONS)
    assert back.error[0] < 5e-3 and back.reversed[0]


def test_the_search_pass_matches_the_curve_within_its_floor(others):
    target = resample(part(2.0)[None, :], OPEN_SAMPLES, closed=False)[0]
    match = open_match(target, others)
    assert match.error[-1] < 1e-2  # the coarse pass's floor (fractions 22 % apart)
    assert np.array_equal(np.isinf(match.error), np.isnan(others).any(axis=1))  # no curve


@pytest.mark.slow
def test_the_fit_from_the_match_passes_through_the_points():
    points = part(4.7)
    target = resample(points[None, :], 32, closed=False)[0]
    curve = FourBar().path(VALUES, 1, TURN)
    match = open_match(target, curve, fractions=FINE_FRACTIONS)
    factor = match.factor[0]
    start = Placement(complex(target.mean()) - factor * match.centre[0], abs(factor),
                      float(np.angle(factor)))
    fitted = polish(FourBar(), fit(FourBar(), VALUES, 1, points, start=start), points)
    assert fitted.error < 1e-12
    traced = fitted.placement.apply(FourBar().path(fitted.values, 1, fitted.crank)[0])
    assert np.abs(traced - points).max() < 1e-12 * 0.2
    assert np.abs(fitted.values / (0.2 * VALUES) - 1).max() < 1e-6


def test_an_open_path_needs_more_points_than_unknowns():
    points = part(0.7, points=9)
    with pytest.raises(InputError, match="at least 10 points") as err:
        parse({"target": {"kind": "path", "closed": False,
                          "points": [[z.real, z.imag] for z in points]}})
    assert err.value.key == "target.points"
    problem = parse({"target": {"kind": "path", "closed": False,
                                "points": [[z.real, z.imag] for z in part(0.7, 12)]}})
    assert not problem.target.closed and problem.target.crank is None


def lengths(data: dict) -> np.ndarray:
    """(a, b, c, d) of a four-bar's mechanism data [m]."""
    frame = data["frame"]["points"]
    d = np.hypot(frame["B0"][0] - frame["A0"][0], frame["B0"][1] - frame["A0"][1])
    return np.array([data["crank"]["length"], *data["dyad"][0]["lengths"], d])


@pytest.mark.slow
def test_recovers_a_fourbar_from_30_points_over_a_third_of_its_curve():
    """The part from crank angle 4.7 rad (where the lengths' weakest direction still
    moves the points by 7e-6 of them per unit: the part from 0.7 rad is 40 times flatter
    and the fit stops in its valley, 1e-8 from the points and ~1 % off in the lengths)."""
    from dyade.synthesis import closed, synthesise
    from dyade.synthesis.topology import fourbar_from_points

    points = part(4.7)
    problem = parse({"target": {"kind": "path", "closed": False,
                                "points": [[z.real, z.imag] for z in points]},
                     "search": {"candidates": 2000, "seed": 1}, "output": {"keep": 1}})
    design = synthesise(problem).designs[0]
    linkage = closed.FourBar(*VALUES, variant=1)
    cognates = []
    for cognate in closed.cognates(linkage):
        (f0, f1), (m0, m1), p = cognate.fixed, cognate.moving, cognate.point
        cognates.append(fourbar_from_points(f0, m0, m1, f1, p)[0][:4] * PLACE.scale)
    misses = [np.abs(lengths(design.data) / c - 1).max() for c in cognates]
    assert min(misses) < 1e-6, misses
    assert design.converged and design.error < 1e-12
