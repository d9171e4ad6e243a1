"""The positions-only stage: where the points asked for are, over blocks of variants ×
positions, and nothing else (issue 41, the first pass of a synthesis's search).

The crank, then each dyad's closed-form closure in assembly order (``dyade.linkage.dyads``,
the very closures of the full sweep), then the world positions of the points asked for;
no velocities, accelerations or forces. A mechanism's numbers may be one per (variant,
position), variant-major (``dyade.linkage.stack``): ``count`` variants over the same
crank angles are swept at once by ``positions(stacked, angle, ..., repeat=count)``.

>>> import numpy as np, dyade
>>> fourbar = dyade.read_mechanism("mechanisms/fourbar.toml")
>>> found = positions(fourbar, np.deg2rad([0.0, 90.0]), [(3, (0.1, 0.04))])
>>> found.points.shape, bool(found.closes.all())
((2, 1, 2), True)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray, Variants, Vec
from dyade.linkage import dyads
from dyade.linkage.components import direction_xy, full, minus, plus, rotate_xy, times
from dyade.linkage.dyads.closure import arm_angle, difference, ends, is_nought, length, scalar
from dyade.linkage.kinematics import cos_sin
from dyade.linkage.motion import Motion
from dyade.model.mechanism import CRANK, FRAME, Mechanism


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Positions:
    """The points asked for over the sweep, and where the linkage closes."""

    points: FloatArray
    """(n, points, 2) world positions of the points asked for [m]; NaN where a dyad on
    the way does not close"""
    closes: FloatArray
    """(n,) bool: every dyad closes at this position"""
    transmission: FloatArray | None
    """(n, dyads) transmission angle μ of each dyad [rad], NaN where it does not close;
    None when only the points were asked for (``angles=False``)"""
    conditioning: FloatArray
    """(n, dyads) distance from a dead centre in [0, 1] (|sin μ| for RRR)"""
    angles: FloatArray | None
    """(n, links) the link angles φ [rad] (the frame's 0), NaN where not placed; None
    when only the points were asked for (``angles=False``)"""


def positions(mechanism: Mechanism, crank_angle: FloatArray,
              points: Sequence[tuple[int, Vec]], repeat: int = 1,
              angles: bool = True) -> Positions:
    """World positions of ``points`` (link, local point (ξ, η) [m]) at every crank angle.

    Parameters
    ----------
    mechanism : Mechanism
        A mechanism, or variants of one stacked into one (its numbers one per
        (variant, position), ``dyade.linkage.stack``).
    crank_angle : ndarray, shape (n,)
        Crank angles φ21 [rad] (for ``count`` stacked variants over the same angles:
        ``np.tile(angle, count)``).
    points : sequence of (int, (ξ, η))
        The link and link-fixed point of each point asked for [m]; a coordinate may be
        one per position like any number of a stacked mechanism.
    repeat : int
        The crank angles are ``crank_angle`` repeated ``repeat`` times (``repeat``
        stacked variants over the same angles): their cosines and sines are taken once.
        The mechanism's numbers may then also be ``Variants`` (one per variant, as a
        block of variants is read at once, ``dyade.linkage.stack.spread``).
    angles : bool
        False: only the points (and where the linkage closes, and the conditioning) are
        wanted; no link angle and no transmission angle is taken, and a mechanism whose
        dyads are all RRR takes the angle-free path (cos/sin pairs over a grid of
        variants × positions, each variant's number a column), the same points to the
        bit.

    Returns
    -------
    Positions
    """
    turn = np.asarray(crank_angle, dtype=np.float64)
    if not angles and _fast_kinds(mechanism):
        return _angle_free(mechanism, turn, points, repeat)
    if repeat > 1:
        from dyade.linkage.stack import spread

        mechanism = spread(mechanism, turn.shape[0])
        points = [(link, tuple(np.repeat(np.asarray(v), turn.shape[0])
                               if isinstance(v, Variants) else v for v in local))
                  for link, local in points]
    n = turn.shape[0] * repeat
    motion = Motion.at_rest(n, mechanism.max_link + 1, tuple(mechanism.moving_links))
    motion.origin[:, CRANK] = mechanism.crank.pivot
    cos, sin = np.empty(turn.shape[0]), np.empty(turn.shape[0])
    cos_sin(turn, cos, sin)
    for array, values in ((motion.angle, turn), (motion.cos, cos), (motion.sin, sin)):
        array[:, CRANK].reshape(repeat, -1)[:] = values
    count = len(mechanism.dyads)
    transmission, conditioning = np.empty((n, count)), np.empty((n, count))
    ok = np.ones(n, dtype=bool)
    for col, dyad in enumerate(mechanism.dyads):
        closure = dyads.close(dyad, motion)
        ok &= closure.closes
        transmission[:, col] = closure.transmission
        conditioning[:, col] = closure.conditioning
        if not ok.all():
            bad = ~ok
            transmission[bad, col] = np.nan
            conditioning[bad, col] = np.nan
            for link in dyad.links:
                motion.invalidate(link, bad)
    out = np.empty((n, len(points), 2))
    for k, (link, local) in enumerate(points):
        out[:, k, 0], out[:, k, 1] = motion.point_xy(link, local)
    if not angles:
        return Positions(out, ok, None, conditioning, None)
    return Positions(out, ok, transmission, conditioning, motion.angle)


# -- the angle-free path ----------------------------------------------------------------
# Only the points are asked for (``angles=False``) and every dyad has a fast closure: the
# links' poses are kept as cos/sin pairs and origins over a (variants, positions) grid,
# each number of a variant a (variants, 1) column broadcast over the positions (a block
# of candidates × positions costs what the closed form costs), no angle and no
# transmission angle taken. The arithmetic is the generic closures', operation for
# operation (``dyade.linkage.dyads.rrr``, ``closure.orient``, ``Motion.point_xy``), so the
# points and the conditioning are the same to the bit.

def _fast_kinds(mechanism: Mechanism) -> bool:
    return all(dyad.kind.name in _FAST for dyad in mechanism.dyads)


class _Grid:
    """The numbers of a mechanism over variants lo..hi−1 × positions (``at``): a plain
    float, a (rows, 1) column for a number per variant (``Variants``), a (rows,
    positions) view for a number per (variant, position); each number looked at once."""

    def __init__(self, count: int, steps: int) -> None:
        self.count, self.steps = count, steps
        self.lo, self.hi = 0, count
        self.seen: dict = {}

    def at(self, lo: int, hi: int) -> _Grid:
        self.lo, self.hi = lo, hi
        return self

    def __call__(self, value):
        if type(value) is float:
            return value
        key = id(value)
        whole = self.seen.get(key)
        if whole is None:
            if isinstance(value, Variants):
                whole = scalar(np.asarray(value)[:, None])
            elif np.ndim(value) == 0:
                whole = float(value)
            else:
                whole = scalar(np.asarray(value).reshape(self.count, self.steps))
            self.seen[key] = whole = (value, whole)  # the value kept alive: its id stays
        whole = whole[1]
        return whole if type(whole) is float else whole[self.lo:self.hi]

    def point(self, local) -> tuple:
        return self(local[0]), self(local[1])


def _pin(joint, unknown: int, poses: dict, grid: _Grid) -> tuple:
    """``closure.pin_xy`` on the grid."""
    (p, q), (u_p, u_q) = joint.links, joint.points
    known, local, other = (q, u_q, u_p) if p == unknown else (p, u_p, u_q)
    local, other = grid.point(local), grid.point(other)
    if known == FRAME:
        return local, other
    cos, sin, ox, oy = _pose(poses, known)
    rx, ry = rotate_xy(cos, sin, local)
    return (plus(ox, rx), plus(oy, ry)), other


def _pose(poses: dict, link: int) -> tuple:
    """A link's (cos, sin, ox, oy), worked out now if it was left for later."""
    pose = poses[link]
    if callable(pose):
        poses[link] = pose = pose()
    return pose


def _rotated(cos, sin, local) -> tuple:
    """``Motion.rotated_xy``."""
    u, v = local
    if np.ndim(v) == 0 and v == 0.0:
        return cos * u, sin * u
    return cos * u - sin * v, sin * u + cos * v


def _orient(wx, wy, arm, length, px, py, local) -> tuple:
    """``closure.orient`` without the angle: the link's (cos, sin, ox, oy)."""
    beta = arm_angle(arm)
    if is_nought(beta):
        cos, sin = wx / length, wy / length
    else:
        ex, ey = wx / length, wy / length
        cb, sb = np.cos(beta), np.sin(beta)
        cos, sin = ex * cb + ey * sb, ey * cb - ex * sb
    if is_nought(local[0]) and is_nought(local[1]):
        return cos, sin, px, py
    rx, ry = _rotated(cos, sin, local)
    return cos, sin, px - rx, py - ry


def _rrr(dyad, poses: dict, grid: _Grid, out) -> FloatArray:
    """``dyads.rrr.close`` on the grid: closes; the conditioning into ``out`` (a
    (variants, positions) view)."""
    i, j = dyad.links
    joint_a, joint_b, joint_c = dyad.joints
    (ax, ay), a_i = _pin(joint_a, i, poses, grid)
    (cx, cy), c_j = _pin(joint_c, j, poses, grid)
    b_i, b_j = ends(joint_b, i)
    arm_i, arm_j = difference(grid.point(b_i), a_i), difference(grid.point(b_j), c_j)
    l_i, l_j = length(arm_i), length(arm_j)
    # the generic closure's operations, in place where an operand is an array of the grid
    dx, dy = np.subtract(cx, ax), np.subtract(cy, ay)
    shape = (grid.hi - grid.lo, grid.steps)
    if np.shape(dx) != shape or np.shape(dy) != shape:  # a group fixed to the frame
        dx, dy = (np.array(np.broadcast_to(v, shape), dtype=np.float64) for v in (dx, dy))
    dist_sq = dx * dx
    work = dy * dy
    dist_sq += work
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inverse = np.sqrt(dist_sq)
        np.divide(1.0, inverse, out=inverse)
        along = dist_sq
        along += l_i * l_i - l_j * l_j
        np.multiply(0.5, inverse, out=work)
        along *= work
        height = np.multiply(along, along, out=work)
        np.subtract(l_i * l_i, height, out=height)
        closes = height >= -1e-12 * l_i * l_i
        ux, uy = dx * inverse, np.multiply(dy, inverse, out=inverse)
    np.maximum(height, 0.0, out=height)
    np.sqrt(height, out=height)
    if not closes.all():
        height[~closes] = np.nan
    side = height if dyad.variant > 0 else np.negative(height, out=height)
    bax, bay = along * ux, along * uy
    np.multiply(side, uy, out=uy)
    bax -= uy
    np.multiply(side, ux, out=ux)
    bay += ux
    # B − C = (A − C) + (B − A) = (B − A) − (C − A): the generic closure's sum to the
    # bit (A − C = −(C − A) exactly; a zero's sign aside, which no point or conditioning
    # below keeps), without taking A − C again
    bcx, bcy = np.subtract(bax, dx, out=dx), np.subtract(bay, dy, out=dy)
    # a link's pose is worked out when first wanted (a rocker no point is asked on: never)
    poses[i] = lambda: _orient(bax, bay, arm_i, l_i, ax, ay, a_i)
    poses[j] = lambda: _orient(bcx, bcy, arm_j, l_j, cx, cy, c_j)
    sin = np.multiply(bax, bcy, out=out)
    sin -= np.multiply(bay, bcx, out=ux)
    np.abs(sin, out=sin)
    sin /= l_i * l_j
    return closes


CACHE_ELEMENTS = 32_768
"""[-] about this many (variant, position) pairs at once on the angle-free path: a few
dozen arrays of them stay in the processor's cache"""


def _angle_free(mechanism: Mechanism, turn: FloatArray, points, repeat: int) -> Positions:
    steps = turn.shape[0]
    n = steps * repeat
    cos, sin = np.empty(steps), np.empty(steps)
    cos_sin(turn, cos, sin)
    crank = (cos[None, :], sin[None, :])
    count = len(mechanism.dyads)
    conditioning = np.empty((repeat, steps, count))
    ok = np.ones((repeat, steps), dtype=bool)
    out = np.empty((repeat, steps, len(points), 2))
    rows = max(1, CACHE_ELEMENTS // max(steps, 1))
    grid = _Grid(repeat, steps)
    for lo in range(0, repeat, rows):
        hi = min(lo + rows, repeat)
        grid.at(lo, hi)
        _chunk(mechanism, grid, crank, points, ok[lo:hi], conditioning[lo:hi], out[lo:hi])
    return Positions(out.reshape(n, len(points), 2), ok.reshape(n), None,
                     conditioning.reshape(n, count), None)


def _chunk(mechanism: Mechanism, grid: _Grid, crank: tuple, points, ok, conditioning,
           out) -> None:
    """Variants grid.lo..grid.hi−1: their closes, conditioning and points into the
    given slices."""
    shape = ok.shape
    px, py = grid.point(mechanism.crank.pivot)
    poses = {FRAME: (1.0, 0.0, 0.0, 0.0), CRANK: (crank[0], crank[1], px, py)}
    for col, dyad in enumerate(mechanism.dyads):
        closes = _FAST[dyad.kind.name](dyad, poses, grid, conditioning[:, :, col])
        ok &= closes
        if not ok.all():
            bad = ~ok
            conditioning[:, :, col][bad] = np.nan
            for link in dyad.links:
                pose = [np.array(np.broadcast_to(v, shape)) for v in _pose(poses, link)]
                for v in pose:
                    v[bad] = np.nan
                poses[link] = tuple(pose)
    for k, (link, local) in enumerate(points):
        c, s, ox, oy = _pose(poses, link)
        x, y = _rotated(c, s, grid.point(local))
        np.add(ox, x, out=out[:, :, k, 0])
        np.add(oy, y, out=out[:, :, k, 1])


def _carry(joint, known: int, unknown: int, poses: dict, grid: _Grid) -> tuple:
    """``closure.carry`` on the grid: the cos and sin of the link across a prismatic
    joint from ``known``."""
    offset = grid(joint.relative_angle)
    if joint.carrier != known:
        offset = -offset
    if known == FRAME:
        return scalar(np.cos(offset)), scalar(np.sin(offset))
    ck, sk = _pose(poses, known)[:2]
    if is_nought(offset):
        return ck, sk
    c, s = np.cos(offset), np.sin(offset)
    return ck * c - sk * s, sk * c + ck * s


def _guide_line(joint, unknown: int, poses: dict, grid: _Grid, cos, sin) -> tuple:
    """``closure.guide_line`` on the grid."""
    if joint.slider == unknown:
        c_c, s_c, ox, oy = _pose(poses, joint.carrier)
        px, py = rotate_xy(c_c, s_c, grid.point(joint.guide_point))
        wx, wy = rotate_xy(cos, sin, grid.point(joint.slider_point))
    else:
        c_c, s_c = cos, sin
        c_s, s_s, ox, oy = _pose(poses, joint.slider)
        px, py = rotate_xy(c_s, s_s, grid.point(joint.slider_point))
        wx, wy = rotate_xy(cos, sin, grid.point(joint.guide_point))
    theta = grid(joint.guide_angle)
    if type(theta) is float:
        dx, dy = rotate_xy(c_c, s_c, (float(np.cos(theta)), float(np.sin(theta))))
    else:
        dx, dy = rotate_xy(c_c, s_c, (np.cos(theta), np.sin(theta)))
    return (dx, dy), -dy * minus(plus(ox, px), wx) + dx * minus(plus(oy, py), wy)


def _rrp(dyad, poses: dict, grid: _Grid, out) -> FloatArray:
    """``dyads.rrp.close`` on the grid: closes; the conditioning into ``out``."""
    i, j = dyad.links
    _, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    (ax, ay), a_i = _pin(joint_a, i, poses, grid)
    shape = (grid.hi - grid.lo, grid.steps)
    if type(ax) is float:
        ax = 0.0 + ax
    if type(ay) is float:
        ay = 0.0 + ay
    if h == FRAME:  # A on the frame too: a constant group
        ax, ay = (np.array(np.broadcast_to(v, shape), dtype=np.float64) for v in (ax, ay))
    b_i, b_j = (grid.point(b) for b in ends(joint_b, i))
    c_j, s_j = _carry(joint_c, h, j, poses, grid)
    (dx, dy), offset = _guide_line(joint_c, j, poses, grid, c_j, s_j)
    nx, ny = -dy, dx
    if not (is_nought(b_j[0]) and is_nought(b_j[1])):  # closure.shift_line
        ux, uy = rotate_xy(c_j, s_j, b_j)
        offset = offset + (-dy * ux + dx * uy)
    arm_i = (b_i[0] - a_i[0], b_i[1] - a_i[1])
    l_i = length(arm_i)
    height = minus(offset, plus(times(nx, ax), times(ny, ay)))
    along = l_i ** 2 - height ** 2
    closes = along >= -1e-12 * l_i ** 2
    np.maximum(along, 0.0, out=along)
    if not closes.all():
        along[~closes] = np.nan
    np.sqrt(along, out=along)
    if dyad.variant < 0:
        np.negative(along, out=along)
    bx = plus(plus(ax, times(height, nx)), times(along, dx))
    by = plus(plus(ay, times(height, ny)), times(along, dy))
    abx, aby = bx - ax, by - ay
    poses[i] = lambda: _orient(abx, aby, arm_i, l_i, ax, ay, a_i)
    rx, ry = rotate_xy(c_j, s_j, b_j)  # closure.place_origin
    poses[j] = (c_j, s_j, minus(bx, rx), minus(by, ry))
    sin = np.abs(minus(times(abx, ny), times(aby, nx)), out=out)
    sin /= l_i
    return closes


_FAST = {"RRR": _rrr, "RRP": _rrp}
"""the dyad kinds the angle-free path closes itself (the others: the generic path)"""
