"""Motion of the links, the joints' screws, and the constraint residuals.

Velocities, accelerations and forces are written with planar screws about the world
origin O (the dyad closures differentiated once and twice in time):

* a twist V = (v_x, v_y, ω): ω and the velocity v_O of the link point passing O;
  a point P of the link moves with v_P = v_O + ω·E·P (E: turn by +90°);
* a wrench W = (f_x, f_y, m): the force and its moment about O;
* a wrench does the power W·V = f·v_O + m·ω on a twist.

A joint's unit twist S is the relative motion it allows: a revolute joint at P gives
S = (P_y, −P_x, 1), a prismatic joint with guide direction d gives S = (d_x, d_y, 0).
So S·W is the moment of W about the pin or the force of W along the guide: the part a
frictionless joint cannot carry ("the reaction has no component along the
joint's freedom"). Arrays of screws have the shape (3, n); links are stored link-major
so that every component over the sweep is contiguous.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dyade.arrays import FloatArray, Vec
from dyade.model.mechanism import Joint, Prismatic, Revolute


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Motion:
    """Pose and its time derivatives of every link frame over the sweep.

    Arrays are indexed ``[position, link]``; link 1 (the frame) stays at rest. Entries
    of links not yet solved, or positions that do not close, are NaN. (They are views
    of link-major arrays: ``origin[:, k, 0]`` is contiguous.)
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
    cos: FloatArray
    """(n, links) cos φ, kept with the angle (see ``set_angle``)"""
    sin: FloatArray
    """(n, links) sin φ"""
    pivoted: bool = True
    """link 2's origin stays put (a crank about its pivot); False: it moves (a sliding
    input, ``dyade.linkage.kinematics.crank_motion``)"""

    @classmethod
    def at_rest(cls, positions: int, links: int, placed: tuple[int, ...] = ()) -> Motion:
        """The frame at rest, every other link NaN; the links in ``placed`` are left
        uninitialised for a caller that fills all their entries."""
        block = np.empty((11, links, positions))  # one allocation for all of them
        unplaced = [link for link in range(2, links) if link not in placed]  # 0: no link
        block[:, 1] = 0.0
        for link in unplaced:
            block[:, link] = np.nan
        block[9, 1] = 1.0  # cos 0

        def vectors(k):  # rows k, k+1: (2, links, n) seen as (n, links, 2)
            return block[k:k + 2].transpose(2, 1, 0)

        return cls(vectors(0), block[2].T, vectors(3), block[5].T, vectors(6), block[8].T,
                   block[9].T, block[10].T)

    def set_angle(self, link: int, angle: FloatArray, cos: FloatArray | None = None,
                  sin: FloatArray | None = None) -> None:
        """Set a link's angle with its cosine and sine (computed unless given)."""
        self.angle[:, link] = angle
        self.cos[:, link] = np.cos(angle) if cos is None else cos
        self.sin[:, link] = np.sin(angle) if sin is None else sin

    def turn_with(self, link: int, known: int, offset: float) -> None:
        """φ_link = φ_known + offset (links joined by a prismatic joint)."""
        c, s = np.cos(offset), np.sin(offset)
        ck, sk = self.cos[:, known], self.sin[:, known]
        self.set_angle(link, self.angle[:, known] + offset, ck * c - sk * s, sk * c + ck * s)

    def invalidate(self, link: int, bad: FloatArray) -> None:
        """Mark a link's pose NaN at the positions ``bad``."""
        for array in (self.origin, self.angle, self.cos, self.sin):
            array[bad, link] = np.nan

    # -- points of links ------------------------------------------------------------
    def rotated_xy(self, link: int, local: Vec) -> tuple[FloatArray, FloatArray]:
        """Components of R(φ_link)·u over the sweep."""
        c, s = self.cos[:, link], self.sin[:, link]
        u, v = local
        if np.ndim(v) == 0 and v == 0.0:
            return c * u, s * u
        return c * u - s * v, s * u + c * v

    def point_xy(self, link: int, local: Vec) -> tuple[FloatArray, FloatArray]:
        """Components of a link point's world position [m]."""
        x, y = self.rotated_xy(link, local)
        return self.origin[:, link, 0] + x, self.origin[:, link, 1] + y

    def point_motion(self, link: int, local: Vec) -> tuple[FloatArray, ...]:
        """A link point's x, y [m], vx, vy [m/s] and ax, ay [m/s²], one array each (the
        numbers of ``point``, ``point_velocity`` and ``point_acceleration`` to the bit,
        without their (n, 2) stacks)."""
        rx, ry = self.rotated_xy(link, local)
        omega, alpha = self.omega[:, link], self.alpha[:, link]
        square = omega ** 2
        return (self.origin[:, link, 0] + rx, self.origin[:, link, 1] + ry,
                self.velocity[:, link, 0] - omega * ry, self.velocity[:, link, 1] + omega * rx,
                self.acceleration[:, link, 0] - alpha * ry - square * rx,
                self.acceleration[:, link, 1] + alpha * rx - square * ry)

    def rotated(self, link: int, local: Vec) -> FloatArray:
        """R(φ_link)·u over the sweep, shape (n, 2)."""
        return np.stack(self.rotated_xy(link, local), axis=-1)

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
        return self.rotated(link, (np.cos(angle), np.sin(angle)))


def rotate(angle: FloatArray, local: Vec | FloatArray) -> FloatArray:
    """Rotate local vector(s) by ``angle`` [rad]; result shape (n, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    u = np.asarray(local, dtype=np.float64)
    return np.stack((c * u[..., 0] - s * u[..., 1], s * u[..., 0] + c * u[..., 1]), axis=-1)


def perp(v: FloatArray) -> FloatArray:
    """E·v: v turned by +90°."""
    return np.stack((-v[..., 1], v[..., 0]), axis=-1)


def dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]


Screw = tuple[FloatArray, FloatArray, float]
"""A unit twist as (v_x (n,), v_y (n,), ω): ω is a constant, 1 or 0, and the
arithmetic uses that (``dyade.linkage.kinematics``)."""


def guide_direction(joint: Prismatic, motion: Motion) -> tuple[FloatArray, FloatArray]:
    """Components of a prismatic joint's guide direction d over the sweep."""
    return motion.rotated_xy(joint.carrier, (np.cos(joint.guide_angle),
                                             np.sin(joint.guide_angle)))


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
    """Slider travel s = (S − G)·d and its first two time derivatives [m, m/s, m/s²],
    in components (w = S − G, d the guide's direction, ḋ = ω·E·d, d̈ = α·E·d − ω²·d)."""
    c, s = joint.carrier, joint.slider
    angle = joint.guide_angle
    dx, dy = motion.rotated_xy(c, (np.cos(angle), np.sin(angle)))
    xs, ys, vxs, vys, axs, ays = motion.point_motion(s, joint.slider_point)
    xc, yc, vxc, vyc, axc, ayc = motion.point_motion(c, joint.guide_point)
    wx, wy, vx, vy, ax, ay = xs - xc, ys - yc, vxs - vxc, vys - vyc, axs - axc, ays - ayc
    om, al = motion.omega[:, c], motion.alpha[:, c]
    square = om ** 2
    turn_x, turn_y = om * -dy, om * dx  # ḋ
    bend_x, bend_y = al * -dy - square * dx, al * dx - square * dy  # d̈
    return (wx * dx + wy * dy, vx * dx + vy * dy + (wx * turn_x + wy * turn_y),
            ax * dx + ay * dy + 2.0 * (vx * turn_x + vy * turn_y)
            + (wx * bend_x + wy * bend_y))
