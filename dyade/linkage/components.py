"""Vectors in components: the arithmetic of the closures and of the loop solves.

A component is an (n,) array over the sweep, or a plain number where it is the same at
every position (the frame's pose, a guide on the frame, a crank turning about a fixed
pivot): the arithmetic below works on both and skips what is known to be zero. The sums
are written in the order of the vector forms they replace (dot and cross products,
``Motion.point``; ``tests/previous_closures.py`` keeps those forms), so the results are
the same to the bit. The dyad closures (``dyade.linkage.dyads``), the kinematics and the
kinetostatics share them.
"""

from __future__ import annotations

import numpy as np

from dyade.arrays import Vec
from dyade.linkage.motion import Motion
from dyade.model.mechanism import CRANK, FRAME, Prismatic


def pose(motion: Motion, link: int) -> tuple:
    """cos φ, sin φ and the origin (x, y) of a link; plain numbers for the frame, and
    for the crank's origin (its fixed pivot, ``dyade.linkage.kinematics.crank_motion``;
    not a sliding input's, ``Motion.pivoted``)."""
    if link == FRAME:
        return 1.0, 0.0, 0.0, 0.0
    cos, sin = motion.cos[:, link], motion.sin[:, link]
    if link == CRANK and motion.pivoted and motion.origin.shape[0]:
        return cos, sin, float(motion.origin[0, CRANK, 0]), float(motion.origin[0, CRANK, 1])
    return cos, sin, motion.origin[:, link, 0], motion.origin[:, link, 1]


def rotate_xy(cos, sin, local: Vec) -> tuple:
    """R(φ)·u from cos φ and sin φ (as ``Motion.rotated_xy``); (0.0, 0.0) for u = 0."""
    u, v = local
    if np.ndim(v) == 0 and v == 0.0:
        if np.ndim(u) == 0 and u == 0.0:
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


def direction_xy(joint: Prismatic, cos, sin) -> tuple:
    """World guide direction d of a prismatic joint from its carrier's cos and sin."""
    theta = joint.guide_angle
    if np.ndim(theta) == 0:
        return rotate_xy(cos, sin, (float(np.cos(theta)), float(np.sin(theta))))
    return rotate_xy(cos, sin, (np.cos(theta), np.sin(theta)))


def magnitude(x, y):
    """|(x, y)| of force or acceleration components as √(x² + y²): to about an ulp, three
    times as fast as ``np.hypot`` (whose care for magnitudes beyond 1e150 or below
    1e-150 no machine's force needs: a component beyond 1e154 gives inf, beyond
    ``columns.PLAUSIBLE`` either way). Every joint force's magnitude is this one
    (columns, summary, balance, accuracy), so that they agree to the bit."""
    size = np.multiply(x, x)
    size += np.multiply(y, y)
    return np.sqrt(size, out=size)
