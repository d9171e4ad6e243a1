"""What the friction solution returns (``FrictionResult``), and which joints never move."""

from __future__ import annotations

from dataclasses import dataclass

from dyade.arrays import FloatArray
from dyade.linkage import kinetostatics
from dyade.linkage.friction.scales import Coupling


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class FrictionResult:
    """Reactions with friction, the friction loads, and where the friction equilibrium
    has no solution (self-locking) or none was found."""

    forces: kinetostatics.Forces
    moments: dict[tuple[int, int], FloatArray]
    """revolute joint with μ > 0 -> (n,) friction moment on the higher-numbered link [N·m]"""
    friction_forces: dict[tuple[int, int], FloatArray]
    """prismatic joint with μ > 0 -> (n,) friction force on the higher-numbered link,
    along the guide direction [N]"""
    power: FloatArray
    """(n,) power lost in all joints [W] (≥ 0)"""
    iterations: FloatArray
    """(n,) largest number of passes (direct) or steps (fixed point) any group needed"""
    residual: FloatArray
    """(n,) largest final relative change a fixed-point step would make [-]"""
    converged: FloatArray
    """(n,) bool: every group with friction found its consistent solution"""
    at_rest: dict[tuple[int, int], FloatArray]
    """joint -> (n,) bool: relative velocity zero, friction direction undefined"""
    never_moves: list[tuple[int, int]]
    """joints with friction whose relative velocity is zero over the whole sweep"""
    determinant: dict[int, FloatArray]
    """dyad number -> (n,) determinant of the friction-augmented equilibrium's Jacobian
    at the solution relative to the frictionless one, det(I + K) [-]: 1 without
    friction, ≤ 0 self-locking; NaN where not solved (direct solution only)"""
    locks: dict[tuple[int, int], FloatArray]
    """joint -> (n,) bool: its dyad self-locks there and this joint's friction is the
    cause (direct solution only)"""
    locked: FloatArray
    """(n,) bool: some dyad self-locks (the first one met in the backward pass)"""
    unsolved: FloatArray
    """(n,) bool: no consistent friction solution found, and no self-locking either"""
    near: dict[int, FloatArray]
    """dyad number -> (n,) bool: solved, but the determinant is below the band
    sin(dead_centre): near self-locking, the friction loads amplified over 1/det"""
    coupling: Coupling
    """what the solution took from the whole sweep (the crank speed, the force floors)"""

    @property
    def blocked(self) -> FloatArray:
        """(n,) bool: forces not given because of friction (locked, unsolved or near)."""
        return blocked(self.locked, self.unsolved, self.near)


def blocked(locked: FloatArray, unsolved: FloatArray, near: dict[int, FloatArray]
            ) -> FloatArray:
    """(n,) bool: where friction keeps the forces from being given: some dyad self-locks
    (``locked``), no solution was found (``unsolved``), or a dyad is near self-locking
    (``near``: dyad number -> (n,) bool)."""
    out = locked | unsolved
    for mask in near.values():
        out = out | mask
    return out


def never_moves(at_rest: dict[tuple[int, int], FloatArray], usable: FloatArray
                ) -> list[tuple[int, int]]:
    """The joints at rest (``at_rest``: joint -> (n,) bool) at every usable position of a
    sweep (``usable``: (n,) bool, the kinematics valid), if there is one."""
    if not usable.any():
        return []
    return [name for name, mask in at_rest.items() if mask[usable].all()]
