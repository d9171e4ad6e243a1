"""The dyad kinds: one module each, and the registry that finds them.

Each kind module exports one description, ``KIND`` (a ``DyadKind``): its number and
name (the joint pattern A-B-C, as in the DYADE paper, Thümmel & Bartke 1987), whether
it has an assembly variant, its keys in a mechanism file with the construction of its
middle joint B and of the link frames, and its closed-form position closure
``close(dyad, motion) -> Closure``, which writes the poses of links i and j into
``motion`` (NaN where the dyad does not close) and returns where it closes and its
transmission angle. Velocities, accelerations and forces do not depend on the kind:
they come from the joints' twists (``dyade.linkage.motion``). No other module tests a
kind's number: adding a kind touches its module and ``REGISTRY`` only.

The transmission angle μ of a dyad is the angle between the two columns of its
2×2 closure Jacobian, so sin μ = 0 exactly at a dead centre or blocked position:

====  =====================================  ==========================
kind  μ is the angle between                 μ = 0° or 180° means
====  =====================================  ==========================
RRR   B−A and B−C (link i and link j at B)   stretched / folded dyad
RRP   B−A and the normal of guide C          link i normal to the guide
RPR   normal of guide B and (pivot − pivot)  slider at the foot point
PRP   guide A and guide C                    parallel guides: blocked
PPR   guide A and guide B                    parallel guides: blocked
====  =====================================  ==========================
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Callable, NamedTuple

import numpy as np

from dyade.linkage.motion import Motion
from dyade.linkage.model import CRANK, FRAME, FloatArray, Prismatic, Revolute, Vec

SINGULAR_SIN = 1e-10  # [-] |sin μ| below this: the closure Jacobian is singular

REGISTRY = ("rrr", "rrp", "rpr", "prp", "ppr")
"""Modules of the dyad kinds; kind number k is entry k (1-based), as in the paper."""


class DyadKind(NamedTuple):
    """What dyade knows of a dyad kind (one per kind module, ``KIND``)."""

    number: int
    """the paper's kind number ("Art") 1-5"""
    name: str
    """the joint pattern A-B-C: RRR, RRP, RPR, PRP, PPR"""
    has_variant: bool
    """two closures, chosen by the assembly variant ±1 (else one, variant 0)"""
    variant_rule: str
    """what variant +1 means (empty without a variant)"""
    frames: tuple[str, str]
    """the link frames of links i and j (origin, ξ axis)"""
    transmission: str
    """the two directions whose angle is the transmission angle μ"""
    singular: str
    """what μ = 0° or 180° is called: "dead centre" or "blocked position" """
    keys: frozenset
    """keys of a [[dyad]] table beyond the common ones"""
    middle: Callable
    """middle(reader, table, key, i, j, dyad_table, dyad_key) -> Joint: joint B from the
    file (``dyade.files.mechanism.Reader``), in the link frames above"""
    close: Callable
    """close(dyad, motion) -> Closure"""

    @property
    def cannot_close(self) -> str:
        """How a failed closure is said."""
        return "is blocked" if self.singular == "blocked position" else "cannot close"


def kind(number: int) -> DyadKind:
    """The kind with this number, its module imported when a mechanism first needs it
    (a four-bar run need not load the four other kinds)."""
    return importlib.import_module(f"dyade.linkage.dyads.{REGISTRY[number - 1]}").KIND


def named(value: object) -> DyadKind | None:
    """The kind a file names by number (1-5) or joint pattern ("RRP"); None if none."""
    if isinstance(value, str) and value.lower() in REGISTRY:
        return kind(REGISTRY.index(value.lower()) + 1)
    if isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= len(REGISTRY):
        return kind(value)
    return None


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
        return (float(local[0]), float(local[1])), other
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
           length: float, px, py, local: Vec) -> None:
    """Place a link whose local vector ``arm`` (of ``length``) lies along the world
    vector (wx, wy) of the same length, with its local point ``local`` on (px, py):
    the cosine and sine of its angle come without trigonometric functions."""
    beta = float(np.arctan2(arm[1], arm[0]))
    cos, sin, angle = motion.cos[:, link], motion.sin[:, link], motion.angle[:, link]
    np.arctan2(wy, wx, out=angle)
    if beta == 0.0:
        np.divide(wx, length, out=cos)
        np.divide(wy, length, out=sin)
    else:
        ex, ey = wx / length, wy / length
        cb, sb = np.cos(beta), np.sin(beta)
        np.add(ex * cb, ey * sb, out=cos)
        np.subtract(ey * cb, ex * sb, out=sin)
        angle -= beta
    if local[0] == 0.0 and local[1] == 0.0:
        motion.origin[:, link, 0] = px
        motion.origin[:, link, 1] = py
    else:
        rx, ry = motion.rotated_xy(link, local)
        motion.origin[:, link, 0] = px - rx
        motion.origin[:, link, 1] = py - ry


def same_pins(joints: dict) -> dict:
    """The pins a closure passes on: joint index -> (joint, unknown link, world (x, y)
    found from the known side) for those whose twist would be computed from that side
    anyway (a revolute joint's unit twist, ``dyade.linkage.kinematics``, takes its
    position from the joint's first link)."""
    return {k: xy for k, (joint, unknown, xy) in joints.items() if joint.links[0] != unknown}


def ends(joint: Revolute, first: int) -> tuple[Vec, Vec]:
    """A revolute joint's local points, the one on link ``first`` first."""
    return joint.points if joint.links[0] == first else joint.points[::-1]


# -- closures in components ---------------------------------------------------------
# A component is an (n,) array, or a plain number where it is the same at every position
# (the frame's pose, a guide on the frame): the arithmetic below works on both and skips
# what is known to be zero. The sums are written in the order of the vector forms they
# replace (``dot``, ``cross``, ``Motion.point``), so the positions are the same to the bit.
def pose(motion: Motion, link: int) -> tuple:
    """cos φ, sin φ and the origin (x, y) of a link; plain numbers for the frame, and
    for the crank's origin (its fixed pivot, ``dyade.linkage.kinematics.crank_motion``)."""
    if link == FRAME:
        return 1.0, 0.0, 0.0, 0.0
    cos, sin = motion.cos[:, link], motion.sin[:, link]
    if link == CRANK and motion.origin.shape[0]:
        return cos, sin, float(motion.origin[0, CRANK, 0]), float(motion.origin[0, CRANK, 1])
    return cos, sin, motion.origin[:, link, 0], motion.origin[:, link, 1]


def rotate_xy(cos, sin, local: Vec) -> tuple:
    """R(φ)·u from cos φ and sin φ (as ``Motion.rotated_xy``); (0.0, 0.0) for u = 0."""
    u, v = local
    if v == 0.0:
        if u == 0.0:
            return 0.0, 0.0
        return cos * u, sin * u
    return cos * u - sin * v, sin * u + cos * v


def is_zero(a) -> bool:
    """A plain number zero (not an array of zeros)."""
    return type(a) is float and a == 0.0


def _scalar_times(c: float, x):
    if c == 0.0:
        return 0.0
    if c == 1.0:
        return x
    return -x if c == -1.0 else c * x


def times(a, b):
    """a·b for components, skipping plain zeros and ±1 (the skipped products differ
    from the computed ones at most in the sign of a zero)."""
    if type(a) is float:
        return _scalar_times(a, b)
    if type(b) is float:
        return _scalar_times(b, a)
    return a * b


def plus(a, b):
    """a + b for components, skipping plain zeros."""
    if type(b) is float and b == 0.0:
        return a
    if type(a) is float and a == 0.0:
        return b
    return a + b


def minus(a, b):
    """a − b for components, skipping plain zeros."""
    if type(b) is float and b == 0.0:
        return a
    if type(a) is float and a == 0.0:
        return -b
    return a - b


def full(motion: Motion, value):
    """A component as an (n,) array (a closure of two frame-fixed joints is constant)."""
    if np.ndim(value) == 0:
        return np.full(motion.angle.shape[0], float(value))
    return value


def carry(joint: Prismatic, known: int, unknown: int, motion: Motion) -> tuple:
    """Set the angle of the link across a prismatic joint from ``known`` (φ_s − φ_c = κ);
    returns its cos and sin (plain numbers when ``known`` is the frame)."""
    offset = joint.relative_angle if joint.carrier == known else -joint.relative_angle
    if known != FRAME:
        return turn(motion, unknown, known, offset)
    cos, sin = float(np.cos(offset)), float(np.sin(offset))
    motion.angle[:, unknown] = offset
    motion.cos[:, unknown] = cos
    motion.sin[:, unknown] = sin
    return cos, sin


def turn(motion: Motion, link: int, known: int, offset: float) -> tuple:
    """φ_link = φ_known + offset (``Motion.turn_with``, a copy for no offset); returns
    the link's cos and sin."""
    if offset == 0.0:
        for array in (motion.angle, motion.cos, motion.sin):
            array[:, link] = array[:, known]
    else:
        motion.turn_with(link, known, offset)
    return motion.cos[:, link], motion.sin[:, link]


def direction_xy(joint: Prismatic, cos, sin) -> tuple:
    """World guide direction d of a prismatic joint from its carrier's cos and sin."""
    theta = joint.guide_angle
    return rotate_xy(cos, sin, (float(np.cos(theta)), float(np.sin(theta))))


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
    if local[0] == 0.0 and local[1] == 0.0:
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
