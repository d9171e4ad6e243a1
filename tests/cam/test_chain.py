"""A cam–linkage chain (issue 40): the cam's oscillating follower is the crank of a dyad
chain; the cam's drive torque closes the power balance of the whole chain and equals
the one of an independent global solve."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import dyade
from dyade.cam import chain, checks
from dyade.errors import InputError
from dyade.model.cam import Cam
from dyade.model.profile import Profile, Segment
from tests.global_solve import global_forces
from tests.linkage.test_kinetostatics import applied_power, kinetic_energy_rate

R = math.radians
PROFILE = Profile((Segment("rise", 0.0, R(100), 0.0, R(20), law="modified-sine"),
                   Segment("dwell", R(100), R(160), R(20), R(20)),
                   Segment("return", R(160), R(280), R(20), 0.0, law="polynomial-4567"),
                   Segment("dwell", R(280), R(360), 0.0, 0.0)), period=2 * math.pi, unit="deg")


@pytest.fixture(scope="module", params=[False, True], ids=["ccw", "cw"])
def solved(request):
    mechanism = dyade.read_mechanism("mechanisms/cams/lever-slider.toml")
    clockwise = request.param
    # the cam centre 90 mm from the lever's pivot A0 = (90, 0): left of it for a
    # counter-clockwise cam; for a clockwise one (the mirror image: the arm on the other
    # side of the line A0→O) up and left at 125°, so that the lever points the same way
    beta = R(125.0)
    centre = (0.0, 0.0) if not clockwise else (0.09 + 0.09 * math.cos(beta), 0.09 * math.sin(beta))
    cam = Cam("oscillating-roller", 0.035, PROFILE, speed=R(200 * 6), roller_radius=0.008,
              pivot_distance=0.09, arm_length=0.07, clockwise=clockwise, mass=2e-4,
              stiffness=3.0, preload=R(30), load=0.5, chain=mechanism, chain_centre=centre)
    theta = np.radians(np.arange(0.0, 360.0, 15.0))
    geo, (s, v, a, _) = checks.curves(cam, theta)
    return cam, mechanism, chain.solve(cam, mechanism, geo, s, v, a, cam.speed), s, v


def test_power_balance_of_the_chain(solved):
    cam, mechanism, result, s, v = solved
    kin = result.kinematics
    assert kin.valid.all()
    omega = cam.speed
    # the chain takes dE/dt − P(gravity, loads, springs) (from the kinematics alone), the
    # follower's extra inertia J·φ̈·φ̇ and its torsion spring and load k·(s + s0) + F
    # against the swing ψ̇ = s′·ω
    taken = (kinetic_energy_rate(mechanism, kin.motion)
             - applied_power(mechanism, kin.motion, kin.crank_angle)
             + cam.mass * result.lever_acceleration * result.lever_speed
             + (cam.stiffness * (s + cam.preload) + cam.load) * v * omega)
    given = result.drive_torque * omega
    assert np.max(np.abs(given - taken)) < 1e-9 * np.max(np.abs(taken))


def test_equals_an_independent_global_solve(solved):
    cam, mechanism, result, s, v = solved
    reference = global_forces(mechanism, result.kinematics, crank_speed=result.lever_speed,
                              crank_acceleration=result.lever_acceleration)["drive"]
    # the lever's torque from the global solve of the bare chain: its own inertia J·φ̈
    # and the torsion spring join it
    sense = 1.0 if cam.clockwise else -1.0
    needed = (reference + cam.mass * result.lever_acceleration
              + (cam.stiffness * (s + cam.preload) + cam.load) * sense)
    assert np.allclose(result.lever_torque, needed, rtol=0, atol=1e-9 * np.max(np.abs(needed)))
    # power: M_cam·ω = (lever torque)·φ̇, an independent path through the contact geometry
    assert np.allclose(result.drive_torque * cam.speed, needed * result.lever_speed, rtol=0,
                       atol=1e-9 * np.max(np.abs(needed * result.lever_speed)))


def test_a_misplaced_chain_is_refused(solved):
    cam, mechanism, *_ = solved
    with pytest.raises(InputError, match="chain_centre puts the cam centre 0.08 m from the "
                                         "chain's crank pivot"):
        dataclasses.replace(cam, chain_centre=(0.01, 0.0))
    with pytest.raises(InputError, match="arm_length = 0.07 m differs from the chain's crank"):
        dataclasses.replace(cam, chain=dataclasses.replace(
            mechanism, crank=dataclasses.replace(mechanism.crank, length=0.08)))
