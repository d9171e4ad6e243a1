"""Kind 3, RPR: both links turn about their pivots, the guide of one passes the slider
point of the other: ρ·sin(β0 − ψ) = c0, a tangent to an offset circle (closed form
derived for dyade).

Variant +1: the guide direction points from the guide link's pivot towards the other
link's pivot (d·(O_slider − O_guide) > 0).
"""

from __future__ import annotations

import numpy as np

from dyade.linkage import dyads
from dyade.linkage.motion import Motion, rotate
from dyade.linkage.model import Dyad, Prismatic



def close(dyad: Dyad, motion: Motion) -> dyads.Closure:
    i, j = dyad.links
    joint_a, joint_b, joint_c = dyad.joints
    pins = {i: dyads.pin(joint_a, i, motion), j: dyads.pin(joint_c, j, motion)}
    c, s = joint_b.carrier, joint_b.slider
    (o_c, p_c), (o_s, p_s) = pins[c], pins[s]
    theta, kappa = joint_b.guide_angle, joint_b.relative_angle
    n_local = np.array([-np.sin(theta), np.cos(theta)])
    slider_arm = rotate(np.array(kappa), np.subtract(joint_b.slider_point, p_s))
    c0 = float(n_local @ np.subtract(joint_b.guide_point, p_c) - n_local @ slider_arm)
    d = o_s - o_c
    rho = np.hypot(d[:, 0], d[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):  # pivots on top of each other
        ratio = c0 / rho
    # lever arm: distance along the guide between the two pivots; 0 at the dead centre
    # where the slider point passes the guide link's pivot foot point (|ratio| = 1: the
    # dyad closes there, singular); where the pivots coincide (ρ = 0) the guide has no
    # direction and the dyad does not close
    arm = np.sqrt(np.maximum(rho ** 2 - c0 ** 2, 0.0))
    closes = np.abs(ratio) <= 1.0 + 1e-12
    tilt = np.arcsin(np.clip(np.where(closes, ratio, np.nan), -1.0, 1.0))
    beta0 = dyads.polar_angle(d)
    psi = beta0 - tilt if dyad.variant > 0 else beta0 - np.pi + tilt
    phi_c = psi - theta
    dyads.place(motion, c, phi_c, o_c, p_c)
    motion.turn_with(s, c, kappa)
    motion.origin[:, s] = o_s - motion.rotated(s, p_s)
    # μ: angle between the guide normal and the pivot line, cos μ = c0/ρ, sin μ = arm/ρ.
    # The closure's determinant is the lever arm itself: with zero offset μ stays 90°
    # while the arm (= ρ) goes to 0 as the pivots approach each other, so the quality is
    # sin μ times the pivot distance ρ against a length of the mechanism (``lever``,
    # combined in ``dyade.linkage.kinematics``), at each position on its own.
    with np.errstate(invalid="ignore"):  # ρ = 0: no closure, NaN
        sin_mu = arm / rho
    return dyads.Closure(closes, np.arctan2(arm, c0), np.abs(sin_mu), lever=rho)


def middle(reader, table, key: str, i: int, j: int, dyad_table, dyad_key: str) -> Prismatic:
    """Joint B: the guide along the ξ axis of its carrier (link j unless ``guide`` says
    otherwise), the slider point at the other link's origin, ``offset`` to its left."""
    offset, extra = reader.middle_prismatic(table, key, point=False)
    guide = reader.guide(table, key, (i, j), j)
    slider = i if guide == j else j
    return Prismatic.through(guide, (0.0, 0.0), 0.0, offset, slider, (0.0, 0.0), 0.0, **extra)


KIND = dyads.DyadKind(
    3, "RPR", True, "the guide direction points from the guide link's pivot towards the other "
                    "link's pivot",
    ("origin A, ξ along the guide at B", "origin C, ξ along the guide at B"),
    "the normal of guide B and the line between the pivots", "dead centre", frozenset(),
    middle, close)
