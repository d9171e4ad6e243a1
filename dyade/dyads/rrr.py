"""Kind 1, RRR: two circles (SPEC §1). Variant +1: B left of the directed line A→C."""

from __future__ import annotations

import numpy as np

from dyade import dyads
from dyade.joints import Motion, dot, perp
from dyade.model import Dyad

NAME = "RRR"
JOINTS = "RRR"
HAS_VARIANT = True


def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    """Place links i and j: B = A + l_i·e(φ_i) = C + l_j·e(φ_j)."""
    i, j = dyad.links
    joint_a, joint_b, joint_c = dyad.joints
    a, a_i = dyads.pin(joint_a, i, motion)
    c, c_j = dyads.pin(joint_c, j, motion)
    b_i, b_j = (joint_b.points if joint_b.links[0] == i else joint_b.points[::-1])
    arm_i = np.subtract(b_i, a_i)
    arm_j = np.subtract(b_j, c_j)
    l_i, l_j = np.hypot(*arm_i), np.hypot(*arm_j)
    ac = c - a
    dist = np.sqrt(dot(ac, ac))
    with np.errstate(divide="ignore", invalid="ignore"):  # A on C: no direction, NaN
        unit = ac / dist[:, None]
        along = (dist ** 2 + l_i ** 2 - l_j ** 2) / (2.0 * dist)
    height_sq = l_i ** 2 - along ** 2
    closes = np.isfinite(height_sq) & (height_sq >= -1e-12 * l_i ** 2)
    height = np.sqrt(np.where(closes, np.maximum(height_sq, 0.0), np.nan))
    b = a + along[:, None] * unit + dyad.variant * height[:, None] * perp(unit)
    dyads.place(motion, i, dyads.polar_angle(b - a) - dyads.polar_angle(arm_i), a, a_i,
                *dyads.aligned(b - a, l_i, arm_i))
    dyads.place(motion, j, dyads.polar_angle(b - c) - dyads.polar_angle(arm_j), c, c_j,
                *dyads.aligned(b - c, l_j, arm_j))
    return dyads.Closure(closes, dyads.angle_between(b - a, b - c))
