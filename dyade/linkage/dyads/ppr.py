"""Kind 5, PPR: link i slides on g, link j turns about C and slides on i; linear, one
closure (derived for dyade: Part 1 of the DYADE paper is not available); blocked when
guides A and B are parallel."""

from __future__ import annotations

import math

from dyade.linkage import dyads
from dyade.linkage.motion import Motion, perp
from dyade.linkage.model import Dyad, Prismatic



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


def middle(reader, table, key: str, i: int, j: int, dyad_table, dyad_key: str) -> Prismatic:
    """Joint B: a guide through ``point`` of link i at ``angle`` to guide A (90° unless
    given; not parallel to it), or on link j with ``guide = j``."""
    offset, extra = reader.middle_prismatic(table, key, point=True)
    theta = reader.angle_of(table.get("angle", 90.0 * math.pi / 180.0 / reader.angle),
                            f"{key}.angle")
    point = reader.point_on(i, table.get("point", [0.0, 0.0]), f"{key}.point")
    if abs(math.sin(theta)) < 1e-9:
        raise reader.fail(f"{key}.angle", "makes guide B parallel to guide A: a PPR dyad is "
                                          "then blocked in every position. Use an angle that "
                                          "is not 0° or 180°.", theta)
    if reader.guide(table, key, (i, j), i) == i:
        return Prismatic.through(i, point, theta, offset, j, (0.0, 0.0), theta, **extra)
    return Prismatic.through(j, (0.0, 0.0), 0.0, offset, i, point, -theta, **extra)


KIND = dyads.DyadKind(
    5, "PPR", False, "", ("origin on guide A, ξ along the guide at A",
                          "origin C, ξ along the guide at B"),
    "guide A and guide B", "blocked position", frozenset(), middle, close)
