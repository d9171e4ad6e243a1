"""A cam in the chain (issue 40): a translating follower is link 2, a sliding input of
the linkage engine, driven along its guide by the cam over the cam angle. The cam
shaft's torque closes the power balance of the whole chain, and the engine's forces equal
an independent global solve (every joint equation of the chain and the cam's contact
force as one linear system per position, written here)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import dyade
from dyade.linkage import kinematics, kinetostatics
from dyade.model.mechanism import CRANK, Revolute
from tests.global_solve import _jacobian
from tests.linkage.test_kinetostatics import applied_power, kinetic_energy_rate

EXAMPLE = "mechanisms/cams/cam-rocker.toml"


def clockwise(mechanism):
    """The same file with the cam turning clockwise and an offset follower."""
    return dyade.read_mechanism(EXAMPLE, {"cam.rotation": "cw", "follower.offset": 6.0,
                                          "cam.direction": 80.0})


def flat():
    """The same chain on a flat-faced follower (its contact off link 2's origin)."""
    import tomllib

    with open(EXAMPLE, "rb") as handle:
        data = tomllib.load(handle)
    data["cam"]["follower"] = "translating-flat"
    del data["follower"]["roller_radius"]
    data["follower"]["offset"] = 4.0
    return dyade.build_mechanism(data, EXAMPLE)


@pytest.fixture(scope="module", params=["ccw", "cw-offset", "flat"])
def solved(request):
    mechanism = dyade.read_mechanism(EXAMPLE)
    if request.param == "cw-offset":
        mechanism = clockwise(mechanism)
    elif request.param == "flat":
        mechanism = flat()
    theta = np.radians(np.arange(0.0, 360.0, 7.5))
    kin = kinematics.sweep(mechanism, theta)
    return mechanism, kin, kinetostatics.solve(mechanism, kin)


def test_the_follower_slides_as_the_profile_says(solved):
    mechanism, kin, _ = solved
    assert mechanism.crank.sliding and kin.valid.all()
    follower, motion = kin.follower, kin.motion
    d = np.array([math.cos(mechanism.crank.guide), math.sin(mechanism.crank.guide)])
    travel = (motion.origin[:, CRANK] - mechanism.crank.pivot) @ d
    assert np.allclose(travel, follower.lift, rtol=0, atol=1e-15)
    omega = mechanism.crank.speed
    assert np.allclose(motion.velocity[:, CRANK] @ d, follower.dq * omega, rtol=0, atol=1e-14)
    # the roller rolls on the cam: the contact point lies a roller radius from link 2's
    # origin along the normal
    cam = mechanism.cam.cam
    gap = motion.origin[:, CRANK] - follower.contact
    if cam.follower == "translating-roller":
        assert np.allclose(gap, cam.roller_radius * follower.normal, rtol=0, atol=1e-15)
    else:  # the face normal to the motion touches the cam s′ across from the stem's line
        assert np.allclose(follower.normal, d, rtol=0, atol=1e-15)
        assert np.allclose(gap @ d, 0.0, rtol=0, atol=1e-15)
        across = gap[:, 0] * d[1] - gap[:, 1] * d[0]
        assert np.allclose(across, cam.offset - follower.dq, rtol=0, atol=1e-15)


def test_velocities_are_the_derivatives_of_the_positions(solved):
    mechanism, kin, _ = solved
    h = 1e-6  # [rad] of cam angle: central differences, error O(h²)
    ahead = kinematics.sweep(mechanism, kin.crank_angle + h).motion
    behind = kinematics.sweep(mechanism, kin.crank_angle - h).motion
    omega = mechanism.crank.speed
    for link in mechanism.moving_links:
        rate = (ahead.point(link, (0.01, 0.02)) - behind.point(link, (0.01, 0.02))) / (2 * h)
        velocity = kin.motion.point_velocity(link, (0.01, 0.02))
        assert np.allclose(rate * omega, velocity, rtol=0, atol=1e-7), link


def test_power_balance_of_the_chain(solved):
    mechanism, kin, forces = solved
    follower = kin.follower
    omega = mechanism.crank.speed
    taken = (kinetic_energy_rate(mechanism, kin.motion)
             - applied_power(mechanism, kin.motion, kin.crank_angle)
             + follower.spring * follower.dq * omega)  # the follower's own spring and load
    given = forces.drive_torque * omega
    assert np.max(np.abs(given - taken)) < 1e-9 * np.max(np.abs(taken))
    # the cam's torque from its contact force: M = ±N·(K − O) × n
    cam = mechanism.cam
    arm = follower.contact - np.asarray(cam.centre)
    moment = arm[:, 0] * follower.normal[:, 1] - arm[:, 1] * follower.normal[:, 0]
    sign = -1.0 if cam.cam.clockwise else 1.0
    assert np.allclose(forces.drive_torque, sign * forces.contact_force * moment, rtol=0,
                       atol=1e-12 * np.max(np.abs(forces.drive_torque)))


def global_solve(mechanism, kin):
    """Per position, λ of every joint and the contact force N from Jᵀ·λ + W·N = −Q: the
    joint equations of the whole chain (``tests.global_solve``'s residual without its
    drive row) and the cam's wrench W = (n, K × n) on link 2."""
    links = mechanism.moving_links
    index = {link: k for k, link in enumerate(links)}
    motion, follower = kin.motion, kin.follower
    g = np.asarray(mechanism.gravity)
    n = kin.crank_angle.shape[0]
    contact, joints = np.empty(n), {joint.name: np.empty((n, 2)) for joint in mechanism.joints}
    d = np.array([math.cos(mechanism.crank.guide), math.sin(mechanism.crank.guide)])
    for row in range(n):
        q = np.concatenate([np.r_[motion.origin[row, link], motion.angle[row, link]]
                            for link in links])
        jac = _jacobian(mechanism, q, index)[:-1]  # the drive row: the cam drives instead
        load = np.zeros(q.size)
        for link in links:
            data, k = mechanism.links[link], index[link]
            arm = motion.point(link, data.centre)[row] - motion.origin[row, link]
            acc = motion.point_acceleration(link, data.centre)[row]
            force = data.mass * (g - acc)
            load[3 * k:3 * k + 2] += force
            load[3 * k + 2] += arm[0] * force[1] - arm[1] * force[0]
            load[3 * k + 2] -= data.inertia * motion.alpha[row, link]
        load[0:2] -= follower.spring[row] * d  # on link 2 (k = 0), at its origin
        normal, at = follower.normal[row], follower.contact[row] - motion.origin[row, CRANK]
        cam = np.zeros(q.size)
        cam[0:3] = normal[0], normal[1], at[0] * normal[1] - at[1] * normal[0]
        solution = np.linalg.solve(np.column_stack((jac.T, cam)), -load)
        lam, contact[row] = solution[:-1], solution[-1]
        for r, joint in enumerate(mechanism.joints):
            pair = -lam[2 * r:2 * r + 2]  # (here the joint's load is +Jᵀ·λ: λ's sign flips)
            if isinstance(joint, Revolute):
                joints[joint.name][row] = pair if joint.links[1] > joint.links[0] else -pair
            else:
                sign = -1.0 if joint.slider > joint.carrier else 1.0
                joints[joint.name][row] = sign * pair[::-1]
    return contact, joints


def test_equals_an_independent_global_solve(solved):
    mechanism, kin, forces = solved
    contact, joints = global_solve(mechanism, kin)
    assert np.allclose(forces.contact_force, contact, rtol=0,
                       atol=1e-9 * np.max(np.abs(contact)))
    scale = np.max(np.abs(contact))
    for joint in mechanism.joints:
        if isinstance(joint, Revolute):
            mine = forces.revolute[joint.name]
        else:
            mine = np.stack((forces.normal[joint.name], forces.moment[joint.name]), axis=-1)
        assert np.allclose(mine, joints[joint.name], rtol=0, atol=1e-9 * scale), joint.name


def test_a_sliding_input_without_a_cam_is_driven_by_a_force_along_its_guide(solved):
    """The same chain with link 2 moved by hand along its guide (no cam): the drive is a
    force, its power F·ṡ that of the chain."""
    mechanism, kin, _ = solved
    bare = dataclasses.replace(mechanism, cam=None)
    follower = kin.follower
    omega = mechanism.crank.speed
    own = kinematics.sweep(bare, follower.q, follower.dq * omega, follower.ddq * omega ** 2)
    forces = kinetostatics.solve(bare, own)
    assert np.array_equal(own.motion.origin[:, 2:], kin.motion.origin[:, 2:])
    taken = (kinetic_energy_rate(bare, own.motion)
             - applied_power(bare, own.motion, own.crank_angle))
    given = forces.drive_torque * follower.dq * omega
    assert np.max(np.abs(given - taken)) < 1e-9 * np.max(np.abs(taken))
    assert np.array_equal(forces.input_load, forces.drive_torque)


def test_friction_in_the_chain_costs_the_cam_its_power():
    """μ on the chain's joints as usual: the cam shaft's power grows by the friction
    power at every position (P_drive(μ) − P_drive(0) = P_friction)."""
    joints = {"dyad.2.A.friction": 0.2, "dyad.2.A.pin_radius": 5, "dyad.2.C.friction": 0.2,
              "dyad.2.C.pin_radius": 5, "sweep.step": 10}
    rubbing = dyade.analyse(dyade.read_mechanism(EXAMPLE, joints)).columns()
    bare = dyade.analyse(dyade.read_mechanism(EXAMPLE, {"sweep.step": 10})).columns()
    assert np.nanmax(rubbing["P_friction"]) > 0.0
    assert np.allclose(rubbing["P_drive"] - bare["P_drive"], rubbing["P_friction"], rtol=0,
                       atol=1e-9 * np.nanmax(np.abs(rubbing["P_friction"])))


def test_the_chain_reduced_to_the_cam_shaft_gives_the_cam_torque():
    """The reduced-inertia path sees the cam: J(θ), J′(θ) and M_L(θ) about the cam shaft
    (the sweep at unit cam speed through the follower's q′, q″) give the cam's torque at
    constant speed, M = ½·J′·ω² − M_L, the follower's own spring in M_L."""
    cols = dyade.analyse(dyade.read_mechanism(EXAMPLE, {"sweep.step": 10})).columns()
    omega = dyade.read_mechanism(EXAMPLE).crank.speed
    machine = 0.5 * cols["dJ_red"] * omega ** 2 - cols["M_load"]
    assert np.allclose(cols["M_drive"], machine, rtol=0,
                       atol=1e-9 * np.max(np.abs(cols["M_drive"])))
    # in the dwells the chain stands still whatever the cam does: J = 0 there (only a
    # flywheel on the cam shaft would give the motor's equation of motion an inertia)
    dwell = (cols["angle_deg"] >= 120) & (cols["angle_deg"] <= 180)
    assert np.all(cols["J_red"][~dwell] >= 0.0) and np.all(cols["J_red"][dwell] == 0.0)


MOTOR = {"drive.motor": "asynchronous", "drive.rated_torque": 2.0,
         "drive.rated_speed_rpm": 115, "drive.synchronous_speed_rpm": 120,
         "drive.flywheel_inertia": 0.002, "drive.tol": 1e-12, "sweep.step": 10}


@pytest.mark.slow  # (1 s: the steady state of the equation of motion)
def test_the_machine_in_motion_turns_the_cam_at_its_real_speed():
    """A [drive] motor and flywheel on the cam shaft: the equation of motion over the cam
    angle (J(θ) of the chain plus J_F) gives the cam's real speed; the chain's
    kinetostatics at that speed needs the motor's torque at every position, and its
    power balance holds with the flywheel's J_F·θ̈·θ̇."""
    mechanism = dyade.read_mechanism(EXAMPLE, MOTOR)
    cols = dyade.analyse(mechanism).columns()
    speed = cols["omega_cam"]
    assert np.ptp(speed) > 0.02 * np.mean(speed)  # the cam slows on the rise
    assert np.max(np.abs(cols["M_drive"] - cols["M_motor"])) < 1e-9 * np.max(
        np.abs(cols["M_drive"]))
    theta = np.radians(cols["angle_deg"])
    # (any θ̈ will do for the balance: the kinematics and the energy rate share it)
    kin = kinematics.sweep(mechanism, theta, speed, np.gradient(speed, theta) * speed)
    forces = kinetostatics.solve(mechanism, kin)
    follower = kin.follower
    taken = (kinetic_energy_rate(mechanism, kin.motion)
             - applied_power(mechanism, kin.motion, kin.crank_angle)
             + follower.spring * follower.dq * speed
             + mechanism.drive.flywheel_inertia * follower.acceleration * speed)
    assert np.max(np.abs(forces.drive_torque * speed - taken)) < 1e-9 * np.max(np.abs(taken))


def test_the_shaking_load_is_the_chains_inertia_and_weight(solved):
    """The frame carries the cam's bearing (−N·n at K) and the follower's spring: with no
    load from outside, what the machine puts on the frame is Σ m·(g − a_S) and its
    moment Σ r_S × m·(g − a_S) − J_S·α about the origin."""
    mechanism, kin, forces = solved
    motion, g = kin.motion, np.asarray(mechanism.gravity)
    force, moment = np.zeros((kin.crank_angle.size, 2)), np.zeros(kin.crank_angle.size)
    for number in mechanism.moving_links:
        link = mechanism.links[number]
        at = motion.point(number, link.centre)
        pull = link.mass * (g - motion.point_acceleration(number, link.centre))
        force += pull
        moment += at[:, 0] * pull[:, 1] - at[:, 1] * pull[:, 0] - link.inertia * motion.alpha[:, number]
    scale = np.max(np.abs(forces.contact_force))
    assert np.allclose(forces.shaking[:, :2], force, rtol=0, atol=1e-9 * scale)
    assert np.allclose(forces.shaking[:, 2], moment, rtol=0, atol=1e-9 * scale * 0.1)
