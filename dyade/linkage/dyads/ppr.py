"""Kind 5, PPR: link i slides on g, link j turns about C and slides on i; linear, one
closure (derived for dyade: Part 1 of the DYADE paper is not available); blocked when
guides A and B are parallel."""

from __future__ import annotations

import math

import numpy as np

from dyade.linkage import dyads
from dyade.linkage.motion import Motion
from dyade.linkage.model import Dyad, Prismatic


def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    """Link i translates along guide A, link j turns with i about the pin C; the origin
    of i is where guide A and guide B (drawn for the origin of i) cross."""
    i, j = dyad.links
    g, _ = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    c_i, s_i = dyads.carry(joint_a, g, i, motion)
    (cx, cy), c_j = dyads.pin(joint_c, j, motion)
    cos_j, sin_j = dyads.carry(joint_b, i, j, motion)
    dyads.place_origin(motion, j, cx, cy, cos_j, sin_j, c_j)
    (dax, day), e_a = dyads.guide_line(joint_a, i, motion, c_i, s_i)
    (dbx, dby), e_b = dyads.guide_line(joint_b, i, motion, c_i, s_i)
    ox, oy, det = dyads.crossing(-day, dax, e_a, -dby, dbx, e_b, motion)
    motion.origin[:, i, 0] = ox
    motion.origin[:, i, 1] = oy
    sin = np.abs(det)  # μ between the guide directions d_a and d_b, |d| = 1
    transmission = np.arctan2(sin, dyads.full(motion, dax * dbx + day * dby))
    return dyads.Closure(sin >= dyads.SINGULAR_SIN, transmission, sin,
                         dyads.same_pins({2: (joint_c, j, (cx, cy))}),
                         {0: (dax, day), 1: (dbx, dby)})


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
