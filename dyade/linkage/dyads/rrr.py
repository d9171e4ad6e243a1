"""Kind 1, RRR: two circles (closed form derived for dyade). Variant +1: B left of the
directed line A→C."""

from __future__ import annotations

import numpy as np

from dyade.linkage.dyads.closure import (Closure, between, difference, ends, length, orient,
                                         pin_xy)
from dyade.linkage.motion import Motion
from dyade.model.mechanism import Dyad


def close(dyad: Dyad, motion: Motion) -> Closure:
    """Place links i and j: B = A + l_i·e(φ_i) = C + l_j·e(φ_j)."""
    i, j = dyad.links
    joint_a, joint_b, joint_c = dyad.joints
    (ax, ay), a_i = pin_xy(joint_a, i, motion)
    (cx, cy), c_j = pin_xy(joint_c, j, motion)
    if np.ndim(ax) == 0 and np.ndim(cx) == 0:  # both on the frame: a fixed group
        ax, ay = np.full(motion.angle.shape[0], ax), np.full(motion.angle.shape[0], ay)
    b_i, b_j = ends(joint_b, i)
    arm_i, arm_j = difference(b_i, a_i), difference(b_j, c_j)
    l_i, l_j = length(arm_i), length(arm_j)
    dx, dy = cx - ax, cy - ay
    dist_sq = dx * dx + dy * dy
    # A on C: no direction, NaN; A a subnormal distance from C: along² overflows to inf,
    # and the dyad does not close (as it cannot: |l_i − l_j| > |AC|)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inverse = 1.0 / np.sqrt(dist_sq)
        along = (dist_sq + (l_i * l_i - l_j * l_j)) * (0.5 * inverse)
        height_sq = l_i * l_i - along * along
        closes = height_sq >= -1e-12 * l_i * l_i
        ux, uy = dx * inverse, dy * inverse
    height = np.sqrt(np.maximum(height_sq, 0.0))
    if not closes.all():
        height[~closes] = np.nan
    side = height if dyad.variant > 0 else -height
    # B − A = along·u + side·E·u and B − C
    bax, bay = along * ux - side * uy, along * uy + side * ux
    bcx, bcy = (ax - cx) + bax, (ay - cy) + bay
    # the arms' directions B − A and B − C: the links' angles, and the transmission
    # angle between them
    to_b_i, to_b_j = np.arctan2(bay, bax), np.arctan2(bcy, bcx)
    orient(motion, i, bax, bay, arm_i, l_i, ax, ay, a_i, to_b_i)
    orient(motion, j, bcx, bcy, arm_j, l_j, cx, cy, c_j, to_b_j)
    sin = bax * bcy - bay * bcx
    transmission = between(to_b_i, to_b_j)
    pins = {0: (ax, ay), 1: (ax + bax, ay + bay), 2: (cx, cy)}
    return Closure(closes, transmission, np.abs(sin) / (l_i * l_j), pins)
