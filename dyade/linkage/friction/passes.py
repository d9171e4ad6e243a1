"""The pass machinery: the friction laws applied group by group inside the backward pass
of ``dyade.linkage.kinetostatics`` (``Rub``; a subclass solves a group: ``solver``), the
size of a change of the friction loads, and one run of the pass to a ``FrictionResult``.
"""

from __future__ import annotations

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage import kinetostatics
from dyade.linkage.friction.laws import AT_REST_RTOL, Law, has_friction
from dyade.linkage.friction.result import FrictionResult, blocked, never_moves
from dyade.linkage.friction.scales import Coupling, force_floor, sample, top_speed
from dyade.linkage.kinematics import Group, Kinematics
from dyade.model.mechanism import CRANK, Joint, Mechanism, Revolute, toward_higher


class Rub:
    """The friction laws, applied group by group inside the backward pass
    (``kinetostatics.backward``); subclasses solve a group."""

    def __init__(self, mechanism: Mechanism, kin: Kinematics, tol: float, max_iter: int,
                 speed: float | None = None, floors: dict | None = None, stride: int | None = None):
        n = kin.crank_angle.shape[0]
        self.mechanism, self.kin, self.tol, self.max_iter = mechanism, kin, tol, max_iter
        self.usable = kin.valid
        self.iterations = np.zeros(n)
        self.residual = np.zeros(n)
        self.converged = np.ones(n, dtype=bool)
        self.taus: dict[tuple[int, int], tuple[int, FloatArray, FloatArray]] = {}
        """joint -> (link it acts on, τ, relative rate), chain orientation"""
        self.surface: dict[tuple[int, int], FloatArray] = {}
        """slider -> friction force at the guide surface, on the slider along d"""
        self.signs: dict[tuple[int, int], FloatArray] = {}
        self.determinant: dict[int, FloatArray] = {}
        self.locks: dict[tuple[int, int], FloatArray] = {}
        self.locked = np.zeros(n, dtype=bool)
        self.unsolved = np.zeros(n, dtype=bool)
        self.near: dict[int, FloatArray] = {}
        self.dyads = {dyad.links: dyad.number for dyad in mechanism.dyads}
        self.crank_rate = kin.motion.omega[:, CRANK]  # constant, or from the equation of motion
        omega = (top_speed(kin) if speed is None else speed) or abs(mechanism.crank.speed)
        self.speed = omega
        self.typical = {"R": omega, "P": omega * mechanism.crank.length}
        self.floors: dict[tuple[int, int], float] = {} if floors is None else dict(floors)
        """dyad (links) -> force floor [N]: given, or taken at every ``stride``-th position"""
        self.stride = sample(n).step if stride is None else stride

    def floored(self, group: Group, scale: FloatArray) -> FloatArray:
        """A group's force size ``scale`` (``scales.force_size``), not below its floor (the
        ``Coupling``'s, or taken here from the sample)."""
        floor = self.floors.get(group.links)
        if floor is None:
            floor = self.floors[group.links] = force_floor(scale, self.stride)
        return np.maximum(scale, floor)

    def _sign(self, joint: Joint, rate: FloatArray) -> FloatArray:
        sign = np.sign(rate)
        sign[np.abs(rate) <= AT_REST_RTOL * self.typical[joint.kind]] = 0.0
        self.signs[joint.name] = sign
        return sign

    def laws(self, group: Group, q_i: FloatArray, q_j: FloatArray) -> list[Law]:
        offsets = (-q_i, None, -q_j)
        return [Law(k, joint, group, offsets[k], joint.friction * self._sign(joint, group.rate(k)),
                    self.kin.motion)
                for k, joint in enumerate(group.joints) if has_friction(joint)]

    def record(self, group: Group, laws: list[Law], taus: list[FloatArray], parts: list
               ) -> None:
        """Keep each joint's τ, and a slider's friction at the guide surface (from the
        ``parts`` the laws measured at the final reactions)."""
        for law, tau, part in zip(laws, taus, parts):
            self.taus[law.name] = (group.on[law.k], tau, group.rate(law.k))
            if not law.revolute:  # on the slider along d, as τ itself: its μ·|FN| part
                self.surface[law.name] = -law.c * part[2] if law.edge else tau

    def crank(self, q_crank: FloatArray) -> FloatArray | float:
        """τ₁₂, the friction moment of joint (1,2) on the crank: its force −Q₂ does not
        depend on the friction, so the law gives it directly."""
        joint = self.mechanism.crank.joint
        if not has_friction(joint):
            return 0.0
        rate = self.crank_rate
        size = np.sqrt(q_crank[0] ** 2 + q_crank[1] ** 2)
        tau = -joint.friction * joint.pin_radius * self._sign(joint, rate) * size
        self.iterations = np.maximum(self.iterations, 1.0)
        self.taus[joint.name] = (CRANK, tau, rate)
        return tau


def change_size(laws: list[Law], change: list[FloatArray], scale: FloatArray) -> FloatArray:
    """(n,) size of a change of the friction loads: the largest change of one load
    relative to μ·(r_z)·``scale``, the load a joint force of the group's size causes."""
    out = np.abs(change[0])
    if laws[0].unit != 1.0:
        out *= 1.0 / laws[0].unit
    for law, d in zip(laws[1:], change[1:]):
        np.maximum(out, np.abs(d) * (1.0 / law.unit), out=out)
    out /= scale
    return out


def run(kind, mechanism: Mechanism, kin: Kinematics, tol: float | None,
        max_iter: int | None, *, speed: float | None = None, floors: dict | None = None,
        stride: int | None = None, whole: bool = True) -> FrictionResult:
    """The backward pass of ``kin`` with the friction laws, each group solved by
    ``kind`` (a ``Rub``), and its ``FrictionResult``. ``tol``, ``max_iter``: default the
    mechanism's; ``speed``, ``floors``: a ``Coupling``'s (default: taken from ``kin``,
    the floors at every ``stride``-th position); ``whole``: decide which joints never
    move (``solver.solve``)."""
    tol = mechanism.friction_tol if tol is None else tol
    max_iter = mechanism.friction_max_iter if max_iter is None else max_iter
    rub = kind(mechanism, kin, tol, max_iter, speed, floors, stride)
    forces = kinetostatics.backward(mechanism, kin, kinetostatics.applied_loads(mechanism, kin),
                                    rub)
    # verdicts count where the frictionless forces are valid (outside the dead-centre band)
    valid = forces.valid
    rub.locked &= valid
    rub.unsolved &= valid
    for masks in (rub.locks, rub.near):
        for key in masks:
            masks[key] = masks[key] & valid
    forces.valid = valid & ~blocked(rub.locked, rub.unsolved, rub.near)
    n = kin.crank_angle.shape[0]
    usable = kin.valid
    moments, friction_forces = {}, {}
    power = np.zeros(n)
    for joint in mechanism.joints:  # in the file's joint order: the column order
        name = joint.name
        if name not in rub.taus:
            continue
        on, tau, rate = rub.taus[name]
        power -= tau * rate
        towards = toward_higher(name, on)
        if isinstance(joint, Revolute):
            moments[name] = towards * tau
        else:
            along = 1.0 if on == joint.slider else -1.0  # the screw is ±d
            friction_forces[name] = towards * along * tau
    at_rest = {joint.name: usable & (rub.signs[joint.name] == 0.0)
               for joint in mechanism.joints if joint.name in rub.signs}
    never = never_moves(at_rest, usable) if whole else []
    for name in never:
        at_rest[name] = np.zeros(n, dtype=bool)
    return FrictionResult(forces, moments, friction_forces, power, rub.iterations,
                          rub.residual, rub.converged, at_rest, never, rub.determinant,
                          rub.locks, rub.locked, rub.unsolved, rub.near,
                          Coupling(rub.speed, rub.floors))
