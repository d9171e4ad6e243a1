"""Joint constraints in link coordinates q = (x, y, φ) of each link's frame origin.

One formulation serves the whole engine: velocities solve J·q̇ = −J_known·q̇_known,
accelerations J·q̈ = γ − J_known·q̈_known, and joint reactions the transposed system
Jᵀ·λ = Q (d'Alembert, Lagrange multipliers). A revolute joint gives two rows, a
prismatic joint two (relative angle, then normal distance to the guide line).

Derivation (SPEC §1, "velocities and accelerations follow from differentiating these
closures once and twice in time"):

* revolute, point u_p of p on point u_q of q:
  Φ = r_p + R_p·u_p − r_q − R_q·u_q,  J_p = [I, E·R_p·u_p],  J_q = −[I, E·R_q·u_q],
  γ = ω_p²·R_p·u_p − ω_q²·R_q·u_q   (E: rotation by +90°).
* prismatic, carrier c with guide (g, direction d, normal n), slider s with point σ:
  Φ1 = φ_s − φ_c − κ;  Φ2 = n·w with w = S − G = r_s + R_s·σ − r_c − R_c·g,
  ∂Φ2/∂r_s = n, ∂Φ2/∂φ_s = n·E·R_s·σ, ∂Φ2/∂r_c = −n, ∂Φ2/∂φ_c = −d·w − n·E·R_c·g,
  γ2 = n·(ω_s²·R_s·σ − ω_c²·R_c·g) + 2·ω_c·d·ẇ + ω_c²·n·w.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.model import FloatArray, Joint, Prismatic, Revolute, Vec


@dataclass(slots=True)
class Motion:
    """Pose and its time derivatives of every link frame over the sweep.

    Arrays are indexed ``[position, link]``; link 1 (the frame) stays at rest. Entries
    of links not yet solved, or positions that do not close, are NaN.
    """

    origin: FloatArray
    """(n, links, 2) frame origins [m]"""
    angle: FloatArray
    """(n, links) frame angles φ [rad]"""
    velocity: FloatArray
    """(n, links, 2) origin velocities [m/s]"""
    omega: FloatArray
    """(n, links) angular velocities ω [rad/s]"""
    acceleration: FloatArray
    """(n, links, 2) origin accelerations [m/s²]"""
    alpha: FloatArray
    """(n, links) angular accelerations [rad/s²]"""

    @classmethod
    def at_rest(cls, positions: int, links: int) -> Motion:
        nan2 = np.full((positions, links, 2), np.nan)
        nan1 = np.full((positions, links), np.nan)
        motion = cls(nan2, nan1, nan2.copy(), nan1.copy(), nan2.copy(), nan1.copy())
        for array in (motion.origin, motion.angle, motion.velocity, motion.omega,
                      motion.acceleration, motion.alpha):
            array[:, 1] = 0.0
        return motion

    # -- points of links ------------------------------------------------------------
    def rotated(self, link: int, local: Vec | FloatArray) -> FloatArray:
        """R(φ_link)·u over the sweep, shape (n, 2)."""
        return rotate(self.angle[:, link], local)

    def point(self, link: int, local: Vec | FloatArray) -> FloatArray:
        """World position of a link-fixed point [m], shape (n, 2)."""
        return self.origin[:, link] + self.rotated(link, local)

    def point_velocity(self, link: int, local: Vec | FloatArray) -> FloatArray:
        """Velocity of a link-fixed point [m/s], shape (n, 2)."""
        return self.velocity[:, link] + self.omega[:, link, None] * perp(self.rotated(link, local))

    def point_acceleration(self, link: int, local: Vec | FloatArray) -> FloatArray:
        """Acceleration of a link-fixed point [m/s²], shape (n, 2)."""
        rel = self.rotated(link, local)
        return (self.acceleration[:, link] + self.alpha[:, link, None] * perp(rel)
                - (self.omega[:, link] ** 2)[:, None] * rel)

    def direction(self, link: int, angle: float) -> FloatArray:
        """World unit vector of a link-fixed direction, shape (n, 2)."""
        phi = self.angle[:, link] + angle
        return np.stack((np.cos(phi), np.sin(phi)), axis=-1)


def rotate(angle: FloatArray, local: Vec | FloatArray) -> FloatArray:
    """Rotate local vector(s) by ``angle`` [rad]; result shape (n, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    u = np.asarray(local, dtype=np.float64)
    return np.stack((c * u[..., 0] - s * u[..., 1], s * u[..., 0] + c * u[..., 1]), axis=-1)


def perp(v: FloatArray) -> FloatArray:
    """E·v: v turned by +90°."""
    return np.stack((-v[..., 1], v[..., 0]), axis=-1)


def cross(a: FloatArray, b: FloatArray) -> FloatArray:
    """z component of a × b."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


Blocks = dict[int, FloatArray]
"""link -> (n, 2, 3) derivative of a joint's two equations by (x, y, φ) of that link"""


def blocks(joint: Joint, motion: Motion) -> Blocks:
    """Jacobian blocks of ``joint``; they depend on the positions only."""
    n = motion.angle.shape[0]
    if isinstance(joint, Revolute):
        out = {}
        for link, local, sign in zip(joint.links, joint.points, (1.0, -1.0)):
            block = np.zeros((n, 2, 3))
            block[:, 0, 0] = sign
            block[:, 1, 1] = sign
            block[:, :, 2] = sign * perp(motion.rotated(link, local))
            out[link] = block
        return out
    c, s = joint.carrier, joint.slider
    d, rel_g, rel_s, w = _guide_geometry(joint, motion)
    normal = perp(d)
    block_c = np.zeros((n, 2, 3))
    block_s = np.zeros((n, 2, 3))
    block_c[:, 0, 2] = -1.0
    block_s[:, 0, 2] = 1.0
    block_s[:, 1, :2] = normal
    block_s[:, 1, 2] = dot(normal, perp(rel_s))
    block_c[:, 1, :2] = -normal
    block_c[:, 1, 2] = -dot(d, w) - dot(normal, perp(rel_g))
    return {c: block_c, s: block_s}


def gamma(joint: Joint, motion: Motion) -> FloatArray:
    """Right-hand side γ = −J̇·q̇ of the acceleration equations, shape (n, 2); needs
    the velocities."""
    if isinstance(joint, Revolute):
        (p, q), (u_p, u_q) = joint.links, joint.points
        return ((motion.omega[:, p] ** 2)[:, None] * motion.rotated(p, u_p)
                - (motion.omega[:, q] ** 2)[:, None] * motion.rotated(q, u_q))
    c, s = joint.carrier, joint.slider
    d, rel_g, rel_s, w = _guide_geometry(joint, motion)
    normal = perp(d)
    om_c, om_s = motion.omega[:, c], motion.omega[:, s]
    w_dot = (motion.velocity[:, s] + om_s[:, None] * perp(rel_s)
             - motion.velocity[:, c] - om_c[:, None] * perp(rel_g))
    out = np.zeros((motion.angle.shape[0], 2))
    out[:, 1] = (dot(normal, om_s[:, None] ** 2 * rel_s - om_c[:, None] ** 2 * rel_g)
                 + 2.0 * om_c * dot(d, w_dot) + om_c ** 2 * dot(normal, w))
    return out


def _guide_geometry(joint: Prismatic, motion: Motion):
    """Guide direction d, the rotated guide and slider points, and w = S − G."""
    c, s = joint.carrier, joint.slider
    d = motion.direction(c, joint.guide_angle)
    rel_g = motion.rotated(c, joint.guide_point)
    rel_s = motion.rotated(s, joint.slider_point)
    return d, rel_g, rel_s, motion.origin[:, s] + rel_s - motion.origin[:, c] - rel_g


def residual(joint: Joint, motion: Motion) -> FloatArray:
    """Constraint residual Φ over the sweep, shape (n, 2) [m or rad]."""
    if isinstance(joint, Revolute):
        (p, q), (u_p, u_q) = joint.links, joint.points
        return motion.point(p, u_p) - motion.point(q, u_q)
    c, s = joint.carrier, joint.slider
    normal = perp(motion.direction(c, joint.guide_angle))
    w = motion.point(s, joint.slider_point) - motion.point(c, joint.guide_point)
    angle = motion.angle[:, s] - motion.angle[:, c] - joint.relative_angle
    angle = np.angle(np.exp(1j * angle))  # wrap to (−π, π]
    return np.stack((angle, dot(normal, w)), axis=-1)


def travel(joint: Prismatic, motion: Motion) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Slider travel s = (S − G)·d and its first two time derivatives [m, m/s, m/s²]."""
    c, s = joint.carrier, joint.slider
    d = motion.direction(c, joint.guide_angle)
    om = motion.omega[:, c][:, None]
    al = motion.alpha[:, c][:, None]
    w = motion.point(s, joint.slider_point) - motion.point(c, joint.guide_point)
    w_dot = (motion.point_velocity(s, joint.slider_point)
             - motion.point_velocity(c, joint.guide_point))
    w_ddot = (motion.point_acceleration(s, joint.slider_point)
              - motion.point_acceleration(c, joint.guide_point))
    d_dot = om * perp(d)
    d_ddot = al * perp(d) - om ** 2 * d
    return (dot(w, d), dot(w_dot, d) + dot(w, d_dot),
            dot(w_ddot, d) + 2.0 * dot(w_dot, d_dot) + dot(w, d_ddot))
