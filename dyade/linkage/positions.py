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

from dyade.arrays import FloatArray, Vec
from dyade.linkage import dyads
from dyade.linkage.kinematics import cos_sin
from dyade.linkage.motion import Motion
from dyade.model.mechanism import CRANK, Mechanism


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Positions:
    """The points asked for over the sweep, and where the linkage closes."""

    points: FloatArray
    """(n, points, 2) world positions of the points asked for [m]; NaN where a dyad on
    the way does not close"""
    closes: FloatArray
    """(n,) bool: every dyad closes at this position"""
    transmission: FloatArray
    """(n, dyads) transmission angle μ of each dyad [rad], NaN where it does not close"""
    conditioning: FloatArray
    """(n, dyads) distance from a dead centre in [0, 1] (|sin μ| for RRR)"""
    angles: FloatArray
    """(n, links) the link angles φ [rad] (the frame's 0), NaN where not placed"""


def positions(mechanism: Mechanism, crank_angle: FloatArray,
              points: Sequence[tuple[int, Vec]], repeat: int = 1) -> Positions:
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

    Returns
    -------
    Positions
    """
    turn = np.asarray(crank_angle, dtype=np.float64)
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
    return Positions(out, ok, transmission, conditioning, motion.angle)
