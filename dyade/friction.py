"""Coulomb friction by iteration, dyad by dyad, over the whole sweep (SPEC §1).

For each group (dyads in reverse assembly order, then the crank): (1) solve without
friction, (2) friction from those reactions, (3) solve again with the friction loads,
(4) repeat, (5) stop per crank position once the relative change of the group's
multipliers is below ``tol``, or after ``max_iter`` steps. Converged groups pass their
reactions and friction loads on to the links they hang on.

* revolute joint (p, q): friction moment on q, RM = −μ·r_z·|F|·sign(ω_q − ω_p), and the
  opposite on p;
* prismatic joint: friction force FR = −μ·|FN|·sign(ṡ) along the guide on the slider,
  acting at the guide surface, H/2 from the slider point on the side that carries the
  normal force; the opposite on the guide.

Where a relative velocity is zero the friction direction is undefined: sign(0) = 0 is
used and the positions are returned in ``at_rest`` so that the caller reports them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade import kinetostatics
from dyade.joints import Motion, cross, perp, travel
from dyade.kinematics import Kinematics, apply
from dyade.model import CRANK, FRAME, FloatArray, Joint, Mechanism, Prismatic, Revolute

AT_REST_RTOL = 1e-9  # [-] relative velocity below this share of the typical one counts as zero
FORCE_FLOOR = 1e-12  # [-] share of the largest multiplier below which changes are not relative


@dataclass(slots=True)
class FrictionResult:
    """Reactions with friction, the friction loads and how the iteration went."""

    forces: kinetostatics.Forces
    moments: dict[tuple[int, int], FloatArray]
    """revolute joint with μ > 0 -> (n,) friction moment on the higher-numbered link [N·m]"""
    friction_forces: dict[tuple[int, int], FloatArray]
    """prismatic joint with μ > 0 -> (n,) friction force on the higher-numbered link,
    along the guide direction [N]"""
    power: FloatArray
    """(n,) power lost in all joints [W] (≥ 0)"""
    iterations: FloatArray
    """(n,) largest number of iterations any group needed at this position"""
    residual: FloatArray
    """(n,) largest final relative change of any group's multipliers [-]"""
    converged: FloatArray
    """(n,) bool"""
    at_rest: dict[tuple[int, int], FloatArray]
    """joint -> (n,) bool: relative velocity zero, friction direction undefined"""
    never_moves: list[tuple[int, int]]
    """joints with friction whose relative velocity is zero over the whole sweep"""


def has_friction(joint: Joint) -> bool:
    return joint.friction > 0.0


def _relative_velocity(joint: Joint, motion: Motion, typical: float) -> tuple[FloatArray, FloatArray]:
    """Relative angular (revolute) or sliding (prismatic) velocity, and its sign with
    zeros where it is below the round-off level of the typical velocity."""
    if isinstance(joint, Revolute):
        p, q = joint.links
        rel = motion.omega[:, q] - motion.omega[:, p]
    else:
        rel = travel(joint, motion)[1]
    sign = np.sign(rel)
    sign[np.abs(rel) <= AT_REST_RTOL * typical] = 0.0
    return rel, sign


class _JointFriction:
    """Friction loads of one joint from its multipliers."""

    def __init__(self, joint: Joint, motion: Motion, mechanism: Mechanism) -> None:
        self.joint = joint
        self.motion = motion
        omega = abs(mechanism.crank.speed)
        typical = omega if isinstance(joint, Revolute) else omega * mechanism.crank.length
        self.velocity, self.sign = _relative_velocity(joint, motion, typical)
        if isinstance(joint, Prismatic):
            self.direction = motion.direction(joint.carrier, joint.guide_angle)
            self.normal = perp(self.direction)
            self.slider_point = motion.point(joint.slider, joint.slider_point)

    def loads(self, lam: FloatArray) -> dict[int, FloatArray]:
        """link -> (n, 3) generalized friction load about that link's origin."""
        joint, mu = self.joint, self.joint.friction
        n = lam.shape[0]
        if isinstance(joint, Revolute):
            p, q = joint.links
            moment = -mu * joint.pin_radius * np.hypot(lam[:, 0], lam[:, 1]) * self.sign
            out_q = np.zeros((n, 3))
            out_q[:, 2] = moment
            return {q: out_q, p: -out_q}
        normal_on_slider = -lam[:, 1]
        contact = (self.slider_point - (np.sign(normal_on_slider) * joint.slider_height / 2.0)[:, None]
                   * self.normal)
        force = (-mu * np.abs(lam[:, 1]) * self.sign)[:, None] * self.direction
        out = {}
        for link, f in ((joint.slider, force), (joint.carrier, -force)):
            load = np.zeros((n, 3))
            load[:, :2] = f
            load[:, 2] = cross(contact - self.motion.origin[:, link], f)
            out[link] = load
        return out

    def power(self, lam: FloatArray) -> FloatArray:
        """Power lost in this joint [W]."""
        joint, mu = self.joint, self.joint.friction
        if isinstance(joint, Revolute):
            return mu * joint.pin_radius * np.hypot(lam[:, 0], lam[:, 1]) * np.abs(self.velocity * self.sign)
        return mu * np.abs(lam[:, 1]) * np.abs(self.velocity * self.sign)


def iterate(mechanism: Mechanism, kin: Kinematics, tol: float | None = None,
            max_iter: int | None = None) -> FrictionResult:
    """Reactions with Coulomb friction in every joint with μ > 0."""
    tol = mechanism.friction_tol if tol is None else tol
    max_iter = mechanism.friction_max_iter if max_iter is None else max_iter
    motion = kin.motion
    n = kin.crank_angle.shape[0]
    usable = kin.valid
    q = kinetostatics.applied_loads(mechanism, kin)
    frictions = {joint.name: _JointFriction(joint, motion, mechanism)
                 for joint in mechanism.joints if has_friction(joint)}
    multipliers: dict[tuple[int, int], FloatArray] = {}
    frame_load = np.zeros((n, 3))
    iterations = np.zeros(n)
    residual = np.zeros(n)
    converged = np.ones(n, dtype=bool)
    groups = [(d.joints, d.links, kin.inverses[col], kin.blocks[col])
              for col, d in reversed(list(enumerate(mechanism.dyads)))]
    crank_inverse, crank_blocks = kinetostatics.crank_inverse(mechanism.crank.joint, motion, usable)
    groups.append(((mechanism.crank.joint,), (CRANK,), crank_inverse, [crank_blocks]))
    drive = np.zeros(n)
    for joints, own, inverse, parts in groups:
        lam, its, change, done = _group(joints, own, inverse, q, usable, frictions, tol,
                                        max_iter)
        iterations = np.maximum(iterations, its)
        residual = np.maximum(residual, np.where(usable, change, 0.0))
        converged &= done | ~usable
        for row, joint in enumerate(joints):
            lam_j = lam[:, 2 * row:2 * row + 2]
            multipliers[joint.name] = lam_j
            kinetostatics.pass_on(parts[row], own, lam_j, q, frame_load)
            if joint.name in frictions:
                for link, load in frictions[joint.name].loads(lam_j).items():
                    if link not in own:
                        _add_load(link, load, motion, q, frame_load)
        if own == (CRANK,):
            drive = -lam[:, 2]
    forces = kinetostatics.assemble_forces(mechanism, kin, multipliers, drive, frame_load)
    moments, friction_forces = {}, {}
    power = np.zeros(n)
    for name, fr in frictions.items():
        lam_j = multipliers[name]
        power += fr.power(lam_j)
        loads = fr.loads(lam_j)
        higher = max(name)
        if isinstance(fr.joint, Revolute):
            moments[name] = loads[higher][:, 2]
        else:
            friction_forces[name] = np.sum(loads[higher][:, :2] * fr.direction, axis=1)
    at_rest = {name: usable & (fr.sign == 0.0) for name, fr in frictions.items()}
    never = [name for name, mask in at_rest.items() if mask[usable].all() and usable.any()]
    for name in never:
        at_rest[name] = np.zeros(n, dtype=bool)
    return FrictionResult(forces, moments, friction_forces, power, iterations, residual,
                          converged, at_rest, never)


def _group(joints: tuple[Joint, ...], own: tuple[int, ...], inverse: FloatArray, q: FloatArray,
           usable: FloatArray, frictions: dict, tol: float, max_iter: int):
    """Fixed-point iteration of one group's Jᵀλ = Q + friction(λ), per position; the
    Jacobian does not change while iterating, so its inverse serves every step."""
    base = np.concatenate([q[:, link] for link in own], axis=1)
    lam = apply(inverse, base, transpose=True)
    n = lam.shape[0]
    its = np.zeros(n)
    change = np.zeros(n)
    active_joints = [(row, frictions[j.name]) for row, j in enumerate(joints) if j.name in frictions]
    if not active_joints:
        return lam, its, change, np.ones(n, dtype=bool)
    active = usable.copy()
    for _ in range(max_iter):
        if not active.any():
            break
        rhs = base.copy()
        for row, fr in active_joints:
            for link, load in fr.loads(lam[:, 2 * row:2 * row + 2]).items():
                if link in own:
                    col = own.index(link)
                    rhs[:, 3 * col:3 * col + 3] += load
        new = apply(inverse, rhs, transpose=True)
        scale = np.max(np.abs(new), axis=1)
        floor = FORCE_FLOOR * max(float(np.nanmax(scale, initial=0.0)), 1e-300)
        step = np.max(np.abs(new - lam), axis=1) / np.maximum(scale, floor)
        lam = np.where(active[:, None], new, lam)
        change = np.where(active, step, change)
        its = its + active
        active = active & (step > tol)
    return lam, its, change, ~active


def _add_load(link: int, load: FloatArray, motion: Motion, q: FloatArray,
              frame_load: FloatArray) -> None:
    if link == FRAME:
        frame_load += load  # frame origin is the world origin
    else:
        q[:, link] += load


def joint_forces_on(link: int, mechanism: Mechanism, result: FrictionResult,
                    motion: Motion) -> dict[tuple[int, int], FloatArray]:
    """World force (n, 2) of every joint of ``link`` on that link (reactions + friction)."""
    out = {}
    for joint in mechanism.joints:
        if link not in joint.links:
            continue
        lam = result.forces.multipliers[joint.name]
        if isinstance(joint, Revolute):
            force = -lam if joint.links[0] == link else lam
        else:
            normal = perp(motion.direction(joint.carrier, joint.guide_angle))
            on_slider = -lam[:, 1:2] * normal
            force = on_slider if joint.slider == link else -on_slider
        out[joint.name] = force.copy()
    for name, value in result.friction_forces.items():
        if name in out:
            joint = next(j for j in mechanism.joints if j.name == name)
            d = motion.direction(joint.carrier, joint.guide_angle)
            on_higher = value[:, None] * d
            out[name] += on_higher if link == max(name) else -on_higher
    return out
