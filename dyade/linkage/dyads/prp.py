"""Kind 4, PRP: the pin B is where two guide lines cross; linear, one closure (derived
for dyade); blocked when the guides are parallel."""

from __future__ import annotations

import numpy as np

from dyade.linkage.components import full
from dyade.linkage.dyads.closure import (Closure, SINGULAR_SIN, carry, crossing, ends, guide_line,
                                         place_origin, shift_line)
from dyade.linkage.motion import Motion
from dyade.model.mechanism import Dyad


def close(dyad: Dyad, motion: Motion) -> Closure:
    """Both links translate (their angles follow g and h); the pin B is where the guide
    lines of A and C, carried to B, cross."""
    i, j = dyad.links
    g, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    b_i, b_j = ends(joint_b, i)
    c_i, s_i = carry(joint_a, g, i, motion)
    c_j, s_j = carry(joint_c, h, j, motion)
    (dax, day), e_a = guide_line(joint_a, i, motion, c_i, s_i)
    (dcx, dcy), e_c = guide_line(joint_c, j, motion, c_j, s_j)
    e_a = shift_line(e_a, dax, day, c_i, s_i, b_i)  # now n_a·B = e_a
    e_c = shift_line(e_c, dcx, dcy, c_j, s_j, b_j)
    bx, by, det = crossing(-day, dax, e_a, -dcy, dcx, e_c, motion)
    place_origin(motion, i, bx, by, c_i, s_i, b_i)
    place_origin(motion, j, bx, by, c_j, s_j, b_j)
    sin = np.abs(det)  # μ between the guide directions d_a and d_c, |d| = 1
    transmission = np.arctan2(sin, full(motion, dax * dcx + day * dcy))
    return Closure(sin >= SINGULAR_SIN, transmission, sin, {},
                   {0: (dax, day), 2: (dcx, dcy)})
