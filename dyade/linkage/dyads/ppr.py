"""Kind 5, PPR: link i slides on g, link j turns about C and slides on i; linear, one
closure (derived for dyade: Part 1 of the DYADE paper is not available); blocked when
guides A and B are parallel."""

from __future__ import annotations

import numpy as np

from dyade.linkage.components import full
from dyade.linkage.dyads.closure import (Closure, SINGULAR_SIN, carry, crossing, guide_line, pin,
                                         place_origin, same_pins)
from dyade.linkage.motion import Motion
from dyade.model.mechanism import Dyad


def close(dyad: Dyad, motion: Motion) -> Closure:
    """Link i translates along guide A, link j turns with i about the pin C; the origin
    of i is where guide A and guide B (drawn for the origin of i) cross."""
    i, j = dyad.links
    g, _ = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    c_i, s_i = carry(joint_a, g, i, motion)
    (cx, cy), c_j = pin(joint_c, j, motion)
    cos_j, sin_j = carry(joint_b, i, j, motion)
    place_origin(motion, j, cx, cy, cos_j, sin_j, c_j)
    (dax, day), e_a = guide_line(joint_a, i, motion, c_i, s_i)
    (dbx, dby), e_b = guide_line(joint_b, i, motion, c_i, s_i)
    ox, oy, det = crossing(-day, dax, e_a, -dby, dbx, e_b, motion)
    motion.origin[:, i, 0] = ox
    motion.origin[:, i, 1] = oy
    sin = np.abs(det)  # μ between the guide directions d_a and d_b, |d| = 1
    transmission = np.arctan2(sin, full(motion, dax * dbx + day * dby))
    return Closure(sin >= SINGULAR_SIN, transmission, sin,
                   same_pins({2: (joint_c, j, (cx, cy))}),
                   {0: (dax, day), 1: (dbx, dby)})
