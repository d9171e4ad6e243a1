"""The direct friction solution of a dyad over the whole sweep (Thümmel & Bartke 1987,
section 4), solved for a consistent pattern of directions of the laws (``laws``), with
the self-locking verdict; the paper's fixed-point iteration is the tests' independent
check (``tests/fixed_point.py``).

**The direct solution** of a group (dyad). With W_B = W_B⁰ + Σ_l τ_l·R_l (W_B⁰ the
frictionless solution, R_l row l of M⁻¹) and W_k = s_k·W_B + q_k (s = +1, +1, −1;
q = −Q_i, 0, −Q_j), the laws linearised at the current pattern give a system over the
joints with friction (one to three unknowns per crank position):

    (I + K)·τ = t,   K_kl = c_k·s_k·a_k·R_l,   t_k = −c_k·a_k·W_k⁰.

Solve, take the pattern of the new reactions, repeat until the laws hold (the change a
fixed-point step would make to a friction load is below ``tol`` times μ·r_z or μ times
the dyad's largest joint force). Every law is homogeneous of degree 1, so this is
Newton's method on τ + c·g(W(τ)) = 0: a slider whose pressure keeps its sign is linear
for a consistent pattern (exact after one or two passes), a pin's direction and a
tilting block's pressure (``laws.Law.curved``) converge quadratically. All positions at
once.

**Self-locking.** det(I + K) = det(Mᵀ + C·A)/det(Mᵀ), with A the laws' gradients at the
solution, is the determinant of the friction-augmented equilibrium's Jacobian relative
to the frictionless one (1 without friction); towards 0
the forces grow like 1/det. A consistent solution with det > 0 is the one dyade reports;
where the passes end at det ≤ 0 or cycle, they start again from every forced pattern
(``_Direct``), since a slider that a load drives while its linkage brakes it also has a
jammed solution (det < 0) beside the braked one. Where no start finds a consistent
solution with det > 0 and some pass met det ≤ 0, the dyad self-locks — a friction dead
centre, beyond which no motion in the prescribed direction is possible (the fixed-point
iteration diverges there too); where none is found otherwise, the position is not
solved. Neither gets forces (NaN), nor do the dyads solved after it at that position.
The joint named is the one whose friction alone would bring the determinant lowest (its
own factor 1 + K_kk). Solved positions with det below sin(dead_centre), or where
friction multiplies the dyad's largest joint force component by more than
1/sin(dead_centre) (the plausibility bound), are near self-locking: their forces are
computed but not valid (``near``).
"""

from __future__ import annotations

import itertools

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.friction.algebra import apply, combine, determinant, dot, invert_small
from dyade.linkage.friction.laws import Law
from dyade.linkage.friction.passes import Rub, change_size, run
from dyade.linkage.friction.result import FrictionResult
from dyade.linkage.friction.scales import Coupling, force_size
from dyade.linkage.kinematics import Group, Kinematics
from dyade.model.mechanism import Mechanism

COMPACT = 0.1  # [-] pass only the unsolved positions on once they are below this share
RENEW_BELOW = 0.5  # [-] det below this: (I + K)⁻¹ renewed at every pass
RESTART_PASSES = 8
"""most Newton passes from each forced pattern (suspect positions); the self-locking
verdict takes the whole search: with fewer passes allowed (``friction_max_iter``) a
position without a solution is "not solved", never "self-locking" """


def _matrix(laws: list[Law], rows: list[FloatArray], parts: list, forced=None
            ) -> tuple[FloatArray, list]:
    """K (m, m, n), K_kl = c_k·s_k·a_k·R_l, at the pattern of ``parts``
    (``Law.measure``) or at the ``forced`` patterns; also the gradients c_k·s_k·a_k."""
    m = len(laws)
    out = np.empty((m, m, rows[0].shape[1]))
    term = np.empty(rows[0].shape[1])
    gradients = []
    for k, (law, part) in enumerate(zip(laws, parts)):
        a = law.gradient(part, None if forced is None else forced[k],
                         law.c if law.side > 0 else -law.c)
        gradients.append(a)
        for l, row in enumerate(rows):
            entry = np.multiply(a[0], row[0], out=out[k, l])
            entry += np.multiply(a[1], row[1], out=term)
            if not (isinstance(a[2], float) and a[2] == 0.0):
                entry += np.multiply(a[2], row[2], out=term)
    return out, gradients


class _View:
    """A group's laws and data at some of the positions (all of them, or an index)."""

    def __init__(self, laws: list[Law], rows: list[FloatArray], w0: FloatArray,
                 scale: FloatArray):
        self.laws, self.rows, self.w0, self.scale = laws, rows, w0, scale
        self.size = scale.shape[0]

    def take(self, index: FloatArray) -> _View:
        return _View([law.take(index) for law in self.laws], [row[:, index] for row in self.rows],
                     self.w0[:, index], self.scale[index])

    def wrench(self, taus: list[FloatArray]) -> FloatArray:
        """W_B = W_B⁰ + Σ τ_l·R_l (its force part only for a group of pins)."""
        return combine(self.w0[:self.rows[0].shape[0]], self.rows, taus)


class _Newton:
    """The state and outcome of Newton passes at the positions of a view."""

    FIELDS = ("det", "lowest", "step", "passes", "done")

    def __init__(self, n: int, m: int):
        self.det = np.full(n, np.nan)
        """det(I + K) at the pattern of the last renewal of (I + K)⁻¹ [-]"""
        self.lowest = np.full(n, np.inf)
        """the lowest det ≤ 0 any pass met (else inf) ..."""
        self.own = np.full((m, n), np.nan)
        """... and each joint's own factor 1 + K_kk at that pass"""
        self.step = np.zeros(n)
        """the last change a fixed-point step would make (``passes.change_size``) [-]"""
        self.passes = np.zeros(n)
        self.done = np.zeros(n, dtype=bool)
        """the laws hold to the tolerance"""
        self.inverse = np.zeros((m, m, n))
        """(I + K)⁻¹ at the last renewal"""
        self.patterns: list = [() for _ in range(m)]
        """each slider's pattern at the last renewal (bool arrays)"""

    def take(self, index: FloatArray) -> _Newton:
        out = object.__new__(_Newton)
        for name in self.FIELDS:
            setattr(out, name, getattr(self, name)[index])
        out.own = self.own[:, index]
        out.inverse = self.inverse[:, :, index]
        out.patterns = [tuple(sign[index] for sign in pattern) for pattern in self.patterns]
        return out

    def put(self, index: FloatArray, other: _Newton) -> None:
        """Take over ``other``, the state at the positions ``index``."""
        for name in self.FIELDS:
            getattr(self, name)[index] = getattr(other, name)
        self.own[:, index] = other.own
        self.inverse[:, :, index] = other.inverse
        for pattern, sub_pattern in zip(self.patterns, other.patterns):
            for sign, sub in zip(pattern, sub_pattern):
                sign[index] = sub

    def renew(self, view: _View, renew: FloatArray, measured: list) -> None:
        """(I + K)⁻¹, det and the patterns where ``renew``, from the reactions
        ``measured`` there (``Law.measure``)."""
        parts = [part for _, part in measured]
        every = renew.all()
        where = None if every else np.flatnonzero(renew)
        if where is not None:
            view = view.take(where)
            parts = [tuple(None if p is None else p[where] for p in part) for part in parts]
        matrix, _ = _matrix(view.laws, view.rows, parts)
        inverse, det = invert_small(matrix)
        at = slice(None) if every else where
        if every:
            self.inverse = inverse
        else:
            self.inverse[:, :, at] = inverse
        for k, law in enumerate(view.laws):
            pattern = law.pattern(parts[k])
            if pattern and not self.patterns[k]:
                self.patterns[k] = tuple(np.zeros(self.done.size, dtype=bool) for _ in pattern)
            for sign, new in zip(self.patterns[k], pattern):
                sign[at] = new
        self.det[at] = det
        self.note_lowest(at, det, matrix)

    def note_lowest(self, at, det: FloatArray, matrix: FloatArray) -> None:
        """Keep the lowest det ≤ 0 met at the positions ``at`` and the own factors
        1 + K_kk there (the diagonal of ``matrix``, I + K)."""
        if not (det <= 0.0).any():
            return
        lower = det < self.lowest[at]
        self.lowest[at] = np.where(lower, det, self.lowest[at])
        for k in range(matrix.shape[0]):
            self.own[k, at] = np.where(lower, matrix[k, k], self.own[k, at])


class _Direct(Rub):
    """The friction-augmented equilibrium solved for its consistent pattern (module
    docstring). Since every g_k is homogeneous, a_k·W_k = g_k, and the system at the
    pattern of the current τ is Newton's step (I + K)·Δτ = −c·g(W) − τ: the change a
    fixed-point step would make, corrected by the friction's own response. (I + K)⁻¹ is
    kept from pass to pass and renewed where a slider's pattern changed or det is below
    ``RENEW_BELOW`` (near self-locking, where a stale inverse is inaccurate): a pin's
    direction turns little, so elsewhere the old inverse converges as fast.

    Where the passes end at det ≤ 0 or find no consistent pattern, they start again
    from every forced pattern (``Law.choices``): a slider that a load drives while its
    linkage brakes it has two consistent solutions, the braked one (det > 0) and a
    jammed one (det < 0), and dyade reports the braked one. Only where no start reaches
    a consistent solution with det > 0 does the dyad self-lock (if a pass met det ≤ 0)
    or stay unsolved."""

    def group(self, group: Group, w0: FloatArray, q_i: FloatArray, q_j: FloatArray
              ) -> FloatArray:
        laws = self.laws(group, q_i, q_j)
        if not laws:
            return w0
        # at and past a friction dead centre the passes may blow up: those positions stay
        # pending and are reported (self-locking or not solved), their forces NaN
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            return self._solve(group, laws, w0, q_i, q_j)

    def _solve(self, group: Group, laws: list[Law], w0: FloatArray, q_i: FloatArray,
               q_j: FloatArray) -> FloatArray:
        n, m = w0.shape[1], len(laws)
        start = self.usable & np.isfinite(w0[0])  # NaN: a dyad solved earlier failed there
        width = 2 if all(law.revolute for law in laws) else 3  # pins need no moments
        rows = [group.inverse[law.k][:width] for law in laws]
        scale = self.floored(group, force_size(w0, q_i, q_j))
        values = [law.measure(w0)[0] for law in laws]
        view = _View(laws, rows, w0, scale)
        taus = [-law.c * g for law, g in zip(laws, values)]  # a first fixed-point step
        index = None if start.all() else np.flatnonzero(start)
        if index is not None:
            view, taus = view.take(index), [tau[index] for tau in taus]
        out = _Newton(view.size, m)
        self.newton(view, taus, out, 0, chord=True)
        suspect = np.flatnonzero(~out.done | (out.det <= 0.0))
        if suspect.size:
            self.restart(view, taus, out, suspect)
        if index is not None:
            whole, full = _Newton(n, m), [np.zeros(n) for _ in laws]
            whole.put(index, out)
            for tau, sub in zip(full, taus):
                tau[index] = sub
            out, taus = whole, full
        rows = [group.inverse[law.k] for law in laws]
        w_b = combine(w0, rows, taus)
        parts = [law.measure(w_b)[1] for law in laws]
        # det at the pattern of the reported solution (the chord's may be a pass old)
        if out.done.any():
            matrix, _ = _matrix(laws, rows, parts)
            out.det = np.where(out.done, determinant(matrix), out.det)
        bad = ~(out.done & (out.det > 0.0))
        if bad.any():
            for tau in taus:
                tau[bad] = np.nan
            w_b[:, bad] = np.nan
        # the plausibility bound: friction multiplies no joint force of the dyad by more
        # than 1/sin(dead_centre) (the largest force component of its three joints)
        band = np.sin(self.mechanism.dead_centre_angle)
        amplified = force_size(w_b, q_i, q_j) * band > scale
        self._verdict(group, laws, out, start, band, amplified)
        self.record(group, laws, taus, parts)
        return w_b

    def newton(self, view: _View, taus: list[FloatArray], out: _Newton, count: int,
               chord: bool, limit: int | None = None, w: FloatArray | None = None) -> None:
        """Newton passes from ``taus`` (updated in place) at the positions of ``view``
        where ``out`` is not done, recording in ``out``; ``count`` passes are spent,
        ``limit`` (default ``max_iter``) is the most in all. ``chord``: keep (I + K)⁻¹
        where it may (class docstring)."""
        limit = self.max_iter if limit is None else limit
        n = view.size
        pending = ~out.done
        every = bool(pending.all())  # the common case, without masks
        w = view.wrench(taus) if w is None else w
        while True:
            measured = [law.measure(w) for law in view.laws]
            change = [-law.c * g - tau for law, (g, _), tau in zip(view.laws, measured, taus)]
            now = change_size(view.laws, change, view.scale)
            np.copyto(out.step, now, where=pending)
            if chord and count > 0:
                renew = ~(out.det >= RENEW_BELOW)  # (NaN: never renewed)
                for law, (_, parts), old in zip(view.laws, measured, out.patterns):
                    for new, was in zip(law.pattern(parts), old):
                        renew |= new != was
                    curved = law.curved(parts)  # its gradient turns from pass to pass
                    if curved is not None:
                        renew |= curved
                renew &= pending
            else:
                renew = pending
            if renew.any():
                out.renew(view, renew, measured)
            done = now <= self.tol
            if not every:
                done &= pending
            if done.any():
                for tau, move in zip(taus, change):  # one last fixed-point step
                    np.add(tau, move, out=tau, where=done)
                out.done |= done
                pending = pending & ~done
                every = False
            if count >= limit or not pending.any():
                return
            delta = apply(out.inverse, change)
            count += 1
            if every:
                for tau, move in zip(taus, delta):
                    tau += move
                out.passes += 1.0
            else:
                for tau, move in zip(taus, delta):
                    np.add(tau, move, out=tau, where=pending)
                out.passes += pending
            term = np.empty_like(w)  # W_B moves with τ (the settled positions too: unused)
            for move, row in zip(delta, view.rows):
                np.multiply(row, move, out=term)
                w += term
            if not every and n > 1 and np.count_nonzero(pending) < COMPACT * n:
                sub = np.flatnonzero(pending)
                inner, sub_taus = out.take(sub), [tau[sub] for tau in taus]
                self.newton(view.take(sub), sub_taus, inner, count, chord, limit, w[:, sub])
                out.put(sub, inner)
                for tau, part in zip(taus, sub_taus):
                    tau[sub] = part
                return

    def restart(self, view: _View, taus: list[FloatArray], out: _Newton,
                suspect: FloatArray) -> None:
        """Newton again at the positions ``suspect`` from every forced pattern; keep the
        first consistent solution with det > 0."""
        left = suspect
        for forced in itertools.product(*(law.choices() for law in view.laws)):
            part = view.take(left)
            w0 = part.w0
            matrix, gradients = _matrix(part.laws, part.rows,
                                        [law.measure(w0)[1] for law in part.laws], forced)
            inverse, det = invert_small(matrix)
            # the forced pattern's own solution: (I + K)·τ = −c·a·W⁰
            # (gradients carry c_k·s_k: t_k = −c_k·a_k·W_k⁰ = −s_k·(c_k·s_k·a_k)·W_k⁰)
            trial_taus = apply(inverse, [-law.side * dot(a, [law.component(w0, i)
                                                             for i in range(3)])
                                         for law, a in zip(part.laws, gradients)])
            trial = _Newton(left.size, len(view.laws))
            trial.note_lowest(slice(None), det, matrix)
            self.newton(part, trial_taus, trial, 1, chord=False,
                        limit=min(RESTART_PASSES, self.max_iter))
            good = trial.done & (trial.det > 0.0)
            # the lowest det met anywhere, for the verdict where nothing is found
            lower = trial.lowest < out.lowest[left]
            out.lowest[left] = np.where(lower, trial.lowest, out.lowest[left])
            out.own[:, left] = np.where(lower, trial.own, out.own[:, left])
            if good.any():
                found = left[good]
                out.put(found, trial.take(np.flatnonzero(good)))
                for tau, sub in zip(taus, trial_taus):
                    tau[found] = sub[good]
                left = left[~good]
                if not left.size:
                    return

    def _verdict(self, group: Group, laws: list[Law], out: _Newton, start: FloatArray,
                 band: float, amplified: FloatArray) -> None:
        """Self-locking, unsolved and near self-locking positions of the group's dyad:
        det below ``band`` or forces ``amplified`` beyond the plausibility bound."""
        number = self.dyads[group.links]
        solved = out.done & (out.det > 0.0)  # (out is all False outside ``start``)
        determinant = np.where(solved, out.det, np.nan)
        failed = start & ~solved
        if failed.any():
            fresh = failed & ~self.locked & ~self.unsolved
            locked = fresh & (out.lowest <= 0.0)
            if self.max_iter < RESTART_PASSES:  # the search was cut short: no verdict
                locked[:] = False
            unsolved = fresh & ~locked
            if locked.any():  # the joint whose friction alone brings det lowest
                cause = np.argmin(np.where(np.isnan(out.own), np.inf, out.own), axis=0)
                for k, law in enumerate(laws):
                    mask = locked & (cause == k)
                    if mask.any():
                        self.locks[law.name] = mask
                determinant[locked] = out.lowest[locked]
            self.locked |= locked
            self.unsolved |= unsolved
            self.converged &= ~(locked | unsolved)
        near = (out.det < band) | amplified
        near &= solved
        if self.locked.any() or self.unsolved.any():
            near &= ~self.locked & ~self.unsolved
        self.near[number] = near
        self.determinant[number] = determinant
        np.maximum(self.iterations, out.passes, out=self.iterations)
        np.maximum(self.residual, np.where(start, out.step, 0.0), out=self.residual)


def solve(mechanism: Mechanism, kin: Kinematics, tol: float | None = None,
          max_iter: int | None = None, *, coupling: Coupling | None = None,
          whole: bool | None = None) -> FrictionResult:
    """Reactions with Coulomb friction in every joint with μ > 0, solved directly for a
    consistent pattern of directions, with the self-locking verdict (module docstring).

    ``tol`` [-]: a position is solved when a fixed-point step would change its joint
    forces by less than this share; ``max_iter``: most passes per group. ``coupling``:
    ``kin`` is a block of a larger sweep, whose ``Coupling`` this is (default: ``kin``
    is the whole sweep, and its own coupling); the block's positions are then solved as
    within that sweep. ``whole`` (default: without ``coupling``): which joints never move
    is decided here; else it is left to the caller (``never_moves`` empty, ``at_rest``
    as found).
    """
    if whole is None:
        whole = coupling is None
    if coupling is None:
        return run(_Direct, mechanism, kin, tol, max_iter, whole=whole)
    return run(_Direct, mechanism, kin, tol, max_iter, speed=coupling.speed,
               floors=coupling.floors, whole=whole)


def coupling(mechanism: Mechanism, kin: Kinematics, speed: float) -> Coupling:
    """The ``Coupling`` of a whole sweep from its sample positions alone: ``kin`` the
    kinematics at ``sample(n)`` of its n positions, ``speed`` its ``top_speed`` [rad/s].
    The friction solution there is the whole sweep's (per position, once the floors
    are known: and they come from these very positions)."""
    return run(_Direct, mechanism, kin, None, None, speed=speed, stride=1).coupling
