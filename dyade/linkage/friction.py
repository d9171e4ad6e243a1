"""Coulomb friction dyad by dyad over the whole sweep (Thümmel & Bartke 1987, section 4):
solved directly for a consistent pattern of directions; the paper's fixed-point
iteration is kept (``iterate``) as an independent check.

**The laws.** In the wrench form of ``dyade.linkage.kinetostatics`` friction is the part
τ = S·W that a joint carries along its freedom S (relative rate r along S):

* revolute joint: τ = −μ·r_z·|F|·sign(r), a moment about the pin;
* prismatic joint: τ = −μ·(|FN| + 3·|M'|/L)·sign(r), a force along the guide. M' =
  M + ½·FN·H·μ·sign(r) is the tilting moment that the normal pressures carry (M: the
  joint's moment about the slider point), and 3·|M'|/L the sum of the two edge pressures
  of a linear pressure distribution over the block length L: the paper's edge friction.
  The part μ·|FN| acts at the guide surface, H/2 from the slider point on the side that
  carries the normal force (so it shifts the reported moment); the edge part acts on
  both faces alike and has no moment. ``edge_friction = false`` leaves out 3·|M'|/L.

Every law reads τ_k = −c_k·g_k(W_k) with c_k = μ·sign(r_k) and g_k ≥ 0 positively
homogeneous of degree 1 in the joint's wrench W_k. For a fixed *pattern* — the direction
of a pin's force, the signs of a slider's FN and M' — g_k is linear: g_k = a_k·W_k.

**The direct solution** of a group (dyad). With W_B = W_B⁰ + Σ_l τ_l·R_l (W_B⁰ the
frictionless solution, R_l row l of M⁻¹) and W_k = s_k·W_B + q_k (s = +1, +1, −1;
q = −Q_i, 0, −Q_j), the laws linearised at the current pattern give a system over the
joints with friction (one to three unknowns per crank position):

    (I + K)·τ = t,   K_kl = c_k·s_k·a_k·R_l,   t_k = −c_k·a_k·W_k⁰.

Solve, take the pattern of the new reactions, repeat until the laws hold (the change a
fixed-point step would make to a friction load is below ``tol`` times μ·r_z or μ times
the dyad's largest joint force). A slider's law is piecewise linear, so a consistent
pattern is exact after one or two passes; a pin's direction update is Newton's method
on |F|, quadratically convergent. All positions at once.

**Self-locking.** det(I + K) = det(Mᵀ + C·A)/det(Mᵀ) is the friction-augmented
determinant of the dyad relative to the frictionless one (1 without friction); towards 0
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

Where a relative velocity is zero the friction direction is undefined: sign(0) = 0 is
used and the positions are returned in ``at_rest`` so that the caller reports them.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from dyade.linkage import kinetostatics
from dyade.linkage.kinematics import Group, Kinematics
from dyade.linkage.model import CRANK, FloatArray, Joint, Mechanism, Revolute, toward_higher

AT_REST_RTOL = 1e-9  # [-] relative velocity below this share of the typical one counts as zero
FORCE_FLOOR = 1e-12  # [-] share of a typical force below which changes are not relative
EDGE = 3.0  # [-] sum of the edge pressures of a linear distribution over L: 3·|M'|/L
COMPACT = 0.1  # [-] pass only the unsolved positions on once they are below this share
RENEW_BELOW = 0.5  # [-] det below this: (I + K)⁻¹ renewed at every pass
RESTART_PASSES = 8
"""most Newton passes from each forced pattern (suspect positions); the self-locking
verdict takes the whole search: with fewer passes allowed (``friction_max_iter``) a
position without a solution is "not solved", never "self-locking" """
SAMPLE = 256  # the force floors are taken from about this many positions of the sweep


@dataclass(frozen=True, slots=True)
class Coupling:
    """What the friction solution takes from the whole sweep rather than from each
    position: given to ``solve`` for a block of positions, the block is solved exactly
    as within the whole sweep (``dyade.linkage.stream``; ``coupling`` computes it from
    the sample positions alone)."""

    speed: float
    """the typical crank speed [rad/s]: the sweep's largest |φ̇21| (else the file's);
    relative rates below ``AT_REST_RTOL`` of it (times the crank length for a slider)
    count as at rest"""
    floors: dict[tuple[int, int], float]
    """dyad (its links) -> force floor [N]: ``FORCE_FLOOR`` times the median size of its
    frictionless joint forces at the sample positions (``sample``), below which changes
    are not relative"""


def sample(positions: int) -> slice:
    """The positions of a sweep the force floors are taken from: every k-th, about
    ``SAMPLE`` of them."""
    return slice(None, None, max(1, positions // SAMPLE))


def top_speed(kin: Kinematics) -> float:
    """The largest crank speed |φ̇21| of ``kin`` [rad/s] (0 if none is finite)."""
    return float(np.nanmax(np.abs(kin.motion.omega[:, CRANK]), initial=0.0))


def coupling(mechanism: Mechanism, kin: Kinematics, speed: float) -> Coupling:
    """The ``Coupling`` of a whole sweep from its sample positions alone: ``kin`` the
    kinematics at ``sample(n)`` of its n positions, ``speed`` its ``top_speed`` [rad/s].
    The friction solution there is the whole sweep's (per position, once the floors
    are known: and they come from these very positions)."""
    return _run(_Direct, mechanism, kin, None, None, speed=speed, stride=1).coupling


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
    """dyad number -> (n,) friction-augmented determinant relative to the frictionless
    one, det(I + K) [-]: 1 without friction, ≤ 0 self-locking; NaN where not solved
    (direct solution only)"""
    locks: dict[tuple[int, int], FloatArray]
    """joint -> (n,) bool: its dyad self-locks there and this joint's friction is the
    cause (direct solution only)"""
    lock_dyad: dict[tuple[int, int], int]
    """joint in ``locks`` -> number of its dyad"""
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
        out = self.locked | self.unsolved
        for mask in self.near.values():
            out = out | mask
        return out


def has_friction(joint: Joint) -> bool:
    return joint.friction > 0.0


class _Law:
    """The Coulomb law of one joint of a group (module docstring): g(W) ≥ 0, its pattern
    and gradient a, and the part of a slider's friction at the guide surface."""

    def __init__(self, k: int, joint: Joint, group: Group, offset, coefficient: FloatArray,
                 motion):
        self.k, self.joint, self.name = k, joint, joint.name
        self.side = -1.0 if k == 2 else 1.0  # s_k: W_k = s_k·W_B + q_k
        self.offset = offset  # q_k (3, n) or None
        self.c = coefficient  # μ·sign(r) (n,)
        self.revolute = isinstance(joint, Revolute)
        # μ·r_z or μ: the friction load per newton of joint force, for relative changes
        self.unit = max(joint.friction * (joint.pin_radius if self.revolute else 1.0), 1e-300)
        self.arm = joint.pin_radius if self.revolute else 1.0
        if self.revolute:
            self.arrays = ("c",)
            return
        ax, ay = group.screws[k][0], group.screws[k][1]  # ζ·d
        self.ax, self.ay = ax, ay
        self.zeta = 1.0 if group.on[k] == joint.slider else -1.0
        px, py = motion.point_xy(joint.slider, joint.slider_point)
        h = 0.5 * joint.slider_height * coefficient  # ½·H·μ·sign(r)
        self.edge = EDGE / joint.slider_length if joint.edge_friction else 0.0
        # M' = ζ·(m − p_x·f_y + p_y·f_x) + h·FN = ζ·m + tx·f_x + ty·f_y
        self.tx, self.ty = self.zeta * py - h * ay, h * ax - self.zeta * px
        self.arrays = ("c", "ax", "ay", "tx", "ty")

    def take(self, index) -> _Law:
        """The law at the positions ``index`` only."""
        out = object.__new__(_Law)
        out.__dict__.update(self.__dict__)
        out.offset = None if self.offset is None else self.offset[:, index]
        for name in self.arrays:
            setattr(out, name, getattr(self, name)[index])
        return out

    def component(self, w_b: FloatArray, index: int) -> FloatArray:
        """Component ``index`` of W_k = s_k·W_B + q_k, the joint's wrench on ``on[k]``."""
        part = w_b[index]
        if self.offset is None:
            return part if self.side > 0 else -part
        return self.offset[index] + part if self.side > 0 else self.offset[index] - part

    def measure(self, w_b: FloatArray) -> tuple[FloatArray, tuple]:
        """g(W_k) (n,) and the parts its pattern and gradient need: (f_x, f_y, |F|) of
        a pin, (FN, M', |FN|) of a slider (FN, M' on the slider)."""
        wx, wy = self.component(w_b, 0), self.component(w_b, 1)
        if self.revolute:
            size = np.sqrt(wx * wx + wy * wy)
            return self.arm * size, (wx, wy, size)
        normal = self.ax * wy - self.ay * wx
        size = np.abs(normal)
        if not self.edge:
            return size, (normal, None, size)
        wm = self.component(w_b, 2)
        tilt = self.tx * wx + self.ty * wy
        tilt += wm if self.zeta > 0 else -wm
        return size + self.edge * np.abs(tilt), (normal, tilt, size)

    def pattern(self, parts: tuple) -> tuple:
        """A slider's pattern: the signs of FN and M' (a pin's direction is continuous)."""
        if self.revolute:
            return ()
        return (parts[0] > 0.0,) if parts[1] is None else (parts[0] > 0.0, parts[1] > 0.0)

    def choices(self) -> list[tuple[float, ...]]:
        """Every pattern a restart may force (``gradient``): the signs of FN and M' of a
        slider, the sense of a pin's force relative to the one measured."""
        if self.revolute:
            return [(1.0,), (-1.0,)]
        if not self.edge:
            return [(1.0,), (-1.0,)]
        return [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]

    def gradient(self, parts: tuple, forced: tuple | None = None, factor=1.0) -> tuple:
        """``factor``·a, with g = a·W_k at the pattern of ``parts``, or at the ``forced``
        one (``choices``): three (n,) arrays (or 0.0)."""
        if self.revolute:
            wx, wy, size = parts
            scale = factor * self.arm / np.maximum(size, 1e-300)  # |F| = 0: f = 0
            if forced is not None:
                scale *= forced[0]
            return wx * scale, wy * scale, 0.0
        normal, tilt, _ = parts
        sn = (np.sign(normal) if forced is None else forced[0]) * factor
        if tilt is None:
            return -self.ay * sn, self.ax * sn, 0.0
        st = (np.sign(tilt) if forced is None else forced[1]) * (self.edge * factor)
        gx = st * self.tx
        gx -= self.ay * sn
        gy = st * self.ty
        gy += self.ax * sn
        return gx, gy, st * self.zeta


class _Rub:
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
        self.lock_dyad: dict[tuple[int, int], int] = {}
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
        """A group's force size ``scale`` (``_scale``), not below its floor (the
        ``Coupling``'s, or taken here from the sample)."""
        floor = self.floors.get(group.links)
        if floor is None:
            floor = self.floors[group.links] = _floor(scale, self.stride)
        return np.maximum(scale, floor)

    def _sign(self, joint: Joint, rate: FloatArray) -> FloatArray:
        sign = np.sign(rate)
        sign[np.abs(rate) <= AT_REST_RTOL * self.typical[joint.kind]] = 0.0
        self.signs[joint.name] = sign
        return sign

    def laws(self, group: Group, q_i: FloatArray, q_j: FloatArray) -> list[_Law]:
        offsets = (-q_i, None, -q_j)
        return [_Law(k, joint, group, offsets[k], joint.friction * self._sign(joint, group.rate(k)),
                     self.kin.motion)
                for k, joint in enumerate(group.joints) if has_friction(joint)]

    def record(self, group: Group, laws: list[_Law], taus: list[FloatArray], parts: list
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


def _scale(w_b: FloatArray, q_i: FloatArray, q_j: FloatArray) -> FloatArray:
    """(n,) the size of a group's joint forces: the largest force component of its three
    joints (W_A = W_B − Q_i, W_B, W_C = −Q_j − W_B); against the frictionless one
    changes are relative (``_Rub.floored``: not below a small share of a typical value)."""
    scale = np.abs(w_b[0])
    for part in (w_b[1], w_b[0] - q_i[0], w_b[1] - q_i[1], w_b[0] + q_j[0], w_b[1] + q_j[1]):
        np.maximum(scale, np.abs(part), out=scale)
    return scale


def _floor(scale: FloatArray, stride: int) -> float:
    """The force floor [N] of a group of force sizes ``scale``: ``FORCE_FLOOR`` times a
    typical size, not the largest (near a dead centre forces reach 1e30): the median of
    every ``stride``-th."""
    values = scale[::stride]
    values = values[np.isfinite(values) & (values > 0.0)]
    least = FORCE_FLOOR * (_median(values) if values.size else 1.0)
    return max(least, 1e-300)


def _median(values: FloatArray) -> float:
    """``np.median`` of finite values, to the bit, without what np.median imports on its
    first call (numpy.ma, about 17 ms of every friction run's start-up)."""
    middle = values.size // 2
    if values.size % 2:
        return float(np.partition(values, middle)[middle])
    part = np.partition(values, (middle - 1, middle))
    return float((part[middle - 1] + part[middle]) / 2.0)


def _step(laws: list[_Law], change: list[FloatArray], scale: FloatArray) -> FloatArray:
    """(n,) size of a change of the friction loads: the largest change of one load
    relative to μ·(r_z)·``scale``, the load a joint force of the group's size causes."""
    out = np.abs(change[0])
    if laws[0].unit != 1.0:
        out *= 1.0 / laws[0].unit
    for law, d in zip(laws[1:], change[1:]):
        np.maximum(out, np.abs(d) * (1.0 / law.unit), out=out)
    out /= scale
    return out


def _combine(w0: FloatArray, rows: list[FloatArray], taus: list[FloatArray]) -> FloatArray:
    """W_B = W_B⁰ + Σ τ_l·R_l."""
    out = w0.copy()
    term = np.empty_like(out)
    for tau, row in zip(taus, rows):
        np.multiply(row, tau, out=term)
        out += term
    return out


def _dot(a, r, out: FloatArray | None = None) -> FloatArray:
    """a·R for a gradient (gx, gy, gm) and a wrench (three (n,) arrays; gm may be 0.0)."""
    out = np.multiply(a[0], r[0], out=out)
    out += a[1] * r[1]
    if not (isinstance(a[2], float) and a[2] == 0.0):
        out += a[2] * r[2]
    return out


def determinant(matrix: FloatArray) -> FloatArray:
    """det(I + K) (n,) for K (m, m, n), m ≤ 3."""
    m = matrix.shape[0]
    a = [[matrix[k, l] + 1.0 if k == l else matrix[k, l] for l in range(m)] for k in range(m)]
    if m == 1:
        return a[0][0]
    if m == 2:
        return a[0][0] * a[1][1] - a[0][1] * a[1][0]
    return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            + a[0][1] * (a[1][2] * a[2][0] - a[1][0] * a[2][2])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))


def invert_small(matrix: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(I + K)⁻¹ (m, m, n) and det(I + K) (n,) at every position, for one to three
    unknowns (cofactors); ``matrix`` holds K (m, m, n) and is turned into I + K. Where
    det = 0 the inverse is set to 0 (a friction dead centre: reported, never stepped
    over)."""
    m, n = matrix.shape[0], matrix.shape[2]
    a = matrix
    for k in range(m):
        a[k, k] += 1.0
    if m == 1:
        det = a[0, 0].copy()
        out = np.empty_like(a)
    elif m == 2:
        det = a[0, 0] * a[1, 1]
        det -= a[0, 1] * a[1, 0]
        out = np.empty_like(a)
        out[0, 0], out[1, 1] = a[1, 1], a[0, 0]
        np.negative(a[0, 1], out=out[0, 1])
        np.negative(a[1, 0], out=out[1, 0])
    else:
        out = np.empty_like(a)
        term = np.empty(n)
        for k, l, (p, q), (r, t) in _COFACTORS:  # out[k, l] = cofactor (l, k) = p·q − r·t
            np.multiply(a[p], a[q], out=out[k, l])
            np.multiply(a[r], a[t], out=term)
            out[k, l] -= term
        det = a[0, 0] * out[0, 0]
        det += a[0, 1] * out[1, 0]
        det += a[0, 2] * out[2, 0]
    scale = np.divide(1.0, det, out=np.zeros(n), where=det != 0.0)
    if m == 1:
        out[0, 0] = scale
    else:
        out *= scale
    return out, det


# (k, l, (p, q), (r, t)): entry (k, l) of the adjugate, a[p]·a[q] − a[r]·a[t]
_COFACTORS = [(0, 0, ((1, 1), (2, 2)), ((1, 2), (2, 1))),
              (1, 0, ((1, 2), (2, 0)), ((1, 0), (2, 2))),
              (2, 0, ((1, 0), (2, 1)), ((1, 1), (2, 0))),
              (0, 1, ((0, 2), (2, 1)), ((0, 1), (2, 2))),
              (1, 1, ((0, 0), (2, 2)), ((0, 2), (2, 0))),
              (2, 1, ((0, 1), (2, 0)), ((0, 0), (2, 1))),
              (0, 2, ((0, 1), (1, 2)), ((0, 2), (1, 1))),
              (1, 2, ((0, 2), (1, 0)), ((0, 0), (1, 2))),
              (2, 2, ((0, 0), (1, 1)), ((0, 1), (1, 0)))]


def _apply(inverse: FloatArray, vector: list[FloatArray]) -> list[FloatArray]:
    """(I + K)⁻¹·vector."""
    out = []
    term = np.empty_like(vector[0])
    for row in inverse:
        total = row[0] * vector[0]
        for entry, value in zip(row[1:], vector[1:]):
            np.multiply(entry, value, out=term)
            total += term
        out.append(total)
    return out


def _matrix(laws: list[_Law], rows: list[FloatArray], parts: list, forced=None
            ) -> tuple[FloatArray, list]:
    """K (m, m, n), K_kl = c_k·s_k·a_k·R_l, at the pattern of ``parts``
    (``_Law.measure``) or at the ``forced`` patterns; also the gradients c_k·s_k·a_k."""
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

    def __init__(self, laws: list[_Law], rows: list[FloatArray], w0: FloatArray,
                 scale: FloatArray):
        self.laws, self.rows, self.w0, self.scale = laws, rows, w0, scale
        self.size = scale.shape[0]

    def take(self, index: FloatArray) -> _View:
        return _View([law.take(index) for law in self.laws], [row[:, index] for row in self.rows],
                     self.w0[:, index], self.scale[index])

    def wrench(self, taus: list[FloatArray]) -> FloatArray:
        """W_B = W_B⁰ + Σ τ_l·R_l (its force part only for a group of pins)."""
        return _combine(self.w0[:self.rows[0].shape[0]], self.rows, taus)


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
        """the last change a fixed-point step would make (``_step``) [-]"""
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
        ``measured`` there (``_Law.measure``)."""
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


class _Direct(_Rub):
    """The friction-augmented equilibrium solved for its consistent pattern (module
    docstring). Since every g_k is homogeneous, a_k·W_k = g_k, and the system at the
    pattern of the current τ is Newton's step (I + K)·Δτ = −c·g(W) − τ: the change a
    fixed-point step would make, corrected by the friction's own response. (I + K)⁻¹ is
    kept from pass to pass and renewed where a slider's pattern changed or det is below
    ``RENEW_BELOW`` (near self-locking, where a stale inverse is inaccurate): a pin's
    direction turns little, so elsewhere the old inverse converges as fast.

    Where the passes end at det ≤ 0 or find no consistent pattern, they start again
    from every forced pattern (``_Law.choices``): a slider that a load drives while its
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

    def _solve(self, group: Group, laws: list[_Law], w0: FloatArray, q_i: FloatArray,
               q_j: FloatArray) -> FloatArray:
        n, m = w0.shape[1], len(laws)
        start = self.usable & np.isfinite(w0[0])  # NaN: a dyad solved earlier failed there
        width = 2 if all(law.revolute for law in laws) else 3  # pins need no moments
        rows = [group.inverse[law.k][:width] for law in laws]
        scale = self.floored(group, _scale(w0, q_i, q_j))
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
        w_b = _combine(w0, rows, taus)
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
        amplified = _scale(w_b, q_i, q_j) * band > scale
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
            now = _step(view.laws, change, view.scale)
            np.copyto(out.step, now, where=pending)
            if chord and count > 0:
                renew = ~(out.det >= RENEW_BELOW)  # (NaN: never renewed)
                for law, (_, parts), old in zip(view.laws, measured, out.patterns):
                    for new, was in zip(law.pattern(parts), old):
                        renew |= new != was
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
            delta = _apply(out.inverse, change)
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
            trial_taus = _apply(inverse, [-law.side * _dot(a, [law.component(w0, i)
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

    def _verdict(self, group: Group, laws: list[_Law], out: _Newton, start: FloatArray,
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
                        self.lock_dyad[law.name] = number
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


class _FixedPoint(_Rub):
    """The paper's iteration: friction from the last reactions, solve again, repeat."""

    def group(self, group: Group, w0: FloatArray, q_i: FloatArray, q_j: FloatArray
              ) -> FloatArray:
        laws = self.laws(group, q_i, q_j)
        if not laws:
            return w0
        rows = [group.inverse[law.k] for law in laws]
        scale = self.floored(group, _scale(w0, q_i, q_j))
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
                step = _step(laws, [a - b for a, b in zip(new, taus)], scale)
                taus = new
                w_b = _combine(w0, rows, taus)
                its += pending
                pending &= ~(step <= self.tol)
                if not pending.any():
                    break
        self.iterations = np.maximum(self.iterations, its)
        self.residual = np.maximum(self.residual, np.where(self.usable, step, 0.0))
        self.converged &= ~pending
        self.record(group, laws, taus, [law.measure(w_b)[1] for law in laws])
        return w_b


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
        return _run(_Direct, mechanism, kin, tol, max_iter, whole=whole)
    return _run(_Direct, mechanism, kin, tol, max_iter, speed=coupling.speed,
                floors=coupling.floors, whole=whole)


def iterate(mechanism: Mechanism, kin: Kinematics, tol: float | None = None,
            max_iter: int | None = None) -> FrictionResult:
    """The same reactions by the paper's fixed-point iteration (an independent check of
    ``solve``; it diverges towards self-locking and says nothing about it)."""
    return _run(_FixedPoint, mechanism, kin, tol, max_iter)


def _run(kind, mechanism: Mechanism, kin: Kinematics, tol: float | None,
         max_iter: int | None, *, speed: float | None = None, floors: dict | None = None,
         stride: int | None = None, whole: bool = True) -> FrictionResult:
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
    blocked = rub.locked | rub.unsolved
    for mask in rub.near.values():
        blocked = blocked | mask
    forces.valid = valid & ~blocked
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
                          rub.locks, rub.lock_dyad, rub.locked, rub.unsolved, rub.near,
                          Coupling(rub.speed, rub.floors))


def never_moves(at_rest: dict[tuple[int, int], FloatArray], usable: FloatArray
                ) -> list[tuple[int, int]]:
    """The joints at rest (``at_rest``: joint -> (n,) bool) at every usable position of a
    sweep (``usable``: (n,) bool, the kinematics valid), if there is one."""
    if not usable.any():
        return []
    return [name for name, mask in at_rest.items() if mask[usable].all()]
