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

from dataclasses import dataclass

import numpy as np

from dyade.linkage import dyads as dyad_kinds
from dyade.linkage.motion import Motion, Screw, guide_direction
from dyade.linkage.model import CRANK, FRAME, FloatArray, Joint, Mechanism, Revolute


def _zero(a) -> bool:
    return isinstance(a, float) and a == 0.0


def _mul(a, b):
    """a·b for components (arrays or plain numbers), skipping plain zeros and ones."""
    for x, y in ((a, b), (b, a)):
        if isinstance(x, float):
            if x == 0.0:
                return 0.0
            if x == 1.0:
                return y
            if x == -1.0:
                return -y
    return a * b


def _add(a, b):
    """a + b for components, skipping plain zeros."""
    if _zero(b):
        return a
    return b if _zero(a) else a + b


def _sub(a, b):
    """a − b for components, skipping plain zeros."""
    if _zero(b):
        return a
    return -b if _zero(a) else a - b


def _cross(u, v):
    """u_x·v_y − u_y·v_x of the (x, y) parts of two screws (components)."""
    return _sub(_mul(u[0], v[1]), _mul(u[1], v[0]))


class Group:
    """One dyad's loop M·r = V_h − V_g (module docstring), as the force stage needs it.

    M⁻¹ is formed entry by entry as it is asked for (``entry``), each the way
    ``inverse3`` forms it, so that the results do not depend on which entries a stage
    needs; an entry that vanishes for the kind is a plain 0.0 and costs nothing.
    """

    __slots__ = ("links", "known", "joints", "on", "units", "usable", "loop", "rates",
                 "_entries", "_scale", "_inverse")

    def __init__(self, links: tuple[int, int], known: tuple[int, int],
                 joints: tuple[Joint, Joint, Joint], units: tuple, usable: FloatArray) -> None:
        self.links = links
        """(i, j)"""
        self.known = known
        """(g, h)"""
        self.joints = joints
        """A, B, C"""
        self.on = (links[0], links[1], links[1])
        """the link each joint's twist and wrench refer to: (i, j, j)"""
        self.units = units
        """unit twists S_A (i rel. g), S_B (j rel. i), S_C (j rel. h) as components
        (x, y, ω), ω a plain 1.0 or 0.0 (``screws`` gives arrays)"""
        self.usable = usable
        """(n,) bool: the dyad closes and is not singular here"""
        self.loop = (0.0, 0.0, 0.0)
        """V_h − V_g, the right-hand side of the velocity loop (components)"""
        self.rates = [None, None, None]
        """joint rates a, b, c (n,) along S_A, S_B, S_C [rad/s or m/s]; on demand"""
        self._entries = {}
        self._scale = None
        self._inverse = None

    def _unscaled(self, k: int, c: int):
        """Entry (k, c) of adj [S_A, S_B, S_C] (``inverse3``'s order of operations)."""
        key = (k, c, False)
        if key not in self._entries:
            (x0, y0, w0), (x1, y1, w1), (x2, y2, w2) = self.units
            self._entries[key] = (
                (_comb(w2, y1, w1, y2), _comb(w1, x2, w2, x1), _cross((x1, y1), (x2, y2))),
                (_comb(w0, y2, w2, y0), _comb(w2, x0, w0, x2), _cross((x2, y2), (x0, y0))),
                (_comb(w1, y0, w0, y1), _comb(w0, x1, w1, x0), _cross((x0, y0), (x1, y1))),
            )[k][c]
        return self._entries[key]

    def scale(self, k: int) -> FloatArray:
        """(n,) the factor of row k of M⁻¹: 1/det [S_A, S_B, S_C], negated for row 2;
        NaN where the dyad is not usable."""
        if self._scale is None:
            x0, y0, w0 = self.units[0]
            det = _add(_mul(x0, self._unscaled(0, 0)), _mul(y0, self._unscaled(0, 1)))
            if w0 != 0.0:
                det = _add(det, _mul(w0, self._unscaled(0, 2)))
            det = np.broadcast_to(det, self.usable.shape)
            # singular rows become NaN below; a determinant below 1e-308 overflows to inf
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                scale = 1.0 / det
            if not self.usable.all():
                scale[~self.usable] = np.nan
            self._scale = [scale, None]
        if k == 2:
            if self._scale[1] is None:
                self._scale[1] = -self._scale[0]
            return self._scale[1]
        return self._scale[0]

    def entry(self, k: int, c: int):
        """Entry (k, c) of M⁻¹ (n,); a plain 0.0 where it vanishes for the kind."""
        key = (k, c, True)
        if key not in self._entries:
            value = self._unscaled(k, c)
            self._entries[key] = 0.0 if _zero(value) else value * self.scale(k)
        return self._entries[key]

    def solve(self, rhs: tuple, k: int) -> FloatArray:
        """Row k of M⁻¹·rhs (``solve_rows``); ``rhs`` in components (x, y, ω)."""
        total = None
        for c, part in enumerate(rhs):
            term = _mul(self.entry(k, c), part)
            if _zero(term):
                continue
            if total is None:
                total = term if not isinstance(term, float) else np.full(self.usable.shape,
                                                                         term)
            else:
                total = total + term
        if total is None:  # no term: zero, NaN where the dyad is not usable
            return self.scale(k) * 0.0
        return total

    def rate(self, k: int) -> FloatArray:
        """Joint rate k (0 A, 1 B, 2 C) over the sweep."""
        if self.rates[k] is None:
            self.rates[k] = self.solve(self.loop, k)
        return self.rates[k]

    def reaction(self, rhs0: FloatArray, rhs2: FloatArray) -> FloatArray:
        """(3, n) M⁻ᵀ·(rhs0, 0, rhs2) (``kinetostatics.solve_transposed``): the load W_B
        of the force stage."""
        out = np.empty((3, self.usable.shape[0]))
        for c, row in enumerate(out):
            first, second = self.entry(0, c), self.entry(2, c)
            if _zero(first):
                np.multiply(second, rhs2, out=row)
            else:
                np.multiply(first, rhs0, out=row)
                if not _zero(second):
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
        (formed on first use, ``inverse3``)."""
        if self._inverse is None:
            self._inverse = np.empty((3, 3, self.usable.shape[0]))
            for k in range(3):
                for c in range(3):
                    value = self.entry(k, c)
                    self._inverse[k, c] = value if not _zero(value) else self.scale(k) * 0.0
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
    closes = np.empty((n, count), dtype=bool)
    transmission = np.empty((n, count))
    singular = np.empty((n, count), dtype=bool)
    conditioning = np.empty((n, count))
    # twists of the moving links and their time derivatives, in components; the frame's
    # are zero (not in the dicts)
    px, py = (float(v) for v in mechanism.crank.pivot)
    speed = mechanism.crank.speed if crank_speed is None else np.broadcast_to(crank_speed, (n,))
    twists = {CRANK: (_mul(py, speed), _mul(-px, speed), speed)}
    changes = {}  # constant speed about a fixed pivot: zero
    if crank_acceleration is not None and np.any(crank_acceleration):
        rate = np.broadcast_to(crank_acceleration, (n,))
        changes[CRANK] = (_mul(py, rate), _mul(-px, rate), rate)
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
        np.less(closure.conditioning, dyad_kinds.SINGULAR_SIN, out=singular[:, col])
        singular[:, col] &= ok
        usable = ok & ~singular[:, col]
        groups.append(_derivatives(dyad, closure, motion, twists, changes, usable))
        upstream_ok = usable
    return Kinematics(crank_angle, motion, closes, transmission, singular, conditioning,
                      groups, upstream_ok)


def _unit(joint: Joint, motion: Motion, on: int, closure, k: int) -> tuple:
    """Unit twist of joint k of a dyad (``dyade.linkage.motion.screw``) in components,
    from the closure's pin or guide where it found one."""
    if isinstance(joint, Revolute):
        x, y = closure.pins[k] if k in closure.pins else motion.point_xy(joint.links[0],
                                                                         joint.points[0])
        return y, _mul(-1.0, x), 1.0
    dx, dy = closure.guides[k] if k in closure.guides else guide_direction(joint, motion)
    if on == joint.slider:
        return dx, dy, 0.0
    return _mul(-1.0, dx), _mul(-1.0, dy), 0.0


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
    group.loop = loop = tuple(_sub(a, b) for a, b in zip(v_h, v_g))
    rate_a, rate_b = group.rate(0), group.rate(1)
    v_i = twists[i] = _advance(v_g, rate_a, units[0])
    v_j = twists[j] = _advance(v_i, rate_b, units[1])
    # M·ṙ = A_h − A_g − V_g×V_i − V_i×V_j + V_h×V_j (ω part: α_h − α_g)
    turn_gi, turn_ij, turn_hj = turn(v_g, v_i), turn(v_i, v_j), turn(v_h, v_j)
    a_g, a_h = changes.get(g, zero), changes.get(h, zero)
    bias = (_add(_sub(_sub(_sub(a_h[0], a_g[0]), turn_ij[0]), turn_gi[0]), turn_hj[0]),
            _add(_sub(_sub(_sub(a_h[1], a_g[1]), turn_ij[1]), turn_gi[1]), turn_hj[1]),
            _sub(a_h[2], a_g[2]))
    accel_a, accel_b = group.solve(bias, 0), group.solve(bias, 1)  # ċ is not needed
    a_i = changes[i] = _advance(a_g, accel_a, units[0], turn_gi)
    a_j = changes[j] = _advance(a_i, accel_b, units[1], turn_ij)
    _frame_motion(motion, i, v_i, a_i)
    _frame_motion(motion, j, v_j, a_j)
    return group


def turn(v: tuple, w: tuple) -> tuple:
    """(x, y) of the twist cross product V×W = (ω_V·E·w − ω_W·E·v, 0): the rate of
    change of a twist W fixed in a body that moves with V (components)."""
    return (_sub(_mul(w[2], v[1]), _mul(v[2], w[1])),
            _sub(_mul(v[2], w[0]), _mul(w[2], v[0])))


def _advance(base: tuple, rate: FloatArray, unit: tuple, extra: tuple = (0.0, 0.0)) -> tuple:
    """base + rate·unit (+ extra in x, y), twists in components."""
    return (_add(_add(base[0], _mul(rate, unit[0])), extra[0]),
            _add(_add(base[1], _mul(rate, unit[1])), extra[1]),
            _add(base[2], _mul(rate, unit[2])))


def _frame_motion(motion: Motion, link: int, twist: tuple, change: tuple) -> None:
    """Velocity and acceleration of a link frame's origin r from the link's twist:
    v = v_O + ω·E·r,  a = A_O + α·E·r + ω·E·v."""
    x, y = motion.origin[:, link, 0], motion.origin[:, link, 1]
    omega, alpha = twist[2], change[2]
    vx, vy = motion.velocity[:, link, 0], motion.velocity[:, link, 1]
    vx[:] = _sub(twist[0], _mul(omega, y))
    vy[:] = _add(twist[1], _mul(omega, x))
    motion.omega[:, link] = omega
    ax, ay = motion.acceleration[:, link, 0], motion.acceleration[:, link, 1]
    ax[:] = _sub(_sub(change[0], _mul(alpha, y)), _mul(omega, vy))
    ay[:] = _add(_add(change[1], _mul(alpha, x)), _mul(omega, vx))
    motion.alpha[:, link] = alpha


# -- derived quantities the reports use --------------------------------------------
def joint_point(joint: Revolute, motion: Motion) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Position, velocity, acceleration of a revolute joint (on its first link)."""
    link, local = joint.links[0], joint.points[0]
    if link == FRAME:
        link, local = joint.links[1], joint.points[1]
    return (motion.point(link, local), motion.point_velocity(link, local),
            motion.point_acceleration(link, local))

