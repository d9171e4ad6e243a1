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
dyad is at a dead centre or blocked. M's inverse is kept: the force stage solves the
transposed system with it. Loops run over dyads, never over crank angles.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.linkage import dyads as dyad_kinds
from dyade.linkage.motion import Motion, Screw, screw
from dyade.linkage.model import CRANK, FRAME, FloatArray, Joint, Mechanism, Revolute


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Group:
    """One dyad's loop, as the force stage needs it."""

    links: tuple[int, int]
    """(i, j)"""
    known: tuple[int, int]
    """(g, h)"""
    joints: tuple[Joint, Joint, Joint]
    """A, B, C"""
    on: tuple[int, int, int]
    """the link each joint's twist and wrench refer to: (i, j, j)"""
    screws: tuple[Screw, Screw, Screw]
    """unit twists S_A (i rel. g), S_B (j rel. i), S_C (j rel. h)"""
    inverse: FloatArray
    """(3, 3, n): rows of M⁻¹, M = [S_A, S_B, −S_C]; NaN where the dyad is not usable"""
    loop: tuple
    """V_h − V_g, the right-hand side of the velocity loop (components; 0.0 for zero)"""
    rates: list
    """joint rates a, b, c (n,) along S_A, S_B, S_C [rad/s or m/s]; c on demand"""

    def rate(self, k: int) -> FloatArray:
        """Joint rate k (0 A, 1 B, 2 C) over the sweep."""
        if self.rates[k] is None:
            self.rates[k] = solve_rows(self.inverse, self.loop, (k,))[0]
        return self.rates[k]


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


def crank_motion(mechanism: Mechanism, crank_angle: FloatArray,
                 placed: tuple[int, ...] = (), crank_speed: FloatArray | float | None = None,
                 crank_acceleration: FloatArray | float | None = None) -> Motion:
    """Motion with the frame at rest and the crank turning about its pivot, at the
    mechanism's constant speed unless ``crank_speed`` [rad/s] and ``crank_acceleration``
    [rad/s²] (scalars or one value per position) are given; the ``placed`` links are left
    for the caller to fill (``Motion.at_rest``)."""
    n = crank_angle.shape[0]
    motion = Motion.at_rest(n, mechanism.max_link + 1, placed)
    motion.origin[:, CRANK] = mechanism.crank.pivot
    motion.set_angle(CRANK, crank_angle)
    motion.velocity[:, CRANK] = 0.0
    motion.omega[:, CRANK] = mechanism.crank.speed if crank_speed is None else crank_speed
    motion.acceleration[:, CRANK] = 0.0  # the pivot (the crank frame's origin) stays put
    motion.alpha[:, CRANK] = 0.0 if crank_acceleration is None else crank_acceleration
    return motion


def crank_screw(mechanism: Mechanism) -> Screw:
    """Unit twist of joint (1,2): the crank turning about its fixed pivot."""
    x, y = mechanism.crank.pivot
    return y, -x, 1.0


def turn(v: FloatArray, w: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(x, y) of the twist cross product V×W = (ω_V·E·w − ω_W·E·v, 0): the rate of
    change of a twist W fixed in a body that moves with V."""
    return w[2] * v[1] - v[2] * w[1], v[2] * w[0] - w[2] * v[0]


def _comb(p: float, a: FloatArray, q: float, b: FloatArray):
    """p·a − q·b for constants p, q (the ω parts of screws, mostly 0 or ±1)."""
    if q == 0.0:
        return 0.0 if p == 0.0 else (a if p == 1.0 else p * a)
    if p == 0.0:
        return -b if q == 1.0 else -q * b
    if p == 1.0 and q == 1.0:
        return a - b
    return p * a - q * b


def inverse3(c0: Screw, c1: Screw, c2: Screw, usable: FloatArray) -> FloatArray:
    """Rows (3, 3, n) of the inverse of the loop matrix [c0, c1, −c2] of three screws;
    NaN where not ``usable``. The rows of [c0, c1, c2]⁻¹ are c1×c2, c2×c0, c0×c1 over
    the determinant; the sign of c2 flips the last row."""
    (x0, y0, w0), (x1, y1, w1), (x2, y2, w2) = c0, c1, c2
    rows = np.empty((3, 3, x0.shape[0]))
    rows[0, 0], rows[0, 1] = _comb(w2, y1, w1, y2), _comb(w1, x2, w2, x1)
    rows[1, 0], rows[1, 1] = _comb(w0, y2, w2, y0), _comb(w2, x0, w0, x2)
    rows[2, 0], rows[2, 1] = _comb(w1, y0, w0, y1), _comb(w0, x1, w1, x0)
    rows[0, 2] = x1 * y2 - y1 * x2
    rows[1, 2] = x2 * y0 - y2 * x0
    rows[2, 2] = x0 * y1 - y0 * x1
    det = x0 * rows[0, 0] + y0 * rows[0, 1]
    if w0 != 0.0:
        det += w0 * rows[0, 2]
    # singular rows become NaN below; a determinant below 1e-308 overflows to inf
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        scale = 1.0 / det
    if not usable.all():
        scale[~usable] = np.nan
    rows[:2] *= scale
    rows[2] *= -scale
    return rows


def solve_rows(inverse: FloatArray, rhs, rows=(0, 1, 2)) -> list[FloatArray]:
    """Rows of M⁻¹·rhs; ``rhs`` has three components, a plain 0.0 for a zero one."""
    out = []
    for k in rows:
        total = None
        for col in range(3):
            if isinstance(rhs[col], float) and rhs[col] == 0.0:
                continue
            term = inverse[k, col] * rhs[col]
            total = term if total is None else np.add(total, term, out=total)
        out.append(np.zeros_like(inverse[k, 0]) if total is None else total)
    return out


def sweep(mechanism: Mechanism, crank_angle: FloatArray | None = None,
          crank_speed: FloatArray | float | None = None,
          crank_acceleration: FloatArray | float | None = None) -> Kinematics:
    """Positions, velocities and accelerations of every link over the crank sweep.

    The crank turns at the mechanism's constant speed Ω unless ``crank_speed`` φ̇21
    [rad/s] and ``crank_acceleration`` φ̈21 [rad/s²] are given (scalars, or one value
    per crank angle): the crank's twist is then φ̇21·S₁₂ and its rate of change
    φ̈21·S₁₂ (S₁₂ is fixed in the frame), and every dyad takes them as its known motion.
    """
    if crank_angle is None:
        crank_angle = mechanism.sweep.angles()
    crank_angle = np.asarray(crank_angle, dtype=np.float64)
    n = crank_angle.shape[0]
    motion = crank_motion(mechanism, crank_angle, tuple(mechanism.moving_links), crank_speed,
                          crank_acceleration)
    count = len(mechanism.dyads)
    closes = np.ones((n, count), dtype=bool)
    transmission = np.full((n, count), np.nan)
    singular = np.zeros((n, count), dtype=bool)
    conditioning = np.full((n, count), np.nan)
    # twists of the moving links and their time derivatives; the frame's are zero
    unit = np.array(crank_screw(mechanism))[:, None]
    if crank_speed is None:
        twists = {CRANK: np.repeat(mechanism.crank.speed * unit, n, axis=1)}
    else:
        twists = {CRANK: unit * np.broadcast_to(crank_speed, (n,))}
    changes = {CRANK: None}  # constant speed about a fixed pivot: zero
    if crank_acceleration is not None and np.any(crank_acceleration):
        changes[CRANK] = unit * np.broadcast_to(crank_acceleration, (n,))
    groups = []
    upstream_ok = np.ones(n, dtype=bool)
    for col, dyad in enumerate(mechanism.dyads):
        closure = dyad.kind.close(dyad, motion)
        ok = closure.closes & upstream_ok
        closes[:, col] = closure.closes
        transmission[:, col] = closure.transmission
        if closure.lever is not None:  # a length scale the angle alone does not see
            closure.conditioning = closure.conditioning * np.minimum(
                1.0, closure.lever / mechanism.crank.length)
        conditioning[:, col] = closure.conditioning
        if not ok.all():
            transmission[~ok, col] = np.nan
            conditioning[~ok, col] = np.nan
            for link in dyad.links:
                motion.invalidate(link, ~ok)
        singular[:, col] = ok & (closure.conditioning < dyad_kinds.SINGULAR_SIN)
        usable = ok & ~singular[:, col]
        groups.append(_derivatives(dyad, closure, motion, twists, changes, usable))
        upstream_ok = usable
    return Kinematics(crank_angle, motion, closes, transmission, singular, conditioning,
                      groups, upstream_ok)


def _derivatives(dyad, closure, motion: Motion, twists: dict, changes: dict,
                 usable: FloatArray) -> Group:
    """Twists and their rates of links i and j (module docstring); writes the link
    frames' velocities and accelerations into ``motion``. ``twists`` and ``changes``
    map link -> (3, n); the frame (and a zero change, None) is not in them."""
    (i, j), (g, h) = dyad.links, dyad.known
    screws = tuple(screw(joint, motion, on, closure.pins.get(k))
                   for k, (joint, on) in enumerate(zip(dyad.joints, (i, j, j))))
    inverse = inverse3(*screws, usable)
    v_g, v_h = twists.get(g), twists.get(h)
    loop = _difference(v_h, v_g)
    rate_a, rate_b = solve_rows(inverse, loop, (0, 1))
    v_i = twists[i] = _advance(v_g, rate_a, screws[0])
    v_j = twists[j] = _advance(v_i, rate_b, screws[1])
    # M·ṙ = A_h − A_g − V_g×V_i − V_i×V_j + V_h×V_j (ω part: α_h − α_g)
    turn_ij = turn(v_i, v_j)
    bias = list(_difference(changes.get(h), changes.get(g)))
    bias[0], bias[1] = bias[0] - turn_ij[0], bias[1] - turn_ij[1]
    turn_gi = None
    if v_g is not None:
        turn_gi = turn(v_g, v_i)
        bias[0], bias[1] = bias[0] - turn_gi[0], bias[1] - turn_gi[1]
    if v_h is not None:
        turn_hj = turn(v_h, v_j)
        bias[0], bias[1] = bias[0] + turn_hj[0], bias[1] + turn_hj[1]
    accel_a, accel_b = solve_rows(inverse, bias, (0, 1))  # ċ is not needed
    a_i = changes[i] = _advance(changes.get(g), accel_a, screws[0], turn_gi)
    a_j = changes[j] = _advance(a_i, accel_b, screws[1], turn_ij)
    _frame_motion(motion, i, v_i, a_i)
    _frame_motion(motion, j, v_j, a_j)
    return Group((i, j), (g, h), dyad.joints, (i, j, j), screws, inverse, loop,
                 [rate_a, rate_b, None])


def _difference(a: FloatArray | None, b: FloatArray | None) -> tuple:
    """Components of a − b for twists (3, n); None and 0.0 stand for zero."""
    if a is None and b is None:
        return 0.0, 0.0, 0.0
    if b is None:
        return a[0], a[1], a[2]
    if a is None:
        return -b[0], -b[1], -b[2]
    return a[0] - b[0], a[1] - b[1], a[2] - b[2]


def _advance(base: FloatArray | None, rate: FloatArray, unit: Screw,
             extra: tuple | None = None) -> FloatArray:
    """base + rate·unit (+ extra in x, y) for twists (3, n); None is zero."""
    x, y, w = unit
    out = np.empty((3, rate.shape[0]))
    np.multiply(rate, x, out=out[0])
    np.multiply(rate, y, out=out[1])
    if w == 1.0:
        out[2] = rate
    else:
        np.multiply(rate, w, out=out[2])
    if base is not None:
        out += base
    if extra is not None:
        out[0] += extra[0]
        out[1] += extra[1]
    return out


def _frame_motion(motion: Motion, link: int, twist: FloatArray, change: FloatArray) -> None:
    """Velocity and acceleration of a link frame's origin r from the link's twist:
    v = v_O + ω·E·r,  a = A_O + α·E·r + ω·E·v."""
    x, y = motion.origin[:, link, 0], motion.origin[:, link, 1]
    omega, alpha = twist[2], change[2]
    vx, vy = motion.velocity[:, link, 0], motion.velocity[:, link, 1]
    np.subtract(twist[0], omega * y, out=vx)
    np.add(twist[1], omega * x, out=vy)
    motion.omega[:, link] = omega
    ax, ay = motion.acceleration[:, link, 0], motion.acceleration[:, link, 1]
    np.subtract(change[0], alpha * y, out=ax)
    ax -= omega * vy
    np.add(change[1], alpha * x, out=ay)
    ay += omega * vx
    motion.alpha[:, link] = alpha


# -- derived quantities the reports use --------------------------------------------
def joint_point(joint: Revolute, motion: Motion) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, velocity, acceleration of a revolute joint (on its first link)."""
    link, local = joint.links[0], joint.points[0]
    if link == FRAME:
        link, local = joint.links[1], joint.points[1]
    return (motion.point(link, local), motion.point_velocity(link, local),
            motion.point_acceleration(link, local))

