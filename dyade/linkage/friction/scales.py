"""The coupling of blocks: the scales the friction solution takes from the whole sweep
rather than from each position (``Coupling``), so that a block of positions is solved
exactly as within the whole sweep. The force floors come from about ``SAMPLE`` positions
(``sample``): the ``Coupling`` can be had from those alone (``solver.coupling``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray
from dyade.linkage.kinematics import Kinematics
from dyade.model.mechanism import CRANK

FORCE_FLOOR = 1e-12  # [-] share of a typical force below which changes are not relative
SAMPLE = 256  # the force floors are taken from about this many positions of the sweep


@dataclass(frozen=True, slots=True)
class Coupling:
    """What the friction solution takes from the whole sweep rather than from each
    position: given to ``solve`` for a block of positions, the block is solved exactly
    as within the whole sweep (``dyade.linkage.pipeline``; ``coupling`` computes it from
    the sample positions alone)."""

    speed: float
    """the typical crank speed [rad/s]: the sweep's largest |φ̇21| (else the file's);
    relative rates below ``AT_REST_RTOL`` of it (times the crank length for a slider)
    count as at rest"""
    floors: dict[tuple[int, int], float]
    """dyad (its links) -> force floor [N]: ``FORCE_FLOOR`` times the median size of its
    frictionless joint forces at the sample positions (``sample``), below which changes
    are not relative"""


def sample(positions: int) -> slice:
    """The positions of a sweep the force floors are taken from: every k-th, about
    ``SAMPLE`` of them."""
    return slice(None, None, max(1, positions // SAMPLE))


def top_speed(kin: Kinematics) -> float:
    """The largest crank speed |φ̇21| of ``kin`` [rad/s] (0 if none is finite)."""
    return float(np.nanmax(np.abs(kin.motion.omega[:, CRANK]), initial=0.0))


def force_size(w_b: FloatArray, q_i: FloatArray, q_j: FloatArray) -> FloatArray:
    """(n,) the size of a group's joint forces: the largest force component of its three
    joints (W_A = W_B − Q_i, W_B, W_C = −Q_j − W_B); against the frictionless one
    changes are relative (``passes.Rub.floored``: not below a small share of a typical value)."""
    scale = np.abs(w_b[0])
    for part in (w_b[1], w_b[0] - q_i[0], w_b[1] - q_i[1], w_b[0] + q_j[0], w_b[1] + q_j[1]):
        np.maximum(scale, np.abs(part), out=scale)
    return scale


def force_floor(scale: FloatArray, stride: int) -> float:
    """The force floor [N] of a group of force sizes ``scale``: ``FORCE_FLOOR`` times a
    typical size, not the largest (near a dead centre forces reach 1e30): the median of
    every ``stride``-th."""
    values = scale[::stride]
    values = values[np.isfinite(values) & (values > 0.0)]
    least = FORCE_FLOOR * (median(values) if values.size else 1.0)
    return max(least, 1e-300)


def median(values: FloatArray) -> float:
    """``np.median`` of finite values, to the bit, without what np.median imports on its
    first call (numpy.ma, about 17 ms of every friction run's start-up)."""
    middle = values.size // 2
    if values.size % 2:
        return float(np.partition(values, middle)[middle])
    part = np.partition(values, (middle - 1, middle))
    return float((part[middle - 1] + part[middle]) / 2.0)
