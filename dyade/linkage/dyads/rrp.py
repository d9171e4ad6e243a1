"""Kind 2, RRP: circle about A meets the guide line at C (closed form derived for dyade).

Variant +1: B lies ahead of the foot point of A in the guide direction.
"""

from __future__ import annotations

import numpy as np

from dyade.linkage import dyads
from dyade.linkage.motion import Motion
from dyade.linkage.model import FRAME, Dyad, Revolute


def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    """B on the circle about A (radius |AB|) and on the guide line: the guide's left
    normal n and direction d give B = A + h·n ± √(|AB|² − h²)·d, h the height of the
    line above A."""
    i, j = dyad.links
    _, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    (ax, ay), a_i = dyads.pin(joint_a, i, motion)
    if h == FRAME:  # A on the frame too: a constant group
        ax, ay = dyads.full(motion, ax), dyads.full(motion, ay)
    b_i, b_j = dyads.ends(joint_b, i)
    c_j, s_j = dyads.carry(joint_c, h, j, motion)
    (dx, dy), offset = dyads.guide_line(joint_c, j, motion, c_j, s_j)
    nx, ny = -dy, dx
    offset = dyads.shift_line(offset, dx, dy, c_j, s_j, b_j)  # now n·B = offset
    arm_i = (b_i[0] - a_i[0], b_i[1] - a_i[1])
    length = float(np.hypot(*arm_i))
    height = dyads.minus(offset, dyads.plus(dyads.times(nx, ax), dyads.times(ny, ay)))
    along = length ** 2 - height ** 2
    closes = along >= -1e-12 * length ** 2
    np.maximum(along, 0.0, out=along)
    if not closes.all():
        along[~closes] = np.nan
    np.sqrt(along, out=along)
    if dyad.variant < 0:
        np.negative(along, out=along)
    bx = dyads.plus(dyads.plus(ax, dyads.times(height, nx)), dyads.times(along, dx))
    by = dyads.plus(dyads.plus(ay, dyads.times(height, ny)), dyads.times(along, dy))
    abx, aby = bx - ax, by - ay
    dyads.orient(motion, i, abx, aby, arm_i, length, ax, ay, a_i)
    dyads.place_origin(motion, j, bx, by, c_j, s_j, b_j)
    # μ between B − A and the guide normal n (|n| = 1)
    sin = np.abs(dyads.minus(dyads.times(abx, ny), dyads.times(aby, nx)))
    transmission = np.arctan2(sin, dyads.plus(dyads.times(abx, nx), dyads.times(aby, ny)))
    sin /= length
    return dyads.Closure(closes, transmission, sin,
                         dyads.same_pins({0: (joint_a, i, (ax, ay))}), {2: (dx, dy)})


def middle(reader, table, key: str, i: int, j: int, dyad_table, dyad_key: str) -> Revolute:
    """Joint B from ``length = |AB|``: at (|AB|, 0) on link i, the origin of link j."""
    friction = reader.middle_revolute(table, key)
    l_i = reader.length_of(reader.required(dyad_table, "length", dyad_key), f"{dyad_key}.length",
                           positive=True)
    return Revolute((i, j), ((l_i, 0.0), (0.0, 0.0)), **friction)


KIND = dyads.DyadKind(
    2, "RRP", True, "B ahead of the foot point of A in the guide direction",
    ("origin A, ξ towards B", "origin B, ξ along the guide at C"),
    "B−A and the normal of guide C", "dead centre", frozenset({"length"}), middle, close)
