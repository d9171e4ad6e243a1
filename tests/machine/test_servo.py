"""The servo motor behind a gear (dyade.machine.servo): closed forms of a pure inertia
driven by a cycloid, the RMS-optimal ratio, the catalogue's checks."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dyade.machine import servo
from dyade.model.servo import Gear, ServoMotor


def cycloid_cycle(inertia: float, rise: float, period: float, samples: int = 720):
    """A pure inertia J raised through h in T by a cycloid (our own, not the laws
    module's): φ = h·(t/T − sin(2πt/T)/(2π)), φ̈ = 2π·h/T²·sin(2πt/T)."""
    t = np.linspace(0.0, period, samples + 1)
    z = t / period
    speed = rise / period * (1.0 - np.cos(2.0 * math.pi * z))
    accel = 2.0 * math.pi * rise / period ** 2 * np.sin(2.0 * math.pi * z)
    return servo.Cycle(t, speed, accel, inertia * accel, np.full(t.size, inertia))


def test_cycloid_peak_and_rms_of_a_pure_inertia():
    # the closed forms: peak J·h·2π/T², RMS over the rise J·h·π·√2/T²
    J, h, T = 0.03, 2.5, 0.4
    cycle = cycloid_cycle(J, h, T)
    figures = servo.sizing(cycle, servo.motor_load(cycle, Gear(), 0.0), Gear())
    assert figures.peak_torque[0] == pytest.approx(J * h * 2 * math.pi / T ** 2, rel=1e-9)
    assert figures.rms_torque[0] == pytest.approx(J * h * math.pi * math.sqrt(2) / T ** 2,
                                                  rel=1e-9)
    assert figures.peak_at[0] in (pytest.approx(T / 4), pytest.approx(3 * T / 4))
    # the energy fed back: the kinetic energy at top speed, given back while braking
    assert figures.regenerated[0] == pytest.approx(0.5 * J * (2 * h / T) ** 2, rel=1e-5)


def test_rms_optimal_ratio_of_an_inertia_load_is_the_inertia_match():
    # ideal gear: M = (J_M·i + J_L/i)·φ̈, smallest RMS at i = √(J_L/J_M)
    J_L, J_M = 0.08, 2.2e-4
    cycle = cycloid_cycle(J_L, 1.0, 0.5)
    ratio = servo.optimal_ratio(cycle, Gear(), J_M, (1.0, 100.0))
    assert ratio == pytest.approx(math.sqrt(J_L / J_M), rel=1e-6)
    load = servo.motor_load(cycle, Gear(ratio=ratio), J_M)
    assert servo.sizing(cycle, load, Gear()).inertia_ratio[0] == pytest.approx(1.0, rel=1e-6)


def test_gear_losses_and_power_balance():
    # motor power = rotor's kinetic energy rate + gear loss + crank power, at every instant
    cycle = cycloid_cycle(0.05, 1.0, 0.5)
    gear = Gear(ratio=7.0, efficiency=0.9, inertia=3e-5)
    load = servo.motor_load(cycle, gear, 1e-4)
    motor_power = load.torque[0] * load.speed[0]
    rotor = (1e-4 + 3e-5) * load.speed[0] * 7.0 * cycle.acceleration
    balance = motor_power - rotor - load.gear_loss[0] - cycle.torque * cycle.speed
    assert np.max(np.abs(balance)) <= 1e-12 * np.max(np.abs(motor_power))
    assert np.all(load.gear_loss[0] >= 0.0)
    # the loss is (1 − η) of the crank's power while driving, of the motor side's braking
    driving = cycle.torque * cycle.speed > 0
    assert load.gear_loss[0][driving] == pytest.approx(
        (1 / 0.9 - 1) * (cycle.torque * cycle.speed)[driving], rel=1e-12)


def motor(name, rated, peak, top_rpm, inertia, envelope=None):
    w = top_rpm * math.pi / 30
    speeds = torques = None
    if envelope is not None:
        speeds = np.array([p[0] for p in envelope]) * math.pi / 30
        torques = np.array([p[1] for p in envelope], dtype=float)
    return ServoMotor(name, rated, peak, 0.5 * w, w, inertia, speeds, torques)


def test_catalogue_picks_the_motor_a_hand_calculation_picks():
    # J_L = 0.02 kg·m², h = 1 rad in T = 0.2 s, i = 4, J_M = 1e-4: by hand
    # φ̈_max = 2π·h/T² = 157.08 rad/s², M = (J_M·i + J_L/i)·φ̈ -> peak 0.848 N·m,
    # RMS = peak/√2 = 0.600 N·m, top speed i·2h/T = 40 rad/s = 382 rpm,
    # λ = 0.02/16/1e-4 = 12.5
    cycle = cycloid_cycle(0.02, 1.0, 0.2)
    motors = [motor("tiny", 0.5, 2.0, 3000, 1e-4),        # RMS 0.600 > 0.5: fails
              motor("small", 0.7, 2.0, 3000, 1e-4),       # passes
              motor("big", 3.0, 9.0, 3000, 1e-4)]
    checks = servo.catalogue_checks(cycle, Gear(ratio=4.0), motors, np.array([4.0]), 20.0)
    assert checks[0].sizing.rms_torque[0] == pytest.approx(
        (1e-4 * 4 + 0.02 / 4) * 2 * math.pi / 0.04 / math.sqrt(2), rel=1e-9)
    chosen = servo.smallest_passing(checks)
    assert chosen.motor.name == "small"
    assert checks[0].failed(0) == ["thermal (RMS)"]
    assert checks[1].inertia[0] == pytest.approx(1 - 12.5 / 20.0)
    # an inertia ratio limit of 10 fails them all
    assert servo.smallest_passing(servo.catalogue_checks(
        cycle, Gear(ratio=4.0), motors, np.array([4.0]), 10.0)) is None


def test_a_peak_outside_the_envelope_at_its_speed_fails_the_motor():
    cycle = cycloid_cycle(0.02, 1.0, 0.2)   # peak 0.848 N·m near 20 rad/s·4 = 382 rpm… 
    ok = motor("flat", 0.7, 2.0, 3000, 1e-4, [(0, 2.0), (3000, 2.0)])
    # the envelope falls to 0.5 N·m by 300 rpm: the peak (at t = T/4, ω = i·h/T = 191 rpm)
    # lies above what it has there
    weak = motor("falling", 0.7, 2.0, 3000, 1e-4, [(0, 2.0), (100, 2.0), (300, 0.5),
                                                  (3000, 0.5)])
    checks = servo.catalogue_checks(cycle, Gear(ratio=4.0), [ok, weak], np.array([4.0]), 20.0)
    assert checks[0].passes[0] and not checks[1].passes[0]
    assert checks[1].failed(0) == ["peak within the envelope"]
