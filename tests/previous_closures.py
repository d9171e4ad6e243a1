"""The closures of the kinds RRP, RPR, PRP and PPR as they were before they were written
in components (issue 17): (n, 2) vectors, ``np.stack`` and ``perp``, kept to test the
component forms against. Each ``close(dyad, motion)`` writes the poses of links i and j
into ``motion`` and returns (closes, transmission angle, conditioning |sin μ|; RPR: and
the pivot distance ρ)."""

from __future__ import annotations

import numpy as np

from dyade.linkage.dyads.closure import SINGULAR_SIN, orient
from dyade.linkage.motion import dot, perp, rotate


def cross(a, b):
    """z component of a × b."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def angle_between(u, v):
    """Angle between two vectors in [0, π] [rad]."""
    return np.arctan2(np.abs(cross(u, v)), dot(u, v))


def polar_angle(v):
    v = np.asarray(v, dtype=np.float64)
    return np.arctan2(v[..., 1], v[..., 0])


def _pin(joint, unknown, motion):
    (p, q), (u_p, u_q) = joint.links, joint.points
    if p == unknown:
        return motion.point(q, u_q), u_p
    return motion.point(p, u_p), u_q


def _ends(joint, first):
    return joint.points if joint.links[0] == first else joint.points[::-1]


def _carry_angle(joint, known, unknown, motion):
    offset = joint.relative_angle if joint.carrier == known else -joint.relative_angle
    motion.turn_with(unknown, known, offset)


def _guide_line(joint, unknown, motion):
    normal = perp(motion.direction(joint.carrier, joint.guide_angle))
    if joint.slider == unknown:
        other = motion.point(joint.carrier, joint.guide_point)
        own = motion.rotated(unknown, joint.slider_point)
    else:
        other = motion.point(joint.slider, joint.slider_point)
        own = motion.rotated(unknown, joint.guide_point)
    return normal, dot(normal, other - own)


def _place(motion, link, angle, world, local):
    motion.set_angle(link, angle)
    motion.origin[:, link] = world - motion.rotated(link, local)


def _solve_lines(n1, c1, n2, c2):
    det = cross(n1, n2)
    sin = det / np.sqrt(dot(n1, n1) * dot(n2, n2))
    blocked = np.abs(sin) < SINGULAR_SIN
    with np.errstate(all="ignore"):
        x = (c1 * n2[:, 1] - c2 * n1[:, 1]) / det
        y = (n1[:, 0] * c2 - n2[:, 0] * c1) / det
    point = np.stack((x, y), axis=-1)
    point[blocked] = np.nan
    return point, sin


def rrp(dyad, motion):
    i, j = dyad.links
    _, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    a, a_i = _pin(joint_a, i, motion)
    b_i, b_j = _ends(joint_b, i)
    _carry_angle(joint_c, h, j, motion)
    normal, offset = _guide_line(joint_c, j, motion)
    offset = offset + dot(normal, motion.rotated(j, b_j))
    direction = -perp(normal)
    arm_i = np.subtract(b_i, a_i)
    length = np.hypot(*arm_i)
    height = offset - dot(normal, a)
    along_sq = length ** 2 - height ** 2
    closes = along_sq >= -1e-12 * length ** 2
    along = np.sqrt(np.where(closes, np.maximum(along_sq, 0.0), np.nan))
    b = a + height[:, None] * normal + dyad.variant * along[:, None] * direction
    ab = b - a
    orient(motion, i, ab[:, 0], ab[:, 1], arm_i, length, a[:, 0], a[:, 1], a_i)  # as RRR's
    motion.origin[:, j] = b - motion.rotated(j, b_j)
    transmission = angle_between(ab, normal)
    return closes, transmission, np.abs(np.sin(transmission))


def rpr(dyad, motion):
    i, j = dyad.links
    joint_a, joint_b, joint_c = dyad.joints
    pins = {i: _pin(joint_a, i, motion), j: _pin(joint_c, j, motion)}
    c, s = joint_b.carrier, joint_b.slider
    (o_c, p_c), (o_s, p_s) = pins[c], pins[s]
    theta, kappa = joint_b.guide_angle, joint_b.relative_angle
    n_local = np.array([-np.sin(theta), np.cos(theta)])
    slider_arm = rotate(np.array(kappa), np.subtract(joint_b.slider_point, p_s))
    c0 = float(n_local @ np.subtract(joint_b.guide_point, p_c) - n_local @ slider_arm)
    d = o_s - o_c
    rho = np.hypot(d[:, 0], d[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = c0 / rho
    arm = np.sqrt(np.maximum(rho ** 2 - c0 ** 2, 0.0))
    closes = np.abs(ratio) <= 1.0 + 1e-12
    tilt = np.arcsin(np.clip(np.where(closes, ratio, np.nan), -1.0, 1.0))
    beta0 = polar_angle(d)
    psi = beta0 - tilt if dyad.variant > 0 else beta0 - np.pi + tilt
    _place(motion, c, psi - theta, o_c, p_c)
    motion.turn_with(s, c, kappa)
    motion.origin[:, s] = o_s - motion.rotated(s, p_s)
    with np.errstate(invalid="ignore"):
        sin_mu = arm / rho
    return closes, np.arctan2(arm, c0), np.abs(sin_mu), rho


def prp(dyad, motion):
    i, j = dyad.links
    g, h = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    b_i, b_j = _ends(joint_b, i)
    _carry_angle(joint_a, g, i, motion)
    _carry_angle(joint_c, h, j, motion)
    n_a, c_a = _guide_line(joint_a, i, motion)
    n_c, c_c = _guide_line(joint_c, j, motion)
    c_a = c_a + dot(n_a, motion.rotated(i, b_i))
    c_c = c_c + dot(n_c, motion.rotated(j, b_j))
    b, sin = _solve_lines(n_a, c_a, n_c, c_c)
    motion.origin[:, i] = b - motion.rotated(i, b_i)
    motion.origin[:, j] = b - motion.rotated(j, b_j)
    transmission = angle_between(-perp(n_a), -perp(n_c))
    return abs(sin) >= SINGULAR_SIN, transmission, np.abs(np.sin(transmission))


def ppr(dyad, motion):
    i, j = dyad.links
    g, _ = dyad.known
    joint_a, joint_b, joint_c = dyad.joints
    _carry_angle(joint_a, g, i, motion)
    c, c_j = _pin(joint_c, j, motion)
    _carry_angle(joint_b, i, j, motion)
    motion.origin[:, j] = c - motion.rotated(j, c_j)
    n_a, c_a = _guide_line(joint_a, i, motion)
    n_b, c_b = _guide_line(joint_b, i, motion)
    origin, sin = _solve_lines(n_a, c_a, n_b, c_b)
    motion.origin[:, i] = origin
    transmission = angle_between(-perp(n_a), -perp(n_b))
    return abs(sin) >= SINGULAR_SIN, transmission, np.abs(np.sin(transmission))


CLOSE = {"RRP": rrp, "RPR": rpr, "PRP": prp, "PPR": ppr}
