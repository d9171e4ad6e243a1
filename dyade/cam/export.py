"""The profile to manufacture: the points of a closed cam curve at a chord tolerance,
and the cutter's path.

A curve is given densely, by its closed form at many cam angles; ``chord_points`` keeps
as few of those points as leave every dense point within the tolerance of the chord
that spans it (the polygon through the kept points lies within the tolerance of the
curve, as far as the dense sampling resolves it: ``dense_count`` sizes it so that it
does).
"""

from __future__ import annotations

import numpy as np

from dyade.arrays import FloatArray

SAFETY = 0.7  # [-] first guess of the chord length as a share of √(8·tol·ρ)
MAX_ROUNDS = 12  # [-] halvings of the chord length at most


def dense_count(length: float, radius_min: float, tolerance: float, least: int = 3600) -> int:
    """Cam angles to sample a closed curve of length ``length`` [m] with a smallest radius
    of curvature ``radius_min`` [m] so that its chords at ``tolerance`` [m] hold at least
    ten dense points each: a chord of an arc of radius ρ with sagitta δ is √(8·δ·ρ) long."""
    chord = np.sqrt(8.0 * tolerance * max(radius_min, tolerance))
    return int(min(2_000_000, max(least, 10 * np.ceil(length / chord))))


def deviations(points: FloatArray, keep: FloatArray) -> FloatArray:
    """The distance [m] of each point of the closed polyline ``points`` (n, 2) from the
    chord of the kept points (indices ``keep``, increasing) that spans it."""
    n = points.shape[0]
    if keep[0] != 0:
        raise ValueError("the kept points must start at index 0")
    owner = np.searchsorted(keep, np.arange(n), side="right") - 1  # the chord from keep[owner]
    start, end = keep[owner], np.append(keep[1:], n)[owner] % n
    a, b = points[start], points[end]
    chord = b - a
    length = np.hypot(chord[:, 0], chord[:, 1])
    rel = points - a
    with np.errstate(divide="ignore", invalid="ignore"):  # a zero chord: the distance to a
        cross = np.abs(chord[:, 0] * rel[:, 1] - chord[:, 1] * rel[:, 0]) / length
    return np.where(length > 0.0, cross, np.hypot(rel[:, 0], rel[:, 1]))


def chord_points(points: FloatArray, radius: FloatArray, tolerance: float) -> FloatArray:
    """Indices of the points of a closed curve, sampled densely in ``points`` (n, 2),
    that make a polygon within ``tolerance`` [m] of every dense point.

    The chord length allowed at radius of curvature ρ is √(8·tol·|ρ|) (the sagitta of an
    arc); the kept points are placed by the running integral of ds/√(8·tol·|ρ|), then
    the chords are checked point by point and shortened until every dense point lies
    within the tolerance.

    Parameters
    ----------
    points : ndarray, shape (n, 2)
        The closed curve [m] (the last point is not the first again).
    radius : ndarray, shape (n,)
        Its radius of curvature [m] at each point (sign ignored).
    tolerance : float
        Chord tolerance [m].

    Returns
    -------
    ndarray of int
        Increasing indices into ``points``, the first 0.
    """
    step = np.hypot(*(np.roll(points, -1, axis=0) - points).T)
    radius = np.abs(np.asarray(radius, dtype=np.float64))
    radius = np.where(np.isfinite(radius), radius, np.inf)
    factor = SAFETY
    for _ in range(MAX_ROUNDS):
        allowed = factor * np.sqrt(8.0 * tolerance * np.maximum(radius, tolerance))
        count = np.concatenate(([0.0], np.cumsum(step / allowed)[:-1]))
        keep = np.flatnonzero(np.diff(np.floor(count), prepend=-1.0) > 0)
        if keep.size < 3:
            keep = np.unique(np.linspace(0, points.shape[0] - 1, 3).astype(int))
        if deviations(points, keep).max() <= tolerance:
            return keep
        factor /= 2.0
    return np.arange(points.shape[0])


def offset_curve(curve: FloatArray, normal: FloatArray, distance: float) -> FloatArray:
    """A curve moved by ``distance`` [m] along its unit ``normal`` (n, 2): the cutter
    centre's path of a cutter of radius r_c is the working curve moved outwards by r_c
    (for a roller cam: the pitch curve moved by r_c − r_r)."""
    return curve + distance * normal
