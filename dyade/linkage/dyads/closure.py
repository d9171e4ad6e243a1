"""What the closures of the dyad kinds share: the ``Closure`` they return, and the
steps they are written in (a pin from its known side, a link oriented along a vector,
a link carried across a prismatic joint, the guide as a line, two lines crossing), in
components (``dyade.linkage.components``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from dyade.arrays import FloatArray, Vec
from dyade.linkage.components import direction_xy, full, minus, plus, pose, rotate_xy
from dyade.linkage.motion import Motion
from dyade.model.mechanism import FRAME, Prismatic, Revolute

SINGULAR_SIN = 1e-10  # [-] |sin μ| below this: the closure Jacobian is singular


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Closure:
    """Where a dyad closes, and its transmission angle."""

    closes: FloatArray
    """(n,) bool: the dyad can be assembled (and is not blocked)"""
    transmission: FloatArray
    """(n,) transmission angle μ in [0, π] [rad]; NaN where it does not close"""
    conditioning: FloatArray | None = None
    """(n,) in [0, 1]: how far from singular the closure Jacobian is (0: dead centre or
    blocked); |sin μ| unless the kind says otherwise (RPR: also the lever arm)"""
    pins: dict = field(default_factory=dict)
    """joint index (0 A, 1 B, 2 C) -> world position (x, y) of a revolute joint the
    closure found on the way (saves recomputing it for the joint's twist)"""
    guides: dict = field(default_factory=dict)
    """joint index -> world guide direction (dx, dy) of a prismatic joint (likewise)"""
    lever: FloatArray | None = None
    """(n,) [m] a distance whose vanishing also makes the closure singular although the
    transmission angle stays away from 0° and 180° (RPR: the pivot distance ρ); it
    scales the conditioning by min(1, lever/ℓ), ℓ the crank length"""

    def __post_init__(self) -> None:
        if self.conditioning is None:
            self.conditioning = np.abs(np.sin(self.transmission))


def pin_xy(joint: Revolute, unknown: int, motion: Motion) -> tuple[tuple, Vec]:
    """Components of a revolute joint's world position, from its known side (plain
    numbers when that is the frame), and its local point on the ``unknown`` link."""
    (p, q), (u_p, u_q) = joint.links, joint.points
    known, local, other = (q, u_q, u_p) if p == unknown else (p, u_p, u_q)
    if known == FRAME:
        return (scalar(local[0]), scalar(local[1])), other
    cos, sin, ox, oy = pose(motion, known)
    rx, ry = rotate_xy(cos, sin, local)
    return (plus(ox, rx), plus(oy, ry)), other


def pin(joint: Revolute, unknown: int, motion: Motion) -> tuple[tuple, Vec]:
    """``pin_xy`` with a frame point taken as the frame's origin plus the point (a zero
    coordinate is +0.0, as ``Motion.point`` gives it: the sign of a zero decides the
    branch of an arctan2 at ±180°)."""
    (x, y), other = pin_xy(joint, unknown, motion)
    if type(x) is float:
        return (0.0 + x, 0.0 + y), other
    return (x, y), other


def orient(motion: Motion, link: int, wx: FloatArray, wy: FloatArray, arm: FloatArray,
           length: float, px, py, local: Vec, direction: FloatArray | None = None) -> None:
    """Place a link whose local vector ``arm`` (of ``length``) lies along the world
    vector (wx, wy) of the same length, with its local point ``local`` on (px, py):
    the cosine and sine of its angle come without trigonometric functions
    (``direction``: the angle of (wx, wy) [rad], where the caller has it)."""
    beta = arm_angle(arm)
    cos, sin, angle = motion.cos[:, link], motion.sin[:, link], motion.angle[:, link]
    if direction is None:
        np.arctan2(wy, wx, out=angle)
    else:
        angle[:] = direction
    if is_nought(beta):
        np.divide(wx, length, out=cos)
        np.divide(wy, length, out=sin)
    else:
        ex, ey = wx / length, wy / length
        cb, sb = np.cos(beta), np.sin(beta)
        np.add(ex * cb, ey * sb, out=cos)
        np.subtract(ey * cb, ex * sb, out=sin)
        angle -= beta
    if is_nought(local[0]) and is_nought(local[1]):
        motion.origin[:, link, 0] = px
        motion.origin[:, link, 1] = py
    else:
        rx, ry = motion.rotated_xy(link, local)
        motion.origin[:, link, 0] = px - rx
        motion.origin[:, link, 1] = py - ry


def between(first: FloatArray, second: FloatArray) -> FloatArray:
    """The angle [rad] in [0, π] between two directions given by their angles [rad]
    (each in [−π, π], as ``np.arctan2`` gives them)."""
    turned = np.abs(first - second)
    return np.where(turned > np.pi, 2.0 * np.pi - turned, turned)


def arm_angle(arm) -> float | FloatArray:
    """The angle of a local vector [rad] (a float, or one per position): exactly 0.0
    (of the y part's sign) without an arctangent for one along +x, as a link's length
    as a parameter of a study gives it (one value per variant and position)."""
    if np.ndim(arm[1]) == 0 and arm[1] == 0.0 and np.all(np.greater(arm[0], 0.0)):
        return float(arm[1])  # arctan2(±0, x > 0) = ±0
    return scalar(np.arctan2(arm[1], arm[0]))


def scalar(value):
    """A plain float for a number, or for an array (a variant's number per position,
    ``dyade.linkage.stack``) that holds one number throughout (an angle of 0 of links of
    different lengths); another array as it is."""
    if np.ndim(value) == 0:
        return float(value)
    first = value.flat[0]
    return float(first) if (value == first).all() else value


def is_nought(value) -> bool:
    """A number (not a per-position array) that is zero."""
    return np.ndim(value) == 0 and value == 0.0


def difference(a: Vec, b: Vec) -> tuple:
    """a − b of two local points, component-wise (numbers or per-position arrays)."""
    if np.ndim(a[0]) == np.ndim(a[1]) == np.ndim(b[0]) == np.ndim(b[1]) == 0:
        return np.subtract(a, b)
    return (np.subtract(a[0], b[0]), np.subtract(a[1], b[1]))


def length(arm) -> float | FloatArray:
    """|arm| (a float, or one per position; hypot(x, ±0) = |x| exactly)."""
    if np.ndim(arm[1]) == 0 and arm[1] == 0.0:
        return scalar(np.abs(arm[0]))
    return scalar(np.hypot(arm[0], arm[1]))


def same_pins(joints: dict) -> dict:
    """The pins a closure passes on: joint index -> (joint, unknown link, world (x, y)
    found from the known side) for those whose twist would be computed from that side
    anyway (a revolute joint's unit twist, ``dyade.linkage.kinematics``, takes its
    position from the joint's first link)."""
    return {k: xy for k, (joint, unknown, xy) in joints.items() if joint.links[0] != unknown}


def ends(joint: Revolute, first: int) -> tuple[Vec, Vec]:
    """A revolute joint's local points, the one on link ``first`` first."""
    return joint.points if joint.links[0] == first else joint.points[::-1]


def carry(joint: Prismatic, known: int, unknown: int, motion: Motion) -> tuple:
    """Set the angle of the link across a prismatic joint from ``known`` (φ_s − φ_c = κ);
    returns its cos and sin (plain numbers when ``known`` is the frame)."""
    offset = joint.relative_angle if joint.carrier == known else -joint.relative_angle
    if known != FRAME:
        return turn(motion, unknown, known, offset)
    cos, sin = scalar(np.cos(offset)), scalar(np.sin(offset))
    motion.angle[:, unknown] = offset
    motion.cos[:, unknown] = cos
    motion.sin[:, unknown] = sin
    return cos, sin


def turn(motion: Motion, link: int, known: int, offset: float) -> tuple:
    """φ_link = φ_known + offset (``Motion.turn_with``, a copy for no offset); returns
    the link's cos and sin."""
    if is_nought(offset):
        for array in (motion.angle, motion.cos, motion.sin):
            array[:, link] = array[:, known]
    else:
        motion.turn_with(link, known, offset)
    return motion.cos[:, link], motion.sin[:, link]


def guide_line(joint: Prismatic, unknown: int, motion: Motion, cos, sin) -> tuple:
    """The prismatic constraint as a line for the origin of a translating link.

    ``cos``, ``sin``: the ``unknown`` link's, already set; the other link's whole pose
    is in ``motion``. Returns (d, c): the guide direction d = (dx, dy) and c with
    n·r_unknown = c, n = E·d the guide's left normal.
    """
    if joint.slider == unknown:
        c_c, s_c, ox, oy = pose(motion, joint.carrier)
        px, py = rotate_xy(c_c, s_c, joint.guide_point)
        wx, wy = rotate_xy(cos, sin, joint.slider_point)
    else:
        c_c, s_c = cos, sin
        c_s, s_s, ox, oy = pose(motion, joint.slider)
        px, py = rotate_xy(c_s, s_s, joint.slider_point)
        wx, wy = rotate_xy(cos, sin, joint.guide_point)
    dx, dy = direction_xy(joint, c_c, s_c)
    return (dx, dy), -dy * minus(plus(ox, px), wx) + dx * minus(plus(oy, py), wy)


def shift_line(c, dx, dy, cos, sin, local: Vec):
    """c + n·R(φ)·u: the line n·r = c of a link's origin moved to its point u."""
    if is_nought(local[0]) and is_nought(local[1]):
        return c
    ux, uy = rotate_xy(cos, sin, local)
    return c + (-dy * ux + dx * uy)


def crossing(nx, ny, c, mx, my, e, motion: Motion) -> tuple:
    """Intersection (x, y) of the lines n·r = c and m·r = e, and det = n × m (the sine of
    the angle between unit normals; 0: parallel, blocked): NaN where |det| is below
    ``SINGULAR_SIN``."""
    det = full(motion, nx * my - ny * mx)
    with np.errstate(all="ignore"):  # blocked (near-parallel) rows overflow; NaN below
        x = full(motion, (c * my - e * ny) / det)
        y = full(motion, (nx * e - mx * c) / det)
    blocked = np.abs(det) < SINGULAR_SIN
    if blocked.any():
        x[blocked] = np.nan
        y[blocked] = np.nan
    return x, y, det


def place_origin(motion: Motion, link: int, px, py, cos, sin, local: Vec) -> None:
    """Put a link's origin so that its point ``local`` lands on (px, py)."""
    rx, ry = rotate_xy(cos, sin, local)
    motion.origin[:, link, 0] = minus(px, rx)
    motion.origin[:, link, 1] = minus(py, ry)
