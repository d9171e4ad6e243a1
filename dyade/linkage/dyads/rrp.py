"""Kind 2, RRP: circle about A meets the guide line at C (closed form derived for dyade).

Variant +1: B lies ahead of the foot point of A in the guide direction.
"""

from __future__ import annotations

import numpy as np

from dyade.linkage import dyads
from dyade.linkage.motion import Motion, dot, perp
from dyade.linkage.model import Dyad, Revolute



def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    i, j = dyad.links
    _, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    a, a_i = dyads.pin(joint_a, i, motion)
    b_i, b_j = dyads.ends(joint_b, i)
    dyads.carry_angle(joint_c, h, j, motion)
    normal, offset = dyads.guide_line(joint_c, j, motion)
    offset = offset + dot(normal, motion.rotated(j, b_j))  # now normal·B = offset
    direction = -perp(normal)
    arm_i = np.subtract(b_i, a_i)
    length = np.hypot(*arm_i)
    height = offset - dot(normal, a)
    along_sq = length ** 2 - height ** 2
    closes = along_sq >= -1e-12 * length ** 2
    along = np.sqrt(np.where(closes, np.maximum(along_sq, 0.0), np.nan))
    b = a + height[:, None] * normal + dyad.variant * along[:, None] * direction
    ab = b - a
    dyads.orient(motion, i, ab[:, 0], ab[:, 1], arm_i, length, a[:, 0], a[:, 1], a_i)
    motion.origin[:, j] = b - motion.rotated(j, b_j)
    return dyads.Closure(closes, dyads.angle_between(ab, normal))


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
