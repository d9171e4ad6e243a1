"""The cam's geometry against closed forms (issue 40): pressure angle, radius of
curvature of the pitch curve (the polar form), undercut, the smallest base circle, for
the translating roller follower with offset, the oscillating roller follower and the
flat-faced follower."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.cam import geometry
from tests.cam.cycloid import cycle, polar_radius_of_curvature

THETA = np.linspace(0.0, 2 * np.pi, 1441)[:-1]
LIFT = 0.02  # [m]


@pytest.mark.parametrize("clockwise", [False, True])
@pytest.mark.parametrize("offset", [0.0, 0.008, -0.012])
def test_translating_pressure_angle_closed_form(offset, clockwise):
    s, ds, dds = cycle(THETA, LIFT)
    cam = geometry.translating_roller(THETA, s, ds, dds, base_radius=0.04, roller_radius=0.01,
                                      offset=offset, clockwise=clockwise)
    e = -offset if clockwise else offset  # the other sense flips the sign of e
    expected = (ds - e) / (s + np.sqrt(0.05 ** 2 - e ** 2))
    assert np.max(np.abs(np.tan(cam.pressure_angle) - expected)) < 1e-10


@pytest.mark.parametrize("offset", [0.0, 0.01])
def test_translating_pitch_curvature_is_the_polar_form(offset):
    s, ds, dds = cycle(THETA, LIFT)
    cam = geometry.translating_roller(THETA, s, ds, dds, base_radius=0.04, roller_radius=0.01,
                                      offset=offset)
    d = np.sqrt(0.05 ** 2 - offset ** 2)
    zero = np.zeros_like(s)
    rho = polar_radius_of_curvature(THETA, offset + zero, d + s, zero, ds, zero, dds)
    assert np.max(np.abs(cam.pitch_curvature_radius / rho - 1.0)) < 1e-9
    # the pitch curve seen from the cam: |P| = distance of the roller centre from O
    assert np.allclose(np.hypot(*cam.pitch.T), np.hypot(offset, d + s), rtol=0, atol=1e-15)
    # the working curve lies r_r inside the pitch curve along the normal
    assert np.allclose(np.hypot(*(cam.pitch - cam.working).T), 0.01, rtol=0, atol=1e-15)


def test_undercut_over_the_right_angles():
    # a small base circle and a big roller: the pitch curve's convex radius falls below r_r
    s, ds, dds = cycle(THETA, 0.03, rise_deg=60.0, dwell_deg=120.0)
    zero = np.zeros_like(s)
    rho = polar_radius_of_curvature(THETA, zero, 0.03 + s, zero, ds, zero, dds)
    roller = 0.025
    cam = geometry.translating_roller(THETA, s, ds, dds, base_radius=0.005, roller_radius=roller)
    expected = (rho > 0) & (rho < roller)
    assert expected.any() and not expected.all()
    assert np.array_equal(cam.undercut, expected)
    # the working curve runs backwards (its tangent against the pitch curve's) exactly there:
    # W′ = P′·(1 − r_r/ρ)
    w_step = np.roll(cam.working, -1, axis=0) - np.roll(cam.working, 1, axis=0)
    p_step = np.roll(cam.pitch, -1, axis=0) - np.roll(cam.pitch, 1, axis=0)
    backwards = np.einsum("ij,ij->i", w_step, p_step) < 0
    inner = expected & np.roll(expected, 1) & np.roll(expected, -1)  # away from the edges
    assert backwards[inner].all() and not backwards[~expected & ~np.roll(expected, 1)
                                                    & ~np.roll(expected, -1)].any()
    spans = geometry.spans(THETA, cam.undercut)
    assert len(spans) == 2  # one in the rise, one in the return (convex humps near the top)
    for first, last in spans:
        assert 0 < np.degrees(first) < 360 and np.degrees(first) <= np.degrees(last)


@pytest.mark.parametrize("offset", [0.0, 0.006])
def test_smallest_base_circle(offset):
    s, ds, _ = cycle(THETA, LIFT)
    limit = np.radians(30.0)
    r_p = geometry.smallest_pitch_radius(s, ds, limit, offset)
    if offset == 0.0:  # the closed form: r_p ≥ max(|s′|/tan α_max − s)
        assert r_p == pytest.approx(np.max(np.abs(ds) / np.tan(limit) - s), rel=1e-12)
    dds = np.zeros_like(s)
    at = geometry.translating_roller(THETA, s, ds, dds, base_radius=r_p - 0.01,
                                     roller_radius=0.01, offset=offset)
    assert np.max(np.abs(at.pressure_angle)) == pytest.approx(limit, abs=1e-12)
    below = geometry.translating_roller(THETA, s, ds, dds, base_radius=r_p * 0.99 - 0.01,
                                        roller_radius=0.01, offset=offset)
    assert np.max(np.abs(below.pressure_angle)) > limit


A, L = 0.1, 0.08  # [m] pivot distance, arm length


@pytest.mark.parametrize("clockwise", [False, True])
def test_oscillating_pressure_angle_by_the_instant_centre(clockwise):
    swing = np.radians(20.0)
    s, ds, dds = cycle(THETA, swing)
    cam = geometry.oscillating_roller(THETA, s, ds, dds, base_radius=0.04, roller_radius=0.01,
                                      pivot_distance=A, arm_length=L, clockwise=clockwise)
    psi = np.arccos((A ** 2 + L ** 2 - 0.05 ** 2) / (2 * A * L)) + s
    # Rothbart ch. 6: the common normal passes through the instant centre of cam and arm on
    # the line of centres OA, at a·s′/(1 + s′) from O
    expected = (L * (1 + ds) - A * np.cos(psi)) / (A * np.sin(psi))
    assert np.max(np.abs(np.tan(cam.pressure_angle) - expected)) < 1e-10
    # the roller centre stays l from the pivot and swings by s
    pivot = np.array([-A if clockwise else A, 0.0])
    assert np.allclose(np.hypot(*(cam.centre - pivot).T), L, rtol=0, atol=1e-15)


def test_oscillating_pitch_curvature_is_the_polar_form():
    s, ds, dds = cycle(THETA, np.radians(15.0))
    cam = geometry.oscillating_roller(THETA, s, ds, dds, base_radius=0.04, roller_radius=0.01,
                                      pivot_distance=A, arm_length=L)
    psi = np.arccos((A ** 2 + L ** 2 - 0.05 ** 2) / (2 * A * L)) + s
    x, y = A - L * np.cos(psi), L * np.sin(psi)
    dx, dy = L * np.sin(psi) * ds, L * np.cos(psi) * ds
    ddx = L * (np.cos(psi) * ds ** 2 + np.sin(psi) * dds)
    ddy = L * (-np.sin(psi) * ds ** 2 + np.cos(psi) * dds)
    rho = polar_radius_of_curvature(THETA, x, y, dx, dy, ddx, ddy)
    assert np.max(np.abs(cam.pitch_curvature_radius / rho - 1.0)) < 1e-9
    assert np.array_equal(cam.undercut, (rho > 0) & (rho < 0.01))


def test_flat_face_curvature_and_smallest_base_circle():
    s, ds, dds = cycle(THETA, LIFT)
    r_b = geometry.smallest_flat_base_radius(s, dds, 0.005)
    assert r_b == pytest.approx(np.max(0.005 - s - dds), rel=1e-12)
    cam = geometry.translating_flat(THETA, s, ds, dds, base_radius=r_b)
    assert np.min(cam.working_curvature_radius) == pytest.approx(0.005, rel=1e-12)
    assert not cam.undercut.any() and np.all(cam.pressure_angle == 0.0)
    # the envelope of the face: the working curve's polar curvature from its fixed-frame
    # contact point (s′, r_b + s), whose θ-derivative is (s″, s′ + ...) by hand
    ddds = np.gradient(dds, THETA)  # only for the polar form's second derivative
    rho = polar_radius_of_curvature(THETA, ds, r_b + s, dds, ds, ddds, dds)
    inner = slice(5, -5)
    assert np.allclose(cam.working_curvature_radius[inner], rho[inner], rtol=2e-3)
    smaller = geometry.translating_flat(THETA, s, ds, dds, base_radius=r_b - 0.01)
    assert smaller.undercut.any()


def _rothbart_max_alpha(pitch_radii, s, ds):
    """max |α| over the cycle of an oscillating follower at each pitch radius, from the
    instant centre's closed form tan α = (l·(1 + s′) − a·cos ψ)/(a·sin ψ), written
    here (a swing past the line of centres, sin ψ ≤ 0, counts as 90°)."""
    r = np.asarray(pitch_radii)[:, None]
    psi = np.arccos((A ** 2 + L ** 2 - r ** 2) / (2 * A * L)) + s
    alpha = np.abs(np.arctan((L * (1 + ds) - A * np.cos(psi)) / (A * np.sin(psi))))
    return np.max(np.where(np.sin(psi) > 0, alpha, np.pi / 2), axis=1)


@pytest.mark.parametrize("limit_deg", [30.0, 40.0])
def test_smallest_base_circle_of_an_oscillating_follower(limit_deg):
    theta = THETA[::4]  # every degree
    s, ds, dds = cycle(theta, np.radians(20.0))
    limit, roller = np.radians(limit_deg), 0.01
    r_b = geometry.smallest_oscillating_base_radius(s, ds, limit, roller_radius=roller,
                                                    pivot_distance=A, arm_length=L)
    r_p = r_b + roller
    assert A - L < r_p < A + L
    # at the root the largest |α| of the cam (the engine's own geometry) is the limit
    at = geometry.oscillating_roller(theta, s, ds, dds, base_radius=r_b, roller_radius=roller,
                                     pivot_distance=A, arm_length=L)
    assert np.max(np.abs(at.pressure_angle)) == pytest.approx(limit, abs=1e-9)
    # an independent dense grid of pitch radii below it, with the closed form: every one
    # breaks the limit, down to 1e-6 relative below the root; just above, it holds
    grid = np.linspace(A - L + 1e-9, r_p * (1 - 1e-6), 2001)
    assert np.all(_rothbart_max_alpha(grid, s, ds) > limit)
    assert _rothbart_max_alpha([r_p * (1 + 1e-6)], s, ds)[0] <= limit
    # the clockwise cam is the mirror image: the same circle
    mirror = geometry.oscillating_roller(theta, s, ds, dds, base_radius=r_b,
                                         roller_radius=roller, pivot_distance=A, arm_length=L,
                                         clockwise=True)
    assert np.max(np.abs(mirror.pressure_angle)) == pytest.approx(limit, abs=1e-9)


def test_no_base_circle_the_arm_reaches_meets_a_tight_limit():
    s, ds, _ = cycle(THETA[::4], np.radians(20.0))
    assert geometry.smallest_oscillating_base_radius(
        s, ds, np.radians(2.0), roller_radius=0.01, pivot_distance=A, arm_length=L) is None
