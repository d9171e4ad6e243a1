"""Backward kinetostatics (d'Alembert), dyad by dyad (SPEC §1).

Dyads are solved in reverse assembly order, k = last … 2, then the crank. For each dyad
the six equilibrium equations of its links i and j read Jᵀ·λ = Q: J is the dyad's
constraint Jacobian (``dyade.joints``, the same matrix as in the velocity analysis), λ
the multipliers of its joints A, B, C, and Q the known loads on i and j reduced to each
link's frame origin (SFX, SFY, SM of the paper): inertia −m·a_S and −J_S·α, gravity,
applied loads, springs, and the reactions of the later dyads at the follow-up points.
The crank's three equations give joint (1,2) and the driving torque (multiplier of the
drive constraint φ2 − Ω·t = 0).

Sign rule (SPEC §1): a joint's force is the one acting on the element of the
higher-numbered link; a prismatic joint carries a normal force FN along the guide's
left normal n (of the carrier's guide) and a moment M about the slider point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.joints import Blocks, Motion, blocks, cross, rotate
from dyade.kinematics import Kinematics, apply, assemble, batched_inverse
from dyade.model import CRANK, FRAME, FloatArray, Joint, Mechanism, Revolute


@dataclass(slots=True)
class Forces:
    """Joint reactions and drive torque over the sweep (SI)."""

    multipliers: dict[tuple[int, int], FloatArray]
    """joint name -> (n, 2) Lagrange multipliers λ of its two constraint rows"""
    revolute: dict[tuple[int, int], FloatArray]
    """revolute joint -> (n, 2) force (Fx, Fy) on the higher-numbered link's element [N]"""
    normal: dict[tuple[int, int], FloatArray]
    """prismatic joint -> (n,) normal force FN along the guide's left normal [N]"""
    moment: dict[tuple[int, int], FloatArray]
    """prismatic joint -> (n,) moment M about the slider point, on the higher link [N·m]"""
    drive_torque: FloatArray
    """(n,) M_drive: torque the drive applies to the crank, counter-clockwise positive [N·m]"""
    shaking: FloatArray
    """(n, 3) force (x, y) [N] and moment about the world origin [N·m] that the mechanism
    exerts on the frame (joints, frame-anchored springs and the drive's reaction)"""
    valid: FloatArray
    """(n,) bool: no dyad within the dead-centre band (forces meaningful)"""


def applied_loads(mechanism: Mechanism, kin: Kinematics) -> FloatArray:
    """Generalized loads on every link frame origin, shape (n, links, 3):
    d'Alembert inertia, gravity, applied forces and moments, springs."""
    motion = kin.motion
    n = kin.crank_angle.shape[0]
    q = np.zeros((n, mechanism.max_link + 1, 3))
    gravity = np.asarray(mechanism.gravity)
    for number, link in mechanism.links.items():
        if number == FRAME or not link.has_mass:
            continue
        force = (-link.mass * motion.point_acceleration(number, link.centre)
                 + link.mass * gravity)
        add_force(q, motion, number, link.centre, force)
        q[:, number, 2] -= link.inertia * motion.alpha[:, number]
    for load in mechanism.loads:
        fx, fy, moment = load_values(load, kin.crank_angle)
        force = np.stack((fx, fy), axis=-1)
        if load.local:
            force = rotate(motion.angle[:, load.link], force)
        add_force(q, motion, load.link, load.point, force)
        q[:, load.link, 2] += moment
    for spring in mechanism.springs:
        for link, local, force in spring_forces(spring, motion):
            add_force(q, motion, link, local, force)
    return q


def load_values(load, crank_angle: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """A load's (Fx, Fy, M) over the sweep; tables are interpolated periodically."""
    if load.angles is None:
        ones = np.ones_like(crank_angle)
        return load.fx[0] * ones, load.fy[0] * ones, load.moment[0] * ones
    period = 2.0 * np.pi
    return tuple(np.interp(crank_angle, load.angles, values, period=period)
                 for values in (load.fx, load.fy, load.moment))


def spring_forces(spring, motion: Motion):
    """(link, local point, force on that link) for both ends of a linear spring."""
    (a, b), (u_a, u_b) = spring.links, spring.points
    d = motion.point(b, u_b) - motion.point(a, u_a)
    length = np.hypot(d[:, 0], d[:, 1])
    with np.errstate(invalid="ignore", divide="ignore"):  # coincident ends: no direction
        unit = d / length[:, None]
    tension = spring.stiffness * (length - spring.free_length)
    pull = np.nan_to_num(tension[:, None] * unit)
    return ((a, u_a, pull), (b, u_b, -pull))


def add_force(q: FloatArray, motion: Motion, link: int, local, force: FloatArray) -> None:
    """Add a force at a link-fixed point to the link's generalized load (about its origin)."""
    q[:, link, :2] += force
    q[:, link, 2] += cross(motion.rotated(link, local), force)


def solve(mechanism: Mechanism, kin: Kinematics, extra: FloatArray | None = None) -> Forces:
    """Joint reactions and drive torque at every crank position.

    ``extra`` (n, links, 3) adds generalized loads, e.g. friction from an iteration.
    """
    q = applied_loads(mechanism, kin)
    if extra is not None:
        q = q + extra
    return reactions(mechanism, kin, q)


def reactions(mechanism: Mechanism, kin: Kinematics, q: FloatArray) -> Forces:
    """Backward pass: dyads in reverse assembly order, then the crank."""
    motion = kin.motion
    n = kin.crank_angle.shape[0]
    usable = kin.valid
    q = q.copy()
    multipliers: dict[tuple[int, int], FloatArray] = {}
    frame_load = np.zeros((n, 3))
    for col in reversed(range(len(mechanism.dyads))):
        dyad = mechanism.dyads[col]
        _group(dyad.joints, dyad.links, kin.blocks[col], kin.inverses[col], q, multipliers,
               frame_load)
    drive = _crank(mechanism, motion, q, usable, multipliers, frame_load)
    return assemble_forces(mechanism, kin, multipliers, drive, frame_load)


def assemble_forces(mechanism: Mechanism, kin: Kinematics, multipliers: dict,
                    drive: FloatArray, frame_load: FloatArray) -> Forces:
    """Physical joint forces (sign rule of SPEC §1) from the multipliers; the shaking
    load gets the frame-anchored springs and the drive's reaction."""
    motion = kin.motion
    frame_load = frame_load.copy()
    for spring in mechanism.springs:
        for link, local, force in spring_forces(spring, motion):
            if link == FRAME:
                frame_load[:, :2] += force
                frame_load[:, 2] += cross(motion.point(FRAME, local), force)
    frame_load[:, 2] -= drive  # the stator takes the reaction of the drive torque
    revolute, normal, moment = {}, {}, {}
    for joint in mechanism.joints:
        lam = multipliers[joint.name]
        if isinstance(joint, Revolute):
            sign = 1.0 if joint.links[1] > joint.links[0] else -1.0
            revolute[joint.name] = sign * lam
        else:
            sign = -1.0 if joint.slider > joint.carrier else 1.0
            normal[joint.name] = sign * lam[:, 1]
            moment[joint.name] = sign * lam[:, 0]
    band = np.sin(mechanism.dead_centre_angle)
    valid = kin.valid & np.all(kin.conditioning > band, axis=1)
    return Forces(multipliers, revolute, normal, moment, drive, frame_load, valid)


def _group(joints: tuple[Joint, ...], own: tuple[int, ...], parts: list[Blocks],
           inverse: FloatArray, q: FloatArray, multipliers: dict, frame_load: FloatArray) -> None:
    """Solve one dyad's Jᵀλ = Q (λ = J⁻ᵀQ with the kinematics' inverse and blocks) and
    pass its reactions on to the links it hangs on."""
    rhs = np.concatenate([q[:, link] for link in own], axis=1)
    lam = apply(inverse, rhs, transpose=True)
    for row, (joint, part) in enumerate(zip(joints, parts)):
        lam_j = lam[:, 2 * row:2 * row + 2]
        multipliers[joint.name] = lam_j
        pass_on(part, own, lam_j, q, frame_load)


def pass_on(blocks: Blocks, own: tuple[int, ...], lam: FloatArray, q: FloatArray,
            frame_load: FloatArray) -> None:
    """Reaction −J_kᵀλ of a joint on the placed links it touches."""
    for link, block in blocks.items():
        if link in own:
            continue
        generalized = -np.einsum("nij,ni->nj", block, lam)
        if link == FRAME:
            # frame coordinates are world coordinates: the moment is about the origin
            frame_load += generalized
        else:
            q[:, link] += generalized


def crank_inverse(joint: Joint, motion: Motion, usable: FloatArray):
    """Inverse of the crank's 3×3 Jacobian: joint (1,2) and the drive constraint
    φ2 − Ω·t = 0 (whose multiplier is minus the drive torque)."""
    part = blocks(joint, motion)
    matrix = assemble([part], (CRANK,))
    full = np.zeros((matrix.shape[0], 3, 3))
    full[:, :2] = matrix
    full[:, 2, 2] = 1.0
    return batched_inverse(full, usable), part


def _crank(mechanism: Mechanism, motion: Motion, q: FloatArray, usable: FloatArray,
           multipliers: dict, frame_load: FloatArray) -> FloatArray:
    """Joint (1,2) and the drive torque from the crank's three equations."""
    joint = mechanism.crank.joint
    inverse, part = crank_inverse(joint, motion, usable)
    lam = apply(inverse, q[:, CRANK], transpose=True)
    multipliers[joint.name] = lam[:, :2]
    pass_on(part, (CRANK,), lam[:, :2], q, frame_load)
    return -lam[:, 2]

