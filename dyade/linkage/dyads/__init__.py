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

from dyade.linkage.motion import Motion, cross, dot, perp
from dyade.linkage.model import FRAME, FloatArray, Prismatic, Revolute, Vec

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
    lever: FloatArray | None = None
    """(n,) [m] a distance whose vanishing also makes the closure singular although the
    transmission angle stays away from 0° and 180° (RPR: the pivot distance ρ); it
    scales the conditioning by min(1, lever/ℓ), ℓ the crank length"""

    def __post_init__(self) -> None:
        if self.conditioning is None:
            self.conditioning = np.abs(np.sin(self.transmission))


def angle_between(u: FloatArray, v: FloatArray) -> FloatArray:
    """Angle between two vectors in [0, π] [rad]."""
    return np.arctan2(np.abs(cross(u, v)), dot(u, v))


def polar_angle(v: FloatArray | Vec) -> FloatArray:
    v = np.asarray(v, dtype=np.float64)
    return np.arctan2(v[..., 1], v[..., 0])


def pin_xy(joint: Revolute, unknown: int, motion: Motion) -> tuple[tuple, Vec]:
    """Components of a revolute joint's world position, from its known side (plain
    numbers when that is the frame), and its local point on the ``unknown`` link."""
    (p, q), (u_p, u_q) = joint.links, joint.points
    known, local, other = (q, u_q, u_p) if p == unknown else (p, u_p, u_q)
    if known == FRAME:
        return (float(local[0]), float(local[1])), other
    return motion.point_xy(known, local), other


def orient(motion: Motion, link: int, wx: FloatArray, wy: FloatArray, arm: FloatArray,
           length: float, px, py, local: Vec) -> None:
    """Place a link whose local vector ``arm`` (of ``length``) lies along the world
    vector (wx, wy) of the same length, with its local point ``local`` on (px, py):
    the cosine and sine of its angle come without trigonometric functions."""
    beta = float(np.arctan2(arm[1], arm[0]))
    ex, ey = wx / length, wy / length
    if beta == 0.0:
        cos, sin = ex, ey
    else:
        cb, sb = np.cos(beta), np.sin(beta)
        cos, sin = ex * cb + ey * sb, ey * cb - ex * sb
    angle = np.arctan2(wy, wx)
    motion.set_angle(link, angle - beta if beta else angle, cos, sin)
    if local[0] == 0.0 and local[1] == 0.0:
        motion.origin[:, link, 0] = px
        motion.origin[:, link, 1] = py
    else:
        rx, ry = motion.rotated_xy(link, local)
        motion.origin[:, link, 0] = px - rx
        motion.origin[:, link, 1] = py - ry


def pin(joint: Revolute, unknown: int, motion: Motion) -> tuple[FloatArray, Vec]:
    """World position of a revolute joint, from its known side, and its local point on
    the ``unknown`` link."""
    (p, q), (u_p, u_q) = joint.links, joint.points
    if p == unknown:
        return motion.point(q, u_q), u_p
    return motion.point(p, u_p), u_q


def ends(joint: Revolute, first: int) -> tuple[Vec, Vec]:
    """A revolute joint's local points, the one on link ``first`` first."""
    return joint.points if joint.links[0] == first else joint.points[::-1]


def carry_angle(joint: Prismatic, known: int, unknown: int, motion: Motion) -> None:
    """Set the angle of the link across a prismatic joint from ``known`` (φ_s − φ_c = κ)."""
    offset = joint.relative_angle if joint.carrier == known else -joint.relative_angle
    motion.turn_with(unknown, known, offset)


def guide_line(joint: Prismatic, unknown: int, motion: Motion) -> tuple[FloatArray, FloatArray]:
    """The prismatic constraint as a line for the origin of a translating link.

    The ``unknown`` link's angle must already be in ``motion``, the other link's whole
    pose too. Returns (normal, c) with normal·r_unknown = c, shapes (n, 2) and (n,).
    """
    normal = perp(motion.direction(joint.carrier, joint.guide_angle))
    if joint.slider == unknown:
        other = motion.point(joint.carrier, joint.guide_point)
        own = motion.rotated(unknown, joint.slider_point)
    else:
        other = motion.point(joint.slider, joint.slider_point)
        own = motion.rotated(unknown, joint.guide_point)
    return normal, dot(normal, other - own)


def place(motion: Motion, link: int, angle: FloatArray, world: FloatArray, local: Vec) -> None:
    """Set a link's angle and put its origin so that ``local`` lands on ``world``."""
    motion.set_angle(link, angle)
    motion.origin[:, link] = world - motion.rotated(link, local)


def solve_lines(n1: FloatArray, c1: FloatArray, n2: FloatArray, c2: FloatArray
                ) -> tuple[FloatArray, FloatArray]:
    """Intersection of n1·x = c1 and n2·x = c2, shape (n, 2); and the sine of the angle
    between the lines (0: parallel, blocked)."""
    det = cross(n1, n2)
    sin = det / np.sqrt(dot(n1, n1) * dot(n2, n2))
    blocked = np.abs(sin) < SINGULAR_SIN
    with np.errstate(all="ignore"):  # blocked (near-parallel) rows overflow; NaN below
        x = (c1 * n2[:, 1] - c2 * n1[:, 1]) / det
        y = (n1[:, 0] * c2 - n2[:, 0] * c1) / det
    point = np.stack((x, y), axis=-1)
    point[blocked] = np.nan
    return point, sin
