"""Kind 5, PPR: link i slides on g, link j turns about C and slides on i (SPEC §1);
linear, one closure; blocked when guides A and B are parallel."""

from __future__ import annotations

from dyade.linkage import dyads
from dyade.linkage.motion import Motion, perp
from dyade.linkage.model import Dyad

NAME = "PPR"
JOINTS = "PPR"
HAS_VARIANT = False


def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    i, j = dyad.links
    g, _ = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    dyads.carry_angle(joint_a, g, i, motion)
    c, c_j = dyads.pin(joint_c, j, motion)
    dyads.carry_angle(joint_b, i, j, motion)
    motion.origin[:, j] = c - motion.rotated(j, c_j)
    n_a, c_a = dyads.guide_line(joint_a, i, motion)
    n_b, c_b = dyads.guide_line(joint_b, i, motion)
    origin, sin = dyads.solve_lines(n_a, c_a, n_b, c_b)
    motion.origin[:, i] = origin
    closes = abs(sin) >= dyads.SINGULAR_SIN
    return dyads.Closure(closes, dyads.angle_between(-perp(n_a), -perp(n_b)))
