"""The fixed-point friction iteration dyade had before issue 15 (dyade/linkage/friction.py
at faca28f): the speed yardstick of ``friction.solve`` (tests/benchmarks/
test_friction_speed.py). Frozen: its model has no edge friction and no self-locking
verdict. Only changes: ``surface = {}`` on ``_Rub``, which today's
``kinetostatics.backward`` reads (empty: the whole along-guide force acts at the surface,
as it did then), and its unused ``joint_forces_on`` left out."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage import kinetostatics
from dyade.linkage.kinematics import Group, Kinematics
from dyade.model.mechanism import CRANK, Joint, Mechanism, Revolute, toward_higher

AT_REST_RTOL = 1e-9  # [-] relative velocity below this share of the typical one counts as zero
FORCE_FLOOR = 1e-12  # [-] share of the largest force below which changes are not relative


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
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
    """(n,) largest final relative change of any group's joint forces [-]"""
    converged: FloatArray
    """(n,) bool"""
    at_rest: dict[tuple[int, int], FloatArray]
    """joint -> (n,) bool: relative velocity zero, friction direction undefined"""
    never_moves: list[tuple[int, int]]
    """joints with friction whose relative velocity is zero over the whole sweep"""


def has_friction(joint: Joint) -> bool:
    return joint.friction > 0.0


class _Rub:
    """The friction laws, applied group by group inside the backward pass."""

    def __init__(self, mechanism: Mechanism, kin: Kinematics, tol: float, max_iter: int):
        n = kin.crank_angle.shape[0]
        self.mechanism, self.tol, self.max_iter = mechanism, tol, max_iter
        self.usable = kin.valid
        self.iterations = np.zeros(n)
        self.residual = np.zeros(n)
        self.converged = np.ones(n, dtype=bool)
        self.taus: dict[tuple[int, int], tuple[int, FloatArray, FloatArray]] = {}
        """joint -> (link it acts on, τ, relative rate), chain orientation"""
        self.signs: dict[tuple[int, int], FloatArray] = {}
        self.surface: dict[tuple[int, int], FloatArray] = {}  # read by today's backward
        self.crank_rate = kin.motion.omega[:, CRANK]
        omega = float(np.nanmax(np.abs(self.crank_rate), initial=0.0)) or abs(mechanism.crank.speed)
        self.typical = {"R": omega, "P": omega * mechanism.crank.length}

    def _sign(self, joint: Joint, rate: FloatArray) -> FloatArray:
        sign = np.sign(rate)
        sign[np.abs(rate) <= AT_REST_RTOL * self.typical[joint.kind]] = 0.0
        self.signs[joint.name] = sign
        return sign

    def _law(self, joint: Joint, rate: FloatArray) -> FloatArray:
        """−τ per unit force: μ·r_z·sign(r) (revolute) or μ·sign(r) (prismatic)."""
        arm = joint.pin_radius if isinstance(joint, Revolute) else 1.0
        return joint.friction * arm * self._sign(joint, rate)

    def group(self, group: Group, w_b: FloatArray, q_i: FloatArray, q_j: FloatArray
              ) -> FloatArray:
        """The group's W_B with friction in its joints (fixed-point iteration)."""
        laws = [(k, self._law(joint, group.rate(k)), isinstance(joint, Revolute))
                for k, joint in enumerate(group.joints) if has_friction(joint)]
        if not laws:
            return w_b
        rows = group.inverse[:, :2]
        f_i, f_j = q_i[:2], q_j[:2]
        start = w_b[:2]
        f_b = start
        scale = np.maximum(np.maximum(np.abs(f_b - f_i).max(axis=0), np.abs(f_b).max(axis=0)),
                           np.abs(f_j + f_b).max(axis=0))
        floor = FORCE_FLOOR * max(float(np.nanmax(scale, initial=0.0)), 1e-300)
        scale = np.maximum(scale, floor)
        n = scale.shape[0]
        taus = [np.zeros(n)] * len(laws)
        pending = self.usable.copy()
        its = np.zeros(n)
        step = np.zeros(n)
        for _ in range(self.max_iter):
            new = start
            for index, (k, coefficient, revolute) in enumerate(laws):
                force = f_b - f_i if k == 0 else (f_b if k == 1 else -f_j - f_b)
                if revolute:
                    size = np.sqrt(force[0] * force[0] + force[1] * force[1])
                else:  # normal force: across the guide direction (the screw's force part)
                    axis = group.screws[k]
                    size = np.abs(axis[0] * force[1] - axis[1] * force[0])
                taus[index] = -coefficient * size
                new = new + taus[index] * rows[k]
            step = np.maximum(np.abs(new[0] - f_b[0]), np.abs(new[1] - f_b[1])) / scale
            f_b = new
            its += pending
            pending &= step > self.tol
            if not pending.any():
                break
        self.iterations = np.maximum(self.iterations, its)
        self.residual = np.maximum(self.residual, np.where(self.usable, step, 0.0))
        self.converged &= ~pending
        for (k, _, _), tau in zip(laws, taus):
            w_b = w_b + tau * group.inverse[k]
            self.taus[group.joints[k].name] = (group.on[k], tau, group.rate(k))
        return w_b

    def crank(self, q_crank: FloatArray) -> FloatArray | float:
        """τ₁₂, the friction moment of joint (1,2) on the crank: its force −Q₂ does not
        depend on the friction, so no iteration."""
        joint = self.mechanism.crank.joint
        if not has_friction(joint):
            return 0.0
        rate = self.crank_rate
        tau = -self._law(joint, rate) * np.sqrt(q_crank[0] ** 2 + q_crank[1] ** 2)
        self.iterations = np.maximum(self.iterations, 1.0)
        self.taus[joint.name] = (CRANK, tau, rate)
        return tau


def iterate(mechanism: Mechanism, kin: Kinematics, tol: float | None = None,
            max_iter: int | None = None) -> FrictionResult:
    """Reactions with Coulomb friction in every joint with μ > 0."""
    tol = mechanism.friction_tol if tol is None else tol
    max_iter = mechanism.friction_max_iter if max_iter is None else max_iter
    rub = _Rub(mechanism, kin, tol, max_iter)
    forces = kinetostatics.backward(mechanism, kin, kinetostatics.applied_loads(mechanism, kin),
                                    rub)
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
    never = [name for name, mask in at_rest.items() if mask[usable].all() and usable.any()]
    for name in never:
        at_rest[name] = np.zeros(n, dtype=bool)
    return FrictionResult(forces, moments, friction_forces, power, rub.iterations,
                          rub.residual, rub.converged, at_rest, never)
