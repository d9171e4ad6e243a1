"""Kind 3, RPR: both links turn about their pivots, the guide of one passes the slider
point of the other: ρ·sin(β0 − ψ) = c0, a tangent to an offset circle (closed form
derived for dyade).

Variant +1: the guide direction points from the guide link's pivot towards the other
link's pivot (d·(O_slider − O_guide) > 0).
"""

from __future__ import annotations

import numpy as np

from dyade.linkage.components import direction_xy, full
from dyade.linkage.dyads.closure import Closure, pin, place_origin, same_pins, turn
from dyade.linkage.motion import Motion, rotate
from dyade.model.mechanism import Dyad


def guide_offset(theta, kappa, guide_point, p_c, slider_point, p_s):
    """c0 = n·(g − p_c) − n·R(κ)·(s − p_s), n = (−sin θ, cos θ): the guide's distance
    from the slider's pivot (a float, or one per position for stacked variants)."""
    if all(np.ndim(v) == 0 for v in (theta, kappa, *guide_point, *p_c, *slider_point, *p_s)):
        n_local = np.array([-np.sin(theta), np.cos(theta)])
        slider_arm = rotate(np.array(kappa), np.subtract(slider_point, p_s))
        return float(n_local @ np.subtract(guide_point, p_c) - n_local @ slider_arm)
    nx, ny = -np.sin(theta), np.cos(theta)
    sx, sy = np.subtract(slider_point[0], p_s[0]), np.subtract(slider_point[1], p_s[1])
    ck, sk = np.cos(kappa), np.sin(kappa)
    ax, ay = ck * sx - sk * sy, sk * sx + ck * sy
    gx, gy = np.subtract(guide_point[0], p_c[0]), np.subtract(guide_point[1], p_c[1])
    return (nx * gx + ny * gy) - (nx * ax + ny * ay)


def close(dyad: Dyad, motion: Motion) -> Closure:
    """The guide through the carrier's pivot O_c passes at distance c0 from the slider's
    pivot O_s: with D = O_s − O_c and ρ = |D|, its angle is ψ = atan2(D) − asin(c0/ρ)
    (variant +1, towards O_s) or atan2(D) − π + asin(c0/ρ), and the lever arm is
    √(ρ² − c0²). (The guide direction could be had without trigonometric functions, as
    (√(ρ² − c0²)·D ± c0·E·D)/ρ²; cos ψ and sin ψ are taken from ψ instead so that the
    results stay the same to the bit.)"""
    i, j = dyad.links
    joint_a, joint_b, joint_c = dyad.joints
    pins = {i: pin(joint_a, i, motion), j: pin(joint_c, j, motion)}
    c, s = joint_b.carrier, joint_b.slider
    ((ocx, ocy), p_c), ((osx, osy), p_s) = pins[c], pins[s]
    theta, kappa = joint_b.guide_angle, joint_b.relative_angle
    c0 = guide_offset(theta, kappa, joint_b.guide_point, p_c, joint_b.slider_point, p_s)
    dx, dy = full(motion, osx - ocx), full(motion, osy - ocy)
    rho = np.hypot(dx, dy)
    # pivots on top of each other (or a subnormal distance apart): no closure
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = c0 / rho
    # lever arm: distance along the guide between the two pivots; 0 at the dead centre
    # where the slider point passes the guide link's pivot foot point (|ratio| = 1: the
    # dyad closes there, singular); where the pivots coincide (ρ = 0) the guide has no
    # direction and the dyad does not close
    arm = np.maximum(rho ** 2 - c0 ** 2, 0.0)
    np.sqrt(arm, out=arm)
    closes = np.abs(ratio) <= 1.0 + 1e-12
    if not closes.all():
        ratio[~closes] = np.nan
        arm[~closes] = np.nan
    tilt = np.arcsin(np.clip(ratio, -1.0, 1.0))
    beta0 = np.arctan2(dy, dx)
    psi = beta0 - tilt if dyad.variant > 0 else beta0 - np.pi + tilt
    # the carrier's frame is the guide turned back by θ, the slider's turned on by κ
    motion.set_angle(c, psi - theta)
    cos_c, sin_c = motion.cos[:, c], motion.sin[:, c]
    place_origin(motion, c, ocx, ocy, cos_c, sin_c, p_c)
    cos_s, sin_s = turn(motion, s, c, kappa)
    place_origin(motion, s, osx, osy, cos_s, sin_s, p_s)
    # μ: angle between the guide normal and the pivot line, cos μ = c0/ρ, sin μ = arm/ρ.
    # The closure's determinant is the lever arm itself: with zero offset μ stays 90°
    # while the arm (= ρ) goes to 0 as the pivots approach each other, so the quality is
    # sin μ times the pivot distance ρ against a length of the mechanism (``lever``,
    # combined in ``dyade.linkage.kinematics``), at each position on its own.
    with np.errstate(invalid="ignore"):  # ρ = 0: no closure, NaN
        sin_mu = arm / rho
    pins = same_pins({0: (joint_a, i, pins[i][0]), 2: (joint_c, j, pins[j][0])})
    return Closure(closes, np.arctan2(arm, c0), sin_mu, pins,
                   {1: direction_xy(joint_b, cos_c, sin_c)}, lever=rho)
