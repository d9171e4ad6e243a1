"""Kind 4, PRP: the pin B is where two guide lines cross; linear, one closure (derived
for dyade); blocked when the guides are parallel."""

from __future__ import annotations

from dyade.linkage import dyads
from dyade.linkage.motion import Motion, dot, perp
from dyade.linkage.model import Dyad, Revolute



def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    i, j = dyad.links
    g, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    b_i, b_j = dyads.ends(joint_b, i)
    dyads.carry_angle(joint_a, g, i, motion)
    dyads.carry_angle(joint_c, h, j, motion)
    n_a, c_a = dyads.guide_line(joint_a, i, motion)
    n_c, c_c = dyads.guide_line(joint_c, j, motion)
    c_a = c_a + dot(n_a, motion.rotated(i, b_i))
    c_c = c_c + dot(n_c, motion.rotated(j, b_j))
    b, sin = dyads.solve_lines(n_a, c_a, n_c, c_c)
    motion.origin[:, i] = b - motion.rotated(i, b_i)
    motion.origin[:, j] = b - motion.rotated(j, b_j)
    closes = abs(sin) >= dyads.SINGULAR_SIN
    return dyads.Closure(closes, dyads.angle_between(-perp(n_a), -perp(n_c)))


def middle(reader, table, key: str, i: int, j: int, dyad_table, dyad_key: str) -> Revolute:
    """Joint B: the pin at the origins of both links."""
    return Revolute((i, j), ((0.0, 0.0), (0.0, 0.0)), **reader.middle_revolute(table, key))


KIND = dyads.DyadKind(
    4, "PRP", False, "", ("origin B, ξ along the guide at A", "origin B, ξ along the guide at C"),
    "guide A and guide C", "blocked position", frozenset(), middle, close)
