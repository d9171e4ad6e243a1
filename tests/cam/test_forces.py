"""Contact force, lift-off speed and Hertz stress of a cam follower (issue 40)."""

from __future__ import annotations

import numpy as np
import pytest

from dyade.cam import forces, geometry
from tests.cam.cycloid import cycle

THETA = np.linspace(0.0, 2 * np.pi, 1441)[:-1]
M, K, S0, F = 0.8, 2000.0, 0.01, 15.0  # [kg], [N/m], [m], [N]


def _cam(offset=0.012, clockwise=False):
    s, ds, dds = cycle(THETA, 0.02)
    cam = geometry.translating_roller(THETA, s, ds, dds, base_radius=0.04, roller_radius=0.01,
                                      offset=offset, clockwise=clockwise)
    return cam, s, ds, dds


@pytest.mark.parametrize("clockwise", [False, True])
def test_contact_force_along_the_normal(clockwise):
    cam, s, ds, dds = _cam(clockwise=clockwise)
    omega = 30.0
    force = forces.contact_force(s, dds, cam.pressure_angle, omega, inertia=M, stiffness=K,
                                 preload=S0, load=F)
    e = -0.012 if clockwise else 0.012
    cos_alpha = (s + np.sqrt(0.05 ** 2 - e ** 2)) / np.hypot(ds - e, s + np.sqrt(0.05 ** 2 - e ** 2))
    expected = (M * dds * omega ** 2 + K * (s + S0) + F) / cos_alpha
    assert np.max(np.abs(force / expected - 1.0)) < 1e-9
    # the force vector's component along the follower balances it (no guide friction) ...
    along = force * np.einsum("ij,ij->i", cam.contact_normal, cam.direction)
    assert np.allclose(along, M * dds * omega ** 2 + K * (s + S0) + F, rtol=1e-12, atol=0)
    # ... and the cam's drive power equals the power into the follower (an independent path:
    # the moment of the force about O from the contact point and the normal)
    torque = forces.drive_torque(cam.contact, cam.contact_normal, force)
    sense = -1.0 if clockwise else 1.0
    power_in = sense * torque * omega
    power_out = (M * dds * omega ** 2 + K * (s + S0) + F) * ds * omega
    assert np.max(np.abs(power_in - power_out)) < 1e-9 * np.max(np.abs(power_out))


def test_lift_off_speed_closed_form():
    # no spring stiffness, a constant load F: lift-off where the return's deceleration
    # peaks, -s″ = 2π·h/β²: ω = √(F·β²/(m·2π·h))
    s, ds, dds = cycle(THETA, 0.02)
    beta = np.radians(120.0)
    lowest, highest, _, where = forces.contact_speeds(s, dds, inertia=M, stiffness=0.0,
                                                      preload=0.0, load=F)
    assert lowest == 0.0
    assert highest == pytest.approx(np.sqrt(F * beta ** 2 / (M * 2 * np.pi * 0.02)), rel=1e-6)
    # sampled at 0.25°: the peak of sin(2πz) is met to (1 - cos(δ)) ≈ 1e-5 relative; the
    # closed form at the sampled angle is exact
    assert highest == pytest.approx(np.sqrt(F / (M * -dds[where])), rel=1e-12)
    # with a spring: the contact force's least value is zero at the lift-off speed
    cam, s, ds, dds = _cam()
    _, highest, _, where = forces.contact_speeds(s, dds, inertia=M, stiffness=K, preload=S0,
                                                 load=F)
    force = forces.contact_force(s, dds, cam.pressure_angle, highest, inertia=M, stiffness=K,
                                 preload=S0, load=F)
    assert force.min() == pytest.approx(0.0, abs=1e-9 * force.max())
    assert int(np.argmin(force)) == where
    above = forces.contact_force(s, dds, cam.pressure_angle, highest * 1.001, inertia=M,
                                 stiffness=K, preload=S0, load=F)
    assert above.min() < 0.0


def test_a_spring_that_pulls_off_never_keeps_contact():
    s, ds, dds = cycle(THETA, 0.02)
    lowest, highest, _, _ = forces.contact_speeds(s, dds, inertia=M, stiffness=K,
                                                  preload=-0.05, load=0.0)
    assert highest == 0.0 or lowest > highest


def test_hertz_line_contact():
    # Johnson, Contact Mechanics §4.2: p0 = √(P·E*/(π·R)) per unit length; two steel
    # cylinders of 20 mm radius, 10 mm long, 1 kN: E* = 210e9/(2·(1 − 0.09)) Pa
    modulus = forces.effective_modulus(210e9, 0.3, 210e9, 0.3)
    assert modulus == pytest.approx(210e9 / (2 * 0.91), rel=1e-15)
    p0 = forces.hertz_line_stress(np.array([1000.0]), 0.02, 0.02, 0.01, modulus)[0]
    radius = 0.01  # 1/R = 1/0.02 + 1/0.02
    half_width = np.sqrt(4 * 1000.0 * radius / (np.pi * 0.01 * modulus))
    assert p0 == pytest.approx(2 * 1000.0 / (np.pi * half_width * 0.01), rel=1e-12)
    assert p0 == pytest.approx(606.04e6, rel=1e-4)  # by hand: √(1e5·1.1538e11/(π·0.01)) Pa
    # lifted off, or a roller in a sharper hollow: no Hertz stress
    assert np.isnan(forces.hertz_line_stress(np.array([-1.0, 1.0]), [0.02, 0.02],
                                             [0.02, -0.01], 0.01, modulus)).all()
