"""Kinematics over the whole crank sweep at once (SPEC §1).

The crank first, then the dyads in assembly order: each dyad's closure in closed form
(``dyade.dyads``), then its velocities and accelerations from one batched linear
solve of the joint constraints (``dyade.joints``), J·q̇ = −J_known·q̇_known and
J·q̈ = γ − J_known·q̈_known. Loops run over dyads, never over crank angles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade import dyads as dyad_kinds
from dyade.joints import Blocks, Motion, blocks, gamma
from dyade.model import CRANK, FRAME, FloatArray, Joint, Mechanism, Revolute


@dataclass(slots=True)
class Kinematics:
    """Result of the kinematic sweep."""

    crank_angle: FloatArray
    """(n,) crank angle φ21 [rad]"""
    motion: Motion
    """poses, velocities and accelerations of every link frame"""
    closes: FloatArray
    """(n, dyads) bool: dyad k closes at this position (column k−2)"""
    transmission: FloatArray
    """(n, dyads) transmission angle μ of each dyad [rad], NaN where it does not close"""
    singular: FloatArray
    """(n, dyads) bool: the dyad is exactly at a dead centre / blocked (velocities NaN)"""
    conditioning: FloatArray
    """(n, dyads) distance from singularity in [0, 1] (0: dead centre / blocked)"""
    inverses: list[FloatArray]
    """per dyad (n, 6, 6): inverse of its constraint Jacobian J (NaN where not usable);
    the force stage reuses it, since Jᵀ·λ = Q gives λ = (J⁻¹)ᵀ·Q"""
    blocks: list[list[Blocks]]
    """per dyad, per joint A, B, C: its Jacobian blocks (the force stage reuses them)"""

    @property
    def valid(self) -> FloatArray:
        """(n,) bool: every dyad closes and none is singular."""
        return self.closes.all(axis=1) & ~self.singular.any(axis=1)


def crank_motion(mechanism: Mechanism, crank_angle: FloatArray) -> Motion:
    """Motion with the frame at rest and the crank turning at constant speed."""
    n = crank_angle.shape[0]
    motion = Motion.at_rest(n, mechanism.max_link + 1)
    motion.origin[:, CRANK] = mechanism.crank.pivot
    motion.angle[:, CRANK] = crank_angle
    motion.velocity[:, CRANK] = 0.0
    motion.omega[:, CRANK] = mechanism.crank.speed
    motion.acceleration[:, CRANK] = 0.0
    motion.alpha[:, CRANK] = 0.0
    return motion


def generalized(vector: FloatArray, scalar: FloatArray) -> FloatArray:
    """Stack (x, y) and φ parts of a link's coordinates, shape (n, 3)."""
    return np.concatenate((vector, scalar[:, None]), axis=1)


def assemble(parts: list[Blocks], own: tuple[int, ...]) -> FloatArray:
    """Jacobian of a group's joints (their ``parts``) by the coordinates of the ``own``
    links, shape (n, 2·joints, 3·links)."""
    n = next(iter(parts[0].values())).shape[0]
    matrix = np.zeros((n, 2 * len(parts), 3 * len(own)))
    for row, part in enumerate(parts):
        for col, link in enumerate(own):
            if link in part:
                matrix[:, 2 * row:2 * row + 2, 3 * col:3 * col + 3] = part[link]
    return matrix


def batched_inverse(matrix: FloatArray, usable: FloatArray) -> FloatArray:
    """Inverse of every usable matrix of the stack; NaN elsewhere."""
    if usable.all():
        return np.linalg.inv(matrix)
    safe = matrix.copy()
    safe[~usable] = np.eye(matrix.shape[1])
    inverse = np.linalg.inv(safe)
    inverse[~usable] = np.nan
    return inverse


def apply(inverse: FloatArray, rhs: FloatArray, transpose: bool = False) -> FloatArray:
    """inverse·rhs (or inverseᵀ·rhs) for a stack, shapes (n, m, m) and (n, m)."""
    return np.einsum("nji,nj->ni" if transpose else "nij,nj->ni", inverse, rhs)


def sweep(mechanism: Mechanism, crank_angle: FloatArray | None = None) -> Kinematics:
    """Positions, velocities and accelerations of every link over the crank sweep."""
    if crank_angle is None:
        crank_angle = mechanism.sweep.angles()
    crank_angle = np.asarray(crank_angle, dtype=np.float64)
    n = crank_angle.shape[0]
    motion = crank_motion(mechanism, crank_angle)
    count = len(mechanism.dyads)
    closes = np.ones((n, count), dtype=bool)
    transmission = np.full((n, count), np.nan)
    singular = np.zeros((n, count), dtype=bool)
    conditioning = np.full((n, count), np.nan)
    inverses, all_blocks = [], []
    upstream_ok = np.ones(n, dtype=bool)
    for col, dyad in enumerate(mechanism.dyads):
        closure = dyad_kinds.DYAD_KINDS[dyad.kind].close(dyad, motion)
        ok = closure.closes & upstream_ok
        closes[:, col] = closure.closes
        transmission[:, col] = np.where(ok, closure.transmission, np.nan)
        conditioning[:, col] = np.where(ok, closure.conditioning, np.nan)
        singular[:, col] = ok & (closure.conditioning < dyad_kinds.SINGULAR_SIN)
        usable = ok & ~singular[:, col]
        parts = [blocks(joint, motion) for joint in dyad.joints]
        inverses.append(_derivatives(dyad.joints, dyad.links, parts, motion, usable))
        all_blocks.append(parts)
        for link in dyad.links:
            motion.origin[~ok, link] = np.nan
            motion.angle[~ok, link] = np.nan
        upstream_ok = usable
    return Kinematics(crank_angle, motion, closes, transmission, singular, conditioning,
                      inverses, all_blocks)


def _derivatives(joints: tuple[Joint, ...], own: tuple[int, ...], parts: list[Blocks],
                 motion: Motion, usable: FloatArray) -> FloatArray:
    """Velocities, then accelerations, of the ``own`` links of one group; returns the
    inverse of its Jacobian."""
    inverse = batched_inverse(assemble(parts, own), usable)
    for rates, derivative in (("velocity", "omega"), ("acceleration", "alpha")):
        rhs = np.zeros(inverse.shape[:2])
        for row, (joint, part) in enumerate(zip(joints, parts)):
            if rates == "acceleration":
                rhs[:, 2 * row:2 * row + 2] = gamma(joint, motion)
            for link, block in part.items():
                if link not in own:
                    known = generalized(getattr(motion, rates)[:, link],
                                        getattr(motion, derivative)[:, link])
                    rhs[:, 2 * row:2 * row + 2] -= np.einsum("nij,nj->ni", block, known)
        solved = apply(inverse, rhs)
        for col, link in enumerate(own):
            getattr(motion, rates)[:, link] = solved[:, 3 * col:3 * col + 2]
            getattr(motion, derivative)[:, link] = solved[:, 3 * col + 2]
    return inverse


# -- derived quantities the reports use --------------------------------------------
def joint_point(joint: Revolute, motion: Motion) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, velocity, acceleration of a revolute joint (on its first link)."""
    link, local = joint.links[0], joint.points[0]
    if link == FRAME:
        link, local = joint.links[1], joint.points[1]
    return (motion.point(link, local), motion.point_velocity(link, local),
            motion.point_acceleration(link, local))

