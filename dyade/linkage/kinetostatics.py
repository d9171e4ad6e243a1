"""Backward kinetostatics (d'Alembert), dyad by dyad (Thümmel & Bartke 1987, sections 2-3).

Dyads are solved in reverse assembly order, k = last … 2, then the crank. Loads are
wrenches about the world origin (``dyade.linkage.motion``): on every link the known loads Q
(inertia −m·a_S and −J_S·α, gravity, applied loads, springs; the SFX, SFY, SM of the
paper) plus the reactions of the later dyads. For a dyad g –A– i –B– j –C– h let W_A
act on i (from g), W_B on j (from i) and W_C on j (from h). Equilibrium of i and j,

    W_A = W_B − Q_i,   W_C = −Q_j − W_B,

and a frictionless joint carries nothing along its freedom, S·W = 0 (a friction law
sets S·W = τ instead, ``dyade.linkage.friction``), give three equations for W_B:

    S_A·W_B = S_A·Q_i + τ_A,   S_B·W_B = τ_B,   −S_C·W_B = S_C·Q_j + τ_C,

i.e. Mᵀ·W_B = rhs with the transposed loop matrix of the velocity analysis: the
kinematics' inverse serves again. −W_A and −W_C pass on to g and h. The crank: with
S₁₂ its unit twist, the drive torque is M_drive = −S₁₂·Q₂ − τ₁₂ and W₁₂ = −Q₂ − M_drive·e_z.

Sign rule (Thümmel & Bartke 1987, section 2): a joint's force is the one acting on the
element of the higher-numbered link; a prismatic joint carries a normal force FN along the guide's
left normal n (of the carrier's guide) and a moment M about the slider point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.components import (direction_xy, is_zero, minus, plus, pose, rotate_xy,
                                      times)
from dyade.linkage.motion import Motion, Screw
from dyade.linkage.kinematics import Kinematics, crank_screw
from dyade.model.mechanism import CRANK, FRAME, Mechanism, Revolute, toward_higher


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Forces:
    """Joint reactions and drive torque over the sweep (SI)."""

    wrenches: dict[tuple[int, int], tuple[int, FloatArray]]
    """joint name -> (link, (3, n) wrench about the world origin the joint exerts on
    that link: the whole transmitted load, friction included)"""
    revolute: dict[tuple[int, int], FloatArray]
    """revolute joint -> (n, 2) force (Fx, Fy) on the higher-numbered link's element [N]"""
    normal: dict[tuple[int, int], FloatArray]
    """prismatic joint -> (n,) normal force FN along the guide's left normal [N]"""
    moment: dict[tuple[int, int], FloatArray]
    """prismatic joint -> (n,) moment M about the slider point, on the higher link [N·m]"""
    drive_torque: FloatArray
    """(n,) M_drive: torque the drive applies to the crank, counter-clockwise positive [N·m]
    (a cam-driven mechanism: the cam shaft's torque, in the cam's sense of rotation)"""
    shaking: FloatArray
    """(n, 3) force (x, y) [N] and moment about the world origin [N·m] that the mechanism
    exerts on the frame (joints, frame-anchored springs and the drive's reaction)"""
    valid: FloatArray
    """(n,) bool: no dyad within the dead-centre band (forces meaningful)"""
    input_load: FloatArray | None = None
    """(n,) the load along link 2's unit twist S₁₂ that drives it, −S₁₂·Q₂ (friction
    included): a torque [N·m] on a turning input, a force [N] along the guide on a
    sliding one; equal to ``drive_torque`` for a crank; None where it is"""
    contact_force: FloatArray | None = None
    """(n,) a cam-driven mechanism's contact force N [N] between cam and follower along
    the common normal (negative: the follower would have to be pulled; a spring-closed
    follower lifts off); None without a cam"""

    def on(self, name: tuple[int, int], link: int) -> FloatArray:
        """(3, n) wrench about the world origin that joint ``name`` exerts on ``link``."""
        target, wrench = self.wrenches[name]
        return wrench if target == link else -wrench


def applied_loads(mechanism: Mechanism, kin: Kinematics) -> FloatArray:
    """Known loads on every link as wrenches about the world origin, shape (links, 3, n):
    d'Alembert inertia, gravity, applied forces and moments, springs."""
    motion = kin.motion
    n = kin.crank_angle.shape[0]
    q = np.empty((mechanism.max_link + 1, 3, n))  # every row written below: no zero fill
    gx, gy = mechanism.gravity                     # of the rows the inertia loads overwrite
    for number in range(mechanism.max_link + 1):
        link = mechanism.links.get(number)
        if number == FRAME or link is None or not link.has_mass:
            q[number] = 0.0
    for number, link in mechanism.links.items():
        if number == FRAME or not link.has_mass:
            continue
        rx, ry = rotate_xy(motion.cos[:, number], motion.sin[:, number], link.centre)
        omega, alpha = motion.omega[:, number], motion.alpha[:, number]
        # the centre's acceleration a_S, then f = m·(g − a_S) and its moment about O
        fx, fy, moment = q[number]
        if is_zero(rx) and is_zero(ry):  # the centre at the frame's origin
            fx[:] = motion.acceleration[:, number, 0]
            fy[:] = motion.acceleration[:, number, 1]
        else:
            squared = omega * omega
            np.subtract(motion.acceleration[:, number, 0], alpha * ry, out=fx)
            fx -= squared * rx
            np.add(motion.acceleration[:, number, 1], alpha * rx, out=fy)
            fy -= squared * ry
        for part, g in ((fx, gx), (fy, gy)):
            if g != 0.0:
                part -= g
            part *= -link.mass
        np.multiply(plus(motion.origin[:, number, 0], rx), fy, out=moment)
        moment -= plus(motion.origin[:, number, 1], ry) * fx
        if np.any(link.inertia):
            moment -= link.inertia * alpha
    add_loads_and_springs(q, mechanism, kin)
    return q


def add_loads_and_springs(q: FloatArray, mechanism: Mechanism, kin: Kinematics) -> None:
    """Add the applied loads and the springs' forces to the wrenches ``q`` (links, 3, n)."""
    motion = kin.motion
    for load in mechanism.loads:
        fx, fy, moment = load_values(load, kin.crank_angle)
        if load.local:
            c, s = motion.cos[:, load.link], motion.sin[:, load.link]
            fx, fy = c * fx - s * fy, s * fx + c * fy
        add_force(q[load.link], motion.point(load.link, load.point), np.stack((fx, fy), -1))
        q[load.link, 2] += moment
    for spring in mechanism.springs:
        for link, point, force in spring_forces(spring, motion):
            if link != FRAME:
                add_force(q[link], point, force)
    follower = kin.follower
    if follower is not None and np.any(follower.spring):
        # the follower's own spring and load k·(s + s0) + F, against its lift or swing
        if mechanism.crank.sliding:
            along = np.stack((motion.cos[:, CRANK], motion.sin[:, CRANK]), -1)
            add_force(q[CRANK], motion.origin[:, CRANK], -follower.spring[:, None] * along)
        else:
            q[CRANK, 2] -= follower.sense * follower.spring


def load_values(load, crank_angle: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A load's (Fx, Fy, M) over the sweep; tables are interpolated periodically."""
    if load.angles is None:
        ones = np.ones_like(crank_angle)
        return load.fx[0] * ones, load.fy[0] * ones, load.moment[0] * ones
    period = 2.0 * np.pi
    return tuple(np.interp(crank_angle, load.angles, values, period=period)
                 for values in (load.fx, load.fy, load.moment))


def spring_forces(spring, motion: Motion):
    """(link, world point, force on that link) for both ends of a linear spring."""
    (a, b), (u_a, u_b) = spring.links, spring.points
    p_a, p_b = motion.point(a, u_a), motion.point(b, u_b)
    d = p_b - p_a
    length = np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2)
    with np.errstate(invalid="ignore", divide="ignore"):  # coincident ends: no direction
        unit = d / length[:, None]
    tension = spring.stiffness * (length - spring.free_length)
    pull = np.nan_to_num(tension[:, None] * unit)
    return ((a, p_a, pull), (b, p_b, -pull))


def add_force(wrench: FloatArray, point: FloatArray, force: FloatArray) -> None:
    """Add a force (n, 2) acting at world points (n, 2) to a wrench (3, n)."""
    wrench[0] += force[:, 0]
    wrench[1] += force[:, 1]
    wrench[2] += point[:, 0] * force[:, 1] - point[:, 1] * force[:, 0]


def _power(unit: Screw, wrench: FloatArray) -> FloatArray:
    """Power pairing S·W of a unit twist (components, ``dyade.linkage.kinematics``) and a
    wrench (3, n): one of the wrench's rows itself (not a copy) where the twist is a unit
    vector."""
    x, y, w = unit
    out = None
    for part, load in ((x, wrench[0]), (y, wrench[1])):
        if type(part) is float:
            if part == 0.0:
                continue
            term = load if part == 1.0 else part * load
        else:
            term = part * load
        out = term if out is None else out + term
    if w != 0.0:
        term = wrench[2] if w == 1.0 else w * wrench[2]
        out = term if out is None else out + term
    return np.zeros_like(wrench[0]) if out is None else out


def solve(mechanism: Mechanism, kin: Kinematics) -> Forces:
    """Joint reactions and drive torque at every crank position."""
    return backward(mechanism, kin, applied_loads(mechanism, kin))


def backward(mechanism: Mechanism, kin: Kinematics, q: FloatArray, rub=None) -> Forces:
    """Backward pass (module docstring): dyads in reverse assembly order, then the crank.

    ``q`` (from ``applied_loads``) is used up: the reactions are added to it.
    ``rub`` (``dyade.linkage.friction``) turns the frictionless joint condition S·W = 0 into its
    friction law; it is called per group with the frictionless solution.
    """
    frame = np.zeros(q.shape[1:])
    wrenches: dict[tuple[int, int], tuple[int, FloatArray]] = {}
    for group in reversed(kin.groups):
        (i, j), (g, h) = group.links, group.known
        q_i, q_j = q[i], q[j]
        s_a, _, s_c = group.units
        w_b = group.reaction(_power(s_a, q_i), _power(s_c, q_j))
        if rub is not None:
            w_b = rub.group(group, w_b, q_i, q_j)
        w_a = w_b - q_i  # on i from g
        on_h = q_j + w_b  # −W_C: on h from j
        joint_a, joint_b, joint_c = group.joints
        wrenches[joint_a.name] = (i, w_a)
        wrenches[joint_b.name] = (j, w_b)
        wrenches[joint_c.name] = (h, on_h)
        (frame if g == FRAME else q[g])[...] -= w_a
        (frame if h == FRAME else q[h])[...] += on_h
    joint = mechanism.crank.joint
    screw = crank_screw(mechanism)
    drive = -_power(screw, q[CRANK])
    if rub is not None:
        drive = drive - rub.crank(q[CRANK])
    w_12 = -q[CRANK]
    if kin.follower is not None:  # the cam drives link 2 through the contact force
        return _cam_driven(mechanism, kin, wrenches, drive, w_12, frame, screw, rub)
    if mechanism.crank.sliding:  # a force along the guide, through link 2's origin
        dx, dy, _ = screw
        ox, oy = kin.motion.origin[:, CRANK, 0], kin.motion.origin[:, CRANK, 1]
        w_12[0] -= drive * dx
        w_12[1] -= drive * dy
        w_12[2] -= drive * (ox * dy - oy * dx)
    else:
        w_12[2] -= drive
    wrenches[joint.name] = (CRANK, w_12)
    frame -= w_12
    forces = assemble_forces(mechanism, kin, wrenches, drive, frame,
                             None if rub is None else rub.surface)
    if mechanism.crank.sliding:
        forces.input_load = drive
    return forces


def _cam_driven(mechanism: Mechanism, kin: Kinematics, wrenches: dict, drive: FloatArray,
                w_12: FloatArray, frame: FloatArray, screw, rub) -> Forces:
    """The end of the backward pass of a cam-driven mechanism: the cam's contact force N
    along the normal n at K (``dyade.cam.follower``) supplies the drive −S₁₂·Q₂ of link
    2, N·S₁₂·(n, K × n) = drive, and joint (1,2) takes the rest of −Q₂ (a guide's side
    thrust, a lever pivot's force). The cam shaft's torque is drive·q′ (its power
    M·θ̇ = drive·q̇); the cam's reaction −N·n at K goes to the frame through the cam
    shaft's bearing, and the follower's spring rests on the frame (``shaking``)."""
    follower = kin.follower
    nx, ny = follower.normal[:, 0], follower.normal[:, 1]
    kx, ky = follower.contact[:, 0], follower.contact[:, 1]
    arm = kx * ny - ky * nx
    pairing = plus(plus(times(screw[0], nx), times(screw[1], ny)), times(screw[2], arm))
    with np.errstate(divide="ignore", invalid="ignore"):  # the normal across the freedom
        force = drive / pairing
    w_12[0] -= force * nx
    w_12[1] -= force * ny
    w_12[2] -= force * arm
    joint = mechanism.crank.joint
    wrenches[joint.name] = (CRANK, w_12)
    frame -= w_12
    # the cam pushes link 2 with N·n at K; the cam itself (massless, its shaft in a
    # bearing of the frame, its motor's stator on the frame) passes −N·n at K on to the
    # frame: the motor's torque and its stator's reaction cancel in the shaking load
    torque = drive * follower.dq
    flywheel = mechanism.drive.flywheel_inertia if mechanism.drive is not None else 0.0
    if flywheel and np.any(follower.acceleration):  # the flywheel turns with the cam shaft
        spin = flywheel * follower.acceleration
        torque = torque + spin
        frame[2] -= spin * (-1.0 if mechanism.cam.cam.clockwise else 1.0)
    frame[0] -= force * nx
    frame[1] -= force * ny
    frame[2] -= force * arm
    if np.any(follower.spring):  # the follower's spring rests on the frame
        if mechanism.crank.sliding:
            along = np.stack((kin.motion.cos[:, CRANK], kin.motion.sin[:, CRANK]), -1)
            add_force(frame, kin.motion.origin[:, CRANK], follower.spring[:, None] * along)
        else:
            frame[2] += follower.sense * follower.spring
    forces = assemble_forces(mechanism, kin, wrenches, torque, frame,
                             None if rub is None else rub.surface, reaction=False)
    forces.input_load = drive
    forces.contact_force = force
    forces.valid &= np.isfinite(force)
    if mechanism.cam.cam.closure == "spring":  # it cannot pull: the follower lifts off
        forces.valid &= ~(force < 0.0)
    return forces


def assemble_forces(mechanism: Mechanism, kin: Kinematics, wrenches: dict,
                    drive: FloatArray, frame: FloatArray, surface: dict | None = None,
                    reaction: bool = True) -> Forces:
    """Physical joint forces (the paper's sign rule) from the joint wrenches; the shaking
    load gets the frame-anchored springs and the drive's reaction. ``surface``: slider
    -> the part of its friction force (on the slider, along the guide) that acts at the
    guide surface (``dyade.linkage.friction``); without it, the whole along-guide force."""
    motion = kin.motion
    for spring in mechanism.springs:
        for link, point, force in spring_forces(spring, motion):
            if link == FRAME:
                add_force(frame, point, force)
    if reaction:
        frame[2] -= drive  # the stator takes the reaction of the drive torque
    band = np.sin(mechanism.dead_centre_angle)
    valid = kin.valid.copy()
    for column in kin.conditioning.T:  # (an axis-1 reduction is slow on a few columns)
        valid &= column > band
    forces = Forces(wrenches, {}, {}, {}, drive, frame.T, valid)
    for joint in mechanism.joints:
        target, wrench = wrenches[joint.name]
        if isinstance(joint, Revolute):
            force = wrench[:2] if target == max(joint.links) else -wrench[:2]
            forces.revolute[joint.name] = force.T
            continue
        # on the slider; frictionless, the sign of the wrench goes into the result's sign
        flip = target != joint.slider and joint.friction == 0.0
        slider = -wrench if target != joint.slider and not flip else wrench  # (3, n)
        dx, dy = direction_xy(joint, *pose(motion, joint.carrier)[:2])
        c, s, ox, oy = pose(motion, joint.slider)
        rx, ry = rotate_xy(c, s, joint.slider_point)
        sx, sy = plus(ox, rx), plus(oy, ry)
        normal = minus(times(dx, slider[1]), times(dy, slider[0]))
        moment = slider[2] - (sx * slider[1] - sy * slider[0])
        if joint.friction > 0.0:  # friction acting H/2 off, at the guide surface
            if surface is not None and joint.name in surface:
                along = surface[joint.name]
            else:
                along = dx * slider[0] + dy * slider[1]
            moment = moment - np.sign(normal) * 0.5 * joint.slider_height * along
        sign = toward_higher(joint.name, joint.slider) * (-1.0 if flip else 1.0)
        forces.normal[joint.name] = sign * normal
        forces.moment[joint.name] = sign * moment
    return forces
