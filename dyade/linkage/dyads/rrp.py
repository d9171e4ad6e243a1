"""Kind 2, RRP: circle about A meets the guide line at C (SPEC §1).

Variant +1: B lies ahead of the foot point of A in the guide direction.
"""

from __future__ import annotations

import numpy as np

from dyade.linkage import dyads
from dyade.linkage.motion import Motion, dot, perp
from dyade.linkage.model import Dyad

NAME = "RRP"
JOINTS = "RRP"
HAS_VARIANT = True


def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    i, j = dyad.links
    _, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    a, a_i = dyads.pin(joint_a, i, motion)
    b_i, b_j = (joint_b.points if joint_b.links[0] == i else joint_b.points[::-1])
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
