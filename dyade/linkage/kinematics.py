"""Kinematics over the whole crank sweep at once, dyad by dyad as in DYADE.

The crank first, then the dyads in assembly order: each dyad's closure in closed form
(``dyade.linkage.dyads``), then its velocities and accelerations by twists (``dyade.linkage.motion``).
A dyad is a loop g –A– i –B– j –C– h between two known links g and h; with the unit
twists S_A (i relative to g), S_B (j relative to i) and S_C (j relative to h) and the
joint rates r = (a, b, c),

    V_i = V_g + a·S_A,   V_j = V_i + b·S_B = V_h + c·S_C,

so M·r = V_h − V_g with the 3×3 loop matrix M = [S_A, S_B, −S_C]. Differentiating once
more, with the twist cross product V×W (``turn``) for the moving joint axes,

    M·ṙ = A_h − A_g − V_g×V_i − V_i×V_j + V_h×V_j,
    A_i = A_g + ȧ·S_A + V_g×V_i,   A_j = A_i + ḃ·S_B + V_i×V_j,

A being the time derivative of the twist (its ω part is α). det M = 0 exactly where the
dyad is at a dead centre or blocked. Loops run over dyads, never over crank angles.

The ω parts of the unit twists are constants (1 for a revolute joint, 0 for a prismatic
one), so M's determinant and the solutions are written by Cramer's rule in components,
det M = −(w_A·S_B×S_C + w_B·S_C×S_A + w_C·S_A×S_B) with × the planar cross product of
the (x, y) parts, and the terms that vanish for a kind are never computed: each kind's
closed form comes out of the one formula (``Group``). A component is an (n,) array, or
a plain number where it is the same at every position (the frame at rest, a crank turning
about the origin, a guide on the frame). The force stage solves the transposed system
with the same determinant; M⁻¹ itself is formed only on demand (``Group.inverse``: the
friction and self-locking stages use its rows).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray, Vec
from dyade.linkage import dyads
from dyade.linkage.components import is_zero, minus, plus, times
from dyade.linkage.dyads.closure import SINGULAR_SIN
from dyade.linkage.motion import Motion, Screw, guide_direction
from dyade.model.mechanism import CRANK, FRAME, Joint, Mechanism, Revolute


def _cross(u, v):
    """u_x·v_y − u_y·v_x of the (x, y) parts of two screws (components)."""
    return minus(times(u[0], v[1]), times(u[1], v[0]))


TINY_DET = 1e-300  # [m²] below this the loop matrix counts as singular (1 µm links: 1e-22)


def _scaled(value, scale: FloatArray, negated: FloatArray):
    """An entry of M⁻¹ from its cofactor and the row's factor (and its negative): a
    plain 0.0 stays one, ±1 gives the factor itself."""
    if type(value) is float and (value == 1.0 or value == -1.0):
        return scale if value == 1.0 else negated
    return times(value, scale)


class Group:
    """One dyad's loop M·r = V_h − V_g (module docstring), as the force stage needs it.

    Attributes: ``links`` (i, j); ``known`` (g, h); ``joints`` A, B, C; ``on``, the link
    each joint's twist and wrench refer to, (i, j, j); ``units``, the unit twists S_A
    (i rel. g), S_B (j rel. i), S_C (j rel. h) as components (x, y, ω) with ω a plain
    1.0 or 0.0 (``screws`` gives arrays); ``usable``, (n,) bool, where the dyad closes
    and is not singular; ``loop``, V_h − V_g (components); ``rates``, the joint rates
    a, b, c (n,) along S_A, S_B, S_C [rad/s or m/s], on demand (``rate``);
    ``entries``, the entries (k, c) of M⁻¹, (n,) arrays or plain zeros, NaN where the
    dyad is not usable, each formed as the general 3×3 inverse forms it (to the bit:
    ``tests/linkage/test_fast_paths.py``).
    """

    __slots__ = ("links", "known", "joints", "on", "units", "usable", "loop", "rates",
                 "entries", "_inverse")

    def __init__(self, links: tuple[int, int], known: tuple[int, int],
                 joints: tuple[Joint, Joint, Joint], units: tuple, usable: FloatArray) -> None:
        self.links, self.known, self.joints, self.units = links, known, joints, units
        self.on = (links[0], links[1], links[1])
        self.usable = usable
        self.loop = (0.0, 0.0, 0.0)
        self.rates = [None, None, None]
        self._inverse = None
        # the rows of adj [S_A, S_B, S_C] are S_B × S_C, S_C × S_A, S_A × S_B
        (x0, y0, w0), (x1, y1, w1), (x2, y2, w2) = units
        rows = ((_comb(w2, y1, w1, y2), _comb(w1, x2, w2, x1), _cross((x1, y1), (x2, y2))),
                (_comb(w0, y2, w2, y0), _comb(w2, x0, w0, x2), _cross((x2, y2), (x0, y0))),
                (_comb(w1, y0, w0, y1), _comb(w0, x1, w1, x0), _cross((x0, y0), (x1, y1))))
        det = plus(times(x0, rows[0][0]), times(y0, rows[0][1]))
        if w0 != 0.0:
            det = plus(det, times(w0, rows[0][2]))
        # 1/det where usable, NaN elsewhere; where |det| is below TINY_DET (lengths far
        # below a micrometre: its inverse would overflow) the dyad counts as singular
        self.usable = usable = usable & (np.abs(det) >= TINY_DET)
        if usable.all():  # (det may be a plain number: screws constant over the sweep)
            scale = np.divide(1.0, det, out=np.empty(usable.shape[0]))
        else:
            scale = np.full(usable.shape[0], np.nan)
            np.divide(1.0, det, out=scale, where=usable)
        flipped = -scale  # M = [S_A, S_B, −S_C]: the last row changes sign
        self.entries = [[_scaled(value, scale, flipped) for value in rows[0]],
                        [_scaled(value, scale, flipped) for value in rows[1]],
                        [_scaled(value, flipped, scale) for value in rows[2]]]

    def solve(self, rhs: tuple, k: int) -> FloatArray:
        """Row k of M⁻¹·rhs; ``rhs`` in components (x, y, ω)."""
        total, given = None, False
        for entry, part in zip(self.entries[k], rhs):
            if type(part) is float and part == 0.0:
                continue
            given = True
            if type(entry) is not float:
                term = entry * part
                total = term if total is None else total + term
        if total is None:  # zero (an entry that vanishes is NaN where not usable)
            return np.where(self.usable, 0.0, np.nan) if given else np.zeros(self.usable.shape)
        return total

    def rate(self, k: int) -> FloatArray:
        """Joint rate k (0 A, 1 B, 2 C) over the sweep."""
        if self.rates[k] is None:
            self.rates[k] = self.solve(self.loop, k)
        return self.rates[k]

    def reaction(self, rhs0: FloatArray, rhs2: FloatArray) -> FloatArray:
        """(3, n) M⁻ᵀ·(rhs0, 0, rhs2): the load W_B of the force stage."""
        out = np.empty((3, self.usable.shape[0]))
        for row, first, second in zip(out, self.entries[0], self.entries[2]):
            if type(first) is float:
                np.multiply(second, rhs2, out=row)
            else:
                np.multiply(first, rhs0, out=row)
                if type(second) is not float:
                    row += second * rhs2
        return out

    @property
    def screws(self) -> tuple:
        """The unit twists S_A, S_B, S_C with (n,) arrays for x and y."""
        n = self.usable.shape[0]
        return tuple((np.broadcast_to(x, (n,)), np.broadcast_to(y, (n,)), w)
                     for x, y, w in self.units)

    @property
    def inverse(self) -> FloatArray:
        """(3, 3, n): rows of M⁻¹, M = [S_A, S_B, −S_C]; NaN where the dyad is not usable
        (formed on first use)."""
        if self._inverse is None:
            self._inverse = np.empty((3, 3, self.usable.shape[0]))
            for k, row in enumerate(self.entries):
                for c, entry in enumerate(row):
                    self._inverse[k, c] = (entry if type(entry) is not float
                                           else np.where(self.usable, 0.0, np.nan))
        return self._inverse


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
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
    groups: list[Group]
    """per dyad, in assembly order: its loop (the force stage reuses it)"""
    valid: FloatArray
    """(n,) bool: every dyad closes and none is singular"""
    follower: object = None
    """``dyade.cam.follower.FollowerMotion`` of a cam-driven mechanism (``crank_angle`` is
    then the cam angle θ, link 2's coordinate its ``q``); None: link 2 is the input"""


def crank_motion(mechanism: Mechanism, crank_angle: FloatArray,
                 placed: tuple[int, ...] = (), crank_speed: FloatArray | float | None = None,
                 crank_acceleration: FloatArray | float | None = None,
                 repeat: int = 1) -> Motion:
    """Motion with the frame at rest and the crank turning about its pivot, at the
    mechanism's constant speed unless ``crank_speed`` [rad/s] and ``crank_acceleration``
    [rad/s²] (scalars or one value per position) are given; the ``placed`` links are left
    for the caller to fill (``Motion.at_rest``). ``repeat``: the crank angles are that
    many copies of the same sweep (a run of variants; its cosines computed once).

    A sliding input (``Crank.guide``): ``crank_angle`` is link 2's travel q [m] along the
    guide, ``crank_speed`` and ``crank_acceleration`` q̇ [m/s] and q̈ [m/s²] (given):
    link 2's origin is at pivot + q·d, its ξ axis along d, and it does not turn."""
    n = crank_angle.shape[0]
    motion = Motion.at_rest(n, mechanism.max_link + 1, placed)
    if mechanism.crank.sliding:
        return _slide(mechanism, motion, crank_angle, crank_speed, crank_acceleration)
    motion.origin[:, CRANK] = mechanism.crank.pivot
    motion.angle[:, CRANK] = crank_angle
    if repeat > 1 and n % repeat == 0:
        cos = motion.cos[:, CRANK].reshape(repeat, -1)  # (views: link-major storage)
        sin = motion.sin[:, CRANK].reshape(repeat, -1)
        cos_sin(crank_angle[:cos.shape[1]], cos[0], sin[0])
        cos[1:], sin[1:] = cos[0], sin[0]
    else:
        cos_sin(crank_angle, motion.cos[:, CRANK], motion.sin[:, CRANK])
    motion.velocity[:, CRANK] = 0.0
    motion.omega[:, CRANK] = mechanism.crank.speed if crank_speed is None else crank_speed
    motion.acceleration[:, CRANK] = 0.0  # the pivot (the crank frame's origin) stays put
    motion.alpha[:, CRANK] = 0.0 if crank_acceleration is None else crank_acceleration
    return motion


def _slide(mechanism: Mechanism, motion: Motion, travel: FloatArray, speed, acceleration
           ) -> Motion:
    """Link 2 sliding along its frame guide (``crank_motion``)."""
    gamma = mechanism.crank.guide
    dx, dy = float(np.cos(gamma)), float(np.sin(gamma))
    px, py = mechanism.crank.pivot
    speed = 0.0 if speed is None else speed
    acceleration = 0.0 if acceleration is None else acceleration
    motion.origin[:, CRANK, 0] = px + travel * dx
    motion.origin[:, CRANK, 1] = py + travel * dy
    motion.angle[:, CRANK] = gamma
    motion.cos[:, CRANK], motion.sin[:, CRANK] = dx, dy
    motion.velocity[:, CRANK, 0] = speed * dx
    motion.velocity[:, CRANK, 1] = speed * dy
    motion.omega[:, CRANK] = 0.0
    motion.acceleration[:, CRANK, 0] = acceleration * dx
    motion.acceleration[:, CRANK, 1] = acceleration * dy
    motion.alpha[:, CRANK] = 0.0
    motion.pivoted = False
    return motion


def cos_sin(angle: FloatArray, cos: FloatArray, sin: FloatArray) -> None:
    """Write cos and sin of ``angle`` into ``cos`` and ``sin``: as e^{iφ}, one complex
    exponential (the C library's sincos: about 15 % less than np.cos and np.sin, the
    same numbers where numpy takes both from the C library, as on x86-64 Linux)."""
    turn = np.empty(angle.shape[0], dtype=np.complex128)
    turn.real = 0.0
    turn.imag = angle
    with np.errstate(invalid="ignore"):  # NaN where the angle is NaN, as np.cos gives it
        np.exp(turn, out=turn)
    cos[:] = turn.real
    sin[:] = turn.imag


def crank_screw(mechanism: Mechanism) -> Screw:
    """Unit twist S₁₂ of joint (1,2): the crank turning about its fixed pivot, or
    (``Crank.guide``) link 2 sliding along its frame guide."""
    if mechanism.crank.sliding:
        gamma = mechanism.crank.guide
        return float(np.cos(gamma)), float(np.sin(gamma)), 0.0
    x, y = mechanism.crank.pivot
    return y, -x, 1.0


def _comb(p: float, a: FloatArray, q: float, b: FloatArray):
    """p·a − q·b for constants p, q (the ω parts of screws, mostly 0 or ±1)."""
    if q == 0.0:
        return 0.0 if p == 0.0 else (a if p == 1.0 else p * a)
    if p == 0.0:
        return -b if q == 1.0 else -q * b
    if p == 1.0 and q == 1.0:
        return a - b
    return p * a - q * b


def sweep(mechanism: Mechanism, crank_angle: FloatArray | None = None,
          crank_speed: FloatArray | float | None = None,
          crank_acceleration: FloatArray | float | None = None, repeat: int = 1
          ) -> Kinematics:
    """Positions, velocities and accelerations of every link over the crank sweep.

    The crank turns at the mechanism's constant speed Ω unless ``crank_speed`` φ̇21
    [rad/s] and ``crank_acceleration`` φ̈21 [rad/s²] are given (scalars, or one value
    per crank angle): the crank's twist is then φ̇21·S₁₂ and its rate of change
    φ̈21·S₁₂ (S₁₂ is fixed in the frame), and every dyad takes them as its known motion.
    ``repeat``: the crank angles are that many copies of one sweep (variants stacked
    into ``mechanism``, ``dyade.linkage.stack``).

    A cam-driven mechanism (``Mechanism.cam``): ``crank_angle`` is the cam angle θ and
    ``crank_speed``, ``crank_acceleration`` θ̇ [rad/s], θ̈ [rad/s²] (default: the cam's
    constant speed); link 2 takes the follower's q, q̇ = q′·θ̇, q̈ = q″·θ̇² + q′·θ̈
    (``dyade.cam.follower``), and the sweep goes on from link 2 as from any input.
    """
    if crank_angle is None:
        crank_angle = mechanism.sweep.angles()
    crank_angle = np.asarray(crank_angle, dtype=np.float64)
    n = crank_angle.shape[0]
    follower, position = None, crank_angle
    if mechanism.cam is not None:
        from dyade.cam.follower import follower_motion

        follower = follower_motion(mechanism.cam, crank_angle)
        master = mechanism.crank.speed if crank_speed is None else crank_speed
        position = follower.q
        rate = follower.ddq * (master * master)
        if crank_acceleration is not None:
            rate = rate + follower.dq * crank_acceleration
        follower = dataclasses.replace(follower, speed=master, acceleration=(
            0.0 if crank_acceleration is None else crank_acceleration))
        crank_speed, crank_acceleration = follower.dq * master, rate
    motion = crank_motion(mechanism, position, tuple(mechanism.moving_links), crank_speed,
                          crank_acceleration, repeat)
    count = len(mechanism.dyads)
    # per dyad and position, each dyad's column contiguous (the results are (n, dyads))
    closes, singular = np.empty((count, n), dtype=bool), np.empty((count, n), dtype=bool)
    transmission, conditioning = np.empty((count, n)), np.empty((count, n))
    # twists of the moving links and their time derivatives, in components; the frame's
    # are zero (not in the dicts)
    sx, sy, sw = (float(v) for v in crank_screw(mechanism))
    speed = mechanism.crank.speed if crank_speed is None else np.broadcast_to(crank_speed, (n,))
    twists = {CRANK: (times(sx, speed), times(sy, speed), times(sw, speed))}
    changes = {}  # constant speed about a fixed pivot: zero
    if crank_acceleration is not None and np.any(crank_acceleration):
        rate = np.broadcast_to(crank_acceleration, (n,))
        changes[CRANK] = (times(sx, rate), times(sy, rate), times(sw, rate))
    groups = []
    upstream_ok = np.ones(n, dtype=bool)
    for col, dyad in enumerate(mechanism.dyads):
        closure = dyads.close(dyad, motion)
        ok = np.logical_and(closure.closes, upstream_ok, out=closes[col])
        if closure.lever is not None:  # a length scale the angle alone does not see
            closure.conditioning = closure.conditioning * np.minimum(
                1.0, closure.lever / mechanism.crank.length)
        transmission[col] = closure.transmission
        conditioning[col] = closure.conditioning
        if not ok.all():
            transmission[col, ~ok] = np.nan
            conditioning[col, ~ok] = np.nan
            for link in dyad.links:
                motion.invalidate(link, ~ok)
        usable = ok & ~(closure.conditioning < SINGULAR_SIN)
        closes[col] = closure.closes
        group = _derivatives(dyad, closure, motion, twists, changes, usable)
        np.logical_and(ok, ~group.usable, out=singular[col])
        groups.append(group)
        upstream_ok = group.usable
    return Kinematics(crank_angle, motion, closes.T, transmission.T, singular.T,
                      conditioning.T, groups, upstream_ok, follower)


def _unit(joint: Joint, motion: Motion, on: int, closure, k: int) -> tuple:
    """Unit twist of joint k of a dyad in components (``dyade.linkage.motion``): a
    revolute joint's ω part is +1, a prismatic joint's translation is along +d, the
    carrier's guide direction, for the slider and along −d for the carrier; a revolute
    joint's position from the closure's pin, a guide's direction from the closure's
    guide where it found one."""
    if isinstance(joint, Revolute):
        x, y = closure.pins[k] if k in closure.pins else motion.point_xy(joint.links[0],
                                                                         joint.points[0])
        return y, times(-1.0, x), 1.0
    dx, dy = closure.guides[k] if k in closure.guides else guide_direction(joint, motion)
    if on == joint.slider:
        return dx, dy, 0.0
    return times(-1.0, dx), times(-1.0, dy), 0.0


def _derivatives(dyad, closure, motion: Motion, twists: dict, changes: dict,
                 usable: FloatArray) -> Group:
    """Twists and their rates of links i and j (module docstring); writes the link
    frames' velocities and accelerations into ``motion``. ``twists`` and ``changes``
    map link -> components (x, y, ω); the frame (and a zero change) is not in them."""
    (i, j), (g, h) = dyad.links, dyad.known
    units = tuple(_unit(joint, motion, on, closure, k)
                  for k, (joint, on) in enumerate(zip(dyad.joints, (i, j, j))))
    group = Group((i, j), (g, h), dyad.joints, units, usable)
    zero = (0.0, 0.0, 0.0)
    v_g, v_h = twists.get(g, zero), twists.get(h, zero)
    group.loop = loop = (minus(v_h[0], v_g[0]), minus(v_h[1], v_g[1]), minus(v_h[2], v_g[2]))
    rate_a, rate_b = group.rate(0), group.rate(1)
    v_i = twists[i] = _advance(v_g, rate_a, units[0], motion.omega[:, i])
    v_j = twists[j] = _advance(v_i, rate_b, units[1], motion.omega[:, j])
    # M·ṙ = A_h − A_g − V_g×V_i − V_i×V_j + V_h×V_j (ω part: α_h − α_g)
    turn_ij = turn(v_i, v_j)
    a_g, a_h = changes.get(g, zero), changes.get(h, zero)
    bias_x, bias_y = minus(minus(a_h[0], a_g[0]), turn_ij[0]), minus(minus(a_h[1], a_g[1]),
                                                                   turn_ij[1])
    turn_gi = (0.0, 0.0)
    if g in twists:
        turn_gi = turn(v_g, v_i)
        bias_x, bias_y = minus(bias_x, turn_gi[0]), minus(bias_y, turn_gi[1])
    if h in twists:
        turn_hj = turn(v_h, v_j)
        bias_x, bias_y = plus(bias_x, turn_hj[0]), plus(bias_y, turn_hj[1])
    bias = (bias_x, bias_y, minus(a_h[2], a_g[2]))
    accel_a, accel_b = group.solve(bias, 0), group.solve(bias, 1)  # ċ is not needed
    a_i = changes[i] = _advance(a_g, accel_a, units[0], motion.alpha[:, i], turn_gi)
    a_j = changes[j] = _advance(a_i, accel_b, units[1], motion.alpha[:, j], turn_ij)
    _frame_motion(motion, i, v_i, a_i)
    _frame_motion(motion, j, v_j, a_j)
    return group


def turn(v: tuple, w: tuple) -> tuple:
    """(x, y) of the twist cross product V×W = (ω_V·E·w − ω_W·E·v, 0): the rate of
    change of a twist W fixed in a body that moves with V (components)."""
    return (minus(times(w[2], v[1]), times(v[2], w[1])),
            minus(times(v[2], w[0]), times(w[2], v[0])))


def _advance(base: tuple, rate: FloatArray, unit: tuple, angular: FloatArray,
             extra: tuple = (0.0, 0.0)) -> tuple:
    """base + rate·unit (+ extra in x, y), twists in components; the ω part is written
    into ``angular`` (the link's ω or α in the motion) and is that view."""
    w = times(rate, unit[2])
    if is_zero(base[2]):
        angular[:] = w
    else:
        np.add(base[2], w, out=angular)
    return (plus(plus(base[0], times(rate, unit[0])), extra[0]),
            plus(plus(base[1], times(rate, unit[1])), extra[1]), angular)


def _frame_motion(motion: Motion, link: int, twist: tuple, change: tuple) -> None:
    """Velocity and acceleration of a link frame's origin r from the link's twist:
    v = v_O + ω·E·r,  a = A_O + α·E·r + ω·E·v (ω and α are in the motion already)."""
    x, y = motion.origin[:, link, 0], motion.origin[:, link, 1]
    omega, alpha = twist[2], change[2]
    vx, vy = motion.velocity[:, link, 0], motion.velocity[:, link, 1]
    np.subtract(twist[0], omega * y, out=vx)
    np.add(twist[1], omega * x, out=vy)
    ax, ay = motion.acceleration[:, link, 0], motion.acceleration[:, link, 1]
    np.subtract(change[0], alpha * y, out=ax)
    ax -= omega * vy
    np.add(change[1], alpha * x, out=ay)
    ay += omega * vx


# -- derived quantities the reports use --------------------------------------------
def joint_anchor(joint: Revolute) -> tuple[int, Vec]:
    """The link and local point a revolute joint's motion is taken on: its first link's,
    or its second's where the first is the frame."""
    if joint.links[0] == FRAME:
        return joint.links[1], joint.points[1]
    return joint.links[0], joint.points[0]


def joint_point(joint: Revolute, motion: Motion) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, velocity, acceleration of a revolute joint (on its first link)."""
    link, local = joint_anchor(joint)
    return (motion.point(link, local), motion.point_velocity(link, local),
            motion.point_acceleration(link, local))

