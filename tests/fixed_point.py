"""An independent check of the friction solution: the paper's fixed-point iteration
(Thümmel & Bartke 1987, section 4), friction from the last reactions, solve again, repeat.

It applies the same laws (``dyade.linkage.friction.laws``) in the same backward pass
(``dyade.linkage.friction.passes``) as ``friction.solve``, but iterates them instead of
solving for a consistent pattern: it converges only where every eigenvalue of K lies
inside the unit circle, diverges towards self-locking and says nothing about it.
"""

from __future__ import annotations

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.friction.algebra import combine
from dyade.linkage.friction.passes import Rub, change_size, run
from dyade.linkage.friction.result import FrictionResult
from dyade.linkage.friction.scales import force_size
from dyade.linkage.kinematics import Group, Kinematics
from dyade.model.mechanism import Mechanism


class FixedPoint(Rub):
    """The paper's iteration: friction from the last reactions, solve again, repeat."""

    def group(self, group: Group, w0: FloatArray, q_i: FloatArray, q_j: FloatArray
              ) -> FloatArray:
        laws = self.laws(group, q_i, q_j)
        if not laws:
            return w0
        rows = [group.inverse[law.k] for law in laws]
        scale = self.floored(group, force_size(w0, q_i, q_j))
        n = scale.shape[0]
        taus = [np.zeros(n) for _ in laws]
        pending = self.usable.copy()
        its = np.zeros(n)
        step = np.zeros(n)
        w_b = w0
        # a diverging iteration (near self-locking) overflows: those positions stay pending
        with np.errstate(over="ignore", invalid="ignore"):
            for _ in range(self.max_iter):
                new = [-law.c * law.measure(w_b)[0] for law in laws]
                step = change_size(laws, [a - b for a, b in zip(new, taus)], scale)
                taus = new
                w_b = combine(w0, rows, taus)
                its += pending
                pending &= ~(step <= self.tol)
                if not pending.any():
                    break
        self.iterations = np.maximum(self.iterations, its)
        self.residual = np.maximum(self.residual, np.where(self.usable, step, 0.0))
        self.converged &= ~pending
        self.record(group, laws, taus, [law.measure(w_b)[1] for law in laws])
        return w_b


def iterate(mechanism: Mechanism, kin: Kinematics, tol: float | None = None,
            max_iter: int | None = None) -> FrictionResult:
    """The reactions of ``friction.solve`` by the fixed-point iteration (``iterations``:
    its steps; no self-locking verdict)."""
    return run(FixedPoint, mechanism, kin, tol, max_iter)
