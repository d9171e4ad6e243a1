"""The servo-driven linkage (dyade.linkage.servo): a profile on the slider inverted
through the slider-crank, the inverse dynamics integrated forward through the machine's
equation of motion, the power balance of motor, gear, loads and kinetic energy."""

from __future__ import annotations

import math

import numpy as np
import pytest

import dyade
from dyade.errors import DyadeError
from dyade.linkage import servo
from dyade.machine import servo as engine
from dyade.model.servo import Gear
from tests.conftest import MECHANISMS


def cycloid(period: float, rise: float, samples: int) -> servo.Target:
    """Our own cycloid (not the laws module's): a rise h in T from rest to rest."""
    t = np.linspace(0.0, period, samples + 1)
    z, w = t / period, 2.0 * math.pi
    return servo.Target(t, rise * (z - np.sin(w * z) / w), rise / period * (1 - np.cos(w * z)),
                        w * rise / period ** 2 * np.sin(w * z),
                        w * w * rise / period ** 3 * np.cos(w * z))


@pytest.fixture(scope="module")
def slider_crank():
    return dyade.read_mechanism(MECHANISMS / "slider-crank.toml")


def test_profile_on_the_slider_is_reproduced_by_the_sweep_at_the_crank_motion(slider_crank):
    # the slider 50 mm to the left in 0.3 s from crank angle 30°, inverted; the sweep at
    # the crank's angle, speed and acceleration found gives back the slider's profile
    target = cycloid(0.3, -0.05, 360)
    motion = servo.crank_motion(slider_crank, "s_1_4", math.radians(30.0), target)
    columns = dyade.analyse(slider_crank, crank_angle_deg=np.degrees(motion.angle),
                            crank_speed=motion.speed,
                            crank_acceleration=motion.acceleration).columns()
    travel = columns["s_1_4"] - columns["s_1_4"][0]
    assert np.max(np.abs(travel - target.position)) < 1e-9                      # [m]
    assert np.max(np.abs(columns["v_1_4"] - target.velocity)) < 1e-9            # [m/s]
    assert np.max(np.abs(columns["a_1_4"] - target.acceleration)) < 1e-9 * 10   # [m/s²]
    # the crank turns backwards (the slider runs left as the crank angle grows)
    assert motion.angle[-1] > motion.angle[0]
    # the branch: the slider's dead centres (rod and crank in line) near 2.9° and 184.8°
    assert np.degrees(motion.branch) == pytest.approx([2.866, 184.78], abs=0.02)


def test_a_profile_beyond_the_dead_centre_is_refused_naming_the_angles(slider_crank):
    with pytest.raises(DyadeError, match=r"beyond a dead centre.*crank angles 2\.86.*° and "
                                         r"184\.7.*°"):
        servo.crank_motion(slider_crank, "s_1_4", math.radians(30.0), cycloid(0.3, -0.09, 72))
    with pytest.raises(DyadeError, match="at a dead centre at the start crank angle"):
        servo.crank_motion(slider_crank, "s_1_4", math.radians(184.78018822),
                           cycloid(0.3, 0.01, 72))


def forward_error(mechanism, target, step_deg):
    """The inverse dynamics' torque applied to the equation of motion in time and
    integrated forward from the profile's first state: the largest angle error [rad]."""
    motion = servo.inverse_dynamics(mechanism, servo.crank_motion(mechanism, "crank", 0.0,
                                                                  target))
    machine = servo.machine_function(mechanism, -0.05, 2 * math.pi + 0.05, math.radians(step_deg))
    followed = engine.follow(machine, motion.torque, motion.friction, motion.time,
                             motion.angle[0], motion.speed[0])
    return float(np.max(np.abs(followed.angle - motion.angle[0::2]))), motion


def test_fourbar_torque_integrated_forward_reproduces_the_profile():
    fourbar = dyade.read_mechanism(MECHANISMS / "fourbar.toml")
    error, motion = forward_error(fourbar, cycloid(0.2, 2 * math.pi, 1000), 0.05)
    assert error < 1e-6                                                  # [rad]
    assert np.max(np.abs(motion.torque)) > 1.0   # a real torque (not a zero echo)


@pytest.mark.slow
def test_dyade16_torque_integrated_forward_reproduces_the_profile():
    # loads (the knife's table), springs and gravity: M_L ≠ 0
    sixteen = dyade.read_mechanism(MECHANISMS / "dyade-16.toml")
    error, motion = forward_error(sixteen, cycloid(0.4, 2 * math.pi, 1600), 0.02)
    assert error < 1e-6
    assert np.max(np.abs(motion.load)) > 1.0


@pytest.mark.parametrize("name", ["fourbar.toml", "dyade-16.toml"])
def test_power_balance_of_motor_gear_loads_and_kinetic_energy(name):
    # at every instant: motor power = d/dt(½·J·φ̇² + ½·(J_M + J_G)·ω²) + gear loss
    # − M_L·φ̇ (the loads' power) + M_F·φ̇; the kinetic energy's rate from J and J′
    # (dyade.linkage.reduced), the motor's torque from the joint forces (kinetostatics)
    mechanism = dyade.read_mechanism(MECHANISMS / name)
    motion = servo.inverse_dynamics(mechanism, servo.crank_motion(
        mechanism, "crank", 0.0, cycloid(0.3, 2 * math.pi, 240)))
    gear, rotor = Gear(ratio=6.0, efficiency=0.92, inertia=2e-5), 1e-4
    load = engine.motor_load(motion.cycle(), gear, rotor, None)
    w, a = motion.speed, motion.acceleration
    power = load.torque[0] * load.speed[0]
    kinetic = (motion.inertia * a + 0.5 * motion.inertia_slope * w * w) * w \
        + (rotor + gear.inertia) * load.speed[0] * 6.0 * a
    balance = power - kinetic - load.gear_loss[0] + motion.load * w - motion.friction * w
    assert np.max(np.abs(balance)) <= 1e-9 * np.max(np.abs(power))
    # over the cycle (rest to rest): the motor's work is the gear's and the loads' only
    work = engine.trapezoid(power, motion.time)
    assert work == pytest.approx(engine.trapezoid(load.gear_loss[0] - motion.load * w,
                                                  motion.time), abs=1e-9 * np.max(np.abs(power)))


def test_profile_on_the_rocker_angle_is_reproduced():
    # a rocker swing of 20° by a cycloid from crank angle 30°: the sweep at the crank's
    # motion gives the rocker's angle, speed and acceleration back
    fourbar = dyade.read_mechanism(MECHANISMS / "fourbar.toml")
    target = cycloid(0.3, math.radians(20.0), 240)
    motion = servo.crank_motion(fourbar, "phi_4", math.radians(30.0), target)
    columns = dyade.analyse(fourbar, crank_angle_deg=np.degrees(motion.angle),
                            crank_speed=motion.speed,
                            crank_acceleration=motion.acceleration).columns()
    swing = np.radians(columns["phi_4_deg"] - columns["phi_4_deg"][0])
    assert np.max(np.abs(swing - target.position)) < 1e-12                     # [rad]
    assert np.max(np.abs(columns["alpha_4"] - target.acceleration)) < 1e-9 * np.max(
        np.abs(target.acceleration))
