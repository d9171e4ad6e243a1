"""Kind 2, RRP: circle about A meets the guide line at C (closed form derived for dyade).

Variant +1: B lies ahead of the foot point of A in the guide direction.
"""

from __future__ import annotations

import numpy as np

from dyade.linkage.components import full, minus, plus, times
from dyade.linkage.dyads.closure import (Closure, carry, ends, guide_line, orient, pin,
                                         length as length_of,
                                         place_origin, same_pins, shift_line)
from dyade.linkage.motion import Motion
from dyade.model.mechanism import FRAME, Dyad


def close(dyad: Dyad, motion: Motion) -> Closure:
    """B on the circle about A (radius |AB|) and on the guide line: the guide's left
    normal n and direction d give B = A + h·n ± √(|AB|² − h²)·d, h the height of the
    line above A."""
    i, j = dyad.links
    _, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    (ax, ay), a_i = pin(joint_a, i, motion)
    if h == FRAME:  # A on the frame too: a constant group
        ax, ay = full(motion, ax), full(motion, ay)
    b_i, b_j = ends(joint_b, i)
    c_j, s_j = carry(joint_c, h, j, motion)
    (dx, dy), offset = guide_line(joint_c, j, motion, c_j, s_j)
    nx, ny = -dy, dx
    offset = shift_line(offset, dx, dy, c_j, s_j, b_j)  # now n·B = offset
    arm_i = (b_i[0] - a_i[0], b_i[1] - a_i[1])
    length = length_of(arm_i)
    height = minus(offset, plus(times(nx, ax), times(ny, ay)))
    along = length ** 2 - height ** 2
    closes = along >= -1e-12 * length ** 2
    np.maximum(along, 0.0, out=along)
    if not closes.all():
        along[~closes] = np.nan
    np.sqrt(along, out=along)
    if dyad.variant < 0:
        np.negative(along, out=along)
    bx = plus(plus(ax, times(height, nx)), times(along, dx))
    by = plus(plus(ay, times(height, ny)), times(along, dy))
    abx, aby = bx - ax, by - ay
    orient(motion, i, abx, aby, arm_i, length, ax, ay, a_i)
    place_origin(motion, j, bx, by, c_j, s_j, b_j)
    # μ between B − A and the guide normal n (|n| = 1)
    sin = np.abs(minus(times(abx, ny), times(aby, nx)))
    transmission = np.arctan2(sin, plus(times(abx, nx), times(aby, ny)))
    sin /= length
    return Closure(closes, transmission, sin,
                   same_pins({0: (joint_a, i, (ax, ay))}), {2: (dx, dy)})
